#include "dispcon/io/dcl_writer.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace dispcon {

namespace {

// Full precision, so that reading back gives the same doubles; `inf` for unbounded.
std::string num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string vec(const Vec3& v) {
  return num(v.x()) + " " + num(v.y()) + " " + num(v.z());
}

std::string bounds(double lo, double hi, double default_lo, double default_hi) {
  std::string out;
  if (lo != default_lo) out += " min " + num(lo);
  if (hi != default_hi) out += " max " + num(hi);
  return out;
}

}  // namespace

std::string write_dcl(const Model& model) {
  std::ostringstream out;
  out << "/* written by dispcon */\n";
  for (int i = 1; i < model.body_count(); ++i) {
    const Body& b = model.body(BodyId{i});
    out << "\nobject " << b.name << ";\n";
    out << "  position " << vec(b.pose.x) << ";\n";
    out << "  rotation " << vec(b.pose.rotation_vector()) << ";\n";
    if (b.fixed) out << "  fixed;\n";
    if (b.rotate) out << "  rotate " << num(*b.rotate) << ";\n";
    if (b.mass) out << "  mass " << num(*b.mass) << ";\n";
    if (b.inertia) {
      const Mat3& J = *b.inertia;
      out << "  inertia " << num(J(0, 0)) << " " << num(J(1, 1)) << " " << num(J(2, 2)) << " "
          << num(J(0, 1)) << " " << num(J(0, 2)) << " " << num(J(1, 2)) << ";\n";
    }
    if (b.center != Vec3::Zero()) out << "  center " << vec(b.center) << ";\n";
    if (b.velocity != Vec3::Zero()) out << "  velocity " << vec(b.velocity) << ";\n";
    if (b.spin != Vec3::Zero()) out << "  spin " << vec(b.spin) << ";\n";
    if (b.force != Vec3::Zero()) out << "  force " << vec(b.force) << ";\n";
    if (b.torque != Vec3::Zero()) out << "  torque " << vec(b.torque) << ";\n";
    out << "end\n";
  }
  for (const Joint& j : model.joints()) {
    out << "\nconstraint\n";
    if (!j.label.empty()) out << "  // " << j.label << "\n";
    out << "  object1 " << model.body(j.body1).name << ";\n";
    out << "  object2 " << model.body(j.body2).name << ";\n";
    if (j.has_hinge) out << "  hinge " << vec(j.p1) << " " << vec(j.p2) << ";\n";
    if (j.guide) {
      const Guide& g = *j.guide;
      switch (g.kind) {
        case GuideKind::Point:
          break;
        case GuideKind::Axial:
          out << "  axial " << vec(g.dir) << bounds(g.min, g.max, -kInf, kInf) << ";\n";
          break;
        case GuideKind::Planar:
          out << "  planar " << vec(g.dir) << bounds(g.min, g.max, 0, kInf) << ";\n";
          break;
        case GuideKind::Sphere:
          out << "  sphere" << bounds(g.min, g.max, 0, kInf) << ";\n";
          break;
        case GuideKind::Circle:
          out << "  circle " << vec(g.dir) << " " << num(g.radius) << ";\n";
          break;
        case GuideKind::Cylinder:
          out << "  cylinder " << vec(g.dir) << " " << num(g.radius)
              << bounds(g.min, g.max, -kInf, kInf) << ";\n";
          break;
        case GuideKind::Polyline:
          out << "  polyline";
          for (const Vec3& p : g.points) out << " " << vec(p);
          out << ";\n";
          break;
      }
    }
    if (j.angle) {
      out << "  angle " << vec(j.angle->a1) << " " << vec(j.angle->a2)
          << bounds(j.angle->min, j.angle->max, 0, kPi) << ";\n";
    }
    if (j.twist) {
      // Twist bounds default to 0 0: write both whenever either differs.
      out << "  twist " << vec(j.twist->b1) << " " << vec(j.twist->b2);
      if (j.twist->min != 0 || j.twist->max != 0) {
        out << " min " << num(j.twist->min) << " max " << num(j.twist->max);
      }
      out << ";\n";
    }
    if (j.move) out << "  move " << num(*j.move) << ";\n";
    if (j.t0 != -kInf || j.t1 != kInf) out << "  time " << num(j.t0) << " " << num(j.t1) << ";\n";
    out << "end\n";
  }
  return out.str();
}

}  // namespace dispcon
