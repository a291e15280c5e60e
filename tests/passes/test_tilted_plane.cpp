// Tilted working planes for 3+2 work (kinematics.indexed = "plane"): the Euler angles of the
// plane for a tool axis against angles worked out by hand, the exact blocks of a short program
// on a Fanuc (G68.2 / G53.1 / G69) and on a Haas (G268 / G269) machine, and the program read
// back through the same rotation (verify accepts it, and refuses it with one angle changed).
#include <cmath>

#include "machine/tilted_plane.h"
#include "readback/gcode_interp.h"
#include "helpers.h"
#include "three_plus_two.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ir::Vec3;

namespace {


void expect_angles(const Vec3& axis, EulerOrder order, const Vec3& want) {
  const ir::Mat3 r = plane::least_tilt(axis.normalized());
  const Vec3 got = plane::angles(r, order);
  EXPECT_LT((got - want).norm(), 1e-9) << got.transpose() << " for " << axis.transpose();
  // The angles stand for the same rotation, and it takes +Z to the tool axis.
  EXPECT_LT((plane::rotation(got, order) - r).norm(), 1e-10);  // the angles are tidied to 1e-9 degrees
  EXPECT_LT((r * Vec3::UnitZ() - axis.normalized()).norm(), 1e-12);
}


Machine fanuc_plane() {
  return machine("fanuc-ac-plane", read_file(source_path("examples/fanuc_ac_plane.toml")));
}

const char* kHaasPlane =
    "[umc-plane]\ninherits = \"haas-umc750\"\n[umc-plane.kinematics]\nindexed = \"plane\"\nplane_euler = \"xyz\"\n"
    "[umc-plane.codes]\nplane_on = \"G268 X{x} Y{y} Z{z} I{i} J{j} K{k} Q123\"\nplane_off = \"G269\"\n";

}  // namespace

// By hand: the least tilt taking +Z to n turns about Z x n by the angle between them.
// (0.5, 0, 0.866): 30 degrees about +Y: Rz(90) Rx(30) Rz(-90), or Ry(30).
// (0, 0.7071, 0.7071): 45 degrees about -X: Rz(180) Rx(45) Rz(180), or Rx(-45).
// (0.5, 0.5, 0.7071): 45 degrees about (-1, 1, 0): Z X Z keeps K = -I (I from the third
// column (sin I sin J, -cos I sin J, cos J) = n: I = atan2(0.5, -0.5) = 135); X Y Z: J =
// asin(n_x) = 30, I = atan2(-n_y, n_z) = -35.26439, K = atan2(-R01, R00) with R00 = 0.85355,
// R01 = -0.14645 (Rodrigues): 9.73561.
TEST(TiltedPlane, EulerAnglesOfThreeToolAxesAgainstTheHandWorkedOnes) {
  expect_angles(Vec3(0.5, 0, std::sqrt(0.75)), EulerOrder::Zxz, Vec3(90, 30, -90));
  expect_angles(Vec3(0.5, 0, std::sqrt(0.75)), EulerOrder::Xyz, Vec3(0, 30, 0));
  expect_angles(Vec3(0, 1, 1), EulerOrder::Zxz, Vec3(180, 45, 180));
  expect_angles(Vec3(0, 1, 1), EulerOrder::Xyz, Vec3(-45, 0, 0));
  expect_angles(Vec3(0.5, 0.5, std::sqrt(0.5)), EulerOrder::Zxz, Vec3(135, 45, -135));
  expect_angles(Vec3(0.5, 0.5, std::sqrt(0.5)), EulerOrder::Xyz, Vec3(-35.264389682754654, 30, 9.73561031724535));
  // Straight down: half a turn about X; Z X Z puts it all in J, X Y Z in I.
  expect_angles(Vec3(0, 0, -1), EulerOrder::Zxz, Vec3(0, 180, 0));
  expect_angles(Vec3(0, 0, -1), EulerOrder::Xyz, Vec3(180, 0, 0));
}

// Each 3+2 operation: the rotaries positioned and clamped, the plane set about the part zero,
// G53.1, and the points in the plane: (10, 0, 50) turned by Ry(30)^T is (-16.340, 0, 48.301);
// (0, 30, 80) by Rx(45) is (0, -35.355, 77.782). G69 before the rotaries move again.
TEST(TiltedPlane, FanucG68_2WritesThePlaneThenThePointsInIt) {
  CompileOptions o;
  o.certify = true;
  Compiled c = compile_text(kThreePlusTwo, fanuc_plane(), o);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N50 G00 A30. C90.\nN60 M10 M12\nN70 G54\nN80 G68.2 X0. Y0. Z0. I90. J30. K-90.\n"
                                  "N90 G53.1\nN100 G00 X-16.34 Y0.\nN110 G43 H01 Z48.301\n"
                                  "N120 G94 G01 X-13.84 Y10. Z43.971 F500.\nN130 X-2.679 Z44.641\n"
                                  "N140 G00 Z79.282\nN150 X-22.679\nN160 G69\n(SIDE_B)\nN170 G91 G28 Z0.\nN180 M11 M13\n"
                                  "N190 G90 G00 A45. C180.\nN200 M10 M12\nN210 G68.2 X0. Y0. Z0. I180. J45. K180.\n"
                                  "N220 G53.1\nN230 G00 X0. Y-35.355\nN240 Z77.782\n"
                                  "N250 G94 G01 Y-7.071 Z63.64 F400.\nN260 X10.\nN270 G00 Z91.924\nN280 Y-35.355\nN290 G69\n"));
  // The retracts go up the tool axis first, then across (rapid-split: non-linear rapids).
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified"));
}

// The Haas form from the TOML: G268 with X Y Z angles and the order's Q word, no G53.1 (the
// program positions B and C itself), G269.
TEST(TiltedPlane, HaasG268FromTheMachineDescription) {
  CompileOptions o;
  o.certify = true;
  Compiled c = compile_text(kThreePlusTwo, machine("umc-plane", kHaasPlane), o);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N30 G00 B30. C0.\nN35 M10 M12\nN40 G54\nN45 G268 X0. Y0. Z0. I0. J30. K0. Q123\n"
                                  "N50 G00 X-0.6433 Y0.\nN55 G43 H01 Z1.9016\n"));
  EXPECT_THAT(c.output, HasSubstr("N70 G00 Z3.1213\nN75 X-0.8929\nN80 G269\n(SIDE_B)\nN85 G53 G00 Z0.\nN90 M11 M13\n"
                                  "N95 G00 B45. C90.\nN100 M10 M12\nN105 G268 X0. Y0. Z0. I-45. J0. K0. Q123\n"
                                  "N110 G00 X0. Y-1.3919\n"));
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified"));
}

// The reader takes X Y Z in a plane through its rotation: G68.2 about (10, 0, 0) with J90 (Z X
// Z: Rx(90)) puts plane (0, 0, 5) at (10, -5, 0); after G69 the words are the part's again. A
// rotary word inside the plane is what the control refuses.
TEST(TiltedPlane, TheReaderTurnsPointsThroughThePlane) {
  const Machine m = fanuc_plane();
  gcode::Result r = gcode::interpret(
      "G21 G90 G17\nT1 M06\nG00 G43 H01 Z100.\nG00 A90. C0.\nG68.2 X10. Y0. Z0. I0. J90. K0.\nG53.1\nG00 X0. Y0. Z5.\n"
      "G69\nG00 X1. Y2. Z50.\nG68.2 X0. Y0. Z0. I0. J90. K0.\nG00 A45.\nM30\n",
      m);
  auto at_line = [&](int line) -> const gcode::Segment* {
    for (const gcode::Segment& g : r.segments)
      if (g.line == line) return &g;
    return nullptr;
  };
  const gcode::Segment* in_plane = at_line(7);
  ASSERT_NE(in_plane, nullptr);
  ASSERT_NE(in_plane->plane, nullptr);
  EXPECT_LT((in_plane->plane->origin + in_plane->plane->rotation * in_plane->end - Vec3(10, -5, 0)).norm(), 1e-12);
  const gcode::Segment* after = at_line(9);
  ASSERT_NE(after, nullptr);
  EXPECT_EQ(after->plane, nullptr);
  EXPECT_LT((after->end - Vec3(1, 2, 50)).norm(), 1e-12);
  // The tool was at plane (0, 0, 5) = part (10, -5, 0) when G69 came: the move starts there.
  EXPECT_LT((after->start - Vec3(10, -5, 0)).norm(), 1e-12);
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_EQ(r.problems[0].line, 11);
  EXPECT_THAT(r.problems[0].message, HasSubstr("a rotary axis moves in a tilted working plane"));
}

// verify reads the plane's angles: the program as written passes; with J 30.5 for J30. (the
// plane half a degree off) the points land up to 0.4 mm away, and it fails.
TEST(TiltedPlane, VerifyChecksThePointsThroughThePlanesAngles) {
  Compiled c = compile_text(kThreePlusTwo, fanuc_plane());
  ASSERT_TRUE(c.ok) << c.diags;
  TempDir t;
  write_file(t.path("p.cls"), kThreePlusTwo);
  write_file(t.path("good.nc"), c.output);
  std::string bad = c.output;
  size_t at = bad.find("J30. K-90.");
  ASSERT_NE(at, std::string::npos);
  bad.replace(at, 4, "J30.5");
  write_file(t.path("bad.nc"), bad);
  const std::string args = " -t fanuc-ac-plane --machines " + source_path("examples/fanuc_ac_plane.toml");
  RunResult good = run_clpc("verify " + t.path("p.cls") + " --program " + t.path("good.nc") + args);
  EXPECT_EQ(good.status, 0) << good.err << good.out;
  RunResult wrong = run_clpc("verify " + t.path("p.cls") + " --program " + t.path("bad.nc") + args);
  EXPECT_EQ(wrong.status, 1);
  EXPECT_THAT(wrong.out + wrong.err, HasSubstr("result: FAIL"));
}
