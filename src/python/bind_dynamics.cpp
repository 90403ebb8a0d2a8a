// The physics variant's animation (seed 2.2).
#include "bindings.hpp"
#include "dispcon/io/svg.hpp"

namespace dispcon::py {

namespace {

struct PyFrame {
  double time = 0, max_residual = 0;
  int iterations = 0;
  bool converged = true;
  std::vector<int> violated;
  std::map<std::string, Vec3> positions;
  std::map<std::string, Eigen::Vector4d> quaternions;
  std::map<std::string, std::pair<Vec3, Eigen::Vector4d>> poses;
};

struct PyAnimation {
  bool converged = true, stopped = false;
  int iterations = 0;
  double max_residual = 0;
  std::vector<std::string> warnings;
  std::string message, svg;
  std::vector<PyFrame> frames;
};

}  // namespace

void bind_dynamics(pyb::module_& m, ModelClass& model) {
  pyb::class_<PyFrame>(m, "Frame")
      .def_readonly("time", &PyFrame::time)
      .def_readonly("iterations", &PyFrame::iterations)
      .def_readonly("max_residual", &PyFrame::max_residual)
      .def_readonly("converged", &PyFrame::converged)
      .def_readonly("violated", &PyFrame::violated)
      .def_readonly("positions", &PyFrame::positions, "body name -> position")
      .def_readonly("quaternions", &PyFrame::quaternions, "body name -> (w, x, y, z)")
      .def_readonly("poses", &PyFrame::poses, "body name -> (position, quaternion (w, x, y, z))");
  pyb::class_<PyAnimation>(m, "AnimateResult")
      .def_readonly("converged", &PyAnimation::converged)
      .def_readonly("stopped", &PyAnimation::stopped)
      .def_readonly("iterations", &PyAnimation::iterations)
      .def_readonly("max_residual", &PyAnimation::max_residual)
      .def_readonly("warnings", &PyAnimation::warnings)
      .def_readonly("message", &PyAnimation::message)
      .def_readonly("frames", &PyAnimation::frames)
      .def_readonly("svg", &PyAnimation::svg, "an animated SVG of the frames");

  model.def(
      "animate",
      [](Model& self, double duration, double dt, const Vec3& gravity, bool stop_on_violation,
         const pyb::kwargs& kw) {
        AnimateOptions o;
        o.duration = duration;
        o.dt = dt;
        o.gravity = gravity;
        o.stop_on_violation = stop_on_violation;
        o.solve = solve_options(kw);
        const AnimateResult r = animate(self, o);
        PyAnimation out;
        out.converged = r.converged;
        out.stopped = r.stopped;
        out.iterations = r.iterations;
        out.max_residual = r.max_residual;
        out.warnings = r.warnings;
        out.message = r.message;
        out.svg = write_animation_svg(self, r);
        for (const Frame& f : r.frames) {
          PyFrame pf;
          pf.time = f.time;
          pf.max_residual = f.max_residual;
          pf.iterations = f.iterations;
          pf.converged = f.converged;
          pf.violated = indices(f.violated);
          for (int i = 1; i < self.body_count(); ++i) {
            const Pose& p = f.poses[static_cast<size_t>(i)];
            const std::string& name = self.body(BodyId{i}).name;
            pf.positions[name] = p.x;
            pf.quaternions[name] = Eigen::Vector4d(p.q.w(), p.q.x(), p.q.y(), p.q.z());
            pf.poses[name] = {pf.positions[name], pf.quaternions[name]};
          }
          out.frames.push_back(std::move(pf));
        }
        return out;
      },
      pyb::arg("duration") = 1.0, pyb::arg("dt") = 0.01, pyb::arg("gravity") = Vec3::Zero(),
      pyb::arg("stop_on_violation") = false,
      "Like `dispcon animate`: the physics variant, from the current poses and speeds.");
}

}  // namespace dispcon::py
