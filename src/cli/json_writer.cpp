#include "json_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

namespace dispcon::cli {

namespace {

// A new line then spaces: any indent up to 128 levels is a prefix of it.
struct Indent {
  static constexpr size_t size = 256;
  char text[size + 1];
  Indent() {
    text[0] = '\n';
    std::memset(text + 1, ' ', size);
  }
};
const Indent kIndent;

// Whether no byte of `s` needs escaping in a JSON string (a control character, a quote, a
// backslash), eight bytes at a time: the classic test for a byte below a bound in a word (the
// bytes below 0x20, or equal to '"' or '\\' once xor'ed to zero). A name or a key shorter than
// a word is read as two overlapping halves, a longer one's tail as the overlapping last word.
bool plain(std::string_view s) {
  constexpr uint64_t kOnes = 0x0101010101010101, kHigh = 0x8080808080808080;
  const auto clean = [](uint64_t x) {
    const auto below = [](uint64_t y, uint64_t n) { return (y - kOnes * n) & ~y & kHigh; };
    return !(below(x, 0x20) | below(x ^ (kOnes * '"'), 1) | below(x ^ (kOnes * '\\'), 1));
  };
  const char* const p = s.data();
  const size_t n = s.size();
  if (n >= 8) {
    uint64_t x;
    for (size_t i = 0; i + 8 < n; i += 8) {
      std::memcpy(&x, p + i, 8);
      if (!clean(x)) return false;
    }
    std::memcpy(&x, p + n - 8, 8);
    return clean(x);
  }
  if (n >= 4) {
    uint32_t lo, hi;
    std::memcpy(&lo, p, 4);
    std::memcpy(&hi, p + n - 4, 4);
    return clean(lo | uint64_t{hi} << 32);
  }
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(p[i]);
    if (c < 0x20 || c == '"' || c == '\\') return false;
  }
  return true;
}

}  // namespace

void JsonWriter::flush() {
  if (sink_) {
    std::fwrite(buffer_, 1, size_, sink_);
  } else {
    out_.append(buffer_, size_);
  }
  size_ = 0;
}

void JsonWriter::put(const char* s, size_t n) {
  while (n > 0) {
    const size_t part = std::min(n, kBuffer);
    std::memcpy(room(part), s, part);
    size_ += part;
    s += part;
    n -= part;
  }
}

void JsonWriter::item() {
  if (after_key_) {  // the value of a member: on the key's line
    after_key_ = false;
    return;
  }
  if (items_.empty()) return;  // the document itself
  if (items_.back()++ > 0) put(',');
  new_line();
}

// A new line and an indent of 30 spaces or more (new_line() in the header writes the shorter).
void JsonWriter::long_line(size_t indent) {
  if (indent < kIndent.size) {  // the new line and its indent in one copy
    std::memcpy(room(indent + 1), kIndent.text, indent + 1);
    size_ += indent + 1;
    return;
  }
  put('\n');
  while (indent > 0) {
    const size_t part = std::min(indent, size_t{256});
    std::memset(room(part), ' ', part);
    size_ += part;
    indent -= part;
  }
}

void JsonWriter::open(char bracket) {
  item();
  put(bracket);
  items_.push_back(0);
}

void JsonWriter::close(char bracket) {
  const int items = items_.back();
  items_.pop_back();
  if (items > 0) new_line();
  put(bracket);
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
  if (k.size() + 4 <= kBuffer && plain(k)) {  // `"key": ` in one piece
    char* const out = room(k.size() + 4);
    out[0] = '"';
    std::memcpy(out + 1, k.data(), k.size());
    std::memcpy(out + 1 + k.size(), "\": ", 3);
    size_ += k.size() + 4;
  } else {
    string(k);
    std::memcpy(room(2), ": ", 2);
    size_ += 2;
  }
  after_key_ = true;
}

void JsonWriter::value(double v) {
  item();
  if (!std::isfinite(v)) {
    put("null", 4);
    return;
  }
  char* const buf = room(64);  // written in place: the longest double takes 25 bytes
  char* end = buf;
  if (v == std::trunc(v) && std::abs(v) < 1e15) {
    // A whole number (a planar model's zeros and ones: half its rotations) as nlohmann writes
    // it, its digits and ".0" (-0.0 too), without its conversion: cli.JsonNumbers compares
    // them on millions of values.
    if (std::signbit(v)) *end++ = '-';
    end = std::to_chars(end, buf + 64, static_cast<long long>(std::abs(v))).ptr;
    *end++ = '.';
    *end++ = '0';
  } else {
    // nlohmann's own conversion (Grisu2): its digits are not always the shortest (std::to_chars
    // writes 1.542053954523393 where it writes 1.5420539545233929), and the documents must not
    // change by a digit.
    end = nlohmann::detail::to_chars(buf, buf + 64, v);
  }
  size_ += static_cast<size_t>(end - buf);
}

void JsonWriter::value(int v) {
  item();
  char* const buf = room(16);
  size_ += static_cast<size_t>(std::to_chars(buf, buf + 16, v).ptr - buf);
}

void JsonWriter::value(bool v) {
  item();
  if (v) {
    put("true", 4);
  } else {
    put("false", 5);
  }
}

void JsonWriter::value(std::string_view s) {
  item();
  string(s);
}

// Quotes, backslashes and control characters escaped (\b \t \n \f \r, else \u00xx), everything
// else as it is: the engine's strings are UTF-8 (names are ASCII, labels are checked).
void JsonWriter::string(std::string_view s) {
  static const char kHex[] = "0123456789abcdef";
  const auto plain_byte = [](char ch) {
    const unsigned char c = static_cast<unsigned char>(ch);
    return c >= 0x20 && c != '"' && c != '\\';
  };
  if (s.size() + 2 <= kBuffer && plain(s)) {
    char* const out = room(s.size() + 2);  // a name or a key: nothing to escape
    out[0] = '"';
    std::memcpy(out + 1, s.data(), s.size());
    out[s.size() + 1] = '"';
    size_ += s.size() + 2;
    return;
  }
  put('"');
  size_t plain = 0;  // start of the run of bytes written as they are
  for (size_t i = 0; i < s.size(); ++i) {
    if (plain_byte(s[i])) continue;
    const unsigned char c = static_cast<unsigned char>(s[i]);
    put(s.data() + plain, i - plain);
    plain = i + 1;
    char* const e = room(6);
    e[0] = '\\';
    size_t n = 2;
    switch (c) {
      case '"':
      case '\\':
        e[1] = static_cast<char>(c);
        break;
      case '\b':
        e[1] = 'b';
        break;
      case '\t':
        e[1] = 't';
        break;
      case '\n':
        e[1] = 'n';
        break;
      case '\f':
        e[1] = 'f';
        break;
      case '\r':
        e[1] = 'r';
        break;
      default:
        e[1] = 'u';
        e[2] = '0';
        e[3] = '0';
        e[4] = kHex[c >> 4];
        e[5] = kHex[c & 15];
        n = 6;
    }
    size_ += n;
  }
  put(s.data() + plain, s.size() - plain);
  put('"');
}

}  // namespace dispcon::cli
