// Tokens of the description language (format.md, "Lexical rules").
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace dispcon {

// At most this many errors are listed for one file (lexer and parser together); the rest are
// counted and summed up in one last line.
constexpr int kErrorCap = 100;

struct Token {
  enum Kind { Word, Number, String, Semicolon, End, Bad } kind = End;
  std::string text;  // as written; String: the value, escapes decoded
  double value = 0;  // Number
  int line = 1;
  int column = 1;
};

struct LexError {
  int line = 1;
  int column = 1;
  std::string message;
};

struct LexErrors {
  std::vector<LexError> listed;  // the first kErrorCap
  long long more = 0;            // how many came after those
  void add(LexError e);
};

// Splits `text` into tokens, skipping white space and comments. Problems (bytes that are not
// text, an unterminated comment or string, a malformed number) are added to `errors`; lexing
// goes on.
std::vector<Token> lex_dcl(std::string_view text, LexErrors& errors);

// A string token as the lexer reads it back: in double quotes, with `\\`, `\"`, `\n`, `\t`, `\r`
// and `\xHH` for any other byte below 0x20 and 0x7F; other bytes (UTF-8 included) as they are.
std::string quote_string(const std::string& value);

}  // namespace dispcon
