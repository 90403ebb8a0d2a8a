// A model: bodies and joints with typed ids. Body 0 is the fixed world.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "dispcon/model/body.hpp"
#include "dispcon/model/ids.hpp"
#include "dispcon/model/joint.hpp"
#include "dispcon/model/numbers.hpp"

namespace dispcon {

// Names of bodies are what the .dcl format can hold (format.md): an ASCII letter, then letters,
// digits, '-', '_' or '.'. The lexer reads names with the same rule (inline: it asks of every
// byte of a name).
inline bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
         c == '_' || c == '.';
}
bool is_valid_name(std::string_view name);

// A joint refused by the model: a ValueError whose field() is the statement ("axial", "move",
// "object2"; empty for the block as a whole) and arg() the argument of it at fault ("u",
// "ratio"; empty for the statement as a whole), so that the reader can point at its place;
// `detail` is the message without the "constraint at line N: " prefix that what() carries.
class JointError : public ValueError {
 public:
  JointError(const std::string& who, std::string keyword, std::string detail, std::string arg = "");
  const std::string& keyword() const { return field(); }
  const std::string& arg() const { return arg_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string detail_;
  std::string arg_;
};

// What add_joint changed while accepting a joint: a bound clamped into its natural range.
struct ModelWarning {
  JointId joint;
  std::string keyword;  // the statement, as for JointError
  std::string message;
};

// The model is the engine's door: every value reaches it through add_body, add_joint or a
// setter below, each of which checks it (numbers.hpp) and throws std::invalid_argument (a
// ValueError naming the statement) before anything changes. Bodies and joints are read only.
class Model {
 public:
  static constexpr BodyId kWorld{0};

  Model();

  // Throws std::invalid_argument naming the problem (duplicate or reserved name, bad value).
  BodyId add_body(Body body);
  // Throws JointError (a std::invalid_argument) when the joint is malformed (unknown body, same
  // body twice, no component, twist without angle, zero vector, min above max, move outside
  // [0, 1], a label that is not UTF-8). Every component is checked by its row of components()
  // (joint_kinds.hpp); a bound outside its natural range is clamped and recorded in warnings().
  JointId add_joint(Joint joint);
  // The warnings of every joint added so far, in order.
  const std::vector<ModelWarning>& warnings() const { return warnings_; }

  std::optional<BodyId> find(std::string_view name) const;

  // Room for this many bodies and joints in all (a reader that knows its file's counts: the
  // model's vectors then never move their contents as they grow).
  void reserve(size_t bodies, size_t joints) {
    bodies_.reserve(bodies);
    joints_.reserve(joints);
    by_name_.reserve(bodies);
  }

  const Body& body(BodyId id) const { return bodies_.at(static_cast<size_t>(id.value)); }
  const Joint& joint(JointId id) const { return joints_.at(static_cast<size_t>(id.value)); }

  // Counts the changes of what a solver session builds on (bodies, joints, fixed, mass, ability
  // to rotate); poses, speeds and hinge points are read afresh by every solve and do not count.
  // A Session made at an older revision rebuilds itself before it solves.
  std::uint64_t revision() const { return revision_; }

  // Validated setters (world: refused). Each throws before changing anything.
  void set_pose(BodyId id, const Pose& pose);
  void set_speeds(BodyId id, const Vec3& velocity, const Vec3& spin);
  void set_fixed(BodyId id, bool fixed);
  void set_mass(BodyId id, std::optional<double> mass);
  void set_rotate(BodyId id, std::optional<double> rotate);
  // Moves a joint's hinge points (a mouse drag's target); the joint must have a hinge.
  void set_hinge(JointId id, const std::optional<Vec3>& p1, const std::optional<Vec3>& p2);
  // Sets a joint's twist range (a sweep's driver); the joint must have a twist.
  void set_twist_range(JointId id, double min, double max);

  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<Joint>& joints() const { return joints_; }
  int body_count() const { return static_cast<int>(bodies_.size()); }
  int joint_count() const { return static_cast<int>(joints_.size()); }

  // Current poses of every body (index = BodyId::value), and setting them back (the world's
  // is ignored; every other one is checked first: nothing changes when one is refused).
  std::vector<Pose> poses() const;
  void set_poses(const std::vector<Pose>& poses);

  // The no-physics "ability to rotate" used for a body: its `rotate` when given, else
  // 1 / rho^2 with rho the RMS distance from its centre to its constrained points (1 without any).
  double ability_to_rotate(BodyId id) const;
  // The same for every body at once (index = BodyId::value), in one pass over the joints.
  std::vector<double> abilities_to_rotate() const;

  // mu12 used for a joint: its `move`, else m2/(m1+m2) when both have mass, else 0.5;
  // 0 when body1 is fixed, 1 when body2 is fixed (whatever was asked).
  double move_share(JointId id) const;

 private:
  Body& movable_body(BodyId id, const char* what);

  std::vector<Body> bodies_;
  std::vector<Joint> joints_;
  std::vector<ModelWarning> warnings_;
  std::unordered_map<std::string, int> by_name_;
  std::uint64_t revision_ = 0;
};

}  // namespace dispcon
