// The lexer walks the text once, keeping its place (line, column) as it goes; tokens are views
// of the text, numbers are read with std::from_chars: no allocation per token.
#include "dispcon/io/dcl_lexer.hpp"

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "dispcon/model/model.hpp"

namespace dispcon {

namespace {

std::string describe_byte(unsigned char c) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%02X", c);
  return buf;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// What each byte can be, looked up once a byte (the lexer's loops test a class, not a chain of
// comparisons): white space, a name's byte (is_name_char), a number's (digits, letters, '.', '_').
enum : unsigned char { kSpace = 1, kDigit = 2, kAlpha = 4, kName = 8, kNumber = 16 };

struct ByteClasses {
  unsigned char of[256] = {};
  ByteClasses() {
    for (const char c : {' ', '\t', '\n', '\r', '\f', '\v'})
      of[static_cast<unsigned char>(c)] = kSpace;
    for (int c = 0; c < 256; ++c) {
      const char ch = static_cast<char>(c);
      const bool digit = ch >= '0' && ch <= '9';
      const bool alpha = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z');
      if (digit) of[c] |= kDigit;
      if (alpha) of[c] |= kAlpha;
      if (is_name_char(ch)) of[c] |= kName;
      if (digit || alpha || ch == '.' || ch == '_') of[c] |= kNumber;
    }
  }
};
const ByteClasses kBytes;

bool is(char c, unsigned char what) {
  return (kBytes.of[static_cast<unsigned char>(c)] & what) != 0;
}

bool is_digit(char c) {
  return is(c, kDigit);
}

bool is_alpha(char c) {
  return is(c, kAlpha);
}

}  // namespace

Token DclLexer::next() {
  Token t;
  while (skip_space_and_comments()) {
    t.line = line_;
    t.column = column_;
    const char c = text_[i_];
    const char next = i_ + 1 < text_.size() ? text_[i_ + 1] : '\0';
    const bool sign = c == '-' || c == '+';
    if (c == ';') {
      t.kind = Token::Semicolon;
      t.text = text_.substr(i_, 1);
      take(1);
    } else if (is_digit(c) || c == '.' ||
               (sign && (is_digit(next) || next == '.' || next == 'i'))) {
      number(t);
    } else if (c == '"') {
      string(t);
    } else if (is_alpha(c)) {
      size_t j = i_;
      while (j < text_.size() && is(text_[j], kName)) ++j;
      t.kind = Token::Word;
      t.text = text_.substr(i_, j - i_);
      take(j - i_);
    } else {
      // Reported and left out: the statement around it reads on as if it were not there.
      const unsigned char b = static_cast<unsigned char>(c);
      if (b < 0x20 || b >= 0x7f) {
        error("byte " + describe_byte(b) + " is not text");
      } else {
        error(std::string("unexpected character '") + c + "'");
      }
      take(1);
      continue;
    }
    return t;
  }
  t.kind = Token::End;
  t.line = line_;
  t.column = column_;
  return t;
}

// Moves past `n` bytes that hold no new line (a token's).
void DclLexer::take(size_t n) {
  i_ += n;
  column_ += static_cast<int>(n);
}

// Moves past one byte, which may be a new line.
void DclLexer::step() {
  if (text_[i_++] == '\n') {
    ++line_;
    column_ = 1;
  } else {
    ++column_;
  }
}

void DclLexer::error(std::string message) {
  errors_.add({line_, column_, std::move(message)});
}

// Skips white space and comments; false at the end of the text. Runs of blanks are the bulk of
// a file: they are walked with the place kept in locals.
bool DclLexer::skip_space_and_comments() {
  while (i_ < text_.size()) {
    const char c = text_[i_];
    if (is(c, kSpace)) {
      const char* p = text_.data() + i_;
      const char* const end = text_.data() + text_.size();
      int line = line_, column = column_;
      for (; p < end && is(*p, kSpace); ++p) {
        if (*p == '\n') {
          ++line;
          column = 1;
        } else {
          ++column;
        }
      }
      i_ = static_cast<size_t>(p - text_.data());
      line_ = line;
      column_ = column;
    } else if (c == '/' && i_ + 1 < text_.size() && text_[i_ + 1] == '/') {
      const size_t eol = text_.find('\n', i_);
      take((eol == std::string_view::npos ? text_.size() : eol) - i_);
    } else if (c == '/' && i_ + 1 < text_.size() && text_[i_ + 1] == '*') {
      const int l0 = line_, c0 = column_;
      take(2);
      while (i_ < text_.size() &&
             !(text_[i_] == '*' && i_ + 1 < text_.size() && text_[i_ + 1] == '/')) {
        const unsigned char b = static_cast<unsigned char>(text_[i_]);
        if (b == 0 || (b < 0x20 && b != '\n' && b != '\r' && b != '\t')) {
          error("byte " + describe_byte(b) + " is not text");
        }
        step();
      }
      if (i_ >= text_.size()) {
        errors_.add({l0, c0, "comment '/*' is never closed with '*/'"});
        return false;
      }
      take(2);
    } else {
      return true;
    }
  }
  return false;
}

// A number: a sign, then letters, digits, '.', '_' and exponent signs, read as one token so
// that "1.5x" is one malformed number, not a number and a word.
void DclLexer::number(Token& t) {
  const bool sign = text_[i_] == '-' || text_[i_] == '+';
  size_t j = sign ? i_ + 1 : i_;
  while (j < text_.size()) {
    const char ch = text_[j];
    if (!is(ch, kNumber) &&
        !((ch == '-' || ch == '+') && (text_[j - 1] == 'e' || text_[j - 1] == 'E')))
      break;
    ++j;
  }
  t.text = text_.substr(i_, j - i_);
  if (parse_number(t.text, t.value)) {
    t.kind = Token::Number;
  } else {
    t.kind = Token::Bad;
    errors_.add({t.line, t.column, "malformed number '" + std::string(t.text) + "'"});
  }
  take(j - i_);
}

// A string ends at the next unescaped quote on the same line: a lost quote cannot swallow the
// rest of the file. Its value is a view of the text unless it has escapes.
void DclLexer::string(Token& t) {
  t.kind = Token::String;
  take(1);
  const size_t start = i_;
  std::string* decoded = nullptr;  // made at the first escape, holding what came before
  auto copy = [&] {
    if (!decoded) decoded = &decoded_.emplace_front(text_.substr(start, i_ - start));
  };
  bool closed = false, bad = false;
  while (i_ < text_.size() && text_[i_] != '\n') {
    const unsigned char b = static_cast<unsigned char>(text_[i_]);
    if (b == '"') {
      closed = true;
      break;
    }
    if (b == '\\') {
      copy();
      const char e = i_ + 1 < text_.size() ? text_[i_ + 1] : '\0';
      const int h1 = i_ + 2 < text_.size() ? hex_digit(text_[i_ + 2]) : -1;
      const int h2 = i_ + 3 < text_.size() ? hex_digit(text_[i_ + 3]) : -1;
      if (e == '\\' || e == '"') {
        *decoded += e;
      } else if (e == 'n' || e == 't' || e == 'r') {
        *decoded += e == 'n' ? '\n' : e == 't' ? '\t' : '\r';
      } else if (e == 'x' && h1 >= 0 && h2 >= 0) {
        *decoded += static_cast<char>(h1 * 16 + h2);
        take(4);
        continue;
      } else {
        error("unknown escape in a string (use \\\\, \\\", \\n, \\t, \\r or \\xHH)");
        bad = true;
        if (e == '\n' || e == '\0') {  // a backslash ending the line escapes nothing
          take(1);
          continue;
        }
      }
      take(2);
      continue;
    }
    if ((b < 0x20 && b != '\t') || b == 0x7f) {
      error("byte " + describe_byte(b) + " in a string: write it as \\xHH");
      bad = true;
      copy();  // left out of the value, which a view of the text would hold
    } else if (decoded) {
      *decoded += static_cast<char>(b);
    }
    take(1);
  }
  t.text = decoded ? std::string_view(*decoded) : text_.substr(start, i_ - start);
  if (closed) {
    take(1);
  } else {
    errors_.add({t.line, t.column, "string is not closed with '\"' on its line"});
    bad = true;
  }
  if (bad) t.kind = Token::Bad;
}

void LexErrors::add(LexError e) {
  if (listed.size() < static_cast<size_t>(kErrorCap)) {
    listed.push_back(std::move(e));
  } else {
    ++more;
  }
}

bool parse_number(std::string_view text, double& value) {
  std::string_view body = text;
  const bool negative = !body.empty() && body[0] == '-';
  if (!body.empty() && (body[0] == '-' || body[0] == '+')) body.remove_prefix(1);
  if (body == "inf") {
    value = negative ? -std::numeric_limits<double>::infinity()
                     : std::numeric_limits<double>::infinity();
    return true;
  }
  // strtod's syntax, which the format names, would also take hexadecimal, nan and infinity.
  if (body.empty() || body[0] == '-' || body[0] == '+') return false;
  for (const char c : body) {
    if (c == 'x' || c == 'X' || c == 'n' || c == 'N') return false;
  }
  double v = 0;
  const char* last = body.data() + body.size();
  const std::from_chars_result r = std::from_chars(body.data(), last, v);
  if (r.ptr != last || r.ec == std::errc::invalid_argument) return false;
  if (r.ec == std::errc::result_out_of_range) {
    // Beyond a double's range from_chars gives no value; strtod's (+-inf, or the nearest
    // subnormal or zero) is what these numbers have always been read as.
    const std::string copy(body);
    v = std::strtod(copy.c_str(), nullptr);
  }
  value = negative ? -v : v;
  return true;
}

std::string quote_string(std::string_view value) {
  std::string out = "\"";
  for (const char ch : value) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

Tokens lex_dcl(std::string_view text, LexErrors& errors) {
  Tokens out;
  DclLexer lexer(text, errors);
  do {
    out.list.push_back(lexer.next());
  } while (out.list.back().kind != Token::End);
  out.decoded = std::move(lexer).decoded();
  return out;
}

}  // namespace dispcon
