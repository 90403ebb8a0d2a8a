// What the command line prints: JSON documents (cli.md, "JSON"), CSV rows and short text.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/solver.hpp"
#include "json_writer.hpp"

namespace dispcon::cli {

// A member of a JSON object: its key and what writes its value.
struct Member {
  std::string_view key;
  std::function<void(JsonWriter&)> write;
};
// An object of `members`, written in the order of their keys: the documents' keys have always
// been sorted (nlohmann's objects are sorted maps), and a subcommand adds its members to the
// common ones in any order.
void write_object(JsonWriter& w, std::vector<Member> members);

// "bodies": every body but the world, at the given poses, by name in sorted order; each with its
// "dof" too when `dof` is given (index = BodyId::value).
void write_bodies(JsonWriter& w, const Model& model, const std::vector<Pose>& poses,
                  const std::vector<int>* dof = nullptr);
// "constraints": one entry per joint.
void write_constraints(JsonWriter& w, const Model& model,
                       const std::vector<ConstraintReport>& reports);
void write_joint_list(JsonWriter& w, const std::vector<JointId>& ids);
void write_strings(JsonWriter& w, const std::vector<std::string>& strings);
// The common members of every solving document: converged, status, iterations,
// seed_iterations, newton_iterations, max_residual, message, bodies, constraints.
std::vector<Member> solve_members(const Model& model, const SolveResult& result,
                                  const std::vector<int>* body_dof = nullptr);
// Writes the document `write` makes on standard output, with its final new line, at once.
void print_json(const std::function<void(JsonWriter&)>& write);

// One CSV row per body: "<first>,<body>,px,py,pz,qw,qx,qy,qz".
void csv_rows(std::ostream& out, const std::string& first, const Model& model,
              const std::vector<Pose>& poses);

// Text for people: the status line, then the violated joints (if any), then the poses.
void print_solve(std::ostream& out, const Model& model, const SolveResult& result);
void print_poses(std::ostream& out, const Model& model, const std::vector<Pose>& poses);

}  // namespace dispcon::cli
