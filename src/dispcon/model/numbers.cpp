#include "dispcon/model/numbers.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace dispcon {

std::string What::str() const {
  std::string out;
  for (const std::string_view p : pieces_) out += p;
  return out;
}

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string format_vector(const Vec3& v) {
  return format_number(v.x()) + " " + format_number(v.y()) + " " + format_number(v.z());
}

// Called only for a value the inline check refused: the same tests, in the same order, name
// what is wrong.
void refuse_number(double v, std::string_view field, const What& what) {
  if (std::isnan(v)) throw ValueError(std::string(field), what.str() + " is not a number (nan)");
  throw ValueError(std::string(field), what.str() + " " + format_number(v) +
                                           " is out of range (at most " + format_number(kLargest) +
                                           " in magnitude)");
}

void refuse_positive(double v, std::string_view field, const What& what) {
  if (std::isnan(v)) throw ValueError(std::string(field), what.str() + " is not a number (nan)");
  throw ValueError(std::string(field), what.str() + " " + format_number(v) + " is out of range [" +
                                           format_number(kSmallest) + ", " +
                                           format_number(kLargest) + "]");
}

void refuse_vector(const Vec3& v, std::string_view field, const What& what) {
  for (int k = 0; k < 3; ++k) {
    if (std::isnan(v[k]) || !(std::abs(v[k]) <= kLargest)) {
      throw ValueError(std::string(field),
                       what.str() + " (" + format_vector(v) + ") is " +
                           (std::isnan(v[k]) ? std::string("not a number (nan)")
                                             : "out of range (at most " + format_number(kLargest) +
                                                   " in magnitude)"));
    }
  }
  throw std::logic_error("refuse_vector: the vector is within range");
}

Vec3 check_direction(const Vec3& v, std::string_view field, const What& what) {
  if (!v.allFinite())
    throw ValueError(std::string(field), what.str() + " (" + format_vector(v) + ") is not finite");
  // Scaled first, so a direction such as (1e200, 1e200, 0) does not overflow to a zero vector.
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0)) throw ValueError(std::string(field), what.str() + " is a zero vector");
  // Already of unit length (as the writer wrote it): kept bit for bit, so that writing and
  // reading back gives the same model.
  if (std::abs(v.squaredNorm() - 1) <= 4 * std::numeric_limits<double>::epsilon()) return v;
  const Vec3 u = v / largest;
  return u / u.norm();
}

Quat rotation_from_vector(const Vec3& v, std::string_view field) {
  if (!v.allFinite() || !(v.norm() <= kLargestAngle)) {
    throw ValueError(
        std::string(field),
        "rotation vector (" + format_vector(v) + ") is " +
            (v.allFinite() ? "out of range (at most " + format_number(kLargestAngle) + " radians)"
                           : std::string("not finite")));
  }
  return quat_from_rotation_vector(v);
}

Quat rotation_from_matrix(const Mat3& R, std::string_view field) {
  if (!R.allFinite() || !(R.transpose() * R).isIdentity(1e-6) || !(R.determinant() > 0)) {
    throw ValueError(std::string(field),
                     "the 3x3 matrix is not a rotation (orthonormal, determinant +1)");
  }
  return Quat(R).normalized();
}

Pose check_pose(const Pose& p, std::string_view field, const What& what) {
  Pose out;
  out.x = check_vector(p.x, field, what + " position");
  if (!p.q.coeffs().allFinite())
    throw ValueError(std::string(field), what.str() + " rotation is not finite");
  const double largest = p.q.coeffs().cwiseAbs().maxCoeff();
  if (!(largest > 0))
    throw ValueError(std::string(field), what.str() + " rotation is a zero quaternion");
  out.q = p.q;
  if (std::abs(p.q.norm() - 1) > 1e-15) {
    out.q.coeffs() /= largest;  // scaled first: (1e200, 0, 0, 0) must not overflow
    out.q.normalize();
  }
  return out;
}

}  // namespace dispcon
