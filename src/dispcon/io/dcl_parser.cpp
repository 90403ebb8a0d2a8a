// The pieces of a statement: numbers, names, `;`, bounds, keywords, the end of a block, and where
// parsing resumes after an error.
#include "dispcon/io/dcl_parser.hpp"

#include <cmath>

namespace dispcon::dcl {

ParseResult Parser::run() {
  while (peek().kind != Token::End) {
    const Token& t = peek();
    if (t.kind == Token::Word && t.text == "object") {
      object_block();
    } else if (t.kind == Token::Word && t.text == "constraint") {
      constraint_block();
    } else if (t.kind == Token::Word && t.text == "include") {
      include_statement();
    } else {
      // A bad token was reported by the lexer; saying so twice would double a flood.
      if (t.kind != Token::Bad)
        error(at(t), "expected 'object', 'constraint' or 'include', found " + quote(t));
      skip();
    }
  }
  return build();
}

void Parser::recover() {
  while (peek().kind != Token::End) {
    const Token& t = peek();
    if (t.kind == Token::Semicolon) {
      skip();
      return;
    }
    if (t.kind == Token::Word &&
        (t.text == "end" || t.text == "object" || t.text == "constraint" || t.text == "include"))
      return;
    skip();
  }
}

double Parser::number(const What& what, bool allow_inf) {
  const Token& t = peek();
  if (t.kind == Token::Number && (allow_inf || !std::isinf(t.value))) {
    const double v = t.value;
    skip();
    return v;
  }
  if (t.kind == Token::Word && t.text == "inf") {
    if (!allow_inf) {
      error(at(t), what.str() + " must be finite, found 'inf' (inf is allowed only as a bound)");
      throw StatementError{};
    }
    skip();
    return kInf;
  }
  if (t.kind == Token::Number) {
    error(at(t), what.str() + " must be finite, found '" + std::string(t.text) +
                     "' (inf is allowed only as a bound)");
    throw StatementError{};
  }
  if (t.kind == Token::Word && (t.text == "nan" || t.text == "NaN" || t.text == "NAN")) {
    error(at(t), "expected a number for " + what.str() + ", found 'nan' (not a number)");
  } else if (t.kind != Token::Bad) {
    error(at(t), "expected a number for " + what.str() + ", found " + quote(t));
  }
  throw StatementError{};
}

Vec3 Parser::vec3(const What& what) {
  Vec3 v;
  for (int k = 0; k < 3; ++k) v[k] = number(what);
  return v;
}

std::string_view Parser::name(const char* what) {
  const Token& t = peek();
  if (t.kind != Token::Word) {
    error(at(t), std::string("expected ") + what + ", found " + quote(t));
    throw StatementError{};
  }
  const std::string_view text = t.text;
  skip();
  return text;
}

void Parser::semicolon(std::string_view after, bool quoted) {
  const Token& t = peek();
  if (t.kind != Token::Semicolon) {
    const std::string what = quoted ? "'" + std::string(after) + "'" : std::string(after);
    error(at(t), "expected ';' after " + what + ", found " + quote(t));
    throw StatementError{};
  }
  skip();
}

void Parser::bounds(std::string_view what, double& lo, double& hi) {
  bool seen_min = false, seen_max = false;
  while (peek().kind == Token::Word && (peek().text == "min" || peek().text == "max")) {
    const Token kw = next();
    const bool is_min = kw.text == "min";
    if ((is_min && seen_min) || (!is_min && seen_max)) {
      error(at(kw), "'" + std::string(kw.text) + "' given twice for " + std::string(what));
      throw StatementError{};
    }
    (is_min ? seen_min : seen_max) = true;
    (is_min ? lo : hi) = number(What(what, " ", kw.text), true);
  }
  if (peek().kind != Token::Semicolon) {
    error(at(peek()),
          "expected 'min', 'max' or ';' in " + std::string(what) + ", found " + quote(peek()));
    throw StatementError{};
  }
  skip();
}

std::string_view Parser::keyword(const Token& t, const char* block, std::string_view object_name,
                                 Statements& seen) {
  const bool object = block[0] == 'o';
  if (t.kind != Token::Word) {
    error(at(t), std::string("expected ") + (object ? "an " : "a ") + block +
                     " statement or 'end', found " + quote(t));
    throw StatementError{};
  }
  if (const Place* first = statement(seen, t.text)) {
    error(at(t), "'" + std::string(t.text) + "' given twice in " +
                     (object ? object_label(object_name) : "this " + std::string(block)) +
                     " (first at line " + std::to_string(first->line) + ")");
    throw StatementError{};
  }
  mark(seen, t.text, {}, at(t));
  return t.text;
}

bool Parser::block_end(bool object, std::string_view object_name, Place open) {
  const Token& t = peek();
  if (t.kind == Token::Word && t.text == "end") {
    skip();
    if (peek().kind == Token::Semicolon) skip();
    return true;
  }
  if (t.kind == Token::End ||
      (t.kind == Token::Word &&
       (t.text == "object" || t.text == "constraint" || t.text == "include"))) {
    error(at(t), "missing 'end' for the " +
                     (object ? object_label(object_name) : std::string("constraint")) +
                     " opened at line " + std::to_string(open.line) + ", found " + quote(t));
    return true;
  }
  return false;
}

ParseResult parse_text(std::string_view text, const std::string& filename, IncludeStack& stack) {
  try {
    return Parser(text, filename, stack).run();
  } catch (const std::exception& e) {
    ParseResult r;
    r.diagnostics.push_back({filename, 0, 0, true, std::string("internal error: ") + e.what()});
    return r;
  }
}

}  // namespace dispcon::dcl
