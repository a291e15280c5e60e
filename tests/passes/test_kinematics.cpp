// Five-axis: the solver, the kinematics and limits passes, and the round trip — forward
// kinematics applied to every emitted block of the corpus five-axis files gives back the CL
// tool tip and tool axis, in both output modes.
#include <cmath>

#include "readback/gcode_interp.h"
#include "machine/kinematics.h"
#include "driver/readback_commands.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ir::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

const KinematicsSettings& umc() {
  static Machine m = machine("haas-umc750");
  return m.kinematics;
}

std::vector<kin::Solution> solve(const Vec3& v) { return kin::solve(umc(), v.normalized()); }

// Every solution turns the tool back onto the axis it was asked for.
void expect_exact(const Vec3& v) {
  auto s = solve(v);
  ASSERT_FALSE(s.empty()) << v.transpose();
  for (const auto& x : s) EXPECT_LT(kin::angle_between(kin::tool_axis_in_part(umc(), x.a), v.normalized()), 1e-9) << v.transpose();
}

// The round-trip machine: the UMC in millimetres with a fine resolution, so that 0.001 mm and
// 0.001 degrees are meaningful (4-decimal inches alone round by up to 0.0013 mm).
std::string fine_umc(const std::string& name, const std::string& extra) {
  return "[" + name + "]\ninherits = \"haas-umc750\"\nunits = \"mm\"\n[" + name +
         ".format]\nX = { decimals = 4 }\nY = { decimals = 4 }\nZ = { decimals = 4 }\nI = { decimals = 4 }\n"
         "J = { decimals = 4 }\nK = { decimals = 4 }\nB = { decimals = 5 }\nC = { decimals = 5 }\n"
         "[" + name + ".kinematics]\ntravel = { x = [-762.0, 0.0], y = [-508.0, 0.0], z = [-508.0, 0.0] }\n" + extra;
}

}  // namespace

// --- the solver ---------------------------------------------------------------------------

TEST(Solver, PrincipalDirections) {
  for (Vec3 v : std::vector<Vec3>{Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()})
    expect_exact(v);
  // +X needs B = 90 with C = 0 (or B = -90, C = 180).
  auto s = solve(Vec3::UnitX());
  ASSERT_EQ(s.size(), 2u);
  EXPECT_NEAR(std::abs(s[0].a[0]), 90, 1e-9);
  EXPECT_NEAR(std::abs(s[1].a[0]), 90, 1e-9);
  // Pointing down: B = 180 (no trunnion reaches it; the limits decide that, not the solver).
  auto d = solve(-Vec3::UnitZ());
  ASSERT_FALSE(d.empty());
  EXPECT_NEAR(std::abs(d[0].a[0]), 180, 1e-9);
}

TEST(Solver, VerticalIsSingular) {
  auto s = solve(Vec3::UnitZ());
  ASSERT_EQ(s.size(), 1u);
  EXPECT_NEAR(s[0].a[0], 0, 1e-12);
  EXPECT_TRUE(s[0].free[1]);  // C: any value
}

TEST(Solver, NearVertical) {
  // 1e-9 off vertical: singular (any C gives the axis to 1e-9 rad).
  Vec3 a(1e-9, 0, 1);
  auto s = solve(a);
  EXPECT_TRUE(s[0].free[1]);
  EXPECT_LT(kin::angle_between(kin::tool_axis_in_part(umc(), {s[0].a[0], 123.0}), a.normalized()), 1e-6);
  // 1e-4 off vertical: C is determined, and exact.
  Vec3 b(0, 1e-4, 1);
  auto t = solve(b);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_FALSE(t[0].free[1]);
  expect_exact(b);
  EXPECT_NEAR(std::abs(t[0].a[0]), std::atan(1e-4) * 180 / kPi, 1e-9);
}

TEST(Solver, RandomAxesAreExact) {
  std::srand(7);
  for (int i = 0; i < 2000; ++i) {
    Vec3 v(std::rand() / double(RAND_MAX) - 0.5, std::rand() / double(RAND_MAX) - 0.5, std::rand() / double(RAND_MAX) - 0.5);
    if (v.norm() < 1e-3) continue;
    expect_exact(v);
  }
}

// The pass's choice, through the whole compile: a path, and what the control is told.
namespace {

struct Path {
  bool ok;
  std::string output, diags;
  gcode::Result read;
};

Path compile_path_axes(const std::vector<Vec3>& axes, const std::string& machine_name = "haas-umc750",
                       const std::string& extra = {}) {
  std::string cl = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\nMULTAX/ON\n";
  for (size_t i = 0; i < axes.size(); ++i) {
    Vec3 a = axes[i].normalized();
    char b[160];
    std::snprintf(b, sizeof b, "GOTO/%.1f,0,10,%.12f,%.12f,%.12f\n", double(i), a.x(), a.y(), a.z());
    cl += b;
  }
  Machine m = machine(machine_name, extra);
  Compiled c = compile_text(cl, m);
  Path p{c.ok, c.output, c.diags, {}};
  if (c.ok) p.read = gcode::interpret(c.output, m);
  return p;
}

Vec3 tilt(double b_deg, double c_deg) {  // the axis the UMC's B and C give
  return kin::tool_axis_in_part(umc(), {b_deg, c_deg});
}

std::vector<std::array<double, 2>> rotaries(const Path& p) {
  std::vector<std::array<double, 2>> r;
  for (const auto& s : p.read.segments) r.push_back({s.rotary[1], s.rotary[2]});  // B, C
  return r;
}

}  // namespace

namespace {
// The UMC preferring negative B, so that a path can run to B's lower limit.
const char* kNegUmc = "[neg-umc]\ninherits = \"haas-umc750\"\n[[neg-umc.kinematics.axes]]\nname = \"B\"\naxis = [0.0, 1.0, 0.0]\n"
                      "direction = -1\nmin = -35.0\nmax = 120.0\nprefer = -1\n[[neg-umc.kinematics.axes]]\nname = \"C\"\n"
                      "axis = [0.0, 0.0, 1.0]\ndirection = -1\ncyclic = \"wind\"\n";
}  // namespace

TEST(KinematicsPass, BExactlyAtItsLimits) {
  Path a = compile_path_axes({tilt(100, 0), tilt(120, 0)});
  ASSERT_TRUE(a.ok) << a.diags;
  EXPECT_NEAR(rotaries(a).back()[0], 120, 1e-9);
  Path b = compile_path_axes({tilt(-30, 0), tilt(-35, 0)}, "neg-umc", kNegUmc);
  ASSERT_TRUE(b.ok) << b.diags;
  EXPECT_NEAR(rotaries(b).back()[0], -35, 1e-9);
  // A CL's tool axis, written with 7 decimals, stands 1e-5 degree off the angle meant (NX's
  // 0.8660254 is 30.0000002 degrees): at the limit it was refused. Within 1e-4 degree it is the
  // limit; beyond it is not.
  Path c = compile_path_axes({tilt(-30, 0), tilt(-35.00002, 0)}, "neg-umc", kNegUmc);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr(" B-35.\n"));
  // And it is written at the limit: with 4 decimals B-35.0000 (it was B-35., rounded, but
  // B-35.0001 past the limit with a finer format).
  Path fine = compile_path_axes({tilt(-30, 0), tilt(-35.00008, 0)}, "neg-umc",
                                std::string(kNegUmc) + "[neg-umc.format]\nB = { decimals = 4 }\n");
  ASSERT_TRUE(fine.ok) << fine.diags;
  EXPECT_THAT(fine.output, HasSubstr(" B-35.\n"));
  Path d = compile_path_axes({tilt(-30, 0), tilt(-35.001, 0)}, "neg-umc", kNegUmc);
  EXPECT_FALSE(d.ok);
  EXPECT_THAT(d.diags, HasSubstr("leaves the rotary limits"));
}

TEST(KinematicsPass, BeyondTheLimitsUsesTheOtherSolutionOrFails) {
  // -50 is out of B's range: the other solution, B +50 with C turned half a turn, does it.
  Path a = compile_path_axes({tilt(-50, 30)});
  ASSERT_TRUE(a.ok) << a.diags;
  EXPECT_NEAR(rotaries(a).back()[0], 50, 1e-9);
  EXPECT_NEAR(std::fmod(rotaries(a).back()[1] + 720, 360), 210, 1e-9);
  // Pointing down (B 150 either way): no solution.
  Path b = compile_path_axes({tilt(10, 0), tilt(150, 0)});
  EXPECT_FALSE(b.ok);
  EXPECT_THAT(b.diags, HasSubstr(":7:1: error: no position of the rotary axes of machine 'haas-umc750' within their limits turns the tool to"));
}

TEST(KinematicsPass, CWindsThroughPlusMinus180And360) {
  std::vector<Vec3> axes;
  for (double c = 150; c <= 420; c += 15) axes.push_back(tilt(30, c));
  Path p = compile_path_axes(axes);
  ASSERT_TRUE(p.ok) << p.diags;
  auto r = rotaries(p);
  // Continuous: every step 15 degrees, through 180 and 360 without a jump back.
  for (size_t i = 2; i < r.size(); ++i) EXPECT_NEAR(r[i][1] - r[i - 1][1], 15, 1e-6) << i;
  EXPECT_NEAR(r.back()[1] - r[0][1], 270, 1e-6);
}

TEST(KinematicsPass, AModuloCWritesAnglesIn0To360) {
  std::string extra = "[mod-umc]\ninherits = \"haas-umc750\"\n[[mod-umc.kinematics.axes]]\nname = \"B\"\naxis = [0.0, 1.0, 0.0]\n"
                      "direction = -1\nmin = -35.0\nmax = 120.0\nprefer = 1\n[[mod-umc.kinematics.axes]]\nname = \"C\"\n"
                      "axis = [0.0, 0.0, 1.0]\ndirection = -1\ncyclic = \"modulo\"\n";
  std::vector<Vec3> axes;
  for (double c = 330; c <= 390; c += 15) axes.push_back(tilt(30, c));
  Path p = compile_path_axes(axes, "mod-umc", extra);
  ASSERT_TRUE(p.ok) << p.diags;
  EXPECT_THAT(p.output, HasSubstr("C345."));
  EXPECT_THAT(p.output, HasSubstr("C15."));
  EXPECT_EQ(p.output.find("C375."), std::string::npos);
}

TEST(KinematicsPass, APathThatNeedsTheSecondSolution) {
  // Through vertical in the YZ plane: B would go negative to -40 past its limit; the pass
  // switches branch exactly at vertical (B 0), turning C half a turn there, tool unmoved.
  std::vector<Vec3> axes;
  for (double b = 30; b >= -40; b -= 10) axes.push_back(tilt(b, 90));
  Path p = compile_path_axes(axes);
  ASSERT_TRUE(p.ok) << p.diags;
  auto r = rotaries(p);
  bool saw_flip_at_vertical = false;
  for (size_t i = 1; i < r.size(); ++i)
    if (std::abs(r[i][1] - r[i - 1][1]) > 90) {
      EXPECT_NEAR(r[i][0], 0, 1e-9);
      EXPECT_NEAR(r[i - 1][0], 0, 1e-9);
      saw_flip_at_vertical = true;
    }
  EXPECT_TRUE(saw_flip_at_vertical);
  for (const auto& x : r) EXPECT_GE(x[0], -1e-9);
}

TEST(KinematicsPass, AJumpTheLimitsForceIsAnErrorOrARetract) {
  // Along the B limit: C turns half way round while B sits near -34; the continuing branch
  // would need B below -35; the other branch is a jump.
  std::vector<Vec3> axes{tilt(-20, 0), tilt(-30, 0), tilt(-34, 0), tilt(-40, 0)};
  std::string strict = kNegUmc;
  Path p = compile_path_axes(axes, "neg-umc", strict);
  EXPECT_FALSE(p.ok);
  EXPECT_THAT(p.diags, HasSubstr(":9:1: error: tool axis"));
  EXPECT_THAT(p.diags, HasSubstr("leaves the rotary limits; the only way on is a jump to B40 C"));
  std::string retract = strict + "[neg-umc.kinematics]\non_limit = \"retract\"\nretract_distance = 2.0\n";
  Path q = compile_path_axes(axes, "neg-umc", retract);
  ASSERT_TRUE(q.ok) << q.diags;
  EXPECT_THAT(q.diags, HasSubstr("warning: the rotary axes must jump here: retracting, rotating and re-engaging"));
}

TEST(KinematicsPass, IndexedOperationPositionsOnceAndUsesG254) {
  Machine m = machine("haas-umc750");
  Compiled c = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\nRAPID\nGOTO/50,0,20,1,0,0\nGOTO/10,0,20,1,0,0\n"
      "GOTO/10,5,20,1,0,0\n",
      m);
  ASSERT_TRUE(c.ok) << c.diags;
  // The tool along +X: B 90, C 0, clamped; G254 turns the work offset; then 3-axis moves.
  EXPECT_THAT(c.output, HasSubstr("N30 G00 B90. C0.\nN35 M10 M12\nN40 G54 G254\nN45 G00 X-0.7874 Y0.\nN50 G43 H01 Z1.9685\n"));
  EXPECT_THAT(c.output, HasSubstr("G01 Z0.3937"));
  EXPECT_THAT(c.output, HasSubstr("G255\n"));
}

// NX and Creo start a 3+2 operation with a RAPID from the vertical tool to the tilted one.
// At the vertical C is free: it turns first, on the spot. That turn was a feed: with no
// FEDRAT yet the post stopped, after one it was G01 C90. at a linear F (degrees per minute).
TEST(KinematicsPass, ARapidLeavingTheVerticalTurnsTheFreeAxisAtRapid) {
  const std::string cl =
      "UNITS/MM\nLOADTL/1\nSPINDL/RPM,5000,CLW\nMULTAX\nRAPID\nGOTO/0,0,50,0,0,1\nRAPID\n"
      "GOTO/0,0,50,0,0.5,0.8660254\nRAPID\nGOTO/10,0,5,0,0.5,0.8660254\nFEDRAT/MMPM,500\n"
      "GOTO/10,0,0,0,0.5,0.8660254\nGOTO/30,0,0,0,0.5,0.8660254\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N35 G00 X0. Y0. B0. C0.\nN40 Z1.9685\nN45 C90.\nN50 B30.\n"));
  EXPECT_THAT(c.output, HasSubstr("G94 G01 Z0. F19.69\n"));
}

// The tool in the spindle loaded again between two points of a five-axis cut changes nothing:
// it switched TCPC off and on in the cut (G49, G234) and forgot the point, so C turned with B
// in the cut instead of alone at the vertical first. (helper-34)
TEST(KinematicsPass, TheSameToolLoadedAgainInACutChangesNothing) {
  const std::string head =
      "TOOL PATH/VAR_AXIS,TOOL,BALL10\nTLDATA/MILL,10,5,75,0,0\nLOAD/TOOL,1,ADJUST,1\nSPINDL/RPM,6000,CLW\nRAPID\n"
      "GOTO/20,10,10,0,0,1\nFEDRAT/MMPM,500\nGOTO/20,10,0,0,0,1\n";
  const std::string tail = "GOTO/25,10,0,0,0.1736482,0.9848078\nGOTO/30,10,0,0,0.3420201,0.9396926\nEND-OF-PATH\n";
  Compiled plain = compile_text(head + tail, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(plain.ok) << plain.diags;
  Compiled again = compile_text(head + "LOAD/TOOL,1,ADJUST,1\n" + tail, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(again.ok) << again.diags;
  EXPECT_EQ(again.output, plain.output);
  EXPECT_THAT(again.output, HasSubstr("\nN50 C90.\nN55 X0.9843 B10.\n"));
}

// From a side face (B90) to a simultaneous operation on the top, same tool: the rapid into it
// turned B while the tip ran straight across from the side face's end, through the part's
// corner. The tool now goes up first, as before a 3+2 operation; after a tool change it is up.
TEST(KinematicsPass, ARapidIntoAnOperationThatTurnsTheRotariesGoesUpFirst) {
  const std::string cl =
      "UNITS/INCHES\nTOOL PATH/SIDE90,TOOL,EM12\nTLDATA/MILL,0.5,0,3,0,0\nLOAD/TOOL,1,ADJUST,1\n"
      "MSYS/0,0,0,1,0,0,0,1,0\nSPINDL/RPM,5000,CLW\nRAPID\nGOTO/3,0,-1,1,0,0\nRAPID\nGOTO/2.1,0,-1\n"
      "FEDRAT/IPM,20\nGOTO/2,0,-1\nGOTO/2,1,-1\nRAPID\nGOTO/3,1,-1\nEND-OF-PATH\nTOOL PATH/TOP,TOOL,EM12\nRAPID\n"
      "GOTO/0,0,1,0,0,1\nRAPID\nGOTO/0,0,0.1\nFEDRAT/IPM,20\nGOTO/0,0,0\nGOTO/1,0,0,0.258819,0,0.9659258\n"
      "RAPID\nGOTO/1,0,1\nEND-OF-PATH\nFINI\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N75 G255\n(TOP)\nN80 G53 G00 Z0.\nN85 M11 M13\nN90 G00 B0.\nN95 M10 M12\n"
                                  "N100 G00 G234 H01\nN105 G00 X0. Y0.\nN110 Z1.\n"));  // CATIA loads the tool at every operation: the same tool again is no change, and the tool is
  // not up (the retract was skipped).
  std::string reload = cl;
  reload.insert(reload.find("TOOL PATH/TOP,TOOL,EM12\n") + 24, "LOAD/TOOL,1,ADJUST,1\n");
  Compiled r = compile_text(reload, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(r.ok) << r.diags;
  EXPECT_THAT(r.output, HasSubstr("(TOP)\nN80 G53 G00 Z0.\nN85 M11 M13\nN90 G00 B0.\n"));
  // An operation ending in a canned cycle leaves the tool at its return level, not up.
  std::string cycle = cl;
  const std::string last_cuts = "GOTO/2,0,-1\nGOTO/2,1,-1\nRAPID\nGOTO/3,1,-1\n";
  cycle.replace(cycle.find(last_cuts), last_cuts.size(), "CYCLE/DRILL,0.5,IPM,20,0.1\nGOTO/2,0,-1\nGOTO/2,1,-1\nCYCLE/OFF\n");
  Compiled h = compile_text(cycle, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(h.ok) << h.diags;
  EXPECT_THAT(h.output, HasSubstr("N70 G80\nN75 G255\n(TOP)\nN80 G53 G00 Z0.\nN85 M11 M13\nN90 G00 B0.\n"));
}

TEST(KinematicsPass, InverseTimeWhereTheMachineAsksForIt) {
  std::string extra = "[inv-umc]\ninherits = \"haas-umc750\"\n[inv-umc.kinematics]\nsimultaneous = \"transform\"\ninverse_time = true\n"
                      "max_inverse_time = 5000.0\n";
  Path p = compile_path_axes({tilt(10, 0), tilt(20, 0), tilt(30, 0)}, "inv-umc", extra);
  ASSERT_TRUE(p.ok) << p.diags;
  // Each CL move (1 mm at 500 mm/min) is split in two by the transform (B swings 10 degrees
  // about a point 10 mm up): each half takes 0.001 min, F1000 (1/min), written on every block.
  EXPECT_THAT(p.output, HasSubstr("N40 G93 X-0.0829 Z0.3854 B15. F1000.\nN45 X-0.0977 Z0.3834 B20. F1000.\n"));
}

// On an inverse-time machine without TCPC: a feed per revolution on a rotary move was written
// G95 F0.1, the tip at five times the CL's feed; a turn about a still tip with no rate to time
// it F1000000000. (helper-57). Both refused, once, at the move.
TEST(KinematicsPass, InverseTimeRefusesAFeedPerRevAndATurnItCannotTime) {
  const Machine m = machine("inv-umc", "[inv-umc]\ninherits = \"haas-umc750\"\n[inv-umc.kinematics]\nsimultaneous = \"transform\"\n"
                                       "inverse_time = true\n");
  const std::string head = "UNITS/MM\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,50,0,0,1\n";
  Compiled per_rev = compile_text(head + "FEDRAT/MMPR,0.1\nGOTO/0,0,10,0,0,1\nGOTO/0,1,10,0,0.0871557,0.9961947\nFINI\n", m);
  EXPECT_FALSE(per_rev.ok);
  EXPECT_THAT(per_rev.diags, HasSubstr(":9:1: error: a feed per revolution on a move that turns the rotaries without tool "
                                       "centre point control: the control reads F over all its axes at once, and the feed "
                                       "that keeps the tip at the CL's (G93) is one per minute; give five-axis moves a feed "
                                       "per minute (FEDRAT/MMPM, IPM)"));
  Compiled still = compile_text(head + "FEDRAT/MMPM,3\nGOTO/0,0,0,0,0,1\nGOTO/0,0,0,0,0.0174524,0.9998477\nFINI\n", m);
  EXPECT_FALSE(still.ok);
  EXPECT_THAT(still.diags, HasSubstr(":9:1: error: the rotaries turn at feed about the tool tip, which stands still: the CL's "
                                     "feed gives the move no time, and machine 'inv-umc' gives its rotary axes no rate"));
}

TEST(KinematicsPass, TransformModeSplitsMovesWhereTheTipWouldLeaveTheSegment) {
  std::string extra = "[tr-umc]\ninherits = \"haas-umc750\"\n[tr-umc.kinematics]\nsimultaneous = \"transform\"\ndegrees_per_minute = true\n";
  // A 40 degree swing of B about a point 100 mm off the rotary centre.
  std::string cl = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\nGOTO/100,0,10,0,0,1\nGOTO/101,0,10," +
                   std::to_string(std::sin(40 * kPi / 180)) + ",0," + std::to_string(std::cos(40 * kPi / 180)) + "\n";
  Machine m = machine("tr-umc", extra);
  Compiled c = compile_text(cl, m);
  ASSERT_TRUE(c.ok) << c.diags;
  gcode::Result g = gcode::interpret(c.output, m);
  EXPECT_GT(g.segments.size(), 8u);  // split into many pieces
}

// Without TCPC, G93 or degrees per minute, the control reads the CL's F over all the axes at
// once (mm and degrees): on a part 100 mm from B the tool would cut at another feed than the
// CL's, certified (helper-44's fault). Said once, at the first such move; a 3+2 job, whose
// rotaries turn only at rapid, still posts on that machine.
TEST(KinematicsPass, RotaryFeedsWithNoFeedModeAreRefusedOnce) {
  Machine m = machine("no-mode", "[no-mode]\ninherits = \"haas-umc750\"\n[no-mode.kinematics]\nsimultaneous = \"transform\"\n"
                                 "indexed = \"transform\"\n");
  Compiled five = compile_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\nRAPID\nGOTO/100,0,10,0,0,1\n"
                               "GOTO/101,0,10,0.5,0,0.8660254\nGOTO/102,0,10,0.6427876,0,0.7660444\n",
                               m);
  EXPECT_FALSE(five.ok);
  EXPECT_THAT(five.diags, HasSubstr(":7:1: error: machine 'no-mode' turns its rotaries while feeding without tool centre point "
                                    "control, and says neither kinematics.inverse_time (G93) nor kinematics.degrees_per_minute"));
  EXPECT_EQ(five.diags.find("says neither"), five.diags.rfind("says neither")) << five.diags;
  Compiled tilted = compile_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\nRAPID\n"
                                 "GOTO/10,0,10,0.5,0,0.8660254\nGOTO/20,0,10,0.5,0,0.8660254\n",
                                 m, {.certify = true});
  EXPECT_TRUE(tilted.ok) << tilted.diags;
}

TEST(KinematicsPass, ThreeAxisMachineRefusesATiltedTool) {
  Compiled c = compile_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/100\nGOTO/0,0,0,0,0.6,0.8\n", machine("fanuc-mill"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":5:1: error: tool axis (0, 0.6, 0.8) is not the spindle axis, and machine 'fanuc-mill' has no rotary axes to tilt it"));
}

TEST(KinematicsPass, HeadTableMachineFromToml) {
  // A B head (tilting the spindle about Y, pivot 200 mm) over a C table: the model solves it and
  // the transform puts the pivot where the tip must be.
  std::string toml = "[bc-head]\ninherits = \"fanuc-mill\"\npipeline = [\"arc-direction\", \"helix\", \"drill-cycles\", \"rapid-split\", \"offset-table\", "
                     "\"kinematics\", \"arc-legalise\"]\n[bc-head.format]\nB = { decimals = 4 }\nC = { decimals = 4 }\nX = { decimals = 4 }\n"
                     "Y = { decimals = 4 }\nZ = { decimals = 4 }\n[bc-head.kinematics]\nsimultaneous = \"transform\"\ndegrees_per_minute = true\n"
                     "pivot = 200.0\n[[bc-head.kinematics.axes]]\nname = \"C\"\naxis = [0.0, 0.0, 1.0]\nside = \"table\"\n"
                     "cyclic = \"wind\"\n[[bc-head.kinematics.axes]]\nname = \"B\"\naxis = [0.0, 1.0, 0.0]\nside = \"head\"\n"
                     "min = -90.0\nmax = 90.0\n";
  Machine m = machine("bc-head", toml);
  for (Vec3 v : std::vector<Vec3>{Vec3(0.3, 0.4, 0.866), Vec3(-0.5, 0.2, 0.8), Vec3(0, 0, 1)}) {
    auto s = kin::solve(m.kinematics, v.normalized());
    ASSERT_FALSE(s.empty());
    for (auto& x : s) EXPECT_LT(kin::angle_between(kin::tool_axis_in_part(m.kinematics, x.a), v.normalized()), 1e-9);
    // Forward then back: the tip survives the trip through the pivot.
    Vec3 tip(12, -7, 3);
    Vec3 mp = kin::machine_point(m.kinematics, s[0].a, tip, 200);
    EXPECT_LT((kin::part_tip(m.kinematics, s[0].a, mp, 200) - tip).norm(), 1e-9);
  }
  Compiled c = compile_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/100\nGOTO/0,0,0,0,0,1\nGOTO/10,0,0,0.5,0,0.866\n", m);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("B30."));
  // A tap along the tilted head: the machine has G84, the hole cannot take it (it was said that
  // codes.cycle_tap is empty; helper-52).
  Compiled tap = compile_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/10,0,20,0.5,0,0.866\n"
                              "CYCLE/TAP,DEPTH,7,PITCH,1,CLEAR,1\nGOTO/10,0,0,0.5,0,0.866\nCYCLE/OFF\n", m);
  EXPECT_FALSE(tap.ok);
  EXPECT_THAT(tap.diags, HasSubstr(":7:1: error: a tap cycle cannot be written as plain moves: the machine needs the canned "
                                   "cycle for it, but this hole cannot take one: its axis is not the machine's Z here"));
  // A vertical tap in a simultaneous operation of a table-table machine: it is the operation,
  // not the hole's axis, that keeps the cycle out (helper-55).
  Compiled simultaneous = compile_text("UNITS/MM\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,500,CLW\nFEDRAT/MMPM,100\nRAPID\n"
                                       "GOTO/10,0,50,0,0,1\nGOTO/10,0,40,0.5,0,0.8660254\nGOTO/10,0,20,0,0,1\n"
                                       "CYCLE/TAP,DEPTH,7,PITCH,1,CLEAR,1\nGOTO/10,0,0,0,0,1\nCYCLE/OFF\n",
                                       machine("haas-umc750"));
  EXPECT_THAT(simultaneous.diags, HasSubstr(":11:1: error: a tap cycle cannot be written as plain moves: the machine needs the "
                                            "canned cycle for it, but this hole is in a simultaneous five-axis operation (its "
                                            "tool axis changes), where the axes follow the tool and no canned cycle runs: give "
                                            "the hole an operation of its own"));
}

namespace {

// A five-axis operation of 20 moves per tool axis given (a null axis: C winds 5 degrees a move
// at B30), one operation, so that its chunks of 8 instructions see the phases apart.
std::string phased_operation(const std::vector<std::optional<Vec3>>& phases) {
  std::string cl = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\nMULTAX/ON\n";
  int n = 0;
  for (const auto& phase : phases)
    for (int i = 0; i < 20; ++i, ++n) {
      Vec3 a = phase ? phase->normalized() : tilt(30, 5.0 * n);
      char b[160];
      std::snprintf(b, sizeof b, "GOTO/%.1f,0,10,%.12f,%.12f,%.12f\n", 0.5 * n, a.x(), a.y(), a.z());
      cl += b;
    }
  return cl + "FINI\n";
}

size_t occurrences(const std::string& text, const std::string& word) {
  size_t n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

CompileOptions short_chunks() {
  CompileOptions o;
  o.lower.chunk_size = 8;
  return o;
}

}  // namespace

// A long operation reaches the pass in chunks (lower/lower.h), each seen alone. Its rotaries are
// indexed at most once: once a chunk needed simultaneous motion the operation stays so, and
// a later run of moves at one axis is not clamped and re-indexed mid-cut.
TEST(KinematicsPass, ALongOperationIndexesAtMostOnceWhateverItsChunks) {
  TempDir t;
  const Machine m = machine("haas-umc750");
  const std::string indexed_then_not = t.path("a.cls");
  write_file(indexed_then_not, phased_operation({tilt(30, 0), std::nullopt, tilt(40, 90)}));
  Compiled c = compile_path(indexed_then_not, m, short_chunks());
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(occurrences(c.output, "M10"), 1u);   // the clamp of the first (indexed) chunks
  EXPECT_EQ(occurrences(c.output, "G254"), 1u);
  EXPECT_EQ(occurrences(c.output, "G234"), 1u);  // then TCPC to the end of the operation
  VerifyOptions vo;
  vo.compile = short_chunks();
  std::ostringstream err;
  VerifyReport r = verify_file(indexed_then_not, m, vo, err);
  EXPECT_TRUE(r.ok) << err.str();
  EXPECT_EQ(r.cl_points, 60);

  // Simultaneous from the first chunk: the chunks change nothing.
  const std::string simultaneous_first = t.path("b.cls");
  write_file(simultaneous_first, phased_operation({std::nullopt, tilt(40, 90), tilt(30, 0)}));
  Compiled whole = compile_path(simultaneous_first, m);
  Compiled chunked = compile_path(simultaneous_first, m, short_chunks());
  ASSERT_TRUE(whole.ok && chunked.ok) << whole.diags << chunked.diags;
  EXPECT_EQ(occurrences(whole.output, "M10"), 0u);
  EXPECT_EQ(chunked.output, whole.output);
}

// --- limits ---------------------------------------------------------------------------------

TEST(Limits, RotaryAndLinearTravelErrorsNameTheRecord) {
  std::string extra = "[zeroed]\ninherits = \"haas-umc750\"\n[zeroed.kinematics]\nwork_zero = [-15.0, -10.0, -15.0]\n";
  Machine m = machine("zeroed", extra);
  Compiled c = compile_text("UNITS/INCHES\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/10\nGOTO/0,0,1\nGOTO/0,12,1\n", m);
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":6:1: error: Y reaches 2 in in machine coordinates, beyond the travel (-20 to 0)"));
  Compiled span = compile_text("UNITS/INCHES\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/10\nGOTO/0,0,1\nGOTO/25,0,1\nGOTO/-6,0,1\n",
                               machine("haas-umc750"));
  EXPECT_FALSE(span.ok);
  EXPECT_THAT(span.diags, HasSubstr(":7:1: error: the program's X positions now span 31 in, more than the machine's 30 in of travel"));
}

// --- the round trip -------------------------------------------------------------------------

namespace {

struct Trip {
  int blocks = 0, cl_points = 0, holes = 0;
  double worst_tip = 0, worst_axis = 0, worst_excess_turn = 0;
};

// The CL's points in order, with their tool axes (lowering only: the reference).
struct ClPoint {
  Vec3 tip, axis;
  bool hole = false;
};

void round_trip(const std::string& file, const Machine& m, Trip& t) {
  SCOPED_TRACE(file + " on " + m.name);
  Compiled c = compile_path(file, m);
  ASSERT_TRUE(c.ok) << c.diags;
  gcode::Result g = gcode::interpret(c.output, m);
  for (auto& p : g.problems) ADD_FAILURE() << "line " << p.line << ": " << p.message;
  Lowered l = lower_text(read_file(file));
  const double k = ir::mm_per_unit(l.info.units) / ir::mm_per_unit(m.units);
  std::vector<ClPoint> cl;
  bool in_cycle = false;
  for (auto& op : l.ops)
    for (auto& in : op.body) {
      if (std::holds_alternative<ir::CycleOn>(in.op)) in_cycle = true;
      if (std::holds_alternative<ir::CycleOff>(in.op)) in_cycle = false;
      if (auto* mv = std::get_if<ir::Move>(&in.op); mv && mv->kind != ir::MoveKind::From)
        cl.push_back({mv->point * k, mv->axis, in_cycle});
      else if (auto* a = std::get_if<ir::Arc>(&in.op))
        cl.push_back({a->end * k, a->tool_axis, false});
    }
  const KinematicsSettings& kin_ = m.kinematics;
  // Every block's tip and axis, back in the part frame.
  struct Back {
    Vec3 tip, axis;
    std::array<double, 2> rot;
    bool cycle;
  };
  std::vector<Back> back;
  for (const auto& s : g.segments) {
    if (std::isnan(s.end.x()) || std::isnan(s.end.y()) || std::isnan(s.end.z())) continue;
    kin::Angles a{s.rotary[1], s.rotary[2]};
    Vec3 part = s.tcp ? s.end : s.dwo ? Vec3(kin::table_rotation(kin_, a).transpose() * s.end) : kin::part_tip(kin_, a, s.end, 0);
    back.push_back({part, kin::tool_axis_in_part(kin_, a), a, s.from_cycle});
    ++t.blocks;
  }
  // Each CL point is reached, in order, with its axis.
  size_t j = 0;
  for (const ClPoint& p : cl) {
    if (p.hole) {
      // A hole: a cycle segment passes through the hole's point along its axis.
      bool found = false;
      for (const Back& b : back) {
        if (!b.cycle) continue;
        Vec3 d = b.tip - p.tip;
        double off_axis = (d - d.dot(p.axis) * p.axis).norm();
        if (off_axis < 0.001 && kin::angle_between(b.axis, p.axis) < 0.001) found = true;
      }
      EXPECT_TRUE(found) << "hole at " << p.tip.transpose();
      ++t.holes;
      continue;
    }
    bool found = false;
    for (size_t i = j; i < back.size(); ++i) {
      double dt = (back[i].tip - p.tip).norm(), da = kin::angle_between(back[i].axis, p.axis);
      if (dt < 0.001 && da < 0.001) {
        t.worst_tip = std::max(t.worst_tip, dt);
        t.worst_axis = std::max(t.worst_axis, da);
        j = i;
        found = true;
        break;
      }
    }
    EXPECT_TRUE(found) << "CL point " << p.tip.transpose() << " axis " << p.axis.transpose() << " is never reached";
    ++t.cl_points;
  }
  // No rotary jump beyond what the CL's change of axis requires: halfway through each block's
  // rotary move, the tool points between the axes at its ends.
  for (size_t i = 1; i < back.size(); ++i) {
    double needed = kin::angle_between(back[i - 1].axis, back[i].axis);
    kin::Angles mid{(back[i - 1].rot[0] + back[i].rot[0]) / 2, (back[i - 1].rot[1] + back[i].rot[1]) / 2};
    Vec3 am = kin::tool_axis_in_part(kin_, mid);
    double excess = std::max(kin::angle_between(am, back[i - 1].axis), kin::angle_between(am, back[i].axis)) - needed;
    t.worst_excess_turn = std::max(t.worst_excess_turn, excess);
    EXPECT_LE(excess, 0.001) << "block " << i << ": the rotaries swing the tool " << excess << " degrees beyond its path";
  }
}

}  // namespace

TEST(RoundTrip, CorpusFiveAxisFilesInBothModes) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR;
  std::string both = fine_umc("umc-tcp", "") + fine_umc("umc-transform", "simultaneous = \"transform\"\nindexed = \"transform\"\ndegrees_per_minute = true\n");
  for (const char* name : {"umc-tcp", "umc-transform"}) {
    Machine m = machine(name, both);
    Trip t;
    for (const char* f : {"nist/multi_axis1.ncl.2", "nist/b45_face.ncl", "nist/b270_alldrill.ncl", "nist/casting_drill_tap.ncl.1"})
      round_trip(corpus_dir() + "/" + f, m, t);
    std::printf("%s: %d blocks, %d CL points, %d holes; worst tip %.2g mm, worst axis %.2g deg, worst swing beyond the path %.2g deg\n",
                name, t.blocks, t.cl_points, t.holes, t.worst_tip, t.worst_axis, t.worst_excess_turn);
    EXPECT_GT(t.cl_points, 150);
  }
}

// A pass 3 degrees from vertical under TCPC: the tip goes straight, but the control turns B and
// C at proportional rates, and C swings 84 degrees in the block while B dips: halfway the tool
// axis was 9.3 degrees off the CL's sweep from one point's axis to the next, certified
// (helper-63). The pass puts points on the sweep; verify fails the one-block program.
TEST(KinematicsPass, TheToolAxisFollowsTheClsSweepBetweenPointsNearThePole) {
  const std::string cl =
      "UNITS/MM\nTOOL PATH/FINISH_5AX,TOOL,BALL10\nTLDATA/MILL,10,5,75,0,0\nLOAD/TOOL,1\nSPINDL/RPM,8000,CLW\nRAPID\n"
      "GOTO/-20,0,50,-0.4993762,0.0499376,0.8650451\nFEDRAT/MMPM,1000\nGOTO/-20,0,0,-0.4993762,0.0499376,0.8650451\n"
      "GOTO/0,0,0,0,0.0499792,0.9987503\nGOTO/20,0,0,0.4993762,0.0499376,0.8650451\nRAPID\n"
      "GOTO/20,0,50,0.4993762,0.0499376,0.8650451\nEND-OF-PATH\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  // Halved where the swing is widest: closest to the pole, the pieces are shortest.
  EXPECT_THAT(c.output, HasSubstr("N45 G94 G01 Z0. F39.37\nN50 X-0.3937 B15.282 C168.685\nN55 X-0.1969 B8.051 C158.522\n"
                                  "N60 X-0.0984 B4.744 C142.155\nN65 X-0.0492 B3.443 C122.96\nN70 X0. B2.865 C90.\n"
                                  "N75 X0.0492 B3.443 C57.04\n"));
  const std::string one_block =
      "%\nO01234\nN10 G20\nN15 G00 G17 G40 G49 G80 G90\nN20 T1 M06\nN25 S8000 M03\nN30 G54 G00 G234 H01\n"
      "N35 G00 X-0.7874 Y0. B30.121 C174.289\nN40 Z1.9685\nN45 G94 G01 Z0. F39.37\nN50 X0. B2.865 C90.\n"
      "N55 X0.7874 B30.121 C5.711\nN60 G00 X1.6376 Y0.085 Z1.4728\nN65 X0.7874 Y0. Z1.9685\nN70 G49\nN75 M05\n"
      "N80 G53 G00 Z0.\nN85 M30\n%\n";
  Compiled v = verify_text(cl, machine("haas-umc750"), one_block);
  EXPECT_FALSE(v.ok);
  EXPECT_THAT(v.diags, HasSubstr("part.cl:10:1: error: halfway between CL points the tool axis is 9.259 degrees off the "
                                 "CL's sweep from one point's axis to the next (the control turns the rotaries at "
                                 "proportional rates; the move wants more points) [G-code line 11]"));
}

// From B20 C0 to an axis 120 degrees round at the same tilt: the least travel was the other
// branch (B-20 C-60), through the pole while the CL's sweep stays 10 degrees from it; certified
// (helper-65). The branch stays, C swings, and the move is split along the sweep.
TEST(KinematicsPass, AFeedKeepsItsBranchWhereTheSweepStaysClearOfThePole) {
  const std::string cl = "UNITS/MM\nMULTAX\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\n"
                         "GOTO/17.101007,0,46.984631,0.342020143,0,0.939692621\nFEDRAT/500,MMPM\n"
                         "GOTO/0,0,0,0.342020143,0,0.939692621\nGOTO/10,0,0,-0.171010072,0.296198133,0.939692621\n"
                         "RAPID\nGOTO/1.449496,14.809907,46.984631,-0.171010072,0.296198133,0.939692621\nEND\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N50 X0.0492 B16.479 C7.967\n"));
  EXPECT_THAT(c.output, HasSubstr("N65 X0.1969 B10.314 C60.\n"));
  EXPECT_THAT(c.output, HasSubstr("N85 X0.3937 B20. C120.\n"));
}
