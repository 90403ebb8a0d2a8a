// Solving: assembly, a solve with held bodies, dragging (whole paths or live, step by step).
#include "bindings.hpp"

namespace dispcon::py {

namespace {

struct PyDragResult {
  bool converged = true;
  int iterations = 0, failed_step = -1;
  double max_residual = 0;
  std::string message;
  std::vector<PySolveResult> steps;
};

// A live drag: the session is built once, each move_to is one frame.
struct PyDragger {
  Model* model;
  Dragger dragger;
  BodyId body;
};

// A mouse drag by a grabbed point: each pull_to is one frame.
struct PyPuller {
  Model* model;
  Puller puller;
};

// Repeated solves of one model whose structure stays (a mouse drag with a moving target joint).
struct PySession {
  Model* model;
  Session session;
  PySolveResult solve(bool keep_best) {
    std::vector<Pose> poses = model->poses();
    const SolveResult r = session.solve(poses);
    if (r.converged) {
      model->set_poses(poses);
    } else if (keep_best && r.status != SolveStatus::Diverged) {
      model->set_poses(r.poses);
    }
    return convert(*model, r);
  }
};

// The target of a drag: the body's pose with what is given replaced (checked by the engine).
Pose target_pose(const Model& model, BodyId body, const pyb::object& position,
                 const pyb::object& rotation) {
  Pose p = model.body(body).pose;
  if (!position.is_none()) p.x = vec3(position, "position");
  if (!rotation.is_none()) p.q = rotation_from(rotation);
  return p;
}

}  // namespace

void bind_solve(pyb::module_& m, ModelClass& model) {
  pyb::class_<PyDragResult>(m, "DragResult")
      .def_readonly("converged", &PyDragResult::converged)
      .def_readonly("iterations", &PyDragResult::iterations)
      .def_readonly("max_residual", &PyDragResult::max_residual)
      .def_readonly("failed_step", &PyDragResult::failed_step)
      .def_readonly("message", &PyDragResult::message)
      .def_readonly("steps", &PyDragResult::steps)
      .def("__repr__", [](const PyDragResult& r) { return "<DragResult " + r.message + ">"; });

  pyb::class_<PyDragger>(m, "Dragger", "A live drag of one body: call move_to once per frame.")
      .def(
          "move_to",
          [](PyDragger& d, const pyb::object& position, const pyb::object& rotation) {
            const Pose p = target_pose(*d.model, d.body, position, rotation);
            return convert(*d.model, d.dragger.move_to(p));
          },
          pyb::arg("position") = pyb::none(), pyb::arg("rotation") = pyb::none(),
          "Holds the body at this pose (rotation vector or 3x3 matrix) while the rest follows. "
          "The model changes only when the solve converged.");

  pyb::class_<PyPuller>(
      m, "Puller", "A pull by a point of one body (a mouse drag): call pull_to once per frame.")
      .def(
          "pull_to",
          [](PyPuller& p, const pyb::object& target) {
            return convert(*p.model, p.puller.pull_to(vec3(target, "target")));
          },
          pyb::arg("target"),
          "Draws the point toward this world point as near as the joints let it, joints exact. "
          "The model takes the poses reached when the joints hold there: converged when the point "
          "got there, status 'out-of-reach' (distance_left: how far it stays) at the nearest "
          "pose; otherwise the model is left as it was.");

  pyb::class_<PySession>(m, "Session", "Repeated solves of a model whose joints keep their number.")
      .def("solve", &PySession::solve, pyb::arg("keep_best") = false,
           "Solves from the model's poses; the model changes only when it converged, or, with "
           "keep_best, to the best poses reached (a compromise between joints that cannot all "
           "hold, such as a mouse pulling a linkage where it cannot go).");

  model
      .def(
          "session",
          [](Model& self, const pyb::kwargs& kw) {
            return new PySession{&self, Session(self, solve_options(kw))};
          },
          pyb::keep_alive<0, 1>(),
          "A solver state kept between solves; it rebuilds itself when the model changed.")
      .def(
          "set_hinge",
          [](Model& self, int index, const std::optional<Vec3>& p1, const std::optional<Vec3>& p2) {
            self.set_hinge(JointId{index}, p1, p2);
          },
          pyb::arg("index"), pyb::arg("p1") = pyb::none(), pyb::arg("p2") = pyb::none(),
          "Moves a joint's hinge points (a mouse drag's target).")
      .def(
          "assemble",
          [](Model& self, const pyb::kwargs& kw) {
            return convert(self, assemble(self, solve_options(kw)));
          },
          "Automatic assembly (seed 2.3) from the current poses. The model changes only when it "
          "converged. Options: tolerance, max_iterations, scheme, relaxation, newton_polish, ...")
      .def(
          "solve",
          [](Model& self, const std::vector<std::string>& held, const pyb::kwargs& kw) {
            std::vector<bool> h(static_cast<size_t>(self.body_count()), false);
            for (const std::string& name : held)
              h[static_cast<size_t>(body_id(self, name).value)] = true;
            std::vector<Pose> poses = self.poses();
            const SolveResult r = solve(self, poses, solve_options(kw), h);
            if (r.converged) self.set_poses(poses);
            return convert(self, r);
          },
          pyb::arg("held") = std::vector<std::string>{},
          "Like assemble, with the named bodies held where they are.")
      .def(
          "residuals",
          [](const Model& self, const pyb::kwargs& kw) {
            return convert(self, measure(self, self.poses(), solve_options(kw)));
          },
          "Every joint's violation at the current poses; nothing moves.")
      .def(
          "drag",
          [](Model& self, const std::string& name, const pyb::object& position,
             const pyb::object& rotation, int steps, const pyb::kwargs& kw) {
            const BodyId body = body_id(self, name);
            const DragResult d = drag(self, body, target_pose(self, body, position, rotation),
                                      steps, solve_options(kw));
            PyDragResult out;
            out.converged = d.converged;
            out.iterations = d.iterations;
            out.max_residual = d.max_residual;
            out.failed_step = d.failed_step;
            out.message = d.message;
            for (const SolveResult& s : d.steps) out.steps.push_back(convert(self, s));
            return out;
          },
          pyb::arg("name"), pyb::arg("position") = pyb::none(), pyb::arg("rotation") = pyb::none(),
          pyb::arg("steps") = 50,
          "Like `dispcon drag`: assembles, then moves the body in equal steps to the target "
          "(rotation vector or 3x3 matrix) while the rest follows.")
      .def(
          "puller",
          [](Model& self, const std::string& name, const pyb::object& point,
             const pyb::kwargs& kw) {
            const BodyId body = body_id(self, name);
            return new PyPuller{&self, Puller(self, body, vec3(point, "point"), solve_options(kw))};
          },
          pyb::arg("name"), pyb::arg("point"), pyb::keep_alive<0, 1>(),
          "A pull of the body's point (local coordinates) toward world points, the body free to "
          "turn (a mouse drag by a grabbed point; the model is not otherwise changed).")
      .def(
          "dragger",
          [](Model& self, const std::string& name, const pyb::kwargs& kw) {
            const BodyId body = body_id(self, name);
            return new PyDragger{&self, Dragger(self, body, solve_options(kw)), body};
          },
          pyb::arg("name"), pyb::keep_alive<0, 1>(),
          "A live drag of one body (for interactive use: the solver's state is built once).");
}

}  // namespace dispcon::py
