// The joint vocabulary: the one table every layer reads (the .dcl reader and writer, the model's
// validation, `to_string`, the Python `add_joint`, the workbench's joint mapping).
//
// Two tables:
// - components(): the statements of a `constraint` block that carry geometry (format.md): `hinge`,
//   the translation guides (seed 4.1), `angle` and `twist` (seed 4.2). Each row says what the
//   statement is written with (points, directions, a radius, a list of points), whether it takes
//   `{min} {max}`, their defaults and their natural range. The couplings of issue 11 (gear, belt,
//   rack, screw) are rows too: their value is a keyword and a number (`ratio 2`), then optional
//   words (`left`) and keyword-number pairs (`phase 0.5`). A new part is a new row plus its case
//   in get_component/set_component.
// - joint_kinds(): the named joints a designer picks (revolute, slider, ball, ...). Each row says
//   which components the joint composes and which limits it takes; make_joint builds a Joint from
//   a row, classify finds the row a Joint matches.
#pragma once

#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dispcon/model/joint.hpp"

namespace dispcon {

// ---------------------------------------------------------------------------------------------
// Components: the statements of a constraint block.

enum class Component {
  Hinge,
  Axial,
  Planar,
  Sphere,
  Circle,
  Cylinder,
  Polyline,
  Angle,
  Twist,
  Gear,
  Belt,
  Rack,
  Screw,
};

// One argument of a component's statement, in the order it is written.
enum class Arg {
  Point,              // three numbers, kept as written
  Direction,          // three numbers, normalised (a zero vector is an error)
  PositiveLength,     // one number > 0
  NonNegativeLength,  // one number >= 0
  Points,             // three numbers per point, at least two points
  NamedPositive,      // the word `name`, then one number > 0 (`ratio 2`)
  Flag,               // optional: the word `name` alone (`left`)
  NamedOption,        // optional: the word `name`, then one number (`phase 0.5`)
};

// Whether an argument may be left out (it is then absent, or false).
bool is_optional(Arg a);

struct ArgSpec {
  Arg kind;
  std::string_view name;  // as format.md writes it: "P1", "u", "r", ...
  int side = 1;           // the object whose frame a point or vector is in (1 or 2)
};

struct Range {
  double min = -kInf;
  double max = kInf;
};

struct ComponentRow {
  Component id;
  std::string_view keyword;              // the .dcl statement
  const char* meaning;                   // one line, for people
  std::optional<GuideKind> guide;        // a translation guide (at most one per joint), or none
  std::vector<ArgSpec> args;             // what follows the keyword, before the bounds
  bool has_bounds = false;               // `{min a} {max b}` follow
  Range defaults;                        // bounds when not given
  Range natural;                         // bounds outside are clamped with a warning
  const char* bound_unit = "";           // "length" or "radians"
  std::optional<CouplingKind> coupling;  // a coupling (at most one per joint), or none
};

// Every component, in the order the writer writes them.
const std::vector<ComponentRow>& components();
const ComponentRow& component(Component id);
const ComponentRow* find_component(std::string_view keyword);
const ComponentRow& component(GuideKind kind);
const ComponentRow& component(CouplingKind kind);

// A list of at most N items held in place: a component's values are read and checked for every
// joint a file holds (the model checks each component it is given), and in place they cost no
// allocation. More than N is a bug in the table (a logic_error).
template <class T, size_t N>
class Few {
 public:
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  Few() = default;
  Few(std::initializer_list<T> items) {
    for (const T& x : items) push_back(x);
  }
  // Only the items held are copied (the rest may be unset: an Eigen vector is not zeroed).
  Few(const Few& other) { *this = other; }
  Few& operator=(const Few& other) {
    for (size_t i = 0; i < other.n_; ++i) items_[i] = other.items_[i];
    n_ = other.n_;
    return *this;
  }

  void push_back(const T& x) {
    if (n_ == N) throw std::logic_error("a component has more values than ComponentValues holds");
    items_[n_++] = x;
  }
  template <class... Args>
  T& emplace_back(Args&&... args) {
    push_back(T(std::forward<Args>(args)...));
    return items_[n_ - 1];
  }
  size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  T& operator[](size_t i) { return items_[i]; }
  const T& operator[](size_t i) const { return items_[i]; }
  T& at(size_t i) { return i < n_ ? items_[i] : throw std::out_of_range("Few::at"); }
  const T& at(size_t i) const { return i < n_ ? items_[i] : throw std::out_of_range("Few::at"); }
  T* begin() { return items_; }
  T* end() { return items_ + n_; }
  const T* begin() const { return items_; }
  const T* end() const { return items_ + n_; }

  friend bool operator==(const Few& a, const Few& b) {
    if (a.n_ != b.n_) return false;
    for (size_t i = 0; i < a.n_; ++i)
      if (!(a.items_[i] == b.items_[i])) return false;
    return true;
  }
  friend bool operator!=(const Few& a, const Few& b) { return !(a == b); }

 private:
  T items_[N];
  size_t n_ = 0;
};

// A component's values in the row's generic form: `vectors` holds the Point and Direction
// arguments in order, `scalars` the lengths and NamedPositive values, `points` a Points argument,
// `flags` the Flag arguments, `options` the NamedOption ones (absent when not given). Each list
// holds as many as the table's rows have at most (a coupling: four vectors); `points` is the one
// list of any length (empty, it allocates nothing).
struct ComponentValues {
  Few<Vec3, 4> vectors;
  Few<double, 1> scalars;
  std::vector<Vec3> points;
  Range bounds;
  Few<bool, 1> flags;
  Few<std::optional<double>, 1> options;
};

bool has_component(const Joint& j, Component id);
ComponentValues get_component(const Joint& j, Component id);
// Sets the component on the joint (a guide replaces any other guide).
void set_component(Joint& j, Component id, const ComponentValues& v);
// The same by the component's row (no search of the table: the model's check of every joint).
bool has_component(const Joint& j, const ComponentRow& row);
void set_component(Joint& j, const ComponentRow& row, const ComponentValues& v);

// ---------------------------------------------------------------------------------------------
// Joint kinds: the named joints.

enum class JointKind {
  Fixed,
  Revolute,
  Slider,
  Cylindrical,
  Ball,
  Planar,
  PointOnLine,
  PointOnPlane,
  PointOnCurve,
  Parallel,
  Perpendicular,
  Angle,
  Distance,
  Gear,
  Belt,
  Rack,
  Screw,
};

// How a kind uses the angle between its two axes.
enum class AngleUse {
  None,
  Fixed,  // min = max = angle_value (0: parallel axes, pi/2: perpendicular)
  Cone,   // optional [0, cone]: a ball's cone
  Range,  // [min, max] given by the `angle` limit (required)
};

// How a kind uses the twist (the turn about the common axis).
enum class TwistUse {
  None,
  Weld,  // min = max = 0: no turn
  Turn,  // optional [min, max] given by the `turn` limit; free without it
};

// The limits a designer may give a joint, each in its natural unit.
enum LimitFlag : unsigned {
  kTurnLimit = 1,      // radians, within [-pi, pi]: the twist
  kTravelLimit = 2,    // length along axis1: the axial guide
  kConeLimit = 4,      // radians, within [0, pi]: a ball's cone
  kAngleLimit = 8,     // radians, within [0, pi]: the angle between the axes
  kDistanceLimit = 16  // length, >= 0: the distance between the points
};

struct JointKindRow {
  JointKind kind;
  const char* name;   // "revolute": Python's kind=, to_string, the writer's comment
  const char* title;  // "Revolute": for menus
  const char* meaning;
  bool hinge = false;              // the two points meet (or are guided, with a guide)
  std::optional<GuideKind> guide;  // point 2 on a line, a plane, a curve, a sphere of point 1
  AngleUse angle = AngleUse::None;
  double angle_value = 0;  // AngleUse::Fixed
  TwistUse twist = TwistUse::None;
  unsigned limits = 0;  // LimitFlag: which limits it takes
  // A coupling between the bodies' turns (issue 11): the anchors' points and axes are its centres
  // and axes (a rack: at2 is a point of the rack and its direction of travel).
  std::optional<CouplingKind> coupling;

  bool needs_axis() const;    // axis1, axis2 are used
  bool needs_across() const;  // across1, across2 (the twist's reference vectors) are used
  bool needs_curve() const;   // a polyline in object1's frame
  bool needs_points() const;  // point1, point2 are used
};

const std::vector<JointKindRow>& joint_kinds();
const JointKindRow& joint_kind(JointKind kind);
const JointKindRow* find_joint_kind(const std::string& name);
const char* to_string(JointKind kind);

// Where a joint meets one of its bodies, in that body's local frame.
struct Anchor {
  Vec3 point = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();    // the joint's axis (a slider's line, a plane's normal)
  Vec3 across = Vec3::UnitX();  // perpendicular to axis: where the turn is measured from
};

// The limits a designer gives; a kind refuses a limit it does not take.
struct JointLimits {
  std::optional<Range> turn;
  std::optional<Range> travel;
  std::optional<double> cone;
  std::optional<Range> angle;
  std::optional<Range> distance;
};

// What a coupling kind takes beside its anchors; the names are its row's of components():
// `value` is the ratio (gear, belt), radius (rack) or pitch (screw).
struct CouplingValues {
  std::optional<double> value;  // required by a coupling kind
  bool left = false;            // a screw only: left-handed
  std::optional<double> phase;  // absent: held at the poses the model has when it is added
};

// Builds the joint a row describes between body1 (at1, the guide's side) and body2 (at2).
// Throws std::invalid_argument naming the kind when a limit is given that it does not take, or a
// required one (angle, distance), a curve or a coupling's value is missing, or coupling values are
// given to a kind without a coupling. Values are checked by Model::add_joint.
Joint make_joint(JointKind kind, BodyId body1, const Anchor& at1, BodyId body2, const Anchor& at2,
                 const JointLimits& limits = {}, const std::vector<Vec3>& curve = {},
                 const CouplingValues& coupling = {});

// The named constructors.
Joint fixed_joint(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2);
Joint revolute(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
               std::optional<Range> turn = {});
Joint slider(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
             std::optional<Range> travel = {});
Joint cylindrical(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
                  std::optional<Range> travel = {}, std::optional<Range> turn = {});
Joint ball(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
           std::optional<double> cone = {});
Joint planar_joint(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2);
Joint point_on_line(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
                    std::optional<Range> travel = {});
Joint point_on_plane(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2);
Joint point_on_curve(BodyId b1, const std::vector<Vec3>& curve, BodyId b2, const Anchor& at2);
Joint parallel(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2);
Joint perpendicular(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2);
Joint angle_joint(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, Range angle);
Joint distance(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, Range distance);
// Couplings: at1 and at2 give each body's centre and axis (a rack: a point and its direction).
Joint gear(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, double ratio,
           std::optional<double> phase = {});
Joint belt(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, double ratio,
           std::optional<double> phase = {});
Joint rack_pinion(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, double radius,
                  std::optional<double> phase = {});
// A cylindrical pair (hinge, axial guide along at1.axis, axes parallel) plus the screw coupling.
Joint screw(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, double pitch,
            bool left = false, std::optional<double> phase = {});

// The first row whose composition the joint has (a revolute whose turn is held at 0 is `fixed`),
// or none for a block that no row names (a custom constraint).
std::optional<JointKind> classify(const Joint& j);
// "revolute", or "constraint" for a custom block.
std::string kind_name(const Joint& j);

}  // namespace dispcon
