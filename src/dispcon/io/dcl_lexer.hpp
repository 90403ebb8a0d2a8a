// Tokens of the description language (format.md, "Lexical rules").
#pragma once

#include <forward_list>
#include <string>
#include <string_view>
#include <vector>

namespace dispcon {

// At most this many errors are listed for one file (lexer and parser together); the rest are
// counted and summed up in one last line.
constexpr int kErrorCap = 100;

struct Token {
  enum Kind { Word, Number, String, Semicolon, End, Bad } kind = End;
  // As written, a view of the text lexed (no copy per token). String: its value, escapes
  // decoded: a view of the text between the quotes, or of the lexer's copy when it had escapes.
  std::string_view text;
  double value = 0;  // Number
  int line = 1;
  int column = 1;
};

// The tokens of a text, ending with an End token. They view the text: it must outlive them.
struct Tokens {
  std::vector<Token> list;
  // The values of the strings written with escapes (a list: its strings never move).
  std::forward_list<std::string> decoded;

  const Token& operator[](size_t i) const { return list[i]; }
  size_t size() const { return list.size(); }
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

// Reads `text` one token at a time, skipping white space and comments (the reader keeps no list
// of tokens: a file's tokens would take ten times its size). Problems (bytes that are not text,
// an unterminated comment or string, a malformed number) are added to `errors`; lexing goes on.
class DclLexer {
 public:
  DclLexer(std::string_view text, LexErrors& errors)
      : errors_(errors), p_(text.data()), end_(text.data() + text.size()), line_start_(p_) {}
  // The next token, written over `t` (the parser's one token: no copy of it is returned); End at
  // the end of the text, and again after that.
  void next(Token& t);
  // The values of the strings written with escapes so far, which their tokens view.
  std::forward_list<std::string> decoded() && { return std::move(decoded_); }

 private:
  // The place is kept as a line and where that line starts: a column is a count of bytes from
  // there, taken only when a token or a message needs it (not counted byte by byte).
  int column() const { return static_cast<int>(p_ - line_start_) + 1; }
  void step();
  void error(std::string message);
  // The messages of a byte that starts no token and of a malformed number, out of line: the
  // strings they build would otherwise give next() and number() a large frame to set up at every
  // token.
  [[gnu::cold, gnu::noinline]] void stray(char c);
  [[gnu::cold, gnu::noinline]] void malformed(const Token& t);
  // A comment at p_ ("//" or "/*") skipped; false when it is never closed (the text ends).
  bool comment();
  void number(Token& t);
  void string(Token& t);

  LexErrors& errors_;
  std::forward_list<std::string> decoded_;
  const char* p_;  // the next byte
  const char* end_;
  const char* line_start_;  // the first byte of p_'s line
  int line_ = 1;
};

// Every token of `text`, with DclLexer.
Tokens lex_dcl(std::string_view text, LexErrors& errors);

// A number token's value, as the lexer reads it: decimal (strtod's syntax without hexadecimal,
// nan or infinity), or `inf`, after an optional sign. False when `text` is not one.
bool parse_number(std::string_view text, double& value);

// A string token as the lexer reads it back: in double quotes, with `\\`, `\"`, `\n`, `\t`, `\r`
// and `\xHH` for any other byte below 0x20 and 0x7F; other bytes (UTF-8 included) as they are.
std::string quote_string(std::string_view value);

}  // namespace dispcon
