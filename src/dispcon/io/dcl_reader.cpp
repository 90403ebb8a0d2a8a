// The description language reader (format.md). Two passes: the statements are parsed into
// blocks with their places, then names are resolved and the model is built, so objects may be
// declared after the constraints that name them. Every problem becomes a diagnostic naming its
// place; parsing resumes at the next `;` or `end`.
//
// Memory speed: the file is read in one go, tokens are views of its text, each name becomes a
// string once (in its object's Body), and a message is built only when it is written.
#include "dispcon/io/dcl_reader.hpp"

#include <Eigen/Cholesky>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <forward_list>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "dispcon/io/dcl_lexer.hpp"
#include "dispcon/io/include.hpp"
#include "dispcon/model/joint_kinds.hpp"

namespace dispcon {

std::string Diagnostic::format() const {
  std::ostringstream out;
  out << file;
  if (line > 0) out << ":" << line << ":" << column;  // line 0: the file as a whole
  out << ": " << (error ? "error" : "warning") << ": " << message;
  return out.str();
}

std::string ParseResult::messages() const {
  std::string out;
  for (const Diagnostic& d : diagnostics) out += d.format() + "\n";
  return out;
}

namespace {

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
using IncludeStack = std::vector<std::string>;

// Every declared name, once: where it was declared and the body it became (none when its block
// had an error, reported there). The names view the text, or included_names_.
struct Declared {
  Place at;
  std::optional<BodyId> body;
};
using Declarations = std::unordered_map<std::string_view, Declared>;

ParseResult parse_text(std::string_view text, const std::string& filename, IncludeStack& stack);
bool read_file(const std::string& path, std::string& text);

// Thrown inside the parser to abandon one statement; caught at statement level.
struct StatementError {};

class Parser {
 public:
  Parser(std::string_view text, const std::string& file, IncludeStack& stack)
      : file_(file), lexer_(text, lex_errors_), current_(lexer_.next()), stack_(stack) {
    // Room for every block at once (a count of the words, in comments too, is an upper bound):
    // blocks of half a kilobyte copied at each growth cost more than the count.
    objects_.reserve(occurrences(text, "object"));
    constraints_.reserve(occurrences(text, "constraint"));
  }

  ParseResult run() {
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
        next();
      }
    }
    return build();
  }

 private:
  // Tokens, read as the parser goes: peek() is valid until the next call of next().
  const Token& peek() const { return current_; }
  Token next() {
    const Token t = current_;
    if (t.kind != Token::End) current_ = lexer_.next();
    return t;
  }
  static Place at(const Token& t) { return {t.line, t.column}; }
  static size_t occurrences(std::string_view text, std::string_view word) {
    size_t n = 0;
    for (size_t i = text.find(word); i != std::string_view::npos; i = text.find(word, i + 1)) ++n;
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
      if (m.keyword == keyword && m.arg == arg) return &m.at;
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
  void recover() {
    while (peek().kind != Token::End) {
      const Token& t = peek();
      if (t.kind == Token::Semicolon) {
        next();
        return;
      }
      if (t.kind == Token::Word &&
          (t.text == "end" || t.text == "object" || t.text == "constraint" || t.text == "include"))
        return;
      next();
    }
  }

  double number(const What& what, bool allow_inf = false) {
    const Token& t = peek();
    if (t.kind == Token::Number && (allow_inf || !std::isinf(t.value))) return next().value;
    if (t.kind == Token::Word && t.text == "inf") {
      if (!allow_inf) {
        error(at(t), what.str() + " must be finite, found 'inf' (inf is allowed only as a bound)");
        throw StatementError{};
      }
      next();
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

  Vec3 vec3(const What& what) {
    Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = number(what);
    return v;
  }

  std::string_view name(const char* what) {
    const Token& t = peek();
    if (t.kind != Token::Word) {
      error(at(t), std::string("expected ") + what + ", found " + quote(t));
      throw StatementError{};
    }
    return next().text;
  }

  // `;` after `after` (in quotes when `quoted`: a statement's keyword).
  void semicolon(std::string_view after, bool quoted = false) {
    const Token& t = peek();
    if (t.kind != Token::Semicolon) {
      const std::string what = quoted ? "'" + std::string(after) + "'" : std::string(after);
      error(at(t), "expected ';' after " + what + ", found " + quote(t));
      throw StatementError{};
    }
    next();
  }

  // `{min a} {max b}` then `;`.
  void bounds(std::string_view what, double& lo, double& hi) {
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
    next();
  }

  // A statement's keyword: a word, not given before in its block or include (`seen` records
  // it). `object_name`: the object block's name, for messages ("this constraint", "this
  // include" otherwise).
  std::string_view keyword(const Token& t, const char* block, std::string_view object_name,
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

  // `end` (with an optional `;`) closing a block opened at `open`: an object block (named
  // `object_name`) or a constraint block.
  bool block_end(bool object, std::string_view object_name, Place open) {
    const Token& t = peek();
    if (t.kind == Token::Word && t.text == "end") {
      next();
      if (peek().kind == Token::Semicolon) next();
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

  void object_block() {
    const Token kw = next();
    ObjectBlock ob;
    ob.at = at(kw);
    ob.body.line = kw.line;
    ob.seen = statements();
    const long long errors_before = errors_;
    try {
      ob.name = name("an object name");
      if (ob.name == "world") {
        error(ob.at, "'world' is reserved for the fixed world frame");
      }
      semicolon("the object name");
    } catch (const StatementError&) {
      recover();
    }
    Vec3 rotation = Vec3::Zero();
    while (!block_end(true, ob.name, ob.at)) {
      const Token t = next();
      try {
        const std::string_view k = keyword(t, "object", ob.name, ob.seen);
        Body& b = ob.body;
        if (k == "position") {
          b.pose.x = vec3("position");
        } else if (k == "rotation") {
          rotation = vec3("rotation");
        } else if (k == "fixed") {
          b.fixed = true;
        } else if (k == "rotate") {
          const double v = number("rotate");
          if (!(v > 0)) error(at(t), "rotate must be positive, found " + format_number(v));
          b.rotate = v;
        } else if (k == "mass") {
          const double v = number("mass");
          if (!(v > 0)) error(at(t), "mass must be positive, found " + format_number(v));
          b.mass = v;
        } else if (k == "inertia") {
          double v[6] = {0, 0, 0, 0, 0, 0};
          for (int i = 0; i < 3; ++i) v[i] = number("inertia");
          if (peek().kind == Token::Number) {
            for (int i = 3; i < 6; ++i) v[i] = number("inertia (Ixy Ixz Iyz)");
          }
          Mat3 J;
          J << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
          Eigen::LLT<Mat3> llt(J);
          if (llt.info() != Eigen::Success) {
            error(at(t), "inertia is not positive definite");
          }
          b.inertia = J;
        } else if (k == "center") {
          b.center = vec3("center");
        } else if (k == "velocity") {
          b.velocity = vec3("velocity");
        } else if (k == "spin") {
          b.spin = vec3("spin");
        } else if (k == "force") {
          b.force = vec3("force");
        } else if (k == "torque") {
          b.torque = vec3("torque");
        } else {
          error(at(t), "unknown object statement '" + std::string(k) +
                           "' (expected position, rotation, fixed, rotate, mass, inertia, center, "
                           "velocity, spin, force, torque or end)");
          throw StatementError{};
        }
        semicolon(k, true);
      } catch (const StatementError&) {
        recover();
      }
    }
    try {
      ob.body.pose.q = rotation_from_vector(rotation, "rotation");
    } catch (const ValueError& e) {
      error(place(ob.seen, e.field(), ob.at), object_label(ob.name) + ": " + e.what());
    }
    ob.ok = errors_ == errors_before;
    objects_.push_back(std::move(ob));
  }

  // A component's statement (hinge, a guide, angle, twist, a coupling) as its row of
  // components() says: its arguments, then `{min} {max}` or its optional words and `;`. The model
  // checks the values; the place of each argument is marked in `cb.seen`, so that a value the
  // model refuses is reported where it is written.
  void component_statement(const ComponentRow& row, std::string_view k, ConstraintBlock& cb) {
    ComponentValues v;
    for (const ArgSpec& a : row.args) {
      const What what(k, " ", a.name);
      mark(cb.seen, k, a.name, at(peek()));
      switch (a.kind) {
        case Arg::Point:
        case Arg::Direction:
          v.vectors.push_back(vec3(what));
          break;
        case Arg::PositiveLength:
        case Arg::NonNegativeLength:
          v.scalars.push_back(number(what));
          break;
        case Arg::NamedPositive: {
          const Token& w = peek();
          if (w.kind != Token::Word || w.text != a.name) {
            error(at(w), "expected '" + std::string(a.name) + "' in " + std::string(k) +
                             ", found " + quote(w));
            throw StatementError{};
          }
          next();
          mark(cb.seen, k, a.name, at(peek()));
          v.scalars.push_back(number(what));
          break;
        }
        case Arg::Points: {
          const Place first = at(peek());
          std::vector<double> x;
          while (peek().kind == Token::Number) x.push_back(number(what));
          if (x.size() % 3 != 0) {
            error(first, std::string(k) + " needs three coordinates per point, found " +
                             std::to_string(x.size()) + " numbers");
            throw StatementError{};
          }
          for (size_t i = 0; i < x.size(); i += 3) v.points.emplace_back(x[i], x[i + 1], x[i + 2]);
          break;
        }
        case Arg::Flag:
          v.flags.push_back(false);
          break;
        case Arg::NamedOption:
          v.options.emplace_back();
          break;
      }
    }
    if (row.has_bounds) {
      v.bounds = row.defaults;
      bounds(k, v.bounds.min, v.bounds.max);
    } else {
      options(row, k, v, cb);
    }
    set_component(cb.joint, row.id, v);
    if (row.guide) cb.guide = k;
    if (row.coupling) cb.coupling = k;
  }

  // The optional words of a statement (`left`, `phase f`), each at most once and in any order,
  // then `;`.
  void options(const ComponentRow& row, std::string_view k, ComponentValues& v,
               ConstraintBlock& cb) {
    std::vector<bool> given(row.args.size(), false);
    while (peek().kind == Token::Word) {
      size_t i = 0, flag = 0, option = 0;
      for (; i < row.args.size(); ++i) {
        const ArgSpec& a = row.args[i];
        if (is_optional(a.kind) && !given[i] && peek().text == a.name) break;
        flag += a.kind == Arg::Flag;
        option += a.kind == Arg::NamedOption;
      }
      if (i == row.args.size()) break;
      given[i] = true;
      const ArgSpec& a = row.args[i];
      next();
      mark(cb.seen, k, a.name, at(peek()));
      if (a.kind == Arg::Flag) {
        v.flags[flag] = true;
      } else {
        v.options[option] = number(What(k, " ", a.name));
      }
    }
    if (peek().kind != Token::Semicolon) {
      std::string expected;  // "'left', 'phase' or "
      for (size_t i = 0; i < row.args.size(); ++i)
        if (is_optional(row.args[i].kind) && !given[i])
          expected += "'" + std::string(row.args[i].name) + "', ";
      if (expected.empty()) semicolon(k);  // "expected ';' after hinge"
      expected.replace(expected.size() - 2, 2, " or ");
      error(at(peek()),
            "expected " + expected + "';' in " + std::string(k) + ", found " + quote(peek()));
      throw StatementError{};
    }
    next();
  }

  // `include "file" as NAME` then, in any order and each at most once, `position x y z`,
  // `rotation rx ry rz`, `on BODY`, `rigid`; then `;`.
  void include_statement() {
    const Token kw = next();
    IncludeBlock ib;
    ib.at = at(kw);
    ib.inc.line = kw.line;
    ib.seen = statements();
    try {
      if (peek().kind != Token::String) {
        error(at(peek()), "expected the file to include in double quotes, found " + quote(peek()));
        throw StatementError{};
      }
      mark(ib.seen, "file", {}, at(peek()));
      ib.path = std::string(next().text);
      if (peek().kind != Token::Word || peek().text != "as") {
        error(at(peek()),
              "expected 'as' and a name after the included file, found " + quote(peek()));
        throw StatementError{};
      }
      next();
      mark(ib.seen, "as", {}, at(peek()));
      ib.inc.name = std::string(name("the included model's name"));
      while (peek().kind == Token::Word) {
        const std::string_view k = peek().text;
        if (k != "position" && k != "rotation" && k != "on" && k != "rigid") break;
        keyword(next(), "include", {}, ib.seen);
        if (k == "position") ib.position = vec3("include position");
        if (k == "rotation") ib.rotation = vec3("include rotation");
        if (k == "on") ib.on = name("the object the included model stands on");
        if (k == "rigid") ib.inc.rigid = true;
      }
      if (peek().kind != Token::Semicolon) {
        error(at(peek()),
              "expected 'position', 'rotation', 'on', 'rigid' or ';' in include, found " +
                  quote(peek()));
        throw StatementError{};
      }
      next();
      includes_.push_back(std::move(ib));
    } catch (const StatementError&) {
      recover();
    }
  }

  // Reads, checks and adds the model an include names, its names declared; every problem is
  // reported at the include statement (and the included file's own errors at their places).
  void include_into(Model& model, IncludeBlock& ib, Declarations& declared) {
    namespace fs = std::filesystem;
    const Place file_at = place(ib.seen, "file", ib.at);
    const fs::path path = fs::path(file_).parent_path() / ib.path;
    std::error_code ec;
    const std::string canonical = fs::weakly_canonical(path, ec).string();
    for (size_t k = 0; k < stack_.size(); ++k) {
      if (stack_[k] != canonical) continue;
      std::string cycle;
      for (size_t i = k; i < stack_.size(); ++i)
        cycle += fs::path(stack_[i]).filename().string() + " -> ";
      error(file_at, "include cycle: " + cycle + fs::path(canonical).filename().string());
      return;
    }
    std::string text;
    if (!read_file(path.string(), text)) {
      error(file_at, "cannot include '" + ib.path + "' (" + text + ")");
      return;
    }
    stack_.push_back(canonical);
    ParseResult sub = parse_text(text, path.string(), stack_);
    stack_.pop_back();
    for (const Diagnostic& d : sub.diagnostics) {
      if (d.error ? errors_++ < kErrorCap : warnings_++ < kErrorCap) diagnostics_.push_back(d);
    }
    if (!sub.ok()) {
      error(file_at, "'" + ib.path + "' has errors (listed above)");
      return;
    }
    if (ib.on != "world") {
      const auto on = model.find(ib.on);
      if (!on) {
        error(place(ib.seen, "on", ib.at), "unknown object '" + std::string(ib.on) + "'");
        return;
      }
      ib.inc.on = *on;
    }
    try {
      ib.inc.placement = Pose{rotation_from_vector(ib.rotation, "rotation"),
                              check_vector(ib.position, "position", "include position")};
      include_model(model, *sub.model, ib.inc);
    } catch (const ValueError& e) {
      error(place(ib.seen, e.field(), ib.at), "include '" + ib.path + "': " + e.what());
      return;
    } catch (const std::invalid_argument& e) {
      error(place(ib.seen, "as", ib.at),
            "include '" + ib.path + "' as " + ib.inc.name + ": " + e.what());
      return;
    }
    // The included bodies' names are new strings: kept in included_names_ for the views.
    auto declare = [&](std::string name) {
      const std::string_view view = included_names_.emplace_front(std::move(name));
      declared[view] = Declared{ib.at, model.find(view)};
    };
    if (ib.inc.rigid) {
      declare(ib.inc.name);
      rigid_.push_back(ib.inc.name);
      return;
    }
    for (int i = 1; i < sub.model->body_count(); ++i)
      declare(ib.inc.name + "." + sub.model->body(BodyId{i}).name);
  }

  void constraint_block() {
    const Token kw = next();
    ConstraintBlock cb;
    cb.at = at(kw);
    cb.joint.line = kw.line;
    cb.seen = statements();
    Joint& j = cb.joint;
    const long long errors_before = errors_;
    while (!block_end(false, {}, cb.at)) {
      const Token t = next();
      try {
        const std::string_view k = keyword(t, "constraint", {}, cb.seen);
        const ComponentRow* row = find_component(k);
        if (row && row->guide && !cb.guide.empty()) {
          error(at(t), "a constraint has at most one translation guide: '" + std::string(k) +
                           "' after '" + std::string(cb.guide) + "' at line " +
                           std::to_string(place(cb.seen, cb.guide, cb.at).line));
          throw StatementError{};
        }
        if (row && row->coupling && !cb.coupling.empty()) {
          error(at(t), "a constraint has at most one coupling: '" + std::string(k) + "' after '" +
                           std::string(cb.coupling) + "' at line " +
                           std::to_string(place(cb.seen, cb.coupling, cb.at).line));
          throw StatementError{};
        }
        if (row) {
          component_statement(*row, k, cb);
        } else if (k == "object1") {
          cb.object1 = name("an object name");
          semicolon("object1");
        } else if (k == "object2") {
          cb.object2 = name("an object name");
          cb.has_object2 = true;
          semicolon("object2");
        } else if (k == "move") {
          j.move = number("move");
          semicolon("move");
        } else if (k == "time") {
          j.t0 = number("time t0", true);
          j.t1 = number("time t1", true);
          semicolon("time");
        } else if (k == "label") {
          if (peek().kind != Token::String) {
            if (peek().kind != Token::Bad)
              error(at(peek()),
                    "expected a string in double quotes for label, found " + quote(peek()));
            throw StatementError{};
          }
          j.label = std::string(next().text);
          semicolon("label");
        } else {
          std::string known;
          for (const ComponentRow& r : components()) known += std::string(r.keyword) + ", ";
          error(at(t), "unknown constraint statement '" + std::string(k) +
                           "' (expected object1, object2, " + known + "move, time, label or end)");
          throw StatementError{};
        }
      } catch (const StatementError&) {
        recover();
      }
    }
    cb.ok = errors_ == errors_before;
    constraints_.push_back(std::move(cb));
  }

  // Names are resolved and the model checks every block that parsed cleanly, so that each
  // problem is reported once, at the statement it is about.
  ParseResult build() {
    ParseResult result;
    Model model;
    model.reserve(objects_.size() + 1, constraints_.size());
    Declarations declared;
    declared.reserve(objects_.size());
    for (ObjectBlock& ob : objects_) {
      if (ob.name.empty() || ob.name == "world") continue;
      const auto [it, first] = declared.try_emplace(ob.name, Declared{ob.at, std::nullopt});
      if (!first) {
        error(ob.at, "duplicate object '" + std::string(ob.name) + "' (first declared at line " +
                         std::to_string(it->second.at.line) + ")");
        continue;
      }
      if (!ob.ok) continue;
      ob.body.name = std::string(ob.name);
      try {
        it->second.body = model.add_body(std::move(ob.body));
      } catch (const ValueError& e) {
        error(place(ob.seen, e.field(), ob.at), e.what());
      } catch (const std::invalid_argument& e) {
        error(ob.at, e.what());
      }
    }
    for (IncludeBlock& ib : includes_) include_into(model, ib, declared);
    for (ConstraintBlock& cb : constraints_) {
      Joint& j = cb.joint;
      bool ok = cb.ok;
      auto resolve = [&](std::string_view name, const char* keyword, BodyId& out) {
        if (name == "world") {
          out = Model::kWorld;
          return;
        }
        const auto it = declared.find(name);
        if (it == declared.end()) {
          std::string why = "no 'object " + std::string(name) + "' block declares it";
          for (const std::string& r : rigid_) {
            if (name.size() > r.size() && name.compare(0, r.size(), r) == 0 &&
                name[r.size()] == '.')
              why = r + " is a rigid include: its objects are one, '" + r + "'";
          }
          error(place(cb.seen, keyword, cb.at),
                "unknown object '" + std::string(name) + "' (" + why + ")");
          ok = false;
          return;
        }
        if (it->second.body) {
          out = *it->second.body;
        } else {
          ok = false;  // its object block had an error, reported there
        }
      };
      if (!cb.has_object2) {
        error(cb.at, "constraint needs 'object2'");
        ok = false;
      } else {
        resolve(cb.object1, "object1", j.body1);
        resolve(cb.object2, "object2", j.body2);
      }
      if (!ok) continue;
      const size_t warned = model.warnings().size();
      try {
        model.add_joint(std::move(j));
      } catch (const JointError& e) {
        const Place statement = place(cb.seen, e.keyword(), cb.at);
        error(e.arg().empty() ? statement : place(cb.seen, e.keyword(), statement, e.arg()),
              e.detail());
      } catch (const ValueError& e) {
        error(place(cb.seen, e.field(), cb.at), e.what());
      } catch (const std::invalid_argument& e) {
        error(cb.at, e.what());
      }
      for (size_t k = warned; k < model.warnings().size(); ++k) {
        const ModelWarning& w = model.warnings()[k];
        warning(place(cb.seen, w.keyword, cb.at), w.message);
      }
    }
    // The lexer's errors first, then the parser's, up to kErrorCap together.
    const long long lexed = static_cast<long long>(lex_errors_.listed.size()) + lex_errors_.more;
    result.diagnostics.reserve(diagnostics_.size() + lex_errors_.listed.size() + 2);
    for (const LexError& e : lex_errors_.listed)
      result.diagnostics.push_back({file_, e.line, e.column, true, e.message});
    long long parsed = 0;  // the parser's errors so far
    for (Diagnostic& d : diagnostics_) {
      if (!d.error || lexed + parsed++ < kErrorCap) result.diagnostics.push_back(std::move(d));
    }
    errors_ += lexed;
    // One last line for what the cap left out, at the end of the file.
    const Place end = at(current_);
    if (errors_ > kErrorCap) {
      result.diagnostics.push_back({file_, end.line, end.column, true,
                                    std::to_string(errors_ - kErrorCap) +
                                        " more errors (only the first " +
                                        std::to_string(kErrorCap) + " are listed)"});
    }
    if (warnings_ > kErrorCap) {
      result.diagnostics.push_back({file_, end.line, end.column, false,
                                    std::to_string(warnings_ - kErrorCap) +
                                        " more warnings (only the first " +
                                        std::to_string(kErrorCap) + " are listed)"});
    }
    if (errors_ == 0) result.model = std::move(model);
    return result;
  }

  std::string file_;
  LexErrors lex_errors_;
  DclLexer lexer_;
  Token current_;
  std::vector<Mark> statements_;  // every block's marks, in order
  std::vector<Diagnostic> diagnostics_;
  long long errors_ = 0;  // every error of the parser's, listed or not (the lexer's: in build())
  long long warnings_ = 0;
  std::vector<ObjectBlock> objects_;
  std::vector<ConstraintBlock> constraints_;
  std::vector<IncludeBlock> includes_;
  std::vector<std::string> rigid_;                 // the names of rigid includes
  std::forward_list<std::string> included_names_;  // what `declared` views for included bodies
  IncludeStack& stack_;
};

// The file's text, or false and the reason in `text`. In one go: sized from the file when it
// says its size, in chunks otherwise (a pipe).
bool read_file(const std::string& path, std::string& text) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    text = "is a directory, not a .dcl file";
    return false;
  }
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) {
    text = std::string("cannot open the file (") + std::strerror(errno) + ")";
    return false;
  }
  text.clear();
  if (std::fseek(in, 0, SEEK_END) == 0) {
    const long size = std::ftell(in);
    if (size > 0) text.resize(static_cast<size_t>(size));
    std::rewind(in);
  }
  text.resize(std::fread(text.data(), 1, text.size(), in));
  char chunk[1 << 16];
  for (size_t n; (n = std::fread(chunk, 1, sizeof chunk, in)) > 0;) text.append(chunk, n);
  std::fclose(in);
  return true;
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

}  // namespace

ParseResult parse_dcl(std::string_view text, const std::string& filename) {
  // A file's own includes of itself are cycles too.
  IncludeStack stack;
  std::error_code ec;
  if (std::filesystem::is_regular_file(filename, ec))
    stack.push_back(std::filesystem::weakly_canonical(filename, ec).string());
  return parse_text(text, filename, stack);
}

ParseResult load_dcl(const std::string& path) {
  ParseResult r;
  std::string text;
  if (!read_file(path, text)) {
    r.diagnostics.push_back({path, 0, 0, true, text});
    return r;
  }
  return parse_dcl(text, path);
}

}  // namespace dispcon
