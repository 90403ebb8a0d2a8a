// libFuzzer target: any bytes through the reader must give diagnostics or a model, never a crash;
// a model must survive write -> read with the same bodies and joints, and a short solve.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/dcl_writer.hpp"
#include "dispcon/solve/solver.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const dispcon::ParseResult r = dispcon::parse_dcl(text, "fuzz.dcl");
  if (!r.ok()) {
    if (r.diagnostics.empty()) std::abort();  // an error must say where
    return 0;
  }
  const std::string written = dispcon::write_dcl(*r.model);
  const dispcon::ParseResult again = dispcon::parse_dcl(written, "written.dcl");
  if (!again.ok() || again.model->body_count() != r.model->body_count() ||
      again.model->joint_count() != r.model->joint_count()) {
    std::abort();
  }
  dispcon::Model m = *r.model;
  dispcon::SolveOptions o;
  o.max_iterations = 50;
  dispcon::assemble(m, o);
  return 0;
}
