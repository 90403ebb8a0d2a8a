// The engine's door for numbers: every non-finite or overflowing value is refused where it
// enters (Model, options), with a message naming it; a file's value is reported at its statement.
#include "dispcon/model/numbers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/model/model.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "dispcon/solve/dynamics.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The message of the std::invalid_argument `f` throws ("" when it throws none).
template <typename F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// The diagnostics of a text that must not parse.
std::string parse_errors(const std::string& text) {
  const ParseResult r = parse_dcl(text, "t.dcl");
  EXPECT_FALSE(r.ok()) << text;
  return r.messages();
}

const char* kPendulum = "object a; position 1 0 0; end\n";

TEST(Numbers, FormatIsReadable) {
  EXPECT_EQ(format_number(1e150), "1e+150");
  EXPECT_EQ(format_number(std::numeric_limits<double>::max()), "1.79769e+308");
  EXPECT_EQ(format_number(0.25), "0.25");
  EXPECT_EQ(format_number(kNaN), "nan");
}

TEST(Numbers, DirectionOfHugeComponentsIsNotZero) {
  const Vec3 u = check_direction(Vec3(1e200, 1e200, 0), "axial", "u");
  EXPECT_NEAR(u.x(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(u.y(), std::sqrt(0.5), 1e-15);
  EXPECT_NE(refusal([] { check_direction(Vec3::Zero(), "axial", "u"); }).find("zero vector"),
            std::string::npos);
}

TEST(Numbers, RotationMatrixMustBeARotation) {
  for (const Mat3& R : {Mat3(Mat3::Identity() * 2), Mat3(Vec3(1, 1, -1).asDiagonal()),
                        Mat3(Mat3::Ones()), Mat3(Mat3::Constant(kNaN))}) {
    EXPECT_NE(refusal([&] { rotation_from_matrix(R, "rotation"); }).find("not a rotation"),
              std::string::npos);
  }
  EXPECT_TRUE(rotation_from_matrix(Mat3::Identity(), "rotation").isApprox(Quat::Identity()));
}

TEST(Numbers, RotationVectorWithinRange) {
  EXPECT_NE(refusal([] { rotation_from_vector(Vec3(1e300, 0, 0), "rotation"); }).find("1e+300"),
            std::string::npos);
  EXPECT_NE(refusal([] { rotation_from_vector(Vec3(kNaN, 0, 0), "rotation"); }), "");
}

TEST(ModelDoor, BodyValuesOutOfRangeAreRefused) {
  Model m;
  Body b;
  b.name = "a";
  auto with = [&](auto change) {
    Body c = b;
    change(c);
    return refusal([&] { Model(m).add_body(c); });
  };
  EXPECT_NE(with([](Body& c) { c.rotate = 1e300; }).find("rotate 1e+300 is out of range"),
            std::string::npos);
  EXPECT_NE(with([](Body& c) { c.mass = 1e-150; }).find("mass 1e-150"), std::string::npos);
  EXPECT_NE(with([](Body& c) { c.inertia = Mat3(Mat3::Identity() * 1e-150); }).find("inertia"),
            std::string::npos);
  EXPECT_NE(with([](Body& c) { c.inertia = Mat3(Mat3::Identity() * 1e300); }).find("inertia"),
            std::string::npos);
  EXPECT_NE(with([](Body& c) { c.velocity = Vec3(1e300, 0, 0); }).find("velocity"),
            std::string::npos);
  EXPECT_NE(with([](Body& c) { c.pose.x = Vec3(kNaN, 0, 0); }).find("not a number"),
            std::string::npos);
  EXPECT_EQ(with([](Body& c) { c.mass = 2; }), "");
}

TEST(ModelDoor, JointValuesOutOfRangeAreRefused) {
  Model m;
  const BodyId a = m.add_body(Body{"a"});
  Joint j;
  j.body2 = a;
  j.has_hinge = true;
  j.p1 = Vec3(1e155, 0, 0);
  EXPECT_NE(refusal([&] { m.add_joint(j); }).find("hinge P1 (1e+155 0 0) is out of range"),
            std::string::npos);
  j.p1 = Vec3::Zero();
  Guide g;
  g.kind = GuideKind::Axial;
  g.max = 1e300;
  j.guide = g;
  EXPECT_NE(refusal([&] { m.add_joint(j); }).find("max 1e+300"), std::string::npos);
  j.guide->max = kInf;  // no bound: allowed
  EXPECT_EQ(refusal([&] { m.add_joint(j); }), "");
  EXPECT_EQ(m.joint_count(), 1);
}

TEST(ModelDoor, SettersCheckAndChangeNothingOnRefusal) {
  Model m;
  const BodyId a = m.add_body(Body{"a"});
  const std::vector<Pose> before = m.poses();
  std::vector<Pose> bad = before;
  bad[1].x = Vec3(kNaN, 0, 0);
  EXPECT_NE(refusal([&] { m.set_poses(bad); }), "");
  Pose p;
  p.q.coeffs() << kNaN, 0, 0, 1;
  EXPECT_NE(refusal([&] { m.set_pose(a, p); }), "");
  EXPECT_NE(refusal([&] { m.set_pose(Model::kWorld, Pose{}); }).find("world"), std::string::npos);
  EXPECT_NE(refusal([&] { m.set_mass(a, kNaN); }), "");
  EXPECT_NE(refusal([&] { m.set_rotate(a, 0.0); }), "");
  EXPECT_EQ(m.poses()[1].x, before[1].x);
  EXPECT_FALSE(m.body(a).mass.has_value());
}

TEST(ModelDoor, FileValuesAreReportedAtTheirStatement) {
  // A joint's value: at its argument.
  EXPECT_NE(parse_errors(std::string(kPendulum) +
                         "constraint object2 a;\n  hinge 1e155 0 0  0 0 0; end\n")
                .find("t.dcl:3:9: error: hinge P1 (1e+155 0 0) is out of range"),
            std::string::npos);
  EXPECT_NE(parse_errors("object a;\n rotate 1e300; end\n").find("t.dcl:2:2: error:"),
            std::string::npos);
  EXPECT_NE(
      parse_errors("object a;\n inertia 1e-150 1e-150 1e-150; end\n").find("t.dcl:2:2: error:"),
      std::string::npos);
  EXPECT_NE(
      parse_errors("object a;\n mass 1; inertia 1e300 1e300 1e300; end\n").find("t.dcl:2:10:"),
      std::string::npos);
  EXPECT_NE(parse_errors("object a; velocity 1e300 0 0; end\n").find("t.dcl:1:11:"),
            std::string::npos);
  EXPECT_NE(parse_errors("object a; rotation 1e300 0 0; end\n").find("t.dcl:1:11:"),
            std::string::npos);
  // A direction with huge components is a direction, not a zero vector.
  const ParseResult r =
      parse_dcl(std::string(kPendulum) + "constraint object2 a;\n axial 1e200 1e200 0; end\n");
  EXPECT_TRUE(r.ok()) << r.messages();
}

TEST(ModelDoor, MissingFileAndDirectoryNameThemselves) {
  const ParseResult missing = load_dcl("/nonexistent/x.dcl");
  EXPECT_EQ(missing.messages().rfind("/nonexistent/x.dcl: error: cannot open the file", 0), 0u)
      << missing.messages();
  const ParseResult dir = load_dcl(DISPCON_SOURCE_DIR);
  ASSERT_FALSE(dir.ok());
  EXPECT_NE(dir.messages().find("is a directory"), std::string::npos);
}

TEST(OptionsDoor, SolveOptionsAreChecked) {
  auto bad = [](auto change) {
    SolveOptions o;
    change(o);
    return refusal([&] { validate(o); });
  };
  EXPECT_NE(bad([](SolveOptions& o) { o.tolerance = kNaN; }).find("tolerance"), std::string::npos);
  EXPECT_NE(bad([](SolveOptions& o) { o.tolerance = 0; }).find("tolerance"), std::string::npos);
  EXPECT_NE(bad([](SolveOptions& o) { o.relaxation = kNaN; }).find("relaxation"),
            std::string::npos);
  EXPECT_NE(bad([](SolveOptions& o) { o.time = kNaN; }).find("time"), std::string::npos);
  EXPECT_NE(bad([](SolveOptions& o) { o.max_iterations = 0; }).find("max_iterations"),
            std::string::npos);
  EXPECT_EQ(bad([](SolveOptions&) {}), "");
  // Every solve goes through it.
  Model m;
  m.add_body(Body{"a"});
  SolveOptions o;
  o.tolerance = kNaN;
  EXPECT_NE(refusal([&] { assemble(m, o); }), "");
  EXPECT_NE(refusal([&] { measure(m, m.poses(), o); }), "");
}

TEST(OptionsDoor, AnimateOptionsAreChecked) {
  Model m;
  Body b{"a"};
  b.mass = 1;
  b.inertia = Mat3::Identity();
  m.add_body(b);
  auto bad = [&](auto change) {
    AnimateOptions o;
    change(o);
    return refusal([&] { animate(m, o); });
  };
  EXPECT_NE(bad([](AnimateOptions& o) { o.gravity = Vec3(kNaN, 0, 0); }).find("gravity"),
            std::string::npos);
  EXPECT_NE(bad([](AnimateOptions& o) { o.duration = kNaN; }).find("duration"), std::string::npos);
  EXPECT_NE(bad([](AnimateOptions& o) { o.dt = 1e-300; }).find("frames"), std::string::npos);
  EXPECT_NE(bad([](AnimateOptions& o) { o.duration = 1e12, o.dt = 1; }).find("1e+12 frames"),
            std::string::npos);
}

TEST(OptionsDoor, SweepAndDragTargetsAreChecked) {
  Model m;
  const BodyId a = m.add_body(Body{"a"});
  SweepOptions s;
  s.body = a;
  s.from = kNaN;
  EXPECT_NE(refusal([&] { sweep(m, s); }).find("from"), std::string::npos);
  Pose target;
  target.x = Vec3(kNaN, 0, 0);
  EXPECT_NE(refusal([&] { drag(m, a, target, 1); }).find("target"), std::string::npos);
  Dragger d(m, a);
  EXPECT_NE(refusal([&] { d.move_to(target); }).find("target"), std::string::npos);
}

}  // namespace
}  // namespace dispcon
