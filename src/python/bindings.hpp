// Shared pieces of the bindings: one bind_* function per area, the option parser and the
// Python-side result types (plain structs with the names resolved).
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "dispcon/solve/dynamics.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon::py {

namespace pyb = pybind11;

using ModelClass = pyb::class_<Model>;
ModelClass bind_model(pyb::module_& m);
void bind_solve(pyb::module_& m, ModelClass& model);
void bind_diagnostics(pyb::module_& m, ModelClass& model);
void bind_dynamics(pyb::module_& m, ModelClass& model);
void bind_results(pyb::module_& m);
void bind_vocabulary(pyb::module_& m);

// warnings.warn(message, dispcon.ModelWarning): what the model changed of a caller's values.
void warn(const std::string& message);

// SolveOptions from keyword arguments; ValueError for an unknown name.
SolveOptions solve_options(const pyb::kwargs& kw,
                           const std::vector<std::string>& also_allowed = {});

BodyId body_id(const Model& model, const std::string& name);

// Python values to the engine's types, ValueError naming `what` when the type or shape is wrong;
// the values themselves are checked by the engine.
Vec3 vec3(const pyb::handle& h, const char* what);
// A rotation vector (three numbers) or a 3x3 rotation matrix, as a unit quaternion.
Quat rotation_from(const pyb::handle& rotation, const char* what = "rotation");

struct Report {
  int index = 0, line = 0;
  std::string object1, object2;
  double residual = 0;
  bool satisfied = true, active = true, at_limit = false;
};

struct PySolveResult {
  bool converged = true;
  std::string status, message;
  int iterations = 0, seed_iterations = 0, newton_iterations = 0;
  double max_residual = 0;
  std::vector<int> violated;
  std::vector<Report> constraints;
  std::optional<std::string> out_of_reach;  // a drag step's held body, when out of reach
  double distance_left = 0;
  double angle_left = 0;  // out of reach by its rotation only: the angle left (radians)
};

PySolveResult convert(const Model& model, const SolveResult& r);
std::vector<Report> convert(const Model& model, const std::vector<ConstraintReport>& reports);
std::vector<int> indices(const std::vector<JointId>& ids);

}  // namespace dispcon::py
