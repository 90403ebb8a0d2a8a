// Diagnostics: check (DOF, redundant, conflicting, limits) and sweep (range of motion).
#include "bindings.hpp"
#include "dispcon/io/sweep_plot.hpp"

namespace dispcon::py {

namespace {

struct PyCheck {
  bool converged = true;
  int dof = 0;
  std::map<std::string, int> body_dof;
  std::vector<int> redundant, conflicting, limits_active, locking;
  std::vector<std::string> advice;
  std::string message;
  PySolveResult solve;
};

struct PySample {
  double value = 0, max_residual = 0;
  bool converged = true;
  std::vector<int> limits_active;
  std::vector<double> joint_values;
};

struct PySweep {
  bool locked = false;
  double lock_value = 0;
  std::string message, svg;
  std::vector<PySample> samples;
};

}  // namespace

void bind_diagnostics(pyb::module_& m, ModelClass& model) {
  pyb::class_<PyCheck>(m, "CheckResult")
      .def_readonly("converged", &PyCheck::converged)
      .def_readonly("dof", &PyCheck::dof)
      .def_readonly("body_dof", &PyCheck::body_dof)
      .def_readonly("redundant", &PyCheck::redundant)
      .def_readonly("conflicting", &PyCheck::conflicting)
      .def_readonly("limits_active", &PyCheck::limits_active)
      .def_readonly("locking", &PyCheck::locking,
                    "couplings of a locked mechanism whose removal frees it")
      .def_readonly("advice", &PyCheck::advice)
      .def_readonly("message", &PyCheck::message)
      .def_readonly("solve", &PyCheck::solve)
      .def("__repr__", [](const PyCheck& c) { return "<CheckResult " + c.message + ">"; });
  pyb::class_<PySample>(m, "SweepSample")
      .def_readonly("value", &PySample::value)
      .def_readonly("converged", &PySample::converged)
      .def_readonly("max_residual", &PySample::max_residual)
      .def_readonly("limits_active", &PySample::limits_active)
      .def_readonly("joint_values", &PySample::joint_values);
  pyb::class_<PySweep>(m, "SweepResult")
      .def_readonly("locked", &PySweep::locked)
      .def_readonly("lock_value", &PySweep::lock_value)
      .def_readonly("message", &PySweep::message)
      .def_readonly("samples", &PySweep::samples)
      .def_readonly("svg", &PySweep::svg, "the plot of every joint's value, as SVG text");

  model
      .def(
          "check",
          [](const Model& self, const pyb::kwargs& kw) {
            const CheckResult r = check(self, solve_options(kw));
            PyCheck out;
            out.converged = r.solve.converged;
            out.dof = r.dof;
            for (int i = 1; i < self.body_count(); ++i) {
              out.body_dof[self.body(BodyId{i}).name] = r.body_dof[static_cast<size_t>(i)];
            }
            out.redundant = indices(r.redundant);
            out.conflicting = indices(r.conflicting);
            out.limits_active = indices(r.limits_active);
            out.locking = indices(r.locking);
            out.advice = r.advice;
            out.message = r.message;
            out.solve = convert(self, r.solve);
            return out;
          },
          "Like `dispcon check`: degrees of freedom, redundant and conflicting joints, limits. "
          "The model does not change.")
      .def(
          "sweep",
          [](const Model& self, const std::string& body, const Vec3& axis, double start,
             double stop, int steps, const pyb::kwargs& kw) {
            SweepOptions o;
            o.body = body_id(self, body);
            o.axis = axis;
            o.from = start;
            o.to = stop;
            o.steps = steps;
            o.solve = solve_options(kw);
            const SweepResult r = sweep(self, o);
            PySweep out;
            out.locked = r.locked;
            out.lock_value = r.lock_value;
            out.message = r.message;
            out.svg = write_sweep_svg(self, r);
            for (const SweepSample& s : r.samples) {
              out.samples.push_back(
                  {s.value, s.max_residual, s.converged, indices(s.limits_active), s.joint_values});
            }
            return out;
          },
          pyb::arg("body"), pyb::arg("axis") = Vec3(0, 0, 1), pyb::arg("start") = 0.0,
          pyb::arg("stop") = 2 * kPi, pyb::arg("steps") = 360,
          "Turns a body about an axis through its centre and reports where the mechanism locks.");
}

}  // namespace dispcon::py
