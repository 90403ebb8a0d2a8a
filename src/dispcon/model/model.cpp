#include "dispcon/model/model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "dispcon/model/bounds_error.hpp"
#include "dispcon/model/joint_kinds.hpp"
#include "dispcon/parts/coupling.hpp"

namespace dispcon {

namespace {

// The message a literal: made a string only for a refusal (a std::string parameter built one,
// on the heap, for every body accepted).
void require(bool ok, const char* message) {
  if (!ok) throw std::invalid_argument(message);
}

// `who` names the object ("object 'crank'"), in three pieces.
void check_inertia(const Mat3& J, const What& who) {
  for (int i = 0; i < 9; ++i) check_number(J.data()[i], "inertia", who + ": inertia");
  if ((J - J.transpose()).norm() > 1e-12 * std::max(1.0, J.norm()))
    throw ValueError("inertia", who.str() + ": inertia is not symmetric");
  // Its principal moments: positive (positive definite) and within range, since the solver
  // inverts it.
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(J, Eigen::EigenvaluesOnly);
  const Vec3 moments = eig.eigenvalues();
  if (!(moments.minCoeff() > 0))
    throw ValueError("inertia", who.str() + ": inertia is not positive definite");
  check_positive(moments.minCoeff(), "inertia", who + ": smallest principal inertia");
  check_positive(moments.maxCoeff(), "inertia", who + ": largest principal inertia");
}

// Valid UTF-8 (no overlong forms, no surrogates, at most U+10FFFF): what Python and FreeCAD hold.
bool is_utf8(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    int extra = 0;
    unsigned lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
    if (c < 0x80) {
      ++i;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      extra = 1;
    } else if (c >= 0xE0 && c <= 0xEF) {
      extra = 2;
      if (c == 0xE0) lo = 0xA0;
      if (c == 0xED) hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      extra = 3;
      if (c == 0xF0) lo = 0x90;
      if (c == 0xF4) hi = 0x8F;
    } else {
      return false;
    }
    if (i + extra >= s.size()) return false;
    for (int k = 1; k <= extra; ++k) {
      const unsigned char b = static_cast<unsigned char>(s[i + k]);
      if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return false;
    }
    i += extra + 1;
  }
  return true;
}

// "constraint at line N" (or "constraint", built in code): what a joint's refusal begins with,
// built only for a refusal.
std::string joint_who(int line) {
  return "constraint" + (line ? " at line " + std::to_string(line) : "");
}

// Checks and normalises one component of a joint by its row: every argument, then the bounds
// (NaN and min above max are errors; outside the natural range is clamped with a warning).
class ComponentCheck {
 public:
  // `who`: what a refusal begins with ("constraint at line 12"), called only for a refusal.
  ComponentCheck(const std::function<std::string()>& who, const ComponentRow& row,
                 std::vector<std::string>& warnings)
      : who_(who), row_(row), warnings_(warnings) {}

  void operator()(ComponentValues& v) const {
    size_t vec = 0, scalar = 0, option = 0;
    for (const ArgSpec& a : row_.args) {
      const What what(row_.keyword, " ", a.name);
      switch (a.kind) {
        case Arg::Point:
          door(a, [&] { check_vector(v.vectors.at(vec), row_.keyword, what); });
          ++vec;
          break;
        case Arg::Direction:
          door(a,
               [&] { v.vectors.at(vec) = check_direction(v.vectors.at(vec), row_.keyword, what); });
          ++vec;
          break;
        case Arg::PositiveLength:
        case Arg::NonNegativeLength:
        case Arg::NamedPositive: {
          const double r = v.scalars.at(scalar++);
          const bool positive = a.kind != Arg::NonNegativeLength;
          door(a, [&] { check_number(r, row_.keyword, what); });
          if (r < 0 || (positive && r == 0))
            fail(what.str() + (positive ? " must be positive" : " must not be negative") +
                     ", found " + format_number(r),
                 a.name);
          break;
        }
        case Arg::Points:
          if (v.points.size() < 2) fail(what.str() + ": at least two points are needed", a.name);
          for (const Vec3& p : v.points)
            door(a, [&] { check_vector(p, row_.keyword, what + " point"); });
          break;
        case Arg::Flag:
          break;
        case Arg::NamedOption:
          if (option < v.options.size() && v.options[option])
            door(a, [&] { check_number(*v.options[option], row_.keyword, what); });
          ++option;
          break;
      }
    }
    if (row_.has_bounds) bounds(v.bounds);
  }

 private:
  [[noreturn]] void fail(const std::string& detail, std::string_view arg = {}) const {
    throw JointError(who_(), std::string(row_.keyword), detail, std::string(arg));
  }

  // The door's checks (numbers.hpp), their message placed at this argument of the statement.
  template <class Check>
  void door(const ArgSpec& a, Check check) const {
    try {
      check();
    } catch (const ValueError& e) {
      fail(e.what(), a.name);
    }
  }

  // Each bound a number within range or an infinity (no bound); min not above max.
  void bounds(Range& b) const {
    const std::string_view what = row_.keyword;
    const ArgSpec lo{Arg::NamedOption, "min"}, hi{Arg::NamedOption, "max"};
    if (!std::isinf(b.min)) door(lo, [&] { check_number(b.min, what, What(what, " min")); });
    if (!std::isinf(b.max)) door(hi, [&] { check_number(b.max, what, What(what, " max")); });
    if (b.min > b.max) {
      const auto unit = std::string_view(row_.bound_unit) == "radians" ? BoundsError::Unit::Angle
                                                                       : BoundsError::Unit::Length;
      throw BoundsError(who_(), std::string(what),
                        std::string(what) + ": min " + format_number(b.min) + " is above max " +
                            format_number(b.max),
                        b.min, b.max, unit);
    }
    clamp(b.min, "min");
    clamp(b.max, "max");
  }

  void clamp(double& v, const char* which) const {
    const Range n = row_.natural;
    if (v >= n.min && v <= n.max) return;
    const double c = v < n.min ? n.min : n.max;
    warnings_.push_back(std::string(row_.keyword) + " " + which + " " + format_number(v) +
                        " is outside [" + format_number(n.min) + ", " + format_number(n.max) +
                        "]; clamped to " + format_number(c));
    v = c;
  }

  const std::function<std::string()>& who_;
  const ComponentRow& row_;
  std::vector<std::string>& warnings_;
};

Frame frame(const Body& b) {
  return Frame{b.pose.rotation(), b.pose.x, b.world_center()};
}

}  // namespace

bool is_valid_name(std::string_view name) {
  const char first = name.empty() ? '\0' : name[0];
  if (!((first >= 'a' && first <= 'z') || (first >= 'A' && first <= 'Z'))) return false;
  // A name's bytes by one table (is_name_char's six comparisons a byte before: every body added
  // passes here).
  static const auto kNameBytes = [] {
    std::array<bool, 256> t{};
    for (int c = 0; c < 256; ++c) t[static_cast<size_t>(c)] = is_name_char(static_cast<char>(c));
    return t;
  }();
  return std::all_of(name.begin(), name.end(),
                     [](char c) { return kNameBytes[static_cast<unsigned char>(c)]; });
}

JointError::JointError(const std::string& who, std::string keyword, std::string detail,
                       std::string arg)
    : ValueError(std::move(keyword), who + ": " + detail),
      detail_(std::move(detail)),
      arg_(std::move(arg)) {}

Model::Model() {
  Body world;
  world.name = "world";
  world.fixed = true;
  bodies_.push_back(world);
  by_name_.emplace("world", 0);
}

BodyId Model::add_body(Body body) {
  // Messages are built only for a refusal: a model of thousands of bodies is read at memory speed.
  const What who("object '", body.name, "'");
  require(!body.name.empty(), "an object needs a name");
  if (!is_valid_name(body.name)) {
    throw std::invalid_argument(
        "object name '" + body.name +
        "' cannot be written in a .dcl file: a name starts with a letter and holds only "
        "letters, digits, '-', '_' and '.'");
  }
  require(std::string_view(body.name) != "world", "'world' is reserved for the fixed world frame");
  // The name's entry made at once (one hash and one lookup, where a count and an emplace took
  // two), and taken back if a value is refused.
  const BodyId id{static_cast<int>(bodies_.size())};
  const auto [entry, fresh] = by_name_.try_emplace(body.name, id.value);
  if (!fresh) throw std::invalid_argument("duplicate object '" + body.name + "'");
  try {
    body.pose = check_pose(body.pose, "position", who);
    check_vector(body.center, "center", who + ": center");
    if (body.rotate) check_positive(*body.rotate, "rotate", who + ": rotate");
    if (body.mass) check_positive(*body.mass, "mass", who + ": mass");
    if (body.inertia) check_inertia(*body.inertia, who);
    check_vector(body.velocity, "velocity", who + ": velocity");
    check_vector(body.spin, "spin", who + ": spin");
    check_vector(body.force, "force", who + ": force");
    check_vector(body.torque, "torque", who + ": torque");
    bodies_.push_back(std::move(body));
  } catch (...) {
    by_name_.erase(entry);
    throw;
  }
  ++revision_;
  return id;
}

JointId Model::add_joint(Joint j) {
  const std::function<std::string()> who = [&j] { return joint_who(j.line); };
  auto fail = [&](const char* keyword, const std::string& detail) {
    throw JointError(who(), keyword, detail);
  };
  auto valid = [&](BodyId b) { return b.value >= 0 && b.value < body_count(); };
  if (!valid(j.body1)) fail("object1", "object1 is not a body of the model");
  if (!valid(j.body2)) fail("object2", "object2 is not a body of the model");
  if (j.body1 == j.body2)
    fail("object2", "object1 and object2 are the same object '" + body(j.body1).name + "'");
  // A point guide is the hinge itself (seed 3): kept as the hinge, which the writer can write.
  if (j.guide && j.guide->kind == GuideKind::Point) {
    j.has_hinge = true;
    j.guide.reset();
  }
  if (!j.has_translation() && !j.angle && !j.coupling && !j.same_rotation)
    fail("", "no component: give a hinge, a translation guide, an angle or a coupling");
  if (j.same_rotation && (j.angle || j.coupling))
    fail("", "a same rotation takes no angle, twist or coupling");
  if (j.twist && !j.angle) fail("twist", "twist needs an angle (it uses the angle's vectors)");
  const JointId id{static_cast<int>(joints_.size())};
  std::vector<ModelWarning> clamped;  // kept only if the joint is accepted
  for (const ComponentRow& row : components()) {
    if (!has_component(j, row)) continue;
    ComponentValues v = get_component(j, row.id);
    std::vector<std::string> messages;
    ComponentCheck(who, row, messages)(v);
    set_component(j, row, v);
    for (std::string& m : messages) clamped.push_back({id, std::string(row.keyword), std::move(m)});
  }
  if (j.coupling) {
    // Its values were checked by its row above; here, whether its turns can be measured.
    CouplingSpec& c = *j.coupling;
    const CouplingMeasure m =
        measure_coupling(c, frame(body(j.body1)), frame(body(j.body2)), false);
    if (!m.valid) {
      fail(to_string(c.kind),
           std::string(to_string(c.kind)) +
               (c.kind == CouplingKind::Screw
                    ? ": the axes are not aligned (a screw needs a cylindrical pair)"
                    : ": the turn has no reference (the line of centres or the rack lies along "
                      "an axis)"));
    }
    // Made at the model's poses unless a phase is given: the equation holds there.
    if (!c.phase) {
      const double turns[2] = {m.theta[0], m.theta[1]};
      c.phase = coupling_residual(m, turns, 0);
    }
  }
  if (j.move && !(*j.move >= 0 && *j.move <= 1))
    fail("move", "move " + format_number(*j.move) + " is not in [0, 1]");
  if (std::isnan(j.t0) || std::isnan(j.t1) || !(j.t0 <= j.t1))
    fail("time", "time interval must have t0 <= t1");
  if (!is_utf8(j.label)) fail("label", "label is not valid UTF-8");
  warnings_.insert(warnings_.end(), clamped.begin(), clamped.end());
  joints_.push_back(std::move(j));
  ++revision_;
  return id;
}

std::optional<BodyId> Model::find(std::string_view name) const {
  auto it = by_name_.find(std::string(name));
  if (it == by_name_.end()) return std::nullopt;
  return BodyId{it->second};
}

std::vector<Pose> Model::poses() const {
  std::vector<Pose> out;
  out.reserve(bodies_.size());
  for (const Body& b : bodies_) out.push_back(b.pose);
  return out;
}

void Model::set_poses(const std::vector<Pose>& poses) {
  require(poses.size() == bodies_.size(), "set_poses: one pose per body expected");
  std::vector<Pose> checked(poses.size());
  for (size_t i = 1; i < bodies_.size(); ++i)
    checked[i] = check_pose(poses[i], "position", What("object '", bodies_[i].name, "'"));
  // A coupling's phase moves on by the whole turns its wrapped turns drop on the way (each turn
  // taken the short way round, or near half a turn the way its equation holds; from poses where
  // it held, the whole turns that make it hold again: unwrap_read), so the couplings hold through
  // full turns.
  std::vector<CouplingMeasure> before;
  for (const Joint& j : joints_) {
    if (j.coupling) {
      before.push_back(
          measure_coupling(*j.coupling, frame(body(j.body1)), frame(body(j.body2)), false));
    }
  }
  for (size_t i = 1; i < bodies_.size(); ++i) bodies_[i].pose = checked[i];
  size_t k = 0;
  for (Joint& j : joints_) {
    if (!j.coupling) continue;
    const CouplingMeasure& old = before[k++];
    const CouplingMeasure now =
        measure_coupling(*j.coupling, frame(body(j.body1)), frame(body(j.body2)), false);
    double turns[2];
    unwrap_read(now, old.theta, *j.coupling->phase, turns, coupling_held(old, *j.coupling->phase));
    for (int i = 0; i < now.angles; ++i) {
      *j.coupling->phase += now.k[i] * (now.theta[i] - turns[i]);
    }
  }
}

Body& Model::movable_body(BodyId id, const char* what) {
  if (id.value <= 0 || id.value >= body_count()) {
    throw std::invalid_argument(std::string(what) + ": " +
                                (id == kWorld ? "the world cannot change" : "no such body"));
  }
  return bodies_[static_cast<size_t>(id.value)];
}

void Model::set_pose(BodyId id, const Pose& pose) {
  movable_body(id, "set_pose");
  std::vector<Pose> all = poses();  // through set_poses, so that the couplings count turns
  all[static_cast<size_t>(id.value)] = pose;
  set_poses(all);
}

void Model::set_speeds(BodyId id, const Vec3& velocity, const Vec3& spin) {
  Body& b = movable_body(id, "set_speeds");
  check_vector(velocity, "velocity", What("object '", b.name, "': velocity"));
  check_vector(spin, "spin", What("object '", b.name, "': spin"));
  b.velocity = velocity;
  b.spin = spin;
}

void Model::set_fixed(BodyId id, bool fixed) {
  movable_body(id, "set_fixed").fixed = fixed;
  ++revision_;
}

void Model::set_mass(BodyId id, std::optional<double> mass) {
  Body& b = movable_body(id, "set_mass");
  if (mass) check_positive(*mass, "mass", What("object '", b.name, "': mass"));
  b.mass = mass;
  ++revision_;
}

void Model::set_rotate(BodyId id, std::optional<double> rotate) {
  Body& b = movable_body(id, "set_rotate");
  if (rotate) check_positive(*rotate, "rotate", What("object '", b.name, "': rotate"));
  b.rotate = rotate;
  ++revision_;
}

void Model::set_hinge(JointId id, const std::optional<Vec3>& p1, const std::optional<Vec3>& p2) {
  if (id.value < 0 || id.value >= joint_count())
    throw std::invalid_argument("no joint " + std::to_string(id.value));
  Joint& j = joints_[static_cast<size_t>(id.value)];
  const std::string who = "joint " + std::to_string(id.value);
  if (!j.has_hinge) throw std::invalid_argument(who + " has no hinge");
  if (p1) check_vector(*p1, "hinge", who + ": hinge P1");
  if (p2) check_vector(*p2, "hinge", who + ": hinge P2");
  if (p1) j.p1 = *p1;
  if (p2) j.p2 = *p2;
}

void Model::set_twist_range(JointId id, double min, double max) {
  if (id.value < 0 || id.value >= joint_count())
    throw std::invalid_argument("no joint " + std::to_string(id.value));
  Joint& j = joints_[static_cast<size_t>(id.value)];
  const std::string who = "joint " + std::to_string(id.value);
  if (!j.twist) throw std::invalid_argument(who + " has no twist");
  // Checked and clamped by the twist's row, as add_joint does.
  ComponentValues v = get_component(j, Component::Twist);
  v.bounds = {min, max};
  std::vector<std::string> messages;
  ComponentCheck([&who] { return who; }, component(Component::Twist), messages)(v);
  for (std::string& m : messages) warnings_.push_back({id, "twist", std::move(m)});
  j.twist->min = v.bounds.min;
  j.twist->max = v.bounds.max;
}

double Model::ability_to_rotate(BodyId id) const {
  return abilities_to_rotate().at(static_cast<size_t>(id.value));
}

std::vector<double> Model::abilities_to_rotate() const {
  std::vector<double> sum(bodies_.size(), 0.0);
  std::vector<int> count(bodies_.size(), 0);
  auto add = [&](BodyId id, const Vec3& p) {
    const size_t i = static_cast<size_t>(id.value);
    sum[i] += (p - bodies_[i].center).squaredNorm();
    ++count[i];
  };
  for (const Joint& j : joints_) {
    if (!j.has_translation()) continue;
    if (j.guide && j.guide->kind == GuideKind::Polyline) {
      for (const Vec3& p : j.guide->points) add(j.body1, p);
    } else {
      add(j.body1, j.p1);
    }
    add(j.body2, j.p2);
  }
  std::vector<double> k(bodies_.size(), 1.0);
  for (size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].rotate) {
      k[i] = *bodies_[i].rotate;
    } else if (count[i] > 0 && sum[i] > 0) {
      k[i] = count[i] / sum[i];  // 1 / rho^2, rho the RMS distance
    }
  }
  return k;
}

double Model::move_share(JointId id) const {
  const Joint& j = joint(id);
  const Body& b1 = body(j.body1);
  const Body& b2 = body(j.body2);
  if (b1.fixed) return 0.0;
  if (b2.fixed) return 1.0;
  if (j.move) return *j.move;
  if (b1.mass && b2.mass) return *b2.mass / (*b1.mass + *b2.mass);
  return 0.5;
}

}  // namespace dispcon
