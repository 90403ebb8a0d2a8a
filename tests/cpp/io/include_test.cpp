// Sub-models (`include "file" as NAME`, format.md): names, placement, rigid welding, the places
// of errors, and the leg linkage of samples/legs.dcl reused four times against the four-bar's
// closure.
#include "dispcon/io/include.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/dcl_writer.hpp"
#include "dispcon/parts/coupling.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "dispcon/solve/solver.hpp"
#include "support/samples.hpp"

namespace dispcon {
namespace {

namespace fs = std::filesystem;
using test_support::id;
using test_support::sample;

// A folder of its own for the files a test writes, removed afterwards.
class Folder {
 public:
  explicit Folder(const std::string& name)
      : path_(fs::temp_directory_path() / ("dispcon-include-" + name)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Folder() { fs::remove_all(path_); }
  std::string write(const std::string& file, const std::string& text) const {
    std::ofstream(path_ / file) << text;
    return (path_ / file).string();
  }

 private:
  fs::path path_;
};

SolveOptions tight() {
  SolveOptions o;
  o.tolerance = 1e-12;
  return o;
}

const std::string kLeg = std::string(DISPCON_SOURCE_DIR) + "/samples/leg.dcl";

// The leg's four-bar (ground 3, crank 1, coupler 3, rocker 2.5) closes with the coupler's far end
// C at distance 2.5 from the rocker's pivot D, on the branch it was drawn on (elbow up): C from the
// crank's angle alone, in the leg's own frame.
Vec3 closure(double crank) {
  const Vec3 B(std::cos(crank), std::sin(crank), 0), D(3, 0, 0);
  const Vec3 d = D - B;
  const double L = d.norm(), a = (9 - 6.25 + L * L) / (2 * L), h = std::sqrt(9 - a * a);
  return B + a * d / L + h * Vec3(-d.y(), d.x(), 0) / L;
}

TEST(Include, FlexibleCopiesAreRenamedPlacedAndKeepTheirJoints) {
  const Model leg = sample("leg.dcl");
  const Model m = sample("legs.dcl");
  EXPECT_EQ(m.body_count(), 1 + 1 + 4 * 3);
  EXPECT_EQ(m.joint_count(), 4 * 4);
  // The back legs: half a turn about y, then 6 along x and 1 along z.
  const Pose P{Quat(Eigen::AngleAxisd(kPi, Vec3::UnitY())), Vec3(6, 0, 1)};
  for (const char* body : {"crank", "coupler", "rocker"}) {
    SCOPED_TRACE(body);
    const Pose& drawn = leg.body(id(leg, body)).pose;
    const Pose& placed = m.body(id(m, std::string("back_left.") + body)).pose;
    EXPECT_LT((placed.x - P.apply(drawn.x)).norm(), 1e-15);
    EXPECT_LT(placed.q.angularDistance(P.q * drawn.q), 1e-15);
    EXPECT_EQ(m.body(id(m, std::string("front_left.") + body)).pose.x, drawn.x + Vec3(0, 0, 1));
  }
  // Its joints to its world stand on the chassis, at the pivots carried into the chassis's frame.
  const Joint& pivot = m.joint(JointId{8 + 3});  // back_left's rocker pivot
  EXPECT_EQ(pivot.body1, id(m, "chassis"));
  EXPECT_LT((pivot.p1 - Vec3(3, 0, 1)).norm(), 1e-14);
  EXPECT_LT((pivot.angle->a1 - Vec3(0, 0, -1)).norm(), 1e-15);
  // The joints name the include's line in the including file, for reports.
  EXPECT_EQ(pivot.line, 15);
}

TEST(Include, LegsSampleHasFourFreedomsAndEachLegDragsAlone) {
  Model m = sample("legs.dcl");
  ASSERT_TRUE(assemble(m, tight()).converged);
  const CheckResult c = check(m);
  EXPECT_EQ(c.dof, 4) << c.message;
  const std::vector<Pose> before = m.poses();
  Dragger drag(m, id(m, "front_left.crank"), tight());
  const Vec3 pivot(0, 0, 1);
  double worst = 0;
  for (int k = 1; k <= 180; ++k) {
    const double t = kPi / 2 + 2 * kPi * k / 180;  // a full turn of the crank from where drawn
    ASSERT_TRUE(drag.move_to(Pose::from(pivot, Vec3(0, 0, t))).converged) << k;
    const Pose& coupler = m.body(id(m, "front_left.coupler")).pose;
    const Pose& rocker = m.body(id(m, "front_left.rocker")).pose;
    const Vec3 C = closure(t) + pivot;
    worst = std::max({worst, (coupler.apply(Vec3(3, 0, 0)) - C).norm(),
                      (rocker.apply(Vec3(2.5, 0, 0)) - C).norm()});
  }
  RecordProperty("closure_error", std::to_string(worst));
  EXPECT_LT(worst, 1e-9);
  // The three other legs did not move, bit for bit.
  for (const char* leg : {"front_right", "back_left", "back_right"}) {
    for (const char* body : {"crank", "coupler", "rocker"}) {
      const BodyId b = id(m, std::string(leg) + "." + body);
      EXPECT_TRUE(same_bits({m.body(b).pose}, {before[static_cast<size_t>(b.value)]}))
          << leg << "." << body;
    }
  }
}

TEST(Include, RigidCopiesAreOneBodyAndDoNotDrag) {
  const std::string text =
      "object chassis; fixed; end\n"
      "include \"" +
      kLeg +
      "\" as flexible on chassis;\n"
      "include \"" +
      kLeg + "\" as stiff on chassis position 0 0 2 rigid;\n";
  ParseResult r = parse_dcl(text, "walker.dcl");
  ASSERT_TRUE(r.ok()) << r.messages();
  Model m = std::move(*r.model);
  EXPECT_EQ(m.body_count(), 1 + 1 + 3 + 1);
  EXPECT_FALSE(m.find("stiff.crank"));
  // Its two pivots (the joints to its world) stay; the two inside it are gone.
  EXPECT_EQ(m.joint_count(), 4 + 2);
  const CheckResult c = check(m);
  EXPECT_EQ(c.dof, 1) << c.message;
  EXPECT_EQ(c.body_dof.at(static_cast<size_t>(id(m, "stiff").value)), 0) << c.message;
  const std::vector<Pose> before = m.poses();
  const DragResult d =
      drag(m, id(m, "stiff"), Pose::from(Vec3(0, 0, 2), Vec3(0, 0, 0.5)), 5, tight());
  EXPECT_FALSE(d.converged);
  EXPECT_TRUE(same_bits(m.poses(), before));
  // A constraint naming one of its parts is told the rigid copy is one object.
  ParseResult bad =
      parse_dcl(text + "constraint object2 stiff.crank; hinge 0 0 0 0 0 0; end\n", "walker.dcl");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.messages().find("walker.dcl:4:12: error: unknown object 'stiff.crank' (stiff is "
                                "a rigid include"),
            std::string::npos)
      << bad.messages();
}

TEST(Include, RigidWeldAddsMassesAboutTheCommonCentre) {
  Folder dir("weld");
  dir.write("pair.dcl",
            "object a; position 1 0 0; mass 2; inertia 1 1 1; end\n"
            "object b; position -1 0 0; mass 2; inertia 1 1 1; end\n"
            "constraint object1 a; object2 b; hinge -1 0 0 1 0 0; end\n");
  const std::string top = dir.write("top.dcl", "include \"pair.dcl\" as p rigid;\n");
  const ParseResult r = load_dcl(top);
  ASSERT_TRUE(r.ok()) << r.messages();
  const Body& p = r.model->body(BodyId{1});
  EXPECT_EQ(p.name, "p");
  EXPECT_EQ(*p.mass, 4);
  EXPECT_LT(p.center.norm(), 1e-15);
  // Two point masses 2 at +-1 on x add 2 * 2 * 1 about y and z, none about x.
  Mat3 expected = 2 * Mat3::Identity();
  expected(1, 1) += 4;
  expected(2, 2) += 4;
  EXPECT_LT((*p.inertia - expected).norm(), 1e-12);
  EXPECT_EQ(r.model->joint_count(), 0);
}

TEST(Include, CouplingsHoldWhereTheyHeldAfterATurnedPlacement) {
  // A gear pair to its world, placed turned: the phase follows the change of frame.
  Folder dir("gears");
  dir.write("pair.dcl",
            "object g; position 3 0 0; rotation 0 0 0.3; end\n"
            "constraint object2 g; hinge 3 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end\n"
            "constraint object2 g; gear 0 0 0 0 0 1 0 0 0 0 0 1 ratio 0.5 phase 0.7; end\n");
  const std::string top =
      dir.write("top.dcl", "include \"pair.dcl\" as s position 1 2 3 rotation 0.4 -0.2 1.1;\n");
  const ParseResult sub = load_dcl(dir.write("copy.dcl", "include \"pair.dcl\" as s;\n"));
  const ParseResult r = load_dcl(top);
  ASSERT_TRUE(r.ok()) << r.messages();
  ASSERT_TRUE(sub.ok()) << sub.messages();
  for (const Model* m : {&*sub.model, &*r.model}) {
    const Joint& j = m->joint(JointId{1});
    const Body& w = m->body(j.body1);
    const Body& g = m->body(j.body2);
    const CouplingMeasure c =
        measure_coupling(*j.coupling, Frame{w.pose.rotation(), w.pose.x, w.world_center()},
                         Frame{g.pose.rotation(), g.pose.x, g.world_center()}, false);
    const double last[2] = {c.theta[0], c.theta[1]};
    // The drawn poses are off the stated phase by the same amount in both frames.
    const double f = coupling_residual(c, last, *j.coupling->phase);
    static double first = f;
    EXPECT_NEAR(f, first, 1e-14);
  }
}

TEST(Include, ErrorsPointAtTheIncludeStatement) {
  Folder dir("errors");
  dir.write("a.dcl", "object x; end\ninclude \"b.dcl\" as b;\n");
  dir.write("b.dcl", "object y; end\n  include \"a.dcl\" as a;\n");
  dir.write("broken.dcl", "object z; mass -1; end\n");
  dir.write("empty.dcl", "// nothing\n");
  dir.write("one.dcl", "object x; end\n");
  struct Bad {
    std::string text;
    int line, column;
    std::string message;
  };
  const Bad cases[] = {
      {"include \"nowhere.dcl\" as n;", 1, 9, "cannot include 'nowhere.dcl' (cannot open"},
      {"object a; end\ninclude \"top.dcl\" as me;", 2, 9, "include cycle: top.dcl -> top.dcl"},
      {"include \"broken.dcl\" as b;", 1, 9, "'broken.dcl' has errors (listed above)"},
      {"include \"empty.dcl\" as e;", 1, 24, "the included model has no object"},
      {"object b.z; end\ninclude \"broken.dcl\" as b;", 2, 9, "has errors"},
      {"object p.x; end\ninclude \"one.dcl\" as p;", 2, 22, "duplicate object 'p.x'"},
      {"include \"one.dcl\" as p on nobody;", 1, 24, "unknown object 'nobody'"},
      {"include \"one.dcl\" as p rotation 1e9 0 0;", 1, 24, "rotation vector"},
      {"include a.dcl as p;", 1, 9, "expected the file to include in double quotes"},
      {"include \"a.dcl\" p;", 1, 17, "expected 'as' and a name"},
      {"include \"a.dcl\" as p sideways;", 1, 22,
       "expected 'position', 'rotation', 'on', 'rigid' or ';' in include, found 'sideways'"},
      {"include \"a.dcl\" as p rigid rigid;", 1, 28, "'rigid' given twice"},
  };
  for (const Bad& c : cases) {
    SCOPED_TRACE(c.text);
    const ParseResult r = load_dcl(dir.write("top.dcl", c.text));
    ASSERT_FALSE(r.ok());
    const Diagnostic* found = nullptr;
    for (const Diagnostic& d : r.diagnostics)
      if (d.error && d.message.find(c.message) != std::string::npos) found = &d;
    ASSERT_NE(found, nullptr) << r.messages();
    EXPECT_EQ(fs::path(found->file).filename(), "top.dcl") << found->format();
    EXPECT_EQ(found->line, c.line) << found->format();
    EXPECT_EQ(found->column, c.column) << found->format();
  }
  // A cycle through two files is reported where it closes, and each include on the way says so.
  const ParseResult cycle = load_dcl(dir.write("top.dcl", "include \"a.dcl\" as a;"));
  EXPECT_NE(cycle.messages().find("b.dcl:2:11: error: include cycle: a.dcl -> b.dcl -> a.dcl"),
            std::string::npos)
      << cycle.messages();
  EXPECT_NE(cycle.messages().find("top.dcl:1:9: error: 'a.dcl' has errors"), std::string::npos);
  // The included file's own error keeps its own place.
  const ParseResult r = load_dcl(dir.write("top.dcl", "include \"broken.dcl\" as b;"));
  EXPECT_NE(r.messages().find("broken.dcl:1:11: error: mass must be positive"), std::string::npos)
      << r.messages();
}

TEST(Include, TheWriterWritesTheFlattenedModelWhichReadsBackTheSame) {
  const Model m = sample("legs.dcl");
  const std::string text = write_dcl(m);
  EXPECT_EQ(text.find("include"), std::string::npos);
  EXPECT_NE(text.find("object back_right.rocker;"), std::string::npos);
  const ParseResult back = parse_dcl(text);
  ASSERT_TRUE(back.ok()) << back.messages();
  EXPECT_EQ(write_dcl(*back.model), text);
  EXPECT_EQ(check(*back.model).dof, 4);
}

}  // namespace
}  // namespace dispcon
