// Result types and the option parser.
#include <pybind11/pybind11.h>

#include "bindings.hpp"

namespace dispcon::py {

std::vector<int> indices(const std::vector<JointId>& ids) {
  std::vector<int> out;
  for (JointId j : ids) out.push_back(j.value);
  return out;
}

std::vector<Report> convert(const Model& model, const std::vector<ConstraintReport>& reports) {
  std::vector<Report> out;
  for (const ConstraintReport& c : reports) {
    const Joint& j = model.joint(c.joint);
    out.push_back({c.joint.value, c.line, model.body(j.body1).name, model.body(j.body2).name,
                   c.residual, c.satisfied, c.active, c.at_limit});
  }
  return out;
}

PySolveResult convert(const Model& model, const SolveResult& r) {
  PySolveResult out;
  out.converged = r.converged;
  out.status = to_string(r.status);
  out.message = r.message;
  out.iterations = r.iterations;
  out.seed_iterations = r.seed_iterations;
  out.newton_iterations = r.polish_iterations;
  out.max_residual = r.max_residual;
  out.violated = indices(r.violated());
  out.constraints = convert(model, r.constraints);
  if (r.status == SolveStatus::OutOfReach) out.out_of_reach = model.body(r.held).name;
  out.distance_left = r.distance_left;
  out.angle_left = r.angle_left;
  return out;
}

BodyId body_id(const Model& model, const std::string& name) {
  const auto id = model.find(name);
  if (!id) throw std::invalid_argument("unknown body '" + name + "'");
  return *id;
}

Vec3 vec3(const pyb::handle& h, const char* what) {
  try {
    return h.cast<Vec3>();
  } catch (const pyb::cast_error&) {
    throw std::invalid_argument(std::string(what) + " must be three numbers");
  }
}

Quat rotation_from(const pyb::handle& rotation, const char* what) {
  const pyb::array_t<double> a = pyb::array_t<double>::ensure(rotation);
  if (a && a.ndim() == 2) {
    if (a.shape(0) != 3 || a.shape(1) != 3)
      throw std::invalid_argument(std::string(what) + ": a matrix must be 3x3");
    return rotation_from_matrix(rotation.cast<Mat3>(), what);
  }
  try {
    return rotation_from_vector(rotation.cast<Vec3>(), what);
  } catch (const pyb::cast_error&) {
    throw std::invalid_argument(std::string(what) +
                                " must be a rotation vector (three numbers) or a 3x3 matrix");
  }
}

namespace {

// A keyword argument as T; ValueError naming it when it is not one (2**40 is no int).
template <typename T>
T argument(const pyb::handle& v, const std::string& key, const char* expected) {
  try {
    return v.cast<T>();
  } catch (const pyb::cast_error&) {
    throw std::invalid_argument(key + " must be " + expected + ", not " +
                                std::string(pyb::str(pyb::repr(v))));
  }
}

}  // namespace

SolveOptions solve_options(const pyb::kwargs& kw, const std::vector<std::string>& also_allowed) {
  SolveOptions o;
  for (const auto& item : kw) {
    const std::string key = pyb::str(item.first);
    const pyb::handle v = item.second;
    auto number = [&] { return argument<double>(v, key, "a number"); };
    auto flag = [&] { return argument<bool>(v, key, "True or False"); };
    if (key == "tolerance") {
      o.tolerance = number();
    } else if (key == "max_iterations") {
      o.max_iterations = argument<int>(v, key, "an int of at most 2**31 - 1");
    } else if (key == "time") {
      o.time = number();
    } else if (key == "scheme") {
      const std::string s = argument<std::string>(v, key, "a string");
      if (s == "jacobi") {
        o.scheme = Scheme::Jacobi;
      } else if (s == "gauss-seidel") {
        o.scheme = Scheme::GaussSeidel;
      } else {
        throw std::invalid_argument("scheme must be 'jacobi' or 'gauss-seidel', not '" + s + "'");
      }
    } else if (key == "relaxation") {
      o.relaxation = number();
    } else if (key == "seed_weights") {
      o.seed_weights = flag();
    } else if (key == "max_rotation_step") {
      o.max_rotation_step = number();
    } else if (key == "translate_after_rotate") {
      o.translate_after_rotate = flag();
    } else if (key == "use_physics") {
      o.use_physics = flag();
    } else if (key == "newton_polish") {
      o.newton_polish = flag();
    } else if (key == "polish_below") {
      o.polish_below = number();
    } else if (std::find(also_allowed.begin(), also_allowed.end(), key) == also_allowed.end()) {
      throw std::invalid_argument("unknown option '" + key + "'");
    }
  }
  validate(o);  // the engine's check, early: before anything runs
  return o;
}

void bind_results(pyb::module_& m) {
  pyb::class_<Report>(m, "ConstraintReport", "One joint as a solve left it.")
      .def_readonly("index", &Report::index)
      .def_readonly("line", &Report::line)
      .def_readonly("object1", &Report::object1)
      .def_readonly("object2", &Report::object2)
      .def_readonly("residual", &Report::residual)
      .def_readonly("satisfied", &Report::satisfied)
      .def_readonly("active", &Report::active)
      .def_readonly("at_limit", &Report::at_limit)
      .def("__repr__", [](const Report& r) {
        return "<ConstraintReport #" + std::to_string(r.index) + " line " + std::to_string(r.line) +
               " " + r.object1 + "/" + r.object2 + " residual " + std::to_string(r.residual) + ">";
      });
  pyb::class_<PySolveResult>(m, "SolveResult", "What a solve did and where it failed.")
      .def_readonly("converged", &PySolveResult::converged)
      .def_readonly("status", &PySolveResult::status)
      .def_readonly("message", &PySolveResult::message)
      .def_readonly("iterations", &PySolveResult::iterations)
      .def_readonly("seed_iterations", &PySolveResult::seed_iterations)
      .def_readonly("newton_iterations", &PySolveResult::newton_iterations)
      .def_readonly("max_residual", &PySolveResult::max_residual)
      .def_readonly("violated", &PySolveResult::violated)
      .def_readonly("constraints", &PySolveResult::constraints)
      .def_readonly("out_of_reach", &PySolveResult::out_of_reach,
                    "A drag step whose target the linkage cannot reach: the held body's name "
                    "(else None); distance_left is how far it stays from the target at least.")
      .def_readonly("distance_left", &PySolveResult::distance_left)
      .def_readonly("angle_left", &PySolveResult::angle_left,
                    "Out of reach by its rotation only (distance_left within the tolerance): the "
                    "angle in radians between the held body's rotation at the nearest pose and "
                    "the target's; else 0.")
      .def("__bool__", [](const PySolveResult& r) { return r.converged; })
      .def("__repr__", [](const PySolveResult& r) { return "<SolveResult " + r.message + ">"; });
}

}  // namespace dispcon::py
