// libFuzzer target: parse, then assemble and drag, and hold the results to an oracle:
//   nan        no non-finite number comes out (a result's residual, a pose the model keeps);
//   converged  a converged result really satisfies its joints, as measure() sees them;
//   unchanged  a failed assembly or drag leaves every pose bit for bit as it was (a drag of one
//              step that fails has made no step).
// A value refused at the engine's door (std::invalid_argument) is a correct answer.
// With DISPCON_ORACLE_COUNT set, each finding prints "oracle: KIND" and the run goes on, so a run
// over a corpus counts them (docs/testing.md); otherwise the first finding aborts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/solve/solver.hpp"

namespace {

using namespace dispcon;

void finding(const char* kind) {
  std::fprintf(stderr, "oracle: %s\n", kind);
  if (!std::getenv("DISPCON_ORACLE_COUNT")) std::abort();
}

bool finite(const std::vector<Pose>& poses) {
  for (const Pose& p : poses) {
    if (!p.x.allFinite() || !p.q.coeffs().allFinite()) return false;
  }
  return true;
}

// The result of an operation that reported `converged` (or not) on `model`, which held `before`.
void judge(const Model& model, const std::vector<Pose>& before, bool converged, double residual,
           const SolveOptions& o) {
  if (std::isnan(residual) || !finite(model.poses())) finding("nan");
  if (converged) {
    for (const ConstraintReport& c : measure(model, model.poses(), o)) {
      if (!(c.residual <= o.tolerance)) {
        finding("converged");
        break;
      }
    }
  } else if (!same_bits(before, model.poses())) {
    finding("unchanged");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const ParseResult r = parse_dcl(text, "fuzz.dcl");
  if (!r.ok()) return 0;
  SolveOptions o;
  o.max_iterations = 200;
  try {
    Model m = *r.model;
    std::vector<Pose> before = m.poses();
    const SolveResult a = assemble(m, o);
    judge(m, before, a.converged, a.max_residual, o);
    // From the model as read (drag assembles it first), drag the last movable body far away in
    // one step: it usually cannot follow, and then nothing may change.
    Model d = *r.model;
    for (int b = d.body_count() - 1; b > 0; --b) {
      if (d.body(BodyId{b}).fixed) continue;
      before = d.poses();
      Pose target = d.body(BodyId{b}).pose;
      target.x += Vec3(50, 50, 50);
      const DragResult dr = drag(d, BodyId{b}, target, 1, o);
      judge(d, before, dr.converged, dr.max_residual, o);
      break;
    }
  } catch (const std::invalid_argument&) {
    return 0;
  }
  return 0;
}
