// The G-code reader runs the lathe's stock-removal cycles (G71, G72 type I, G70) as
// ir/stock_model.h models a Fanuc doing it: the level cuts, pull-outs, the last cut along the
// profile shifted by the allowances, and the return; the profile's blocks read, not run.
#include "helpers.h"
#include "readback/gcode_interp.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

// Segments as "R|F|A(ccw|cw c=z,x) z,x -> z,x @line" in radius, 4 decimals.
std::string moves(const gcode::Result& r, size_t from = 0) {
  std::string s;
  char b[160];
  for (size_t i = from; i < r.segments.size(); ++i) {
    const gcode::Segment& g = r.segments[i];
    const char* k = g.kind == gcode::Segment::Kind::Rapid ? "R" : g.kind == gcode::Segment::Kind::Feed ? "F" : (g.ccw ? "A+" : "A-");
    std::snprintf(b, sizeof b, "%s %.4f,%.4f -> %.4f,%.4f @%d%s\n", k, g.start.z(), g.start.x(), g.end.z(), g.end.x(), g.line,
                  g.from_cycle ? " cycle" : "");
    s += b;
  }
  return s;
}

const std::string kHead =
    "%\nO0001\nG18 G21 G40 G99\nT0101\nG97 S800 M03\nG00 X52. Z2.\n";  // lines 1-6: A = (z 2, x 26)

}  // namespace

TEST(StockCycles, G71TurnsInLevelsThenFollowsTheShiftedProfile) {
  const std::string prog = kHead +
                           "G71 U4. R1.\n"                        // 7: Δd 4, e 1 (radius)
                           "G71 P10 Q20 U0.4 W0.1 F0.25\n"        // 8: Δu 0.4 (diameter), Δw 0.1
                           "N10 G00 X20.\n"                       // 9: A' x 10
                           "G01 Z-15.\n"                          // 10
                           "X30. Z-25.\n"                         // 11
                           "N20 X52.\n"                           // 12: B x 26
                           "G00 X100. Z50.\n"                     // 13: runs after the cycle
                           "M30\n%\n";
  gcode::Result r = gcode::interpret(prog, machine("fanuc-lathe"));
  for (auto& p : r.problems) ADD_FAILURE() << "line " << p.line << ": " << p.message;
  EXPECT_EQ(r.cycles, 1);
  // Shifted profile: x + 0.2, z + 0.1. Levels x 22, 18, 14 (the next, 10, is not above
  // A' + 0.2). Level 22 meets the profile on X30 Z-25 -> X52 (x 15.2 .. 26.2) at z -24.9; 18
  // too; 14 on the taper (x 10.2 -> 15.2 over z -14.9 -> -24.9) at z -22.5.
  EXPECT_EQ(moves(r, 1),
            "R 2.0000,26.0000 -> 2.0000,22.0000 @8 cycle\n"
            "F 2.0000,22.0000 -> -24.9000,22.0000 @8 cycle\n"
            "F -24.9000,22.0000 -> -23.9000,23.0000 @8 cycle\n"
            "R -23.9000,23.0000 -> 2.0000,23.0000 @8 cycle\n"
            "R 2.0000,23.0000 -> 2.0000,18.0000 @8 cycle\n"
            "F 2.0000,18.0000 -> -24.9000,18.0000 @8 cycle\n"
            "F -24.9000,18.0000 -> -23.9000,19.0000 @8 cycle\n"
            "R -23.9000,19.0000 -> 2.0000,19.0000 @8 cycle\n"
            "R 2.0000,19.0000 -> 2.0000,14.0000 @8 cycle\n"
            "F 2.0000,14.0000 -> -22.5000,14.0000 @8 cycle\n"
            "F -22.5000,14.0000 -> -21.5000,15.0000 @8 cycle\n"
            "R -21.5000,15.0000 -> 2.0000,15.0000 @8 cycle\n"
            "R 2.0000,15.0000 -> 2.1000,10.2000 @8 cycle\n"
            "F 2.1000,10.2000 -> -14.9000,10.2000 @8 cycle\n"
            "F -14.9000,10.2000 -> -24.9000,15.2000 @8 cycle\n"
            "F -24.9000,15.2000 -> -24.9000,26.2000 @8 cycle\n"
            "R -24.9000,26.2000 -> 2.0000,26.0000 @8 cycle\n"
            "R 2.0000,26.0000 -> 50.0000,50.0000 @13\n");
}

TEST(StockCycles, G72FacesInLevelsAndG70RunsTheProfileAsWritten) {
  const std::string prog = kHead +
                           "G72 W2. R0.5\n"                   // 7: Δd 2 along Z, e 0.5
                           "G72 P30 Q40 U0.2 W0.1 F0.2\n"     // 8
                           "N30 G00 Z-6.\n"                   // 9: A' (x 26, z -6)
                           "G01 X30.\n"                       // 10
                           "X20. Z-3.\n"                      // 11
                           "N40 X0.\n"                        // 12: B (x 0, z -3)
                           "G70 P30 Q40\n"                    // 13
                           "M30\n%\n";
  gcode::Result r = gcode::interpret(prog, machine("fanuc-lathe"));
  for (auto& p : r.problems) ADD_FAILURE() << "line " << p.line << ": " << p.message;
  EXPECT_EQ(r.cycles, 2);
  // Levels z 0, -2 (the profile lies below them all: cut to B's x + 0.1) and -4 (meets the
  // taper x 15.1 -> 10.1 over z -5.9 -> -2.9 at x 11.9333); then the shifted profile; then
  // G70: the blocks as written and back to the start.
  EXPECT_EQ(moves(r, 1),
            "R 2.0000,26.0000 -> 0.0000,26.0000 @8 cycle\n"
            "F 0.0000,26.0000 -> 0.0000,0.1000 @8 cycle\n"
            "F 0.0000,0.1000 -> 0.5000,0.6000 @8 cycle\n"
            "R 0.5000,0.6000 -> 0.5000,26.0000 @8 cycle\n"
            "R 0.5000,26.0000 -> -2.0000,26.0000 @8 cycle\n"
            "F -2.0000,26.0000 -> -2.0000,0.1000 @8 cycle\n"
            "F -2.0000,0.1000 -> -1.5000,0.6000 @8 cycle\n"
            "R -1.5000,0.6000 -> -1.5000,26.0000 @8 cycle\n"
            "R -1.5000,26.0000 -> -4.0000,26.0000 @8 cycle\n"
            "F -4.0000,26.0000 -> -4.0000,11.9333 @8 cycle\n"
            "F -4.0000,11.9333 -> -3.5000,12.4333 @8 cycle\n"
            "R -3.5000,12.4333 -> -3.5000,26.0000 @8 cycle\n"
            "R -3.5000,26.0000 -> -5.9000,26.1000 @8 cycle\n"
            "F -5.9000,26.1000 -> -5.9000,15.1000 @8 cycle\n"
            "F -5.9000,15.1000 -> -2.9000,10.1000 @8 cycle\n"
            "F -2.9000,10.1000 -> -2.9000,0.1000 @8 cycle\n"
            "R -2.9000,0.1000 -> 2.0000,26.0000 @8 cycle\n"
            "R 2.0000,26.0000 -> -6.0000,26.0000 @9 cycle\n"
            "F -6.0000,26.0000 -> -6.0000,15.0000 @10 cycle\n"
            "F -6.0000,15.0000 -> -3.0000,10.0000 @11 cycle\n"
            "F -3.0000,10.0000 -> -3.0000,0.0000 @12 cycle\n"
            "R -3.0000,0.0000 -> 2.0000,26.0000 @13 cycle\n");
}

TEST(StockCycles, LevelsMeetAnArcOfTheProfile) {
  const std::string prog = kHead +
                           "G71 U4. R1.\n"
                           "G71 P10 Q20 U0. W0. F0.25\n"
                           "N10 G01 X20.\n"                  // 9: entered at feed
                           "Z-10.\n"
                           "G03 X40. Z-20. I0. K-10.\n"      // 11: centre (z -20, x 10), r 10
                           "N20 G01 X52.\n"
                           "M30\n%\n";
  gcode::Result r = gcode::interpret(prog, machine("fanuc-lathe"));
  for (auto& p : r.problems) ADD_FAILURE() << "line " << p.line << ": " << p.message;
  const std::string m = moves(r, 1);
  EXPECT_THAT(m, HasSubstr("F 2.0000,26.0000 -> 2.0000,22.0000 @8 cycle\nF 2.0000,22.0000 -> -20.0000,22.0000 @8"));
  EXPECT_THAT(m, HasSubstr("F 2.0000,18.0000 -> -14.0000,18.0000 @8"));  // z = -20 + sqrt(100 - 8²)
  EXPECT_THAT(m, HasSubstr("F 2.0000,14.0000 -> -10.8348,14.0000 @8"));  // z = -20 + sqrt(100 - 4²)
  EXPECT_THAT(m, HasSubstr("F 2.0000,10.0000 -> -10.0000,10.0000 @8 cycle\nA+ -10.0000,10.0000 -> -20.0000,20.0000 @8 cycle\n"));
  EXPECT_EQ(r.segments.back().end, ir::Vec3(26, 0, 2));
}

TEST(StockCycles, WhatTheControlAlarmsOnIsAProblem) {
  auto problems = [](const std::string& body) {
    gcode::Result r = gcode::interpret(kHead + body + "M30\n%\n", machine("fanuc-lathe"));
    std::string s;
    for (auto& p : r.problems) s += std::to_string(p.line) + ": " + p.message + "\n";
    return s;
  };
  EXPECT_EQ(problems("G71 U2. R0.5\nG71 P10 Q20 F0.2\nN10 G00 X20.\nG01 Z-10.\nX16. Z-15.\nN20 X52.\n"),
            "8: G71: the profile turns back along X (G-code line 11): a pocket, which a type I cycle does not cut; the "
            "control alarms\n");
  EXPECT_EQ(problems("G71 U2. R0.5\nG71 P10 Q20 F0.2\nN10 G00 X20. Z0.\nG01 Z-10.\nN20 X52.\n"),
            "8: G71: its first block (G-code line 9) moves along Z: a type I cycle's first block moves along X alone; the "
            "control alarms\n");
  EXPECT_EQ(problems("G71 U2. R0.5\nG71 P10 Q20 F0.2\nG00 X20.\n"),
            "8: G71 P10 Q20: the block after it is not N10: clpc's reader takes the profile only where it follows its cycle\n");
  EXPECT_EQ(problems("G71 U2. R0.5\nG71 P10 Q20 F0.2\nN10 G00 X20.\nG01 Z-10.\n"),
            "8: G71 P10 Q20: no block N20 ends the profile before line 11\n");
  EXPECT_EQ(problems("G70 P10 Q20\n"), "7: G70 P10 Q20: no profile of those blocks was read with a G71/G72 before it\n");
  EXPECT_EQ(problems("G71 U0. R0.5\nG71 P10 Q20 F0.2\nN10 G00 X20.\nN20 G01 Z-10.\n"),
            "8: G71: the depth of cut is not above zero; the control alarms\n");
}
