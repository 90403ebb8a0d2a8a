// The lexer walks the text once, keeping its place (line, column) as it goes; tokens are views
// of the text, numbers are read with std::from_chars: no allocation per token.
#include "dispcon/io/dcl_lexer.hpp"

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

// m / 10^after for 2^53 < m < 2^64, where doubles lose m's last digits: in the x87's 64-bit
// significand (long double on x86) both are still exact, so the division rounds once to 64 bits;
// rounding that to a double gives the correctly rounded value too, unless the quotient fell
// exactly half-way between two doubles (11 bits below a double's last: 100 0000 0000), where a
// second rounding may go the wrong way: those, and every number where long double is not the
// x87's, are left to from_chars. (Half-way points are 64-bit numbers: a quotient on either side
// of one rounds to that side or onto it, never across.)
bool wide_decimal(std::uint64_t m, int after, double& value) {
  if constexpr (std::numeric_limits<long double>::digits != 64) {
    return false;
  } else {
    static constexpr long double kPowers[] = {
        1e0L,  1e1L,  1e2L,  1e3L,  1e4L,  1e5L,  1e6L,  1e7L,  1e8L,  1e9L,  1e10L, 1e11L,
        1e12L, 1e13L, 1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L, 1e20L, 1e21L, 1e22L};
    const long double q = static_cast<long double>(m) / kPowers[after];
    std::uint64_t significand = 0;  // the low 8 bytes of the x87 format
    std::memcpy(&significand, &q, sizeof significand);
    if ((significand & 0x7FF) == 0x400) return false;
    value = static_cast<double>(q);
    return true;
  }
}

// Most numbers of a file are short decimals ("0", "1", "2.5", "0.7648421872844885"): digits with
// at most one '.', whose digits as a whole number m fit in a double (m <= 2^53) and with at most
// 22 of them after the point. Their value m / 10^k is then one correctly rounded division of two
// exact doubles, the very double std::from_chars gives (Clinger's fast path), at a fraction of
// its cost; up to 19 digits (a double's 17 significant digits as the writer writes them:
// "0.69999999999999996"), wide_decimal. `digits` counts them all (beyond 19, m may have
// wrapped); false when neither applies (from_chars reads the number).
bool exact_decimal(std::uint64_t m, int digits, int after, double& value) {
  static constexpr double kPowers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  if (digits == 0 || digits > 19 || after > 22) return false;
  if (m > (std::uint64_t{1} << 53)) return wide_decimal(m, after, value);
  value = static_cast<double>(m) / kPowers[after];
  return true;
}

// Whether the eight bytes at p are all digits, and if so their number: each byte's high nibble
// is 3 and adding 6 leaves it 3 only for '0' to '9'; then the digits summed in pairs, fours and
// eights by three multiplications (the bytes in memory order, the first the most significant).
bool eight_digits(const char* p, std::uint64_t& v) {
  std::uint64_t x;
  std::memcpy(&x, p, sizeof x);
  if (((x & 0xF0F0F0F0F0F0F0F0) | (((x + 0x0606060606060606) & 0xF0F0F0F0F0F0F0F0) >> 4)) !=
      0x3333333333333333)
    return false;
  x = (x & 0x0F0F0F0F0F0F0F0F) * 2561 >> 8;
  x = (x & 0x00FF00FF00FF00FF) * 6553601 >> 16;
  v = (x & 0x0000FFFF0000FFFF) * 42949672960001 >> 32;
  return true;
}

// The digits of `p`..`end` with at most one point, as far as they go: their whole number, their
// count and how many follow the point. Returns where they stop. The digits after a point, the
// bulk of a file's long numbers ("0.7648421872844885"), eight at a time while eight come: m
// gets the same value (modulo 2^64, as digit by digit past 19 digits).
const char* scan_decimal(const char* p, const char* end, std::uint64_t& m, int& digits,
                         int& after) {
  m = 0;
  digits = 0;
  int point = -1;  // the count of digits before the point, if any
  for (; p < end; ++p) {
    const unsigned d = static_cast<unsigned>(static_cast<unsigned char>(*p)) - '0';
    if (d < 10) {
      m = 10 * m + d;
      ++digits;
    } else if (*p == '.' && point < 0) {
      point = digits;
      std::uint64_t eight = 0;
      while (end - p > 8 && eight_digits(p + 1, eight)) {
        m = 100000000 * m + eight;
        digits += 8;
        p += 8;
      }
    } else {
      break;
    }
  }
  after = point < 0 ? 0 : digits - point;
  return p;
}

bool fast_decimal(std::string_view body, double& value) {
  std::uint64_t m = 0;
  int digits = 0, after = 0;
  const char* end = body.data() + body.size();
  return scan_decimal(body.data(), end, m, digits, after) == end &&
         exact_decimal(m, digits, after, value);
}

}  // namespace

// Blanks are the bulk of a file between tokens: walked here, with the place in locals; comments
// out of line.
void DclLexer::next(Token& t) {
  for (;;) {
    const char* p = p_;
    if (p < end_ && is(*p, kSpace)) {
      const char* line_start = line_start_;
      int line = line_;
      do {
        if (*p++ == '\n') {
          ++line;
          line_start = p;
        }
      } while (p < end_ && is(*p, kSpace));
      p_ = p;
      line_start_ = line_start;
      line_ = line;
    }
    if (p == end_) break;
    const char c = *p;
    if (c == '/' && p + 1 < end_ && (p[1] == '/' || p[1] == '*')) {
      if (!comment()) break;
      continue;
    }
    t.line = line_;
    t.column = column();
    t.value = 0;
    if (c == ';') {
      t.kind = Token::Semicolon;
      t.text = std::string_view(p_, 1);
      ++p_;
    } else if (is_digit(c) && !(p + 1 < end_ && is(p[1], kNumber))) {
      // A lone digit ("0", "1": 18,800 of the 22,800 numbers of the 400 four-bars), read here
      // as number() reads it: the call and its walks cost more than the rest of the token.
      t.kind = Token::Number;
      t.text = std::string_view(p, 1);
      t.value = c - '0';
      p_ = p + 1;
    } else if (is_alpha(c)) {
      const char* q = p_ + 1;
      while (q < end_ && is(*q, kName)) ++q;
      t.kind = Token::Word;
      t.text = std::string_view(p_, static_cast<size_t>(q - p_));
      p_ = q;
    } else if (is_digit(c) || c == '.' ||
               ((c == '-' || c == '+') && p_ + 1 < end_ &&
                (is_digit(p_[1]) || p_[1] == '.' || p_[1] == 'i'))) {
      number(t);
    } else if (c == '"') {
      string(t);
    } else {
      // Reported and left out: the statement around it reads on as if it were not there.
      stray(c);
      ++p_;
      continue;
    }
    return;
  }
  t.kind = Token::End;
  t.text = {};
  t.value = 0;
  t.line = line_;
  t.column = column();
}

void DclLexer::stray(char c) {
  const unsigned char b = static_cast<unsigned char>(c);
  if (b < 0x20 || b >= 0x7f) {
    error("byte " + describe_byte(b) + " is not text");
  } else {
    error(std::string("unexpected character '") + c + "'");
  }
}

void DclLexer::malformed(const Token& t) {
  errors_.add({t.line, t.column, "malformed number '" + std::string(t.text) + "'"});
}

// Moves past one byte, which may be a new line.
void DclLexer::step() {
  if (*p_++ == '\n') {
    ++line_;
    line_start_ = p_;
  }
}

void DclLexer::error(std::string message) {
  errors_.add({line_, column(), std::move(message)});
}

// A line comment ends before its new line (read as a blank); a block comment after its "*/".
bool DclLexer::comment() {
  if (p_[1] == '/') {
    const void* eol = std::memchr(p_, '\n', static_cast<size_t>(end_ - p_));
    p_ = eol ? static_cast<const char*>(eol) : end_;
    return true;
  }
  const int l0 = line_, c0 = column();
  p_ += 2;
  while (p_ < end_ && !(*p_ == '*' && p_ + 1 < end_ && p_[1] == '/')) {
    const unsigned char b = static_cast<unsigned char>(*p_);
    if (b == 0 || (b < 0x20 && b != '\n' && b != '\r' && b != '\t')) {
      error("byte " + describe_byte(b) + " is not text");
    }
    step();
  }
  if (p_ >= end_) {
    errors_.add({l0, c0, "comment '/*' is never closed with '*/'"});
    return false;
  }
  p_ += 2;
  return true;
}

// A number: a sign, then letters, digits, '.', '_' and exponent signs, read as one token so
// that "1.5x" is one malformed number, not a number and a word.
void DclLexer::number(Token& t) {
  const bool negative = *p_ == '-';
  // The plain decimal it most often is, read on the way (parse_number's fast path, one walk).
  std::uint64_t m = 0;
  int digits = 0, after = 0;
  const char* const plain =
      scan_decimal(*p_ == '-' || *p_ == '+' ? p_ + 1 : p_, end_, m, digits, after);
  const char* q = plain;
  while (q < end_) {
    const char ch = *q;
    if (!is(ch, kNumber) && !((ch == '-' || ch == '+') && (q[-1] == 'e' || q[-1] == 'E'))) break;
    ++q;
  }
  t.text = std::string_view(p_, static_cast<size_t>(q - p_));
  if (q == plain && exact_decimal(m, digits, after, t.value)) {
    if (negative) t.value = -t.value;
    t.kind = Token::Number;
  } else if (parse_number(t.text, t.value)) {
    t.kind = Token::Number;
  } else {
    t.kind = Token::Bad;
    malformed(t);
  }
  p_ = q;
}

// A string ends at the next unescaped quote on the same line: a lost quote cannot swallow the
// rest of the file. Its value is a view of the text unless it has escapes. Nothing in it moves
// past a new line but step().
void DclLexer::string(Token& t) {
  t.kind = Token::String;
  ++p_;
  const char* const start = p_;
  std::string* decoded = nullptr;  // made at the first escape, holding what came before
  auto copy = [&] {
    if (!decoded) decoded = &decoded_.emplace_front(start, static_cast<size_t>(p_ - start));
  };
  bool closed = false, bad = false;
  while (p_ < end_ && *p_ != '\n') {
    const unsigned char b = static_cast<unsigned char>(*p_);
    if (b == '"') {
      closed = true;
      break;
    }
    if (b == '\\') {
      copy();
      const char e = p_ + 1 < end_ ? p_[1] : '\0';
      const int h1 = p_ + 2 < end_ ? hex_digit(p_[2]) : -1;
      const int h2 = p_ + 3 < end_ ? hex_digit(p_[3]) : -1;
      if (e == '\\' || e == '"') {
        *decoded += e;
      } else if (e == 'n' || e == 't' || e == 'r') {
        *decoded += e == 'n' ? '\n' : e == 't' ? '\t' : '\r';
      } else if (e == 'x' && h1 >= 0 && h2 >= 0) {
        *decoded += static_cast<char>(h1 * 16 + h2);
        p_ += 4;
        continue;
      } else {
        error("unknown escape in a string (use \\\\, \\\", \\n, \\t, \\r or \\xHH)");
        bad = true;
        if (e == '\n' || e == '\0') {  // a backslash ending the line escapes nothing
          ++p_;
          continue;
        }
      }
      p_ += 2;
      continue;
    }
    if ((b < 0x20 && b != '\t') || b == 0x7f) {
      error("byte " + describe_byte(b) + " in a string: write it as \\xHH");
      bad = true;
      copy();  // left out of the value, which a view of the text would hold
    } else if (decoded) {
      *decoded += static_cast<char>(b);
    }
    ++p_;
  }
  t.text = decoded ? std::string_view(*decoded)
                   : std::string_view(start, static_cast<size_t>(p_ - start));
  if (closed) {
    ++p_;
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
  if (fast_decimal(body, value)) {
    if (negative) value = -value;
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
  Token t;
  do {
    lexer.next(t);
    out.list.push_back(t);
  } while (t.kind != Token::End);
  out.decoded = std::move(lexer).decoded();
  return out;
}

}  // namespace dispcon
