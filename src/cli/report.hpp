// What the command line prints: JSON documents (cli.md, "JSON"), CSV rows and short text.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon::cli {

nlohmann::json pose_json(const Pose& pose);
// "bodies": every body but the world, at the given poses.
nlohmann::json bodies_json(const Model& model, const std::vector<Pose>& poses);
// "constraints": one entry per joint.
nlohmann::json constraints_json(const Model& model, const std::vector<ConstraintReport>& reports);
// The common fields of every document: converged, iterations, max_residual, bodies, constraints.
nlohmann::json solve_json(const Model& model, const SolveResult& result);

// One CSV row per body: "<first>,<body>,px,py,pz,qw,qx,qy,qz".
void csv_rows(std::ostream& out, const std::string& first, const Model& model,
              const std::vector<Pose>& poses);

// Text for people: the status line, then the violated joints (if any), then the poses.
void print_solve(std::ostream& out, const Model& model, const SolveResult& result);
void print_poses(std::ostream& out, const Model& model, const std::vector<Pose>& poses);

}  // namespace dispcon::cli
