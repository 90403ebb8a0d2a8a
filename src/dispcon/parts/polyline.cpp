#include "dispcon/parts/polyline.hpp"

#include <algorithm>
#include <limits>

namespace dispcon {

Nearest nearest_on_polyline(const std::vector<Vec3>& v, const Vec3& p, BoundTest bound) {
  Nearest out;
  double best = std::numeric_limits<double>::infinity();
  size_t best_k = 0;
  double best_t = 0, best_free = 0;  // clamped and unclamped parameter on the best segment
  for (size_t k = 0; k + 1 < v.size(); ++k) {
    const Vec3 s = v[k + 1] - v[k];
    const double len2 = s.squaredNorm();
    const double free = len2 > 0 ? (p - v[k]).dot(s) / len2 : 0.0;
    const double t = std::clamp(free, 0.0, 1.0);
    const double dist2 = (v[k] + t * s - p).squaredNorm();
    if (dist2 < best) best = dist2, best_k = k, best_t = t, best_free = free;
  }
  const Vec3 s = v[best_k + 1] - v[best_k];
  out.q = v[best_k] + best_t * s;
  const double len = s.norm();
  // Contact with an end: the point's projection on the first or last segment is at, beyond, or
  // within `band` of the end.
  const double along = best_free * len;
  const bool first_end = best_k == 0 && along <= bound.band;
  const bool last_end = best_k + 2 == v.size() && len - along <= bound.band;
  if (first_end || last_end) {
    out.at_limit = true;
    out.q = first_end ? v.front() : v.back();
    out.rows = 3;
    out.normals = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    return out;
  }
  Vec3 tangent = unit_or(s, Vec3::UnitX());
  if (best_t >= 1.0 && best_k + 2 < v.size()) {
    tangent = unit_or(tangent + unit_or(v[best_k + 2] - v[best_k + 1], tangent), tangent);
  } else if (best_t <= 0.0 && best_k > 0) {
    tangent = unit_or(tangent + unit_or(v[best_k] - v[best_k - 1], tangent), tangent);
  }
  const Vec3 off = p - out.q;
  out.normals[0] = unit_or(off - off.dot(tangent) * tangent, any_perpendicular(tangent));
  out.normals[1] = tangent.cross(out.normals[0]);
  out.rows = 2;
  return out;
}

}  // namespace dispcon
