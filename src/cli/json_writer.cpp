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

// Doubles as nlohmann::detail::to_chars writes them, digit for digit: its Grisu2 (the same
// products, boundaries and digit loop, so the same digits, which are not always the shortest),
// with less work a number than its own code (9,200 numbers in the 400 four-bars' document, about
// 580 instructions each there): the normalisations by a count of leading zeros instead of a shift
// a bit at a time, the products of 64-bit significands as one 128-bit product (rounded as
// nlohmann rounds them: the top 64 bits of the product plus 2^63), the integral part's digits
// without a division each when its loop cannot stop early, and the layout written from the digits
// without moving them. cli.JsonNumbers compares it with nlohmann on millions of doubles of every
// magnitude and bit pattern.
namespace grisu {

namespace dtoa = nlohmann::detail::dtoa_impl;

// (x * y + 2^63) div 2^64: nlohmann's diyfp::mul (its four partial products sum to the same).
inline std::uint64_t mul(std::uint64_t x, std::uint64_t y) {
  const unsigned __int128 p = static_cast<unsigned __int128>(x) * y;
  return static_cast<std::uint64_t>((p + (static_cast<unsigned __int128>(1) << 63)) >> 64);
}

// Two decimal digits of 0..99 at a time.
constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// The k digits of n (10^(k-1) <= n < 10^k), two at a time from the end.
inline void write_digits(char* out, std::uint32_t n, int k) {
  char* p = out + k;
  while (n >= 100) {
    const std::uint32_t r = n % 100;
    n /= 100;
    p -= 2;
    std::memcpy(p, kPairs + 2 * r, 2);
  }
  if (n >= 10) {
    p -= 2;
    std::memcpy(p, kPairs + 2 * n, 2);
  } else {
    *--p = static_cast<char>('0' + n);
  }
}

constexpr std::uint64_t kPow10[] = {1,
                                    10,
                                    100,
                                    1000,
                                    10000,
                                    100000,
                                    1000000,
                                    10000000,
                                    100000000,
                                    1000000000,
                                    10000000000,
                                    100000000000,
                                    1000000000000,
                                    10000000000000,
                                    100000000000000,
                                    1000000000000000,
                                    10000000000000000,
                                    100000000000000000,
                                    1000000000000000000,
                                    10000000000000000000u};

// grisu2_round: the last digit moved toward w while that stays within the bounds and nearer.
inline void round(char* buf, int len, std::uint64_t dist, std::uint64_t delta, std::uint64_t rest,
                  std::uint64_t ten_k) {
  while (rest < dist && delta - rest >= ten_k &&
         (rest + ten_k < dist || dist - rest > rest + ten_k - dist)) {
    buf[len - 1]--;
    rest += ten_k;
  }
}

// The digits of v > 0 (finite) into buf, their count in len and v = buf * 10^exponent.
inline void digits(double v, char* buf, int& len, int& exponent) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  const std::uint64_t E = bits >> 52, F = bits & ((std::uint64_t{1} << 52) - 1);
  // v = f 2^e, and the bounds m- and m+ half-way to its neighbours (compute_boundaries).
  const std::uint64_t f = E == 0 ? F : F + (std::uint64_t{1} << 52);
  const int e = E == 0 ? -1074 : static_cast<int>(E) - 1075;
  const bool lower_closer = F == 0 && E > 1;
  const std::uint64_t plus = 2 * f + 1;
  const int shift_plus = __builtin_clzll(plus);
  const int e_plus = e - 1 - shift_plus;  // every value below shares this exponent
  const std::uint64_t m_plus = plus << shift_plus;
  const std::uint64_t m_minus =
      lower_closer ? (4 * f - 1) << (e - 2 - e_plus) : (2 * f - 1) << (e - 1 - e_plus);
  const std::uint64_t w0 = f << __builtin_clzll(f);
  // Scaled by the cached power c ~ 10^-k into the exponent range [-60, -32] (grisu2).
  const dtoa::cached_power c = dtoa::get_cached_power_for_binary_exponent(e_plus);
  const std::uint64_t w = mul(w0, c.f);
  const std::uint64_t M_minus = mul(m_minus, c.f) + 1;
  const std::uint64_t M_plus = mul(m_plus, c.f) - 1;
  exponent = -c.k;
  // grisu2_digit_gen.
  const int s = -(e_plus + c.e + 64);
  const std::uint64_t one = std::uint64_t{1} << s;
  std::uint64_t delta = M_plus - M_minus;
  std::uint64_t dist = M_plus - w;
  std::uint32_t p1 = static_cast<std::uint32_t>(M_plus >> s);
  std::uint64_t p2 = M_plus & (one - 1);
  std::uint32_t pow10 = 0;
  const int k = dtoa::find_largest_pow10(p1, pow10);
  len = 0;
  if (p2 > delta) {
    // The integral part's loop stops only where its rest, (p1 mod 10^n) 2^s + p2, is within
    // delta: never, when p2 is not. All k digits then, without a division each.
    write_digits(buf, p1, k);
    len = k;
  } else {
    for (int n = k; n > 0;) {
      const std::uint32_t d = p1 / pow10;
      p1 %= pow10;
      buf[len++] = static_cast<char>('0' + d);
      --n;
      const std::uint64_t rest = (std::uint64_t{p1} << s) + p2;
      if (rest <= delta) {
        exponent += n;
        round(buf, len, dist, delta, rest, std::uint64_t{pow10} << s);
        return;
      }
      pow10 /= 10;
    }
  }
  if (delta < one) {
    // The loop below with less in it: it stops by the time delta 10^m reaches 2^s (p2 is below
    // that), after at most 19 digits, so dist 10^m (dist <= delta) is taken once at the end.
    char* const first = buf + len;
    char* p = first;
    do {
      p2 *= 10;
      *p++ = static_cast<char>('0' + (p2 >> s));
      p2 &= one - 1;
      delta *= 10;
    } while (p2 > delta);
    const int m = static_cast<int>(p - first);
    len += m;
    exponent -= m;
    return round(buf, len, dist * kPow10[m], delta, p2, one);
  }
  int m = 0;  // where delta 10^m may wrap (subnormals), nlohmann's loop as it is
  for (;;) {
    p2 *= 10;
    buf[len++] = static_cast<char>('0' + (p2 >> s));
    p2 &= one - 1;
    ++m;
    delta *= 10;
    dist *= 10;
    if (p2 <= delta) break;
  }
  exponent -= m;
  round(buf, len, dist, delta, p2, one);
}

// v > 0 (finite) as nlohmann::detail::to_chars writes it, at `out`, with 40 bytes of room there;
// returns the end. format_buffer's layouts, written from the digits where they are: fixed point
// from 1e-4 up to 1e15, else d.ddde+XX. (The sign, and zero, are JsonWriter::value's.)
char* write(char* out, double v) {
  char d[40];  // the digits (at most 17), and room to copy them in blocks of 16 or 17
  int k = 0, exponent = 0;
  digits(v, d, k, exponent);
  const int n = k + exponent;  // the decimal point's place after the first digit
  if (k <= n && n <= 15) {     // digits, zeros, ".0"
    std::memcpy(out, d, 17);
    std::memset(out + k, '0', static_cast<size_t>(n - k));
    std::memcpy(out + n, ".0", 2);
    return out + n + 2;
  }
  if (0 < n && n <= 15) {  // digits with the point among them
    std::memcpy(out, d, 16);
    out[n] = '.';
    std::memcpy(out + n + 1, d + n, 16);
    return out + k + 1;
  }
  if (-4 < n && n <= 0) {  // 0.000digits
    std::memcpy(out, "0.0000", 6);
    std::memcpy(out + 2 - n, d, 17);
    return out + 2 - n + k;
  }
  out[0] = d[0];
  if (k == 1) {
    ++out;
  } else {
    out[1] = '.';
    std::memcpy(out + 2, d + 1, 16);
    out += 1 + k;
  }
  *out++ = 'e';
  return dtoa::append_exponent(out, n - 1);
}

}  // namespace grisu

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

void JsonWriter::next_item() {
  if (items_.empty()) return;  // the document itself
  const size_t comma = items_.back()++ > 0 ? 1 : 0;
  const size_t indent = 2 * items_.size();
  if (indent + 1 >= kShortLine) {
    if (comma) put(',');
    return long_line(indent);
  }
  // The comma (written, and kept only when there is one), the new line and the indent in one
  // room and one copy of fixed size (new_line()'s).
  char* const out = room(kShortLine + 1);
  *out = ',';
  std::memcpy(out + comma, kShortLineText, kShortLine);
  size_ += comma + indent + 1;
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
  if (k.size() + 4 <= kBuffer && plain(k)) return plain_key(k);
  item();
  string(k);
  std::memcpy(room(2), ": ", 2);
  size_ += 2;
  after_key_ = true;
}

void JsonWriter::plain_key(std::string_view k) {
  item();
  char* const out = room(k.size() + 4);  // `"key": ` in one piece
  out[0] = '"';
  std::memcpy(out + 1, k.data(), k.size());
  std::memcpy(out + 1 + k.size(), "\": ", 3);
  size_ += k.size() + 4;
  after_key_ = true;
}

// The text of v at `out`, with 64 bytes of room there (the longest double takes 25; the
// conversion writes scratch bytes past its end); returns the end.
inline char* JsonWriter::number_text(char* out, double v) {
  if (!std::isfinite(v)) {
    std::memcpy(out, "null", 4);
    return out + 4;
  }
  if (std::signbit(v)) *out++ = '-';  // -0.0 too, as nlohmann writes it
  const double a = std::abs(v);
  if (a == 0) {  // half a planar model's rotations
    std::memcpy(out, "0.0", 3);
    return out + 3;
  }
  if (a < 1e15 && static_cast<double>(static_cast<long long>(a)) == a) {
    // A whole number (a planar model's zeros and ones: half its rotations) as nlohmann writes
    // it, its digits and ".0", without its conversion: cli.JsonNumbers compares them on
    // millions of values.
    out = std::to_chars(out, out + 32, static_cast<long long>(a)).ptr;
    std::memcpy(out, ".0", 2);
    return out + 2;
  }
  // nlohmann's conversion (Grisu2, above): its digits are not always the shortest
  // (std::to_chars writes 1.542053954523393 where it writes 1.5420539545233929), and the
  // documents must not change by a digit. Through the memo of the last numbers converted.
  std::uint64_t bits;
  std::memcpy(&bits, &a, sizeof bits);
  Memo& m = memo_[(bits * 0x9E3779B97F4A7C15u) >> (64 - kMemoBits)];
  if (m.bits == bits) {
    std::memcpy(out, m.text, 24);  // the text and its size byte: room is there, size_ says
    return out + m.size;
  }
  char* const end = grisu::write(out, a);
  m.bits = bits;
  m.size = static_cast<std::uint8_t>(end - out);
  std::memcpy(m.text, out, sizeof m.text);
  return end;
}

void JsonWriter::value(double v) {
  item();
  char* const out = room(64);
  size_ += static_cast<size_t>(number_text(out, v) - out);
}

void JsonWriter::numbers(const double* v, size_t n) {
  const size_t indent = 2 * (items_.size() + 1);  // the numbers' own
  if (n == 0 || indent + 1 >= kShortLine) {
    begin_array();
    for (size_t i = 0; i < n; ++i) value(v[i]);
    return end_array();
  }
  open('[');  // its item() before the array, its count of items below
  items_.back() = static_cast<int>(n);
  for (size_t i = 0; i < n; ++i) {
    // The comma (kept only after the first), the new line and the indent, as item() writes them,
    // then the number, in one room.
    char* const out = room(kShortLine + 1 + 64);
    const size_t comma = i > 0 ? 1 : 0;
    *out = ',';
    std::memcpy(out + comma, kShortLineText, kShortLine);
    size_ += static_cast<size_t>(number_text(out + comma + indent + 1, v[i]) - out);
  }
  close(']');
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
