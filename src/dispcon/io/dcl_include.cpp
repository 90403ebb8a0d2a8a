// `include` statements: parsed with the rest, then the included file read, checked and added to
// the model (include.hpp) once every object is known.
#include <filesystem>

#include "dispcon/io/dcl_parser.hpp"

namespace dispcon::dcl {

void Parser::include_statement() {
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
      error(at(peek()), "expected 'as' and a name after the included file, found " + quote(peek()));
      throw StatementError{};
    }
    skip();
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
      error(at(peek()), "expected 'position', 'rotation', 'on', 'rigid' or ';' in include, found " +
                            quote(peek()));
      throw StatementError{};
    }
    skip();
    includes_.push_back(std::move(ib));
  } catch (const StatementError&) {
    recover();
  }
}

void Parser::include_into(Model& model, IncludeBlock& ib, Declarations& declared) {
  namespace fs = std::filesystem;
  const Place file_at = place(ib.seen, "file", ib.at);
  const fs::path path = fs::path(file_).parent_path() / ib.path;
  std::error_code ec;
  const std::string canonical = fs::weakly_canonical(path, ec).string();
  const std::vector<std::string>& files = stack_.files();
  for (size_t k = 0; k < files.size(); ++k) {
    if (files[k] != canonical) continue;
    std::string cycle;
    for (size_t i = k; i < files.size(); ++i)
      cycle += fs::path(files[i]).filename().string() + " -> ";
    error(file_at, "include cycle: " + cycle + fs::path(canonical).filename().string());
    return;
  }
  FileText text;
  std::string why;
  if (!read_file(path.string(), text, why)) {
    error(file_at, "cannot include '" + ib.path + "' (" + why + ")");
    return;
  }
  stack_.push(canonical);
  ParseResult sub = parse_text(text.view(), path.string(), stack_);
  stack_.pop();
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

}  // namespace dispcon::dcl
