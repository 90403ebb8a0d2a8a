#include "dispcon/io/dcl_lexer.hpp"

#include <cctype>
#include <cmath>
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

}  // namespace

void LexErrors::add(LexError e) {
  if (listed.size() < static_cast<size_t>(kErrorCap)) {
    listed.push_back(std::move(e));
  } else {
    ++more;
  }
}

std::string quote_string(const std::string& value) {
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

std::vector<Token> lex_dcl(std::string_view text, LexErrors& errors) {
  std::vector<Token> out;
  size_t i = 0;
  int line = 1, column = 1;
  auto advance = [&](size_t n) {
    for (size_t k = 0; k < n && i < text.size(); ++k, ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
  };
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
      advance(1);
      continue;
    }
    if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      while (i < text.size() && text[i] != '\n') advance(1);
      continue;
    }
    if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      const int l0 = line, c0 = column;
      advance(2);
      while (i < text.size() && !(text[i] == '*' && i + 1 < text.size() && text[i + 1] == '/')) {
        const unsigned char b = static_cast<unsigned char>(text[i]);
        if (b == 0 || (b < 0x20 && b != '\n' && b != '\r' && b != '\t')) {
          errors.add({line, column, "byte " + describe_byte(b) + " is not text"});
        }
        advance(1);
      }
      if (i >= text.size()) {
        errors.add({l0, c0, "comment '/*' is never closed with '*/'"});
        break;
      }
      advance(2);
      continue;
    }
    Token t;
    t.line = line;
    t.column = column;
    if (c == ';') {
      t.kind = Token::Semicolon;
      t.text = ";";
      advance(1);
      out.push_back(t);
      continue;
    }
    const bool sign = (c == '-' || c == '+');
    const char next = i + 1 < text.size() ? text[i + 1] : '\0';
    if (std::isdigit(c) || c == '.' ||
        (sign && (std::isdigit(static_cast<unsigned char>(next)) || next == '.' || next == 'i'))) {
      size_t j = sign ? i + 1 : i;
      while (j < text.size()) {
        const char ch = text[j];
        const bool exponent_sign =
            (ch == '-' || ch == '+') && (text[j - 1] == 'e' || text[j - 1] == 'E');
        if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' ||
              exponent_sign)) {
          break;
        }
        ++j;
      }
      t.text = std::string(text.substr(i, j - i));
      std::string body = t.text;
      double sgn = 1;
      if (!body.empty() && (body[0] == '-' || body[0] == '+')) {
        sgn = body[0] == '-' ? -1 : 1;
        body = body.substr(1);
      }
      if (body == "inf") {
        t.kind = Token::Number;
        t.value = sgn * std::numeric_limits<double>::infinity();
      } else {
        char* end = nullptr;
        const double v = std::strtod(t.text.c_str(), &end);
        const bool hex_or_word = body.find_first_of("xXnN") != std::string::npos;
        if (end != t.text.c_str() + t.text.size() || hex_or_word || body.empty()) {
          t.kind = Token::Bad;
          errors.add({t.line, t.column, "malformed number '" + t.text + "'"});
        } else {
          t.kind = Token::Number;
          t.value = v;
        }
      }
      advance(j - i);
      out.push_back(t);
      continue;
    }
    if (c == '"') {
      // A string ends at the next unescaped quote on the same line: a lost quote cannot
      // swallow the rest of the file.
      t.kind = Token::String;
      advance(1);
      bool closed = false, bad = false;
      while (i < text.size() && text[i] != '\n') {
        const unsigned char b = static_cast<unsigned char>(text[i]);
        if (b == '"') {
          closed = true;
          advance(1);
          break;
        }
        if (b == '\\') {
          const char e = i + 1 < text.size() ? text[i + 1] : '\0';
          const int h1 = i + 2 < text.size() ? hex_digit(text[i + 2]) : -1;
          const int h2 = i + 3 < text.size() ? hex_digit(text[i + 3]) : -1;
          if (e == '\\' || e == '"') {
            t.text += e;
          } else if (e == 'n' || e == 't' || e == 'r') {
            t.text += e == 'n' ? '\n' : e == 't' ? '\t' : '\r';
          } else if (e == 'x' && h1 >= 0 && h2 >= 0) {
            t.text += static_cast<char>(h1 * 16 + h2);
            advance(4);
            continue;
          } else {
            errors.add({line, column,
                        "unknown escape in a string (use \\\\, \\\", \\n, \\t, \\r or \\xHH)"});
            bad = true;
            if (e == '\n' || e == '\0') {  // a backslash ending the line escapes nothing
              advance(1);
              continue;
            }
          }
          advance(2);
          continue;
        }
        if ((b < 0x20 && b != '\t') || b == 0x7f) {
          errors.add(
              {line, column, "byte " + describe_byte(b) + " in a string: write it as \\xHH"});
          bad = true;
        } else {
          t.text += static_cast<char>(b);
        }
        advance(1);
      }
      if (!closed) {
        errors.add({t.line, t.column, "string is not closed with '\"' on its line"});
        bad = true;
      }
      if (bad) t.kind = Token::Bad;
      out.push_back(t);
      continue;
    }
    if (std::isalpha(c)) {
      size_t j = i;
      while (j < text.size() && is_name_char(text[j])) ++j;
      t.kind = Token::Word;
      t.text = std::string(text.substr(i, j - i));
      advance(j - i);
      out.push_back(t);
      continue;
    }
    t.kind = Token::Bad;
    if (c < 0x20 || c >= 0x7f) {
      errors.add({line, column, "byte " + describe_byte(c) + " is not text"});
    } else {
      errors.add(
          {line, column, std::string("unexpected character '") + static_cast<char>(c) + "'"});
    }
    advance(1);
  }
  Token end;
  end.kind = Token::End;
  end.line = line;
  end.column = column;
  out.push_back(end);
  return out;
}

}  // namespace dispcon
