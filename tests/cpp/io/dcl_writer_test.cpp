// Names and labels: whatever the model accepts, the writer writes so that reading it back gives
// the same model (a property over arbitrary strings), and what the format cannot hold the model
// refuses.
#include "dispcon/io/dcl_writer.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "dispcon/io/dcl_lexer.hpp"
#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/model/joint_kinds.hpp"

namespace dispcon {
namespace {

// Strings a hostile user or a FreeCAD label might hold: the format's own punctuation, escapes,
// new lines, UTF-8 (valid or cut short) and any byte at all.
std::string arbitrary(std::mt19937& rng) {
  static const char* pieces[] = {
      "\n",   "\"", "\\",         ";",        "end",  "object evil; fixed;",
      "//",   "/*", "*/",         "\\x41",    "\\n",  "\r\n",
      "\t",   " ",  "é",          "→",        "🙂", "\xE2\x82",
      "\xFF", "\0", "constraint", "label \"", "a",    "Z9_.-"};
  std::uniform_int_distribution<int> length(0, 12);
  std::uniform_int_distribution<int> which(0, static_cast<int>(std::size(pieces)));
  std::uniform_int_distribution<int> byte(0, 255);
  std::string s;
  for (int n = length(rng); n > 0; --n) {
    const int k = which(rng);
    if (k == static_cast<int>(std::size(pieces))) {
      s += static_cast<char>(byte(rng));
    } else if (pieces[k][0] == '\0') {
      s += '\0';
    } else {
      s += pieces[k];
    }
  }
  return s;
}

Model pendulum(const std::string& body_name) {
  Model m;
  Body b;
  b.name = body_name;
  b.pose.x = Vec3(0.5, 0, 0);
  const BodyId id = m.add_body(b);
  m.add_joint(revolute(Model::kWorld, Anchor{}, id, Anchor{}));
  return m;
}

TEST(DclWriter, LabelsRoundTripWhateverTheyHold) {
  std::mt19937 rng(13);
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::string label = arbitrary(rng);
    Model m = pendulum("bar");
    Joint j = ball(Model::kWorld, Anchor{}, BodyId{1}, Anchor{});
    j.label = label;
    try {
      m.add_joint(j);
    } catch (const JointError& e) {
      // Only labels that are not UTF-8 are refused (Python and FreeCAD hold UTF-8 text).
      EXPECT_EQ(e.keyword(), "label") << e.what();
      ++refused;
      continue;
    }
    ++accepted;
    const std::string text = write_dcl(m);
    const ParseResult back = parse_dcl(text, "written.dcl");
    ASSERT_TRUE(back.ok()) << back.messages() << text;
    ASSERT_EQ(back.model->joint_count(), 2) << text;
    ASSERT_EQ(back.model->body_count(), 2) << text;
    EXPECT_EQ(back.model->joint(JointId{1}).label, label) << text;
    EXPECT_EQ(write_dcl(*back.model), text);
  }
  EXPECT_GT(accepted, 1000);
  EXPECT_GT(refused, 100);
}

TEST(DclWriter, NamesAreRefusedOrRoundTrip) {
  std::mt19937 rng(11);
  int accepted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::string name = arbitrary(rng);
    Model m;
    try {
      m = pendulum(name);
    } catch (const std::invalid_argument&) {
      EXPECT_FALSE(is_valid_name(name) && name != "world") << name;
      continue;
    }
    ++accepted;
    EXPECT_TRUE(is_valid_name(name));
    const ParseResult back = parse_dcl(write_dcl(m));
    ASSERT_TRUE(back.ok()) << back.messages();
    ASSERT_EQ(back.model->body_count(), 2);
    EXPECT_EQ(back.model->body(BodyId{1}).name, name);
  }
  EXPECT_GT(accepted, 30);
}

TEST(DclWriter, TheIssuesLabelStaysALabel) {
  Model m = pendulum("y");
  Joint j = ball(Model::kWorld, Anchor{}, BodyId{1}, Anchor{});
  j.label = "Joint\nobject evil; fixed; end";
  m.add_joint(j);
  const std::string text = write_dcl(m);
  EXPECT_NE(text.find(R"(label "Joint\nobject evil; fixed; end";)"), std::string::npos) << text;
  const ParseResult back = parse_dcl(text);
  ASSERT_TRUE(back.ok()) << back.messages();
  EXPECT_EQ(back.model->body_count(), 2);  // no body 'evil'
  EXPECT_FALSE(back.model->find("evil"));
}

TEST(DclWriter, NamesTheFormatCannotHoldAreRefusedWithTheRule) {
  Model m;
  Body b;
  b.name = "y; fixed";
  try {
    m.add_body(b);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'y; fixed' cannot be written in a .dcl file"),
              std::string::npos)
        << e.what();
  }
  for (const char* bad : {"", "1a", "-a", "a b", "a\n", "é", "a\"", "_a"}) {
    b.name = bad;
    EXPECT_THROW(m.add_body(b), std::invalid_argument) << bad;
  }
  for (const char* good : {"a", "A-1", "link_2.b", "inf", "end", "nan"}) {
    b.name = good;
    EXPECT_NO_THROW(m.add_body(b)) << good;
  }
  const ParseResult back = parse_dcl(write_dcl(m));
  ASSERT_TRUE(back.ok()) << back.messages();
  EXPECT_EQ(back.model->body_count(), 7);
}

TEST(DclLexer, StringEscapes) {
  LexErrors errors;
  const Tokens t = lex_dcl(R"("a\"b\\c\n\t\r\x00\x7Fé" "x)", errors);
  ASSERT_GE(t.size(), 2u);
  EXPECT_EQ(t[0].kind, Token::String);
  EXPECT_EQ(t[0].text, std::string("a\"b\\c\n\t\r\0\x7F\xC3\xA9", 12));
  EXPECT_EQ(t[1].kind, Token::Bad);  // never closed
  ASSERT_EQ(errors.listed.size(), 1u);
  EXPECT_EQ(errors.listed[0].column, 27);
  EXPECT_EQ(quote_string(t[0].text), R"("a\"b\\c\n\t\r\x00\x7Fé")");
  // A raw new line ends an unclosed string: the next line is read as usual.
  const Tokens u = lex_dcl("\"abc\nend", errors);
  EXPECT_EQ(u[0].kind, Token::Bad);
  EXPECT_EQ(u[1].kind, Token::Word);
  EXPECT_EQ(u[1].text, "end");
  LexErrors escape;
  lex_dcl(R"("\q")", escape);
  ASSERT_EQ(escape.listed.size(), 1u);
  EXPECT_NE(escape.listed[0].message.find("unknown escape"), std::string::npos);
}

// The lexer reads short decimals itself (parse_number's fast path, and beyond 2^53 up to 19
// digits by a long double division) and the rest with std::from_chars: both must give the same
// double for every number, read alone or as the lexer's token, at the fast paths' edges too (2^53
// and 2^53 + 1 as digits, 22 and 23 digits after the point, 19 and 20 digits, and numbers exactly
// half-way between two doubles, where the long double's quotient would round twice).
TEST(DclLexer, NumbersAsFromChars) {
  auto expect_same = [](const std::string& text) {
    double fast = 0, exact = 0;
    ASSERT_TRUE(parse_number(text, fast)) << text;
    const std::string_view body = text[0] == '-' ? std::string_view(text).substr(1) : text;
    ASSERT_EQ(std::from_chars(body.data(), body.data() + body.size(), exact).ptr,
              body.data() + body.size())
        << text;
    if (text[0] == '-') exact = -exact;
    EXPECT_EQ(std::memcmp(&fast, &exact, sizeof fast), 0) << text;  // -0 too
    LexErrors errors;
    const Tokens lexed = lex_dcl(text + ";", errors);
    ASSERT_EQ(lexed[0].kind, Token::Number) << text;
    EXPECT_EQ(std::memcmp(&lexed[0].value, &exact, sizeof exact), 0) << text;
  };
  for (const char* edge :
       {"0", "-0", "0.", ".5", "9007199254740992", "9007199254740993", "900719925474099.3",
        "0.9007199254740993", "1.0000000000000000000001", "1.00000000000000000000001",
        "1234567890123456789", "12345678901234567890", "0.69999999999999996", "2.5", "007",
        // half-way between two doubles: 2^53 + 1, 2^54 + 2, 2^63 + 2^10, 2^64 - 2^10, and
        // 2^53 + 3 (rounds up to even); just beside them
        "9007199254740993", "18014398509481986", "9223372036854776832", "18446744073709550592",
        "9007199254740995", "9007199254740994", "18014398509481985", "18014398509481987",
        "900719925474099.3", "9.007199254740993", "0.9007199254740993", "1.8014398509481986",
        "9999999999999999999", "0.0000009007199254740993", "-9007199254740993",
        // the digits after a point, eight at a time: 7, 8, 9, 16, 17 and 24 of them, and a
        // chunk cut by the text's end
        "0.1234567", "0.12345678", "0.123456789", "0.7648421872844885", "3.1415926535897931",
        "0.123456789012345678901234", "12.00000000", "1.99999999999999999"}) {
    expect_same(edge);
  }
  // Half-way points between two doubles in [1, 10) written with 19 digits: about half of their
  // long double quotients land on the half-way point itself (the second rounding would then go
  // the wrong way for half of those): they must be left to from_chars.
  std::mt19937_64 halves(53);
  for (int i = 0; i < 20000; ++i) {
    const double d = 1 + static_cast<double>(halves() >> 11) * 0x1p-53 * 9;
    const long double mid =
        (static_cast<long double>(d) + static_cast<long double>(std::nextafter(d, 20.0))) / 2;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.18Lf", mid);
    expect_same(buf);
  }
  // Doubles written with 17 significant digits (as the writer writes them) read back exactly.
  std::mt19937_64 bits(17);
  for (int i = 0; i < 20000; ++i) {
    const double x =
        std::ldexp(static_cast<double>(bits() >> 11), -53 + static_cast<int>(bits() % 40));
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    if (std::strchr(buf, 'e')) continue;
    expect_same(buf);
  }
  std::mt19937_64 rng(14);
  std::uniform_int_distribution<int> digits(1, 20), point(0, 20), coin(0, 1);
  for (int i = 0; i < 200000; ++i) {
    std::string text = coin(rng) ? "-" : "";
    const int n = digits(rng), at = point(rng);
    for (int k = 0; k < n; ++k) {
      if (k == at) text += '.';
      text += static_cast<char>('0' + rng() % 10);
    }
    expect_same(text);
  }
  double v = 0;
  EXPECT_FALSE(parse_number(".", v));
  EXPECT_FALSE(parse_number("1.2.3", v));
}

// A lone digit is read by the lexer's own short path; after a sign it goes the number's whole
// way. Every digit before every byte, both ways: the same tokens (the sign aside), the same
// values to the bit and the same errors.
TEST(DclLexer, LoneDigitsAsNumbers) {
  for (char digit = '0'; digit <= '9'; ++digit) {
    for (int b = 0; b < 256; ++b) {
      const std::string tail = std::string(1, static_cast<char>(b)) + " 1;";
      LexErrors short_errors, long_errors;
      const std::string short_text = digit + tail, long_text = "+" + short_text;
      const Tokens short_way = lex_dcl(short_text, short_errors);  // tokens view the text
      const Tokens long_way = lex_dcl(long_text, long_errors);
      ASSERT_EQ(short_way.size(), long_way.size()) << digit << " " << b;
      for (size_t i = 0; i < short_way.size(); ++i) {
        const Token &s = short_way[i], &l = long_way[i];
        EXPECT_EQ(s.kind, l.kind) << digit << " " << b << " token " << i;
        EXPECT_EQ(std::memcmp(&s.value, &l.value, sizeof s.value), 0) << digit << " " << b;
        EXPECT_EQ(i == 0 ? "+" + std::string(s.text) : std::string(s.text), std::string(l.text))
            << digit << " " << b;
      }
      ASSERT_EQ(short_errors.listed.size(), long_errors.listed.size()) << digit << " " << b;
      for (size_t i = 0; i < short_errors.listed.size(); ++i) {
        std::string message = long_errors.listed[i].message;  // a malformed number's, signed
        const std::string signed_number = "malformed number '+";
        if (message.compare(0, signed_number.size(), signed_number) == 0)
          message.erase(signed_number.size() - 1, 1);
        EXPECT_EQ(short_errors.listed[i].message, message) << digit << " " << b;
      }
    }
  }
}

}  // namespace
}  // namespace dispcon
