// Tokens of the description language (format.md, "Lexical rules").
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace dispcon {

struct Token {
  enum Kind { Word, Number, Semicolon, End, Bad } kind = End;
  std::string text;  // as written
  double value = 0;  // Number
  int line = 1;
  int column = 1;
};

struct LexError {
  int line = 1;
  int column = 1;
  std::string message;
};

// Splits `text` into tokens, skipping white space and comments. Problems (bytes that are not
// text, an unterminated comment, a malformed number) are appended to `errors`; lexing goes on.
std::vector<Token> lex_dcl(std::string_view text, std::vector<LexError>& errors);

}  // namespace dispcon
