// The .dcl reader's parser, inside src/dispcon/io only (format.md). The statements are parsed
// into blocks with their places (dcl_parser.cpp: the pieces of a statement; dcl_blocks.cpp:
// object and constraint blocks; dcl_include.cpp: include statements) and the model is built
// (dcl_build.cpp): each object is added to it as its block ends, each constraint too when both
// its objects are known by then; the constraints after one that names an object not yet declared
// wait, with the includes, for the end, so objects may be declared after the constraints that
// name them. Every problem becomes a diagnostic naming its place; parsing resumes at the next `;`
// or `end`. The model's own refusals are listed after the parse's errors, as if found at the end.
//
// Memory speed: tokens are views of the file's text pulled one at a time, each name becomes a
// string once (in its object's Body), a message is built only when it is written, and a block
// added as it ends is built in place (one block, its marks dropped once added): the parse touches
// little memory beside the model it builds.
#pragma once

#include <cstdint>
#include <filesystem>
#include <forward_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dispcon/io/dcl_lexer.hpp"
#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/include.hpp"
#include "dispcon/model/joint_kinds.hpp"

namespace dispcon::dcl {

struct Place {
  int line = 0, column = 0;
};

// Where each statement of a block was, by keyword, and each argument of a component's statement,
// by keyword and argument name: a value the model refuses (a ValueError naming its statement, a
// JointError its argument) is reported there. Blocks do not nest, so each block's marks are a
// run [begin, end) of the parser's one list (a handful each: searched in order).
struct Mark {
  std::string_view keyword, arg;  // arg empty: the statement itself
  Place at;
};
struct Statements {
  size_t begin = 0, end = 0;
};

struct ObjectBlock {
  Place at;
  std::string_view name;  // a view of the text; the Body's own copy is made once, at the end
  Body body;
  Statements seen;
  bool ok = true;  // parsed without error: the model checks it
};

struct ConstraintBlock {
  Place at;
  std::string_view object1 = "world", object2;  // views of the text
  bool has_object2 = false;
  Joint joint;
  Statements seen;
  std::string_view guide;     // the keyword of its translation guide
  std::string_view coupling;  // the keyword of its coupling
  bool ok = true;
};

// `include "file" as NAME {position x y z} {rotation r} {on BODY} {rigid};` (format.md).
struct IncludeBlock {
  Place at;
  std::string path;
  Inclusion inc;
  Vec3 position = Vec3::Zero(), rotation = Vec3::Zero();
  std::string_view on = "world";
  Statements seen;
};

// The files being read, outermost first (canonical paths): an include of one of them is a cycle.
// The outermost file's canonical path is asked of the system only when a file includes another
// (a look at each folder of its path, some seven system calls a start of the command for a file
// with no include at all).
class IncludeStack {
 public:
  IncludeStack() = default;
  // The outermost file, when it is a regular file (a text read from elsewhere has none).
  explicit IncludeStack(std::string outermost) : outermost_(std::move(outermost)) {}
  // The canonical paths, outermost first.
  const std::vector<std::string>& files() {
    if (!outermost_.empty()) {
      std::error_code ec;
      if (std::filesystem::is_regular_file(outermost_, ec))
        files_.insert(files_.begin(), std::filesystem::weakly_canonical(outermost_, ec).string());
      outermost_.clear();
    }
    return files_;
  }
  void push(std::string canonical) {
    files();
    files_.push_back(std::move(canonical));
  }
  void pop() { files_.pop_back(); }

 private:
  std::string outermost_;  // not yet made canonical (empty: done, or none)
  std::vector<std::string> files_;
};

// Every declared name, once: where it was declared and the body it became (none when its block
// had an error, reported there). The names view the text, or included_names_.
struct Declared {
  Place at;
  std::optional<BodyId> body;
};
// The table of them: the names in the order declared, and an open-addressed index into them (a
// power of two of slots, at most half full, probed one after another). A lookup hashes the name
// and compares a slot or two: std::unordered_map's chains cost a cache miss a node and a division
// a node visited (its buckets are a prime in number), and a node allocated a name.
class Declarations {
 public:
  void reserve(size_t names);
  Declared* find(std::string_view name) {
    const uint32_t* slot = lookup(name);
    return *slot ? &entries_[*slot - 1].second : nullptr;
  }
  const Declared* find(std::string_view name) const {
    return const_cast<Declarations*>(this)->find(name);
  }
  // The name's entry, made from `d` when it is new (then true).
  std::pair<Declared*, bool> try_emplace(std::string_view name, const Declared& d);
  Declared& operator[](std::string_view name) { return *try_emplace(name, Declared{}).first; }

 private:
  static uint64_t hash(std::string_view name);
  // The slot holding the name's entry (its index + 1), or the empty slot (0) where it would go.
  uint32_t* lookup(std::string_view name) {
    if (slots_.empty()) reserve(8);
    const size_t mask = slots_.size() - 1;
    for (size_t i = hash(name) & mask;; i = (i + 1) & mask) {
      uint32_t& slot = slots_[i];
      if (!slot || entries_[slot - 1].first == name) return &slot;
    }
  }

  std::vector<std::pair<std::string_view, Declared>> entries_;
  std::vector<uint32_t> slots_;
};

// A diagnostic of the model's (a value it refuses, a bound it clamps, a duplicate object) met
// while a block was added as it ended: kept to be listed where the model's diagnostics have always
// been, after every error of the parse itself. Past kErrorCap errors (or warnings) they are only
// counted: none of those could be listed.
struct Later {
  Place at;
  bool error = true;
  std::string message;
};
struct LaterList {
  std::vector<Later> listed;
  long long errors = 0, warnings = 0;  // all of them, listed or not
  void add(Place at, bool error, std::string message);
};

// Thrown inside the parser to abandon one statement; caught at statement level.
struct StatementError {};

class Parser {
 public:
  Parser(std::string_view text, const std::string& file, IncludeStack& stack)
      : file_(file), lexer_(text, lex_errors_), stack_(stack) {
    lexer_.next(current_);
    // The model's room for every body and joint at once: a count of the words (in comments too,
    // so an upper bound), not of object1 and object2, whose room would push the model and the
    // solver's state up into more of the heap's huge pages (each zeroed when first touched).
    const size_t objects = words(text, "object", 1);
    model_.reserve(objects + 1, words(text, "constraint", 3));
    declared_.reserve(objects);
    // An included model's joints come before the constraints' (include_into runs at the end):
    // with an include in the text, no constraint is added as it ends.
    in_place_ = words(text, "include", 3) == 0;
    // Marks: a block's statements and their arguments (a hinge: three), dropped when the block is
    // added as it ends; the list grows when blocks wait for the end.
    statements_.reserve(64);
  }

  ParseResult run();

 private:
  // Tokens, read as the parser goes: peek() is valid until the next call of next() or skip().
  const Token& peek() const { return current_; }
  Token next() {
    const Token t = current_;
    skip();
    return t;
  }
  // Past the token peek() gives (no copy of it).
  void skip() {
    if (current_.kind != Token::End) lexer_.next(current_);
  }
  static Place at(const Token& t) { return {t.line, t.column}; }
  // How many times `word` stands alone in `text` (no name's byte after it). It is sought by its
  // tail from `rare` on, whose first letter is rarer than the word's: a search stops at every
  // occurrence of its first letter.
  static size_t words(std::string_view text, std::string_view word, size_t rare) {
    const std::string_view tail = word.substr(rare);
    size_t n = 0;
    for (size_t i = text.find(tail, rare); i != std::string_view::npos;
         i = text.find(tail, i + 1)) {
      const size_t end = i + tail.size();
      n += text.compare(i - rare, rare, word.substr(0, rare)) == 0 &&
           (end == text.size() || !is_name_char(text[end]));
    }
    return n;
  }
  static std::string quote(const Token& t) {
    switch (t.kind) {
      case Token::End:
        return "the end of the file";
      case Token::Semicolon:
        return "';'";
      case Token::String:
        return "a string";
      default:
        return "'" + std::string(t.text) + "'";
    }
  }
  static std::string object_label(std::string_view name) {
    return "object '" + std::string(name) + "'";
  }

  // Marks a block's statement `keyword` (or its argument `arg`) at `p`.
  void mark(Statements& seen, std::string_view keyword, std::string_view arg, Place p) {
    statements_.push_back({keyword, arg, p});
    seen.end = statements_.size();
  }
  // The place of a block's statement `keyword` (or its argument `arg`), or null. The last mark
  // wins: an argument is marked where its value starts, then again at its number.
  const Place* statement(const Statements& seen, std::string_view keyword,
                         std::string_view arg = {}) const {
    for (size_t i = seen.end; i-- > seen.begin;) {
      const Mark& m = statements_[i];
      // The argument first: a statement's own mark has none, so a keyword's search passes its
      // arguments' marks by their lengths alone.
      if (m.arg == arg && m.keyword == keyword) return &m.at;
    }
    return nullptr;
  }
  // The place of a block's statement `keyword` (or its argument `arg`), or `fallback`.
  Place place(const Statements& seen, std::string_view keyword, Place fallback,
              std::string_view arg = {}) const {
    const Place* p = statement(seen, keyword, arg);
    return p ? *p : fallback;
  }
  // A new block's (empty) run of marks.
  Statements statements() const { return {statements_.size(), statements_.size()}; }

  // Past kErrorCap, errors (and warnings) are counted, not listed: a binary file or 200,000
  // duplicate objects print about a hundred lines, then one line with the count of the rest.
  // The lexer's errors come first, and how many it finds is known only at the end: the parser's
  // first kErrorCap are kept, the cap applied to both in build().
  void error(Place p, const std::string& message) {
    if (errors_++ < kErrorCap) diagnostics_.push_back({file_, p.line, p.column, true, message});
  }
  void warning(Place p, const std::string& message) {
    if (warnings_++ < kErrorCap) diagnostics_.push_back({file_, p.line, p.column, false, message});
  }

  // Skips to just after the next ';', or to (not past) `end`, `object`, `constraint`.
  void recover();

  // A number (`inf` only when `allow_inf`: a bound); `what` names it in messages ("hinge P1").
  double number(const What& what, bool allow_inf = false);

  Vec3 vec3(const What& what);

  std::string_view name(const char* what);

  // `;` after `after` (in quotes when `quoted`: a statement's keyword).
  void semicolon(std::string_view after, bool quoted = false);

  // `{min a} {max b}` then `;`.
  void bounds(std::string_view what, double& lo, double& hi);

  // A statement's keyword: a word, not given before in its block or include (`seen` records
  // it). `object_name`: the object block's name, for messages ("this constraint", "this
  // include" otherwise).
  std::string_view keyword(const Token& t, const char* block, std::string_view object_name,
                           Statements& seen);

  // `end` (with an optional `;`) closing a block opened at `open`: an object block (named
  // `object_name`) or a constraint block.
  bool block_end(bool object, std::string_view object_name, Place open);

  void object_block();

  // A component's statement (hinge, a guide, angle, twist, a coupling) as its row of
  // components() says: its arguments, then `{min} {max}` or its optional words and `;`. The model
  // checks the values; the place of each argument is marked in `cb.seen`, so that a value the
  // model refuses is reported where it is written.
  void component_statement(const ComponentRow& row, std::string_view k, ConstraintBlock& cb);

  // The optional words of a statement (`left`, `phase f`), each at most once and in any order,
  // then `;`.
  void options(const ComponentRow& row, std::string_view k, ComponentValues& v,
               ConstraintBlock& cb);

  // `include "file" as NAME` then, in any order and each at most once, `position x y z`,
  // `rotation rx ry rz`, `on BODY`, `rigid`; then `;`.
  void include_statement();

  // Reads, checks and adds the model an include names, its names declared; every problem is
  // reported at the include statement (and the included file's own errors at their places).
  void include_into(Model& model, IncludeBlock& ib, Declarations& declared);

  void constraint_block();

  // An error or a warning at `at`, listed now, or kept in `later` when not null.
  void report(LaterList* later, Place at, bool is_error, std::string message);
  // Lists what `later` kept (and counts what it only counted), as if met now.
  void replay(const LaterList& later);
  // The object declared (a duplicate is an error), its body checked by the model and added to it
  // when its block parsed cleanly; the problems kept in objects_later_.
  void add_object(ObjectBlock& ob);
  // The body `name` is already (the world too), or none: not declared yet, or refused.
  std::optional<BodyId> body_of(std::string_view name) const;
  // The constraint's objects resolved and its joint checked by the model and added to it when
  // its block parsed cleanly; the problems listed, or kept in `later`.
  void add_constraint(ConstraintBlock& cb, LaterList* later);
  // The same once its objects are resolved (its joint's bodies set) and its block is clean.
  void add_resolved(ConstraintBlock& cb, LaterList* later);

  // The includes and the constraints that waited are added, and the diagnostics put in order:
  // each problem is reported once, at the statement it is about.
  ParseResult build();

  std::string file_;
  LexErrors lex_errors_;
  DclLexer lexer_;
  Token current_;
  std::vector<Mark> statements_;  // every block's marks, in order
  std::vector<Diagnostic> diagnostics_;
  long long errors_ = 0;  // every error of the parser's, listed or not (the lexer's: in build())
  long long warnings_ = 0;
  Model model_;
  Declarations declared_;
  bool in_place_ = true;  // constraints are added as they end (no include, none waiting)
  LaterList objects_later_, constraints_later_;
  std::vector<ConstraintBlock> constraints_;  // those that wait for the end, in order
  std::vector<IncludeBlock> includes_;
  std::vector<std::string> rigid_;                 // the names of rigid includes
  std::forward_list<std::string> included_names_;  // what `declared` views for included bodies
  IncludeStack& stack_;
};

// The text's model or diagnostics; `stack` holds the files being read (include cycles).
ParseResult parse_text(std::string_view text, const std::string& filename, IncludeStack& stack);
// A file's bytes as read_file reads them.
class FileText {
 public:
  std::string_view view() const { return {data_.get(), size_}; }

 private:
  friend bool read_file(const std::string& path, FileText& text, std::string& why);
  // Room for `room` bytes, the bytes held kept.
  void reserve(size_t room);
  std::unique_ptr<char[]> data_;
  size_t size_ = 0, room_ = 0;
};
// The file's text, or false and the reason in `why`.
bool read_file(const std::string& path, FileText& text, std::string& why);

}  // namespace dispcon::dcl
