// The .dcl reader against format.md: Appendix A verbatim, every listed error with its place,
// and the writer's round trip.
#include "dispcon/io/dcl_reader.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <thread>

#include "dispcon/io/dcl_parser.hpp"
#include "dispcon/io/dcl_writer.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {
namespace {

// Appendix A of the paper, as printed (the last code block first).
const char* kAppendixA = R"(/* Constraint between the wheel and the
character's body */
constraint object1 body; object2 wheel;
hinge 0 -2.0 0 0 0 0;
angle 1 0 0 1 0 0 max 0; end

/* Angle constraint preventing the character
from falling */
constraint object2 body; /* default object1:
world-fixed coordinate system */
angle 0 1 0 0 1 0 max 0.066; end

/* Constraints along the left leg */
constraint object1 body; object2 left-thigh;
hinge 0.4 -0.6 0 0 0 0;
angle 1 0 0 1 0 0 max 0; end

constraint object1 left-thigh;
object2 left-leg; hinge 0 0 1 0 0 0;
angle 1 0 0 1 0 0 max 0; end

constraint object1 left-leg;
object2 left-foot; hinge 0 0 1.4 0 0 -0.1;
angle 1 0 0 1 0 0 max 0; end

constraint object1 wheel; object2 left-foot;
hinge 0.4 0 -0.5 0 0 0; end
constraint object1 body; object2 left-foot;
angle 0 0 1 0 0 1 max .1; end

/* Constraints along the right leg */
constraint object1 body;
object2 right-thigh;
hinge -.4 -0.6 0 0 0 0;
angle 1 0 0 1 0 0 max 0.04; end

constraint object1 right-thigh;
object2 right-leg; hinge 0 0 1 0 0 0;
angle 1 0 0 1 0 0 max 0; end

constraint object1 right-leg;
object2 right-foot; hinge 0 0 1.4 0 0 -0.1;
angle 1 0 0 1 0 0 max 9; end

constraint object1 wheel;
object2 right-foot;
hinge -0.4 0 0.5 0 0 0; end

constraint object1 body; object2 right-foot;
angle 0 0 1 0 0 1 max .1; end
)";

const char* kObjects = R"(
object body; end
object wheel; end
object left-thigh; end
object right-thigh; end
object left-leg; end
object right-leg; end
object left-foot; end
object right-foot; end
)";

TEST(DclReader, AppendixAParsesVerbatim) {
  const ParseResult r = parse_dcl(std::string(kAppendixA) + kObjects, "mono.dcl");
  ASSERT_TRUE(r.ok()) << r.messages();
  const Model& m = *r.model;
  EXPECT_EQ(m.body_count(), 9);
  ASSERT_EQ(m.joint_count(), 12);
  // The block holding the character upright: world -> body, angle only.
  const Joint& upright = m.joint(JointId{1});
  EXPECT_EQ(upright.body1, Model::kWorld);
  EXPECT_EQ(m.body(upright.body2).name, "body");
  EXPECT_FALSE(upright.has_translation());
  ASSERT_TRUE(upright.angle);
  EXPECT_DOUBLE_EQ(upright.angle->max, 0.066);
  EXPECT_EQ(upright.line, 9);
  // `hinge -.4 -0.6 0 0 0 0`
  EXPECT_EQ(m.joint(JointId{7}).p1, Vec3(-0.4, -0.6, 0));
  // `max 9` is clamped to pi, with a warning at its statement.
  EXPECT_DOUBLE_EQ(m.joint(JointId{9}).angle->max, kPi);
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_FALSE(r.diagnostics[0].error);
  EXPECT_EQ(r.diagnostics[0].line, 43);
  EXPECT_EQ(r.diagnostics[0].format().rfind("mono.dcl:43:1: warning: angle max 9", 0), 0u)
      << r.diagnostics[0].format();
}

TEST(DclReader, MonocycleSampleAssemblesFromRoughPositions) {
  ParseResult r = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/monocycle.dcl");
  ASSERT_TRUE(r.ok()) << r.messages();
  Model& m = *r.model;
  const double before = [&] {
    double worst = 0;
    for (const ConstraintReport& c : measure(m, m.poses(), SolveOptions{})) {
      worst = std::max(worst, c.residual);
    }
    return worst;
  }();
  EXPECT_GT(before, 0.1);  // rough positions indeed
  const SolveResult s = assemble(m);
  EXPECT_TRUE(s.converged) << s.message;
  EXPECT_LT(s.max_residual, 1e-9);
}

struct Bad {
  const char* text;
  int line, column;
  const char* message;  // a part of the message
};

TEST(DclReader, EveryErrorNamesItsPlace) {
  const Bad cases[] = {
      {"object a; end\nconstraint object2 a; hinge 0 0 0 0 0 0; bogus 1; end", 2, 42,
       "unknown constraint statement 'bogus'"},
      {"object a; end\nconstraint object2 a; hinge 0 0 0 0 0 0 end", 2, 41,
       "expected ';' after hinge"},
      {"object a;\nconstraint object2 a; hinge 0 0 0 0 0 0; end", 2, 1, "missing 'end'"},
      {"object a; end\nconstraint object2 b; hinge 0 0 0 0 0 0; end", 2, 12, "unknown object 'b'"},
      {"object a; end\nobject a; end", 2, 1, "duplicate object 'a'"},
      {"object a; end\nconstraint object1 a; object2 a; hinge 0 0 0 0 0 0; end", 2, 23,
       "same object 'a'"},
      {"object a; position nan 0 0; end", 1, 20, "'nan' (not a number)"},
      {"object a; mass -2; end", 1, 11, "mass must be positive"},
      {"object a; end\nconstraint object2 a; hinge 0 0 0 0 0 0; move 1.5; end", 2, 42,
       "move 1.5 is not in [0, 1]"},
      {"object a; inertia 1 1 -1; end", 1, 11, "inertia is not positive definite"},
      {"object a; end\x01", 1, 14, "byte 0x01 is not text"},
      {"object a; end\nconstraint object2 a; axial 0 0 0; end", 2, 29, "axial u is a zero vector"},
      {"object a; end\nconstraint object2 a; hinge 0 0 0 0 0 0; label \"x;", 2, 48, "not closed"},
      {"object a; end\nconstraint object2 a; hinge 0 0 0 0 0 0; label x; end", 2, 48,
       "expected a string in double quotes for label"},
      {"object a; end\nconstraint object2 a; axial 1 0 0; planar 0 0 1; end", 2, 36,
       "at most one translation guide"},
      {"object a; end\nconstraint object2 a; end", 2, 1, "no component"},
      {"object a; end\nconstraint object2 a; axial 1 0 0 min 2 max 1; end", 2, 23,
       "min 2 is above max 1"},
      {"object a; end\nconstraint object2 a; hinge 0 0 0 0 0 0; twist 1 0 0 1 0 0; end", 2, 42,
       "twist needs an angle"},
      {"object a; end\nconstraint hinge 0 0 0 0 0 0; end", 2, 1, "needs 'object2'"},
      {"object world; end", 1, 1, "reserved"},
      {"object a; end\nconstraint object2 a; hinge 0 0 0 0 0; end", 2, 38, "expected a number"},
      {"/* never closed", 1, 1, "never closed"},
      {"object a; position 1x 0 0; end", 1, 20, "malformed number '1x'"},
      {"object a; position inf 0 0; end", 1, 20, "must be finite"},
      {"stuff", 1, 1, "expected 'object', 'constraint' or 'include'"},
      {"object a; end\nconstraint object2 a; gear 1 0 0 0 0 1 0 0 0 0 0 1 ratio -2; end", 2, 58,
       "gear ratio must be positive"},
      {"object a; end\nconstraint object2 a; gear 1 0 0 0 0 0 0 0 0 0 0 1 ratio 2; end", 2, 34,
       "gear a1 is a zero vector"},
      {"object a; end\nconstraint object2 a; rack 1 0 0 0 0 1 0 0 0 1 0 0 ratio 2; end", 2, 52,
       "expected 'radius' in rack, found 'ratio'"},
      {"object a; end\nconstraint object2 a; belt 1 0 0 0 0 1 0 0 0 0 0 1 ratio 2 phase; end", 2,
       65, "expected a number for belt phase"},
      {"object a; end\nconstraint object2 a; screw 0 0 0 1 0 0 0 0 0 1 0 0 pitch 1 right; end", 2,
       61, "expected 'left', 'phase' or ';' in screw, found 'right'"},
      {"object a; end\nconstraint object2 a; gear 1 0 0 0 0 1 0 0 0 0 0 1 ratio 2;\n"
       "  belt 1 0 0 0 0 1 0 0 0 0 0 1 ratio 2; end",
       3, 3, "at most one coupling: 'belt' after 'gear' at line 2"},
      // Concentric gears: the line of centres, from which turns are measured, lies on the axis.
      {"object a; end\nconstraint object2 a; gear 0 0 0 0 0 1 0 0 0 0 0 1 ratio 2; end", 2, 23,
       "gear: the turn has no reference"},
  };
  for (const Bad& c : cases) {
    SCOPED_TRACE(c.text);
    const ParseResult r = parse_dcl(c.text, "f.dcl");
    EXPECT_FALSE(r.ok());
    ASSERT_FALSE(r.diagnostics.empty());
    const Diagnostic* found = nullptr;
    for (const Diagnostic& d : r.diagnostics) {
      if (d.error && d.message.find(c.message) != std::string::npos) found = &d;
    }
    ASSERT_NE(found, nullptr) << r.messages();
    EXPECT_EQ(found->line, c.line) << found->format();
    EXPECT_EQ(found->column, c.column) << found->format();
    EXPECT_EQ(found->format().rfind("f.dcl:" + std::to_string(c.line) + ":", 0), 0u);
  }
}

TEST(DclReader, ErrorsAreCappedWithACountOfTheRest) {
  // A megabyte of binary: a hundred errors, then one line with the count of the rest.
  std::string binary(1 << 20, '\0');
  std::mt19937 rng(7);
  for (char& c : binary) c = static_cast<char>(rng() & 0xFF);
  const ParseResult noise = parse_dcl(binary, "noise.bin");
  EXPECT_FALSE(noise.ok());
  ASSERT_EQ(noise.diagnostics.size(), 101u);
  const Diagnostic& last = noise.diagnostics.back();
  EXPECT_TRUE(last.error);
  EXPECT_NE(last.message.find(" more errors (only the first 100 are listed)"), std::string::npos)
      << last.message;
  EXPECT_GT(std::stoll(last.message), 100000);

  std::string duplicates;
  for (int i = 0; i < 200000; ++i) duplicates += "object a; end\n";
  const ParseResult dup = parse_dcl(duplicates, "dup.dcl");
  ASSERT_EQ(dup.diagnostics.size(), 101u);
  EXPECT_EQ(dup.diagnostics.back().message,
            "199899 more errors (only the first 100 are listed)");  // 199,999 duplicates
  EXPECT_EQ(dup.diagnostics.back().format().rfind("dup.dcl:200001:1: error:", 0), 0u);

  // Warnings likewise, and the file still reads.
  std::string clamped = "object a; end\n";
  for (int i = 0; i < 150; ++i) clamped += "constraint object2 a; angle 0 0 1 0 0 1 max 9; end\n";
  const ParseResult warned = parse_dcl(clamped);
  ASSERT_TRUE(warned.ok()) << warned.messages();
  ASSERT_EQ(warned.diagnostics.size(), 101u);
  EXPECT_EQ(warned.diagnostics.back().message, "50 more warnings (only the first 100 are listed)");
}

TEST(DclReader, ModelChecksArePlacedAtTheirStatement) {
  // Scaled before the norm, 1e200 1e200 0 is a direction, not an overflow to a zero vector.
  const ParseResult big =
      parse_dcl("object a; end\nconstraint object2 a; axial 1e200 1e200 0; end");
  ASSERT_TRUE(big.ok()) << big.messages();
  EXPECT_NEAR(big.model->joint(JointId{0}).guide->dir.x(), std::sqrt(0.5), 1e-15);
  // Errors from the model (here a negative radius) point at the argument, even after an earlier
  // error in another block.
  const ParseResult r = parse_dcl(
      "object a; mass -1; end\nobject b; end\n"
      "constraint object2 b;\n  cylinder 0 0 1 -2; end",
      "f.dcl");
  EXPECT_NE(r.messages().find("f.dcl:1:11: error: mass must be positive"), std::string::npos)
      << r.messages();
  EXPECT_NE(r.messages().find("f.dcl:4:18: error: cylinder r must not be negative, found -2"),
            std::string::npos)
      << r.messages();
  // The warning of a clamp is the model's, placed at the statement.
  const ParseResult w = parse_dcl(
      "object a; end\nconstraint object2 a;\n twist 0 1 0 0 1 0 max 4;\n"
      " angle 0 0 1 0 0 1 max 0; end",
      "w.dcl");
  ASSERT_TRUE(w.ok()) << w.messages();
  EXPECT_EQ(w.messages(),
            "w.dcl:3:2: warning: twist max 4 is outside [-3.14159, 3.14159]; clamped to 3.14159\n");
}

TEST(DclReader, LabelsAreStrings) {
  const ParseResult r = parse_dcl(
      "object a; end\nconstraint label \"Revolute 1\\n\\\"crank\\\"\"; object2 a; hinge 0 0 0 0 0 "
      "0; end");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(r.model->joint(JointId{0}).label, "Revolute 1\n\"crank\"");
}

TEST(DclReader, LexicalForms) {
  const ParseResult r = parse_dcl(R"(
    // a line comment
    object a; position .1 -2.0 1e-3; end;
    constraint object2 a; axial 1 0 0 min -inf max 2.5e0; end;
    constraint object2 a; sphere max inf; end
  )");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(r.model->body(BodyId{1}).pose.x, Vec3(0.1, -2.0, 1e-3));
  EXPECT_EQ(r.model->joint(JointId{0}).guide->min, -kInf);
  EXPECT_EQ(r.model->joint(JointId{0}).guide->max, 2.5);
}

// A file read whole as its size says, and the same text through a pipe (no size: read on as it
// comes), each of sizes around the reader's first 64 kB of room and its doublings.
TEST(DclReader, FileAndPipeReadTheSameText) {
  const std::string dir = ::testing::TempDir();
  for (const int objects : {0, 1, 2000, 2049, 6000}) {
    std::string text = "// " + std::to_string(objects) + " objects\n";
    for (int i = 0; i < objects; ++i) {
      text += "object o" + std::to_string(i) + "; position " + std::to_string(i) + " 0 0; end\n";
    }
    const std::string file = dir + "/read_" + std::to_string(objects) + ".dcl";
    std::FILE* out = std::fopen(file.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    std::fwrite(text.data(), 1, text.size(), out);
    std::fclose(out);
    dcl::FileText read;
    std::string why;
    ASSERT_TRUE(dcl::read_file(file, read, why)) << why;
    EXPECT_EQ(read.view(), text);
    const std::string fifo = dir + "/read_" + std::to_string(objects) + ".fifo";
    std::remove(fifo.c_str());
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] {
      std::FILE* w = std::fopen(fifo.c_str(), "wb");
      if (!w) return;
      // In pieces of 1,000 bytes, as a pipe fills.
      for (size_t at = 0; at < text.size(); at += 1000) {
        std::fwrite(text.data() + at, 1, std::min<size_t>(1000, text.size() - at), w);
        std::fflush(w);
      }
      std::fclose(w);
    });
    dcl::FileText piped;
    const bool ok = dcl::read_file(fifo, piped, why);
    writer.join();
    ASSERT_TRUE(ok) << why;
    EXPECT_EQ(piped.view(), text);
    std::remove(fifo.c_str());
    std::remove(file.c_str());
  }
}

TEST(DclWriter, RoundTripKeepsEveryField) {
  const char* text = R"(
object crank; position 0.1 0.2 0.3; rotation 0.3 -0.2 1.1; mass 2; inertia 1 2 3 0.1 0.2 0.3;
  center 0.5 0 0; velocity 1 2 3; spin 0 0 1; force 0 -9.8 0; torque 1 0 0; end
object slider; position 1 0 0; rotate 0.7; fixed; end
object pin; position 0 1 0; end
constraint object2 crank; hinge 0 0 0 0.1 0 0; axial 0 0 1 min -1 max 2; move 0.25; time 0.5 1.5; end
constraint object1 crank; object2 pin; planar 0 1 0 min 0.5 max 2; angle 0 0 1 0 1 1 min 0.2 max 1; twist 1 0 0 1 0 0 min -0.5 max 0.5; end
constraint object1 slider; object2 pin; sphere min 1 max 1; end
constraint object1 slider; object2 crank; circle 0 0 1 0.75; end
constraint object1 pin; object2 crank; cylinder 1 0 0 0.3 max 4; end
constraint object1 pin; object2 slider; polyline 0 0 0 1 0 0 1 1 0; end
constraint object1 crank; object2 pin; gear 0.5 0 0 0 0 1 0 0 0 0 0 1 ratio 1.5; end
constraint object1 pin; object2 crank; belt 0 0 0 0 0 1 0 0 0 0 0 1 ratio 0.25 phase 0.125; end
constraint object1 pin; object2 slider; rack 0 0 0 0 0 1 0 0 0 1 0 0 radius 0.3; end
constraint object1 slider; object2 crank; hinge 0 0 0 0 0 0; axial 1 0 0;
  screw 0 0 0 1 0 0 0 0 0 1 0 0 pitch 0.2 left; end
)";
  const ParseResult a = parse_dcl(text);
  ASSERT_TRUE(a.ok()) << a.messages();
  const std::string written = write_dcl(*a.model);
  const ParseResult b = parse_dcl(written, "written.dcl");
  ASSERT_TRUE(b.ok()) << b.messages() << written;
  const Model& m1 = *a.model;
  const Model& m2 = *b.model;
  ASSERT_EQ(m1.body_count(), m2.body_count());
  for (int i = 0; i < m1.body_count(); ++i) {
    const Body& x = m1.body(BodyId{i});
    const Body& y = m2.body(BodyId{i});
    EXPECT_EQ(x.name, y.name);
    EXPECT_LT((x.pose.x - y.pose.x).norm(), 1e-15);
    EXPECT_LT(x.pose.q.angularDistance(y.pose.q), 1e-15);
    EXPECT_EQ(x.fixed, y.fixed);
    EXPECT_EQ(x.rotate, y.rotate);
    EXPECT_EQ(x.mass, y.mass);
    EXPECT_EQ(x.inertia.has_value(), y.inertia.has_value());
    if (x.inertia) EXPECT_EQ(*x.inertia, *y.inertia);
    EXPECT_EQ(x.center, y.center);
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.spin, y.spin);
    EXPECT_EQ(x.force, y.force);
    EXPECT_EQ(x.torque, y.torque);
  }
  ASSERT_EQ(m1.joint_count(), m2.joint_count());
  for (int c = 0; c < m1.joint_count(); ++c) {
    const Joint& x = m1.joint(JointId{c});
    const Joint& y = m2.joint(JointId{c});
    EXPECT_EQ(x.body1, y.body1);
    EXPECT_EQ(x.body2, y.body2);
    EXPECT_EQ(x.has_hinge, y.has_hinge);
    EXPECT_EQ(x.p1, y.p1);
    EXPECT_EQ(x.p2, y.p2);
    ASSERT_EQ(x.guide.has_value(), y.guide.has_value());
    if (x.guide) {
      EXPECT_EQ(x.guide->kind, y.guide->kind);
      EXPECT_EQ(x.guide->dir, y.guide->dir);
      EXPECT_EQ(x.guide->min, y.guide->min);
      EXPECT_EQ(x.guide->max, y.guide->max);
      EXPECT_EQ(x.guide->radius, y.guide->radius);
      EXPECT_EQ(x.guide->points, y.guide->points);
    }
    ASSERT_EQ(x.angle.has_value(), y.angle.has_value());
    if (x.angle) {
      EXPECT_EQ(x.angle->a1, y.angle->a1);
      EXPECT_EQ(x.angle->a2, y.angle->a2);
      EXPECT_EQ(x.angle->min, y.angle->min);
      EXPECT_EQ(x.angle->max, y.angle->max);
    }
    ASSERT_EQ(x.twist.has_value(), y.twist.has_value());
    if (x.twist) {
      EXPECT_EQ(x.twist->b1, y.twist->b1);
      EXPECT_EQ(x.twist->min, y.twist->min);
      EXPECT_EQ(x.twist->max, y.twist->max);
    }
    ASSERT_EQ(x.coupling.has_value(), y.coupling.has_value());
    if (x.coupling) {
      EXPECT_EQ(x.coupling->kind, y.coupling->kind);
      EXPECT_EQ(x.coupling->c1, y.coupling->c1);
      EXPECT_EQ(x.coupling->a1, y.coupling->a1);
      EXPECT_EQ(x.coupling->c2, y.coupling->c2);
      EXPECT_EQ(x.coupling->a2, y.coupling->a2);
      EXPECT_EQ(x.coupling->value, y.coupling->value);
      EXPECT_EQ(x.coupling->left, y.coupling->left);
      EXPECT_EQ(x.coupling->phase, y.coupling->phase);
    }
    EXPECT_EQ(x.move, y.move);
    EXPECT_EQ(x.t0, y.t0);
    EXPECT_EQ(x.t1, y.t1);
  }
}

}  // namespace
}  // namespace dispcon
