#include "dispcon/io/dcl_writer.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "dispcon/io/dcl_lexer.hpp"
#include "dispcon/model/joint_kinds.hpp"

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
    // The kind is a comment for people; the statements below are the joint.
    out << "\nconstraint  // " << kind_name(j) << "\n";
    if (!j.label.empty()) out << "  label " << quote_string(j.label) << ";\n";
    out << "  object1 " << model.body(j.body1).name << ";\n";
    out << "  object2 " << model.body(j.body2).name << ";\n";
    for (const ComponentRow& row : components()) {
      if (!has_component(j, row.id)) continue;
      const ComponentValues v = get_component(j, row.id);
      out << "  " << row.keyword;
      size_t vector = 0, scalar = 0, flag = 0, option = 0;
      for (const ArgSpec& a : row.args) {
        switch (a.kind) {
          case Arg::Point:
          case Arg::Direction:
            out << " " << vec(v.vectors.at(vector++));
            break;
          case Arg::PositiveLength:
          case Arg::NonNegativeLength:
            out << " " << num(v.scalars.at(scalar++));
            break;
          case Arg::NamedPositive:
            out << " " << a.name << " " << num(v.scalars.at(scalar++));
            break;
          case Arg::Points:
            for (const Vec3& x : v.points) out << " " << vec(x);
            break;
          case Arg::Flag:
            if (v.flags.at(flag++)) out << " " << a.name;
            break;
          case Arg::NamedOption: {
            const std::optional<double>& x = v.options.at(option++);
            if (x) out << " " << a.name << " " << num(*x);
            break;
          }
        }
      }
      // Bounds equal to the defaults are left out (reading fills them back in).
      if (row.has_bounds) {
        if (v.bounds.min != row.defaults.min) out << " min " << num(v.bounds.min);
        if (v.bounds.max != row.defaults.max) out << " max " << num(v.bounds.max);
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
