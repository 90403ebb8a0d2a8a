// What the subcommands share: the common options, loading a file, naming a body.
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "dispcon/io/dcl_reader.hpp"

namespace dispcon::cli {

void add_common(CLI::App* sub, Common& common, bool solves) {
  sub->add_option("FILE", common.file, "the .dcl file")->required();
  if (solves) {
    // Their values are checked by the engine (validate(SolveOptions)), not here; their defaults
    // are the engine's (SolveOptions), shown by --help.
    sub->add_option("--tolerance", common.tolerance, "largest violation accepted")
        ->capture_default_str();
    sub->add_option("--max-iterations", common.max_iterations, "iteration cap")
        ->capture_default_str();
  }
  sub->add_flag("--json", common.json, "print one JSON document on standard output");
}

SolveOptions options(const Common& common) {
  SolveOptions o;
  o.tolerance = common.tolerance;
  o.max_iterations = common.max_iterations;
  return o;
}

std::optional<Model> load(const std::string& file) {
  ParseResult r = load_dcl(file);
  std::cerr << r.messages();
  return std::move(r.model);
}

BodyId body_named(const Model& model, const std::string& name) {
  const auto id = model.find(name);
  if (!id || *id == Model::kWorld)
    throw CLI::ValidationError("--body", "unknown body '" + name + "'");
  return *id;
}

Vec3 vec(const std::vector<double>& v) {
  return Vec3(v[0], v[1], v[2]);
}

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  return written(out, path);
}

bool written(std::ofstream& out, const std::string& path) {
  out.flush();  // a full disk shows only when the buffer goes out
  if (out) out.close();
  if (!out) std::cerr << path << ": error: cannot write the file\n";
  return !out.fail();
}

}  // namespace dispcon::cli
