// CYCLE/ROUGH (docs/lathe.md, "Stock removal"): the record read, the cycle written as G71/G72
// with its profile numbered and G70, certified; what the control would refuse is a located
// error at compile time, and verify catches a program whose cycle is not the CL's.
#include "helpers.h"
#include "readback/gcode_interp.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

// A metric lathe file: the tool at A = (x 26, z 2), then `cycle` and its profile.
std::string rough_cl(const std::string& cycle, const std::string& profile) {
  return "PARTNO / ROUGH\nMACHIN / TURN, 01\nUNITS / MM\nTURRET / 1\nSPINDL / RPM, 800.0, CLW\nFEDRAT / 0.25, MMPR\n"
         "RAPID\nGOTO / 26.0, 0.0, 2.0\n" +  // lines 1-8
         cycle + "\n" + profile + "CYCLE / OFF\nRAPID\nGOTO / 60.0, 0.0, 50.0\nFINI\n";
}

const std::string kTaper =
    "RAPID\nGOTO / 10.0, 0.0, 2.0\nGOTO / 10.0, 0.0, -15.0\nGOTO / 15.0, 0.0, -25.0\nGOTO / 26.0, 0.0, -25.0\n";

}  // namespace

TEST(Rough, TurningWrittenAsG71WithItsProfileAndG70Certified) {
  Compiled c = compile_text(rough_cl("CYCLE / ROUGH, TURN, DEPTH, 4, RETRACT, 1, ALLOW, 0.2, 0.1, FINISH", kTaper),
                            machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  // P and Q are taken from the block numbers before the cycle's blocks are numbered: unique,
  // out of order (the control searches for them, in any order).
  EXPECT_THAT(c.output, HasSubstr("N50 G00 X52. Z2.\n"
                                  "N80 G71 U4. R1.\n"
                                  "N90 G99 G71 P60 Q70 U0.4 W0.1 F0.25\n"
                                  "N60 G00 X20.\n"
                                  "N100 G01 Z-15. F0.25\n"
                                  "N110 X30. Z-25.\n"
                                  "N120 X52.\n"
                                  "N70 X52. Z-25.\n"
                                  "N130 G70 P60 Q70\n"
                                  "N140 G00 X120. Z50.\n"));
}

TEST(Rough, FacingWithoutFinishWritesG72Only) {
  Compiled c = compile_text(rough_cl("CYCLE / ROUGH, FACE, DEPTH, 1.5, RETRACT, 0.5, MMPR, 0.2",
                                     "RAPID\nGOTO / 26.0, 0.0, -3.0\nGOTO / 8.0, 0.0, -3.0\nGOTO / 0.0, 0.0, 0.0\n"),
                            machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N50 G00 X52. Z2.\n"
                                  "N80 G72 W1.5 R0.5\n"
                                  "N90 G99 G72 P60 Q70 U0. W0. F0.2\n"
                                  "N60 G00 Z-3.\n"
                                  "N100 G01 X16. F0.25\n"
                                  "N110 X0. Z0.\n"
                                  "N70 X0. Z0.\n"
                                  "N120 G00 X120. Z50.\n"));
  EXPECT_THAT(c.output, ::testing::Not(HasSubstr("G70")));
}

TEST(Rough, WhatTheControlRefusesIsALocatedError) {
  auto errors = [](const std::string& cycle, const std::string& profile, const std::string& machine_name = "fanuc-lathe") {
    Compiled c = compile_text(rough_cl(cycle, profile), machine(machine_name));
    EXPECT_FALSE(c.ok);
    return c.diags;
  };
  const std::string turn = "CYCLE / ROUGH, TURN, DEPTH, 2, RETRACT, 0.5";
  // A pocket: the profile dips back towards the axis.
  EXPECT_THAT(errors(turn, "RAPID\nGOTO / 10.0, 0.0, 2.0\nGOTO / 10.0, 0.0, -10.0\nGOTO / 8.0, 0.0, -15.0\nGOTO / 26.0, 0.0, -20.0\n"),
              HasSubstr("part.cls:9:1: error: CYCLE/ROUGH: the control's G71 cannot cut this profile: the profile turns back "
                        "along X: a pocket, which a type I cycle does not cut"));
  EXPECT_THAT(errors(turn, "RAPID\nGOTO / 10.0, 0.0, 0.0\nGOTO / 26.0, 0.0, -20.0\n"),
              HasSubstr("9:1: error: CYCLE/ROUGH: the control's G71 cannot cut this profile: its first block moves along Z: "
                        "a type I cycle's first block moves along X alone"));
  EXPECT_THAT(errors("CYCLE / ROUGH, TURN, RETRACT, 0.5", kTaper), HasSubstr("9:1: error: CYCLE/ROUGH: missing DEPTH"));
  EXPECT_THAT(errors("CYCLE / ROUGH, TURN, DEPTH, 0, RETRACT, 0.5", kTaper),
              HasSubstr("9:29: error: CYCLE/ROUGH: DEPTH must be greater than zero, found 0"));
  EXPECT_THAT(errors("CYCLE / ROUGH, TURN, DEPTH, 2, RETRACT, 0.5, STEP, 3", kTaper),
              HasSubstr("9:46: error: CYCLE/ROUGH: unknown word 'STEP'"));
  EXPECT_THAT(errors("CYCLE / ROUGH, SPIRAL, DEPTH, 2", kTaper),
              HasSubstr("9:16: error: CYCLE/ROUGH: expected TURN (G71, levels along X) or FACE (G72, levels along Z)"));
  EXPECT_THAT(errors(turn, "THREAD / TURN, 1.5\n" + kTaper), HasSubstr("10:1: error: THREAD inside a CYCLE/ROUGH"));
  EXPECT_THAT(errors(turn, "RAPID\nGOTO / 10.0, 0.0, 2.0\nCOOLNT / FLOOD\nGOTO / 10.0, 0.0, -15.0\n"),
              HasSubstr("12:1: error: inside CYCLE/ROUGH only the profile's motion (and its feeds) may stand"));
  Machine without = machine("no-g71", "[no-g71]\ninherits = \"fanuc-lathe\"\n[no-g71.codes]\nrough_turn = \"\"\n");
  Compiled c = compile_text(rough_cl(turn, kTaper), without);
  EXPECT_THAT(c.diags, HasSubstr("9:1: error: machine 'no-g71' has no G71 (codes.rough_turn): CYCLE/ROUGH cannot be written"));
}

TEST(Rough, VerifyCatchesACycleThatIsNotTheCls) {
  const Machine m = machine("fanuc-lathe");
  TempDir t;
  write_file(t.path("part.cls"), rough_cl("CYCLE / ROUGH, TURN, DEPTH, 4, RETRACT, 1, ALLOW, 0.2, 0.1, FINISH", kTaper));
  RunResult good = run_clpc("compile " + t.path("part.cls") + " -t fanuc-lathe -o " + t.path("part.nc"));
  ASSERT_EQ(good.status, 0) << good.err;
  const std::string program = read_file(t.path("part.nc"));
  // Each edit moves the tool off the CL's cycle: a deeper cut, another allowance, a profile
  // block moved, the finishing pass gone.
  for (auto [from, to] : std::vector<std::pair<std::string, std::string>>{{"G71 U4.", "G71 U5."},
                                                                        {"U0.4 W0.1", "U0.2 W0.1"},
                                                                        {"N110 X30. Z-25.", "N110 X30. Z-24."},
                                                                        {"N130 G70 P60 Q70", "N130 M01"}}) {
    SCOPED_TRACE(to);
    std::string bad = program;
    ASSERT_NE(bad.find(from), std::string::npos);
    bad.replace(bad.find(from), from.size(), to);
    write_file(t.path("bad.nc"), bad);
    RunResult r = run_clpc("verify " + t.path("part.cls") + " -t fanuc-lathe --program " + t.path("bad.nc"));
    EXPECT_EQ(r.status, 1);
    EXPECT_THAT(r.err, HasSubstr("error: the G71 cycle's"));
  }
  RunResult same = run_clpc("verify " + t.path("part.cls") + " -t fanuc-lathe --program " + t.path("part.nc"));
  EXPECT_EQ(same.status, 0) << same.err;
}

// rough-cycles: roughing written as moves.
namespace {

// A lathe file whose motion after A = (x 26, z 2) is `moves`: "R x z" rapid, "F x z" feed.
std::string moves_cl(const std::vector<std::string>& moves) {
  std::string s = "PARTNO / MOVES\nMACHIN / TURN, 01\nUNITS / MM\nTURRET / 1\nSPINDL / RPM, 800.0, CLW\n"
                  "FEDRAT / 0.25, MMPR\nRAPID\nGOTO / 26.0, 0.0, 2.0\n";
  for (const std::string& m : moves) {
    std::istringstream in(m);
    char k;
    std::string x, z;
    in >> k >> x >> z;
    if (k == 'R') s += "RAPID\n";
    s += "GOTO / " + x + ", 0.0, " + z + "\n";
  }
  return s + "RAPID\nGOTO / 60.0, 0.0, 50.0\nFINI\n";
}

// Fanuc's G71 from A over the profile x 10 (z 2) -> (10, -15) -> (15, -25) -> (26, -25), depth
// 4, pull-out 1, allowances 0.2 (x) and 0.1 (z): levels x 22, 18, 14, then the shifted profile.
const std::vector<std::string> kG71 = {"R 22 2",       "F 22 -24.9",   "F 23 -23.9", "R 23 2",   "R 18 2",
                                       "F 18 -24.9",   "F 19 -23.9",   "R 19 2",     "R 14 2",   "F 14 -22.5",
                                       "F 15 -21.5",   "R 15 2",       "R 10.2 2.1", "F 10.2 -14.9", "F 15.2 -24.9",
                                       "F 26.2 -24.9", "R 26 2"};
const std::vector<std::string> kFinish = {"R 10 2", "F 10 -15", "F 15 -25", "F 26 -25", "R 26 2"};

}  // namespace

TEST(RoughCycles, RoughingAsMovesThatIsG71BecomesG71AndG70) {
  std::vector<std::string> all = kG71;
  all.insert(all.end(), kFinish.begin(), kFinish.end());
  Compiled c = compile_text(moves_cl(all), machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N50 G00 X52. Z2.\n"
                                  "N80 G71 U4. R1.\n"
                                  "N90 G99 G71 P60 Q70 U0.4 W0.1 F0.25\n"
                                  "N60 G00 X20.\n"
                                  "N100 G01 Z-15. F0.25\n"
                                  "N110 X30. Z-25.\n"
                                  "N120 X52.\n"
                                  "N70 X52. Z-25.\n"
                                  "N130 G70 P60 Q70\n"
                                  "N140 G00 X120. Z50.\n"));
}

// The FEDRAT given once after the approach, before the first level (NX writes it once per
// operation): the pass dropped it, and the finishing pass after the cycle was refused with "no
// feed rate" (helper-54).
TEST(RoughCycles, AFeedAfterTheApproachStillStandsAfterTheCycle) {
  std::vector<std::string> all = kG71;
  all.insert(all.end(), kFinish.begin(), kFinish.end());
  std::string cl = moves_cl(all);
  cl.replace(cl.find("FEDRAT / 0.25, MMPR\n"), 20, "");
  cl.replace(cl.find("GOTO / 26.0, 0.0, 2.0\n"), 22, "GOTO / 26.0, 0.0, 2.0\nFEDRAT / 0.25, MMPR\n");
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N90 G99 G71 P60 Q70 U0.4 W0.1 F0.25\n"));
  EXPECT_THAT(c.output, HasSubstr("N130 G70 P60 Q70\n"));
}

TEST(RoughCycles, WithoutAFinishingPassTheLastCutIsTheProfile) {
  // Allowances 0: the levels meet the profile itself; x 22 and 18 at z -25, 14 on the taper.
  const std::vector<std::string> moves = {"R 22 2", "F 22 -25", "F 23 -24", "R 23 2", "R 18 2",   "F 18 -25",
                                          "F 19 -24", "R 19 2",  "R 14 2",   "F 14 -23", "F 15 -22", "R 15 2",
                                          "R 10 2",  "F 10 -15", "F 15 -25", "F 26 -25", "R 26 2"};
  Compiled c = compile_text(moves_cl(moves), machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N80 G71 U4. R1.\n"
                                  "N90 G99 G71 P60 Q70 U0. W0. F0.25\n"
                                  "N60 G00 X20.\n"
                                  "N100 G01 Z-15. F0.25\n"
                                  "N110 X30. Z-25.\n"
                                  "N120 X52.\n"
                                  "N70 X52. Z-25.\n"
                                  "N130 G00 X120. Z50.\n"));
}

TEST(RoughCycles, OtherRoughingStaysAsMovesWithANoteThatSaysWhy) {
  auto compiled = [](const std::vector<std::string>& moves) {
    Compiled c = compile_text(moves_cl(moves), machine("fanuc-lathe"), {.certify = true});
    EXPECT_TRUE(c.ok) << c.diags;
    EXPECT_THAT(c.output, ::testing::Not(HasSubstr("G71")));
    return c.diags;
  };
  // Pulled out along X alone, as Creo's area turning does (nist/turn_op10.ncl.4).
  EXPECT_THAT(compiled({"R 22 2", "F 22 -25", "F 23 -25", "R 23 2", "R 18 2", "F 18 -25", "F 19 -25", "R 19 2", "R 60 50"}),
              HasSubstr("part.cls:10:1: note: roughing of 2 levels kept as moves, not G71: level 1 pulls out along X alone (G71 "
                        "pulls out at 45 degrees)"));
  // The second level one deeper than the first.
  std::vector<std::string> uneven = kG71;
  uneven[4] = "R 17 2";
  uneven[5] = "F 17 -24.9";
  uneven[6] = "F 18 -23.9";
  uneven[7] = "R 18 2";
  EXPECT_THAT(compiled(uneven), HasSubstr("note: roughing of 3 levels kept as moves, not G71: level 2 is 5 deeper than the one "
                                          "before it where the first is 4 (G71's levels are evenly deep)"));
  // The third level stops 0.1 short of the shifted profile: the proof finds the move.
  std::vector<std::string> off = kG71;
  off.insert(off.end(), kFinish.begin(), kFinish.end());
  off[9] = "F 14 -22.4";
  off[10] = "F 15 -21.4";
  EXPECT_THAT(compiled(off), HasSubstr("not G71: the cycle's move 10 goes to (x 14, z -22.5) where the CL's goes to (x 14, "
                                       "z -22.4)"));
}

TEST(Rough, BoringTheStockInsideSignsTheAllowanceAndCertifies) {
  // ID turning: A at x 5 inside the bore, levels outwards (x 7, 9, 11, 13), the allowance on
  // the stock's side (inside: negative), the pull-outs inwards.
  const std::string cl =
      "PARTNO / BORE\nMACHIN / TURN, 01\nUNITS / MM\nTURRET / 1\nSPINDL / RPM, 800.0, CLW\nFEDRAT / 0.2, MMPR\n"
      "RAPID\nGOTO / 5.0, 0.0, 2.0\nCYCLE / ROUGH, TURN, DEPTH, 2, RETRACT, 1, ALLOW, -0.2, 0.1, FINISH\n"
      "RAPID\nGOTO / 15.0, 0.0, 2.0\nGOTO / 15.0, 0.0, -10.0\nGOTO / 10.0, 0.0, -15.0\nGOTO / 5.0, 0.0, -15.0\n"
      "CYCLE / OFF\nRAPID\nGOTO / 5.0, 0.0, 50.0\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N50 G00 X10. Z2.\n"
                                  "N80 G71 U2. R1.\n"
                                  "N90 G99 G71 P60 Q70 U-0.4 W0.1 F0.2\n"
                                  "N60 G00 X30.\n"
                                  "N100 G01 Z-10. F0.2\n"
                                  "N110 X20. Z-15.\n"
                                  "N120 X10.\n"
                                  "N70 X10. Z-15.\n"
                                  "N130 G70 P60 Q70\n"
                                  "N140 G00 Z50.\n"));
  // The reader's expansion: the last level (x 13) meets the taper at z -11.7 and pulls out
  // inwards to (x 12, z -10.7).
  gcode::Result r = gcode::interpret(c.output, machine("fanuc-lathe"));
  bool found = false;
  for (const gcode::Segment& s : r.segments)
    if ((s.start - ir::Vec3(13, 0, -11.7)).norm() < 1e-9 && (s.end - ir::Vec3(12, 0, -10.7)).norm() < 1e-9) found = true;
  EXPECT_TRUE(found);
}

// A CUTCOM/RIGHT after the move to A started G42 on the profile's second block, inside G71:
// the control ramps the nose radius on along the first finishing cut (a taper the CL has
// not), and roughs uncompensated. CYCLE/ROUGH is refused; roughing as moves stays moves.
TEST(Rough, CompensationStartingInsideTheCycleIsRefusedOrKeptAsMoves) {
  const std::string a = "GOTO / 26.0, 0.0, 2.0\n";
  std::string cl = rough_cl("CYCLE / ROUGH, TURN, DEPTH, 4, RETRACT, 1, ALLOW, 0.2, 0.1, FINISH", kTaper);
  cl.replace(cl.find(a), a.size(), a + "CUTCOM / RIGHT\n");
  Compiled c = compile_text(cl, machine("fanuc-lathe"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("part.cls:10:1: error: cutter compensation (CUTCOM) starts inside the G71 cycle's "
                                 "profile: the control would start it on a profile block, not where the CL does"));
  std::vector<std::string> all = kG71;
  all.insert(all.end(), kFinish.begin(), kFinish.end());
  std::string moves = moves_cl(all);
  moves.replace(moves.find(a), a.size(), a + "CUTCOM / RIGHT\n");
  Compiled m = compile_text(moves, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(m.ok) << m.diags;
  EXPECT_THAT(m.diags, HasSubstr("part.cls:11:1: note: roughing of 3 levels kept as moves, not G71: cutter compensation "
                                 "starts at its first level, and would start on a profile block of the cycle"));
  EXPECT_THAT(m.output, HasSubstr("\nN60 G42 X44.\n"));
  EXPECT_EQ(m.output.find("G71"), std::string::npos);
  // A move to where the tool stands between them starts nothing (a lone G42 was written, and
  // the cycle after it passed both checks).
  const std::string once = a + "CUTCOM / RIGHT\n";
  cl.replace(cl.find(once), once.size(), once + "RAPID\n" + a);
  Compiled record = compile_text(cl, machine("fanuc-lathe"));
  EXPECT_FALSE(record.ok);
  EXPECT_THAT(record.diags, HasSubstr("part.cls:12:1: error: cutter compensation (CUTCOM) starts inside the G71"));
  moves.replace(moves.find(once), once.size(), once + "RAPID\n" + a);
  Compiled kept = compile_text(moves, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(kept.ok) << kept.diags;
  EXPECT_THAT(kept.output, HasSubstr("\nN60 G42 X44.\n"));
  EXPECT_EQ(kept.output.find("G71"), std::string::npos);
}
