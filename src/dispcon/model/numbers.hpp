// The engine's door for numbers. Every number that enters the engine (a .dcl file, the command
// line, Python, the FreeCAD adapter) is checked once, here, by the Model and by the options'
// validate(), never again in a shell: a non-finite value, or one so large that its squares and
// products would overflow inside the solver, is refused with a message naming it and its place.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

#include "dispcon/math/rotation.hpp"

namespace dispcon {

// A value refused at the door. `field` is the .dcl statement or the option it came in
// ("hinge", "rotate", "tolerance", ...), so the reader can point at its line and column.
class ValueError : public std::invalid_argument {
 public:
  ValueError(std::string field, const std::string& message)
      : std::invalid_argument(message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// Largest magnitude of a length, speed, force or time accepted: its square and the products the
// Newton polish forms (about the fourth power) stay far below overflow, and 1e15 still leaves a
// tolerance of 1e-9 meaningful relative to a mechanism's size.
constexpr double kLargest = 1e15;
// Positive physical quantities (mass, inertia, the ability to rotate) lie in [kSmallest,
// kLargest]: their inverses are taken too.
constexpr double kSmallest = 1e-15;
// Largest angle of a rotation vector, radians: beyond, sin and cos keep no correct digit.
constexpr double kLargestAngle = 1e6;

// What a checked value is, as the message of its refusal names it ("object 'crank': center",
// "hinge P1"): up to four pieces, joined only when a message is written, so that a value that
// passes costs no string. It views its pieces: made for a call, never kept.
class What {
 public:
  What(const char* s) : What(std::string_view(s)) {}         // NOLINT: any text reads as one
  What(const std::string& s) : What(std::string_view(s)) {}  // NOLINT
  What(std::string_view a, std::string_view b = {}, std::string_view c = {},
       std::string_view d = {})
      : pieces_{a, b, c, d} {}
  // These pieces and `more` after them (the last piece must be free). Inline, as the checks'
  // accepting paths below: a file's every number passes here.
  What operator+(std::string_view more) const {
    What out = *this;
    for (std::string_view& p : out.pieces_) {
      if (p.empty()) {
        p = more;
        return out;
      }
    }
    throw std::logic_error("What: more than four pieces");
  }
  std::string str() const;

 private:
  std::string_view pieces_[4];
};

// A number as people read it: at most 6 significant digits ("1e+300", "0.25", "-3.14159").
std::string format_number(double v);
std::string format_vector(const Vec3& v);

// The refusals of the checks below, out of line (they build the message).
[[noreturn]] void refuse_number(double v, std::string_view field, const What& what);
[[noreturn]] void refuse_positive(double v, std::string_view field, const What& what);
[[noreturn]] void refuse_vector(const Vec3& v, std::string_view field, const What& what);

// Each returns its (checked) value or throws ValueError "WHAT VALUE is ...". The accepting path
// is inline: one comparison a coordinate (NaN fails it).
// Finite with |v| <= kLargest.
inline double check_number(double v, std::string_view field, const What& what) {
  if (!(std::abs(v) <= kLargest)) refuse_number(v, field, what);
  return v;
}
// In [kSmallest, kLargest].
inline double check_positive(double v, std::string_view field, const What& what) {
  if (!(v >= kSmallest && v <= kLargest)) refuse_positive(v, field, what);
  return v;
}
inline Vec3 check_vector(const Vec3& v, std::string_view field, const What& what) {
  if (!(std::abs(v.x()) <= kLargest && std::abs(v.y()) <= kLargest && std::abs(v.z()) <= kLargest))
    refuse_vector(v, field, what);
  return v;
}
// A direction of any finite length but zero; returns it as a unit vector.
Vec3 check_direction(const Vec3& v, std::string_view field, const What& what);
// A rotation vector (axis times angle, |v| <= kLargestAngle) as a unit quaternion.
Quat rotation_from_vector(const Vec3& v, std::string_view field);
// A 3x3 matrix that is a rotation (orthonormal within 1e-6, determinant +1) as a quaternion.
Quat rotation_from_matrix(const Mat3& R, std::string_view field);
// A placement: position by check_vector, a finite non-zero quaternion, returned normalised
// (unchanged, bit for bit, when it is already of unit length). `what` has a piece free.
Pose check_pose(const Pose& p, std::string_view field, const What& what);

}  // namespace dispcon
