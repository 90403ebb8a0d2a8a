#include "json_writer.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

namespace dispcon::cli {

void JsonWriter::item() {
  if (sink_ && out_.size() >= (1 << 16)) {
    std::fwrite(out_.data(), 1, out_.size(), sink_);
    out_.clear();
  }
  if (after_key_) {  // the value of a member: on the key's line
    after_key_ = false;
    return;
  }
  if (items_.empty()) return;  // the document itself
  if (items_.back()++ > 0) out_ += ',';
  new_line();
}

// A new line and the indent of the open containers (copied from spaces, not filled a byte at a
// time: a document of 400 four-bars has some 60,000 of them).
void JsonWriter::new_line() {
  static const std::string kSpaces(64, ' ');
  size_t indent = 2 * items_.size();
  out_ += '\n';
  for (; indent > kSpaces.size(); indent -= kSpaces.size()) out_ += kSpaces;
  out_.append(kSpaces.data(), indent);
}

void JsonWriter::open(char bracket) {
  item();
  out_ += bracket;
  items_.push_back(0);
}

void JsonWriter::close(char bracket) {
  const int items = items_.back();
  items_.pop_back();
  if (items > 0) new_line();
  out_ += bracket;
}

void JsonWriter::begin_object() {
  open('{');
}
void JsonWriter::end_object() {
  close('}');
}
void JsonWriter::begin_array() {
  open('[');
}
void JsonWriter::end_array() {
  close(']');
}

void JsonWriter::key(std::string_view k) {
  item();
  string(k);
  out_ += ": ";
  after_key_ = true;
}

void JsonWriter::value(double v) {
  item();
  if (!std::isfinite(v)) {
    out_ += "null";
    return;
  }
  char buf[64];
  char* end = buf;
  if (v == std::trunc(v) && std::abs(v) < 1e15) {
    // A whole number (a planar model's zeros and ones: half its rotations) as nlohmann writes
    // it, its digits and ".0" (-0.0 too), without its conversion: cli.JsonNumbers compares
    // them on millions of values.
    if (std::signbit(v)) *end++ = '-';
    end = std::to_chars(end, buf + sizeof buf, static_cast<long long>(std::abs(v))).ptr;
    *end++ = '.';
    *end++ = '0';
  } else {
    // nlohmann's own conversion (Grisu2): its digits are not always the shortest (std::to_chars
    // writes 1.542053954523393 where it writes 1.5420539545233929), and the documents must not
    // change by a digit.
    end = nlohmann::detail::to_chars(buf, buf + sizeof buf, v);
  }
  out_.append(buf, static_cast<size_t>(end - buf));
}

void JsonWriter::value(int v) {
  item();
  char buf[16];
  out_.append(buf, static_cast<size_t>(std::to_chars(buf, buf + sizeof buf, v).ptr - buf));
}

void JsonWriter::value(bool v) {
  item();
  out_ += v ? "true" : "false";
}

void JsonWriter::value(std::string_view s) {
  item();
  string(s);
}

// Quotes, backslashes and control characters escaped (\b \t \n \f \r, else \u00xx), everything
// else as it is: the engine's strings are UTF-8 (names are ASCII, labels are checked).
void JsonWriter::string(std::string_view s) {
  static const char kHex[] = "0123456789abcdef";
  out_ += '"';
  size_t plain = 0;  // start of the run of bytes written as they are
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c != '"' && c != '\\') continue;
    out_.append(s.data() + plain, i - plain);
    plain = i + 1;
    out_ += '\\';
    switch (c) {
      case '"':
      case '\\':
        out_ += static_cast<char>(c);
        break;
      case '\b':
        out_ += 'b';
        break;
      case '\t':
        out_ += 't';
        break;
      case '\n':
        out_ += 'n';
        break;
      case '\f':
        out_ += 'f';
        break;
      case '\r':
        out_ += 'r';
        break;
      default:
        out_ += "u00";
        out_ += kHex[c >> 4];
        out_ += kHex[c & 15];
    }
  }
  out_.append(s.data() + plain, s.size() - plain);
  out_ += '"';
}

}  // namespace dispcon::cli
