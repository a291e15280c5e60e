// Drilling, tapping and boring cycles: each kind, each dialect's parameter order, errors,
// expansion where the machine lacks a cycle, and the holes read back from the G-code.
#include "readback/gcode_interp.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

const char* kHead = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/10,10,20\n";

// The cycle blocks of compiling `cycle` + holes at (10,10,0) and (30,10,0) for fanuc-mill.
std::string cycle_blocks(const std::string& cycle, const std::string& machine_name = "fanuc-mill",
                         const std::string& extra = {}) {
  Machine m = machine(machine_name, extra);
  Compiled c = compile_text(std::string(kHead) + cycle + "\nGOTO/10,10,0\nGOTO/30,10,0\nCYCLE/OFF\n", m);
  EXPECT_TRUE(c.ok) << c.diags;
  // From the first block after the G43 positioning to G80.
  size_t from = c.output.find("N70 ");
  size_t to = from == std::string::npos ? from : c.output.find("G80", from);
  if (from == std::string::npos || to == std::string::npos) return c.output;
  return c.output.substr(from, to - from + 3);
}

}  // namespace

TEST(Cycles, CreoDrill) {
  EXPECT_EQ(cycle_blocks("CYCLE / DRILL, DEPTH, 5.0, MMPM, 80.0, CLEAR, 2.0"),
            "N70 G94 G98 G81 X10. Y10. Z-5. R2. F80.\nN80 X30.\nN90 G80");
}

TEST(Cycles, NxDrillKeywordsInAnotherOrder) {
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,RAPTO,2.0,FEDTO,5.0,MMPM,80.0"),
            "N70 G94 G98 G81 X10. Y10. Z-5. R2. F80.\nN80 X30.\nN90 G80");
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,MMPM,80,CLEAR,2,DEPTH,5"), cycle_blocks("CYCLE/DRILL,FEDTO,5,RAPTO,2,MMPM,80"));
}

// APT's positional form: depth, the feed with its unit, clearance (CYCLE/DRILL,d,IPM,f,c).
TEST(Cycles, AptPositionalDepthFeedClearance) {
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,5,MMPM,80,2"), "N70 G94 G98 G81 X10. Y10. Z-5. R2. F80.\nN80 X30.\nN90 G80");
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,5,MMPM,80,2,DWELL,1"), "N70 G94 G98 G82 X10. Y10. Z-5. R2. P1000 F80.\nN80 X30.\nN90 G80");
  Compiled c = compile_text(std::string(kHead) + "CYCLE/DRILL,5,MMPM,80,2,7\nGOTO/10,10,0\nCYCLE/OFF\n",
                            machine("fanuc-mill"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:7:25: error: CYCLE: the number 7 has no keyword before it"));
  c = compile_text(std::string(kHead) + "CYCLE/DRILL,5,MMPM\nGOTO/10,10,0\nCYCLE/OFF\n", machine("fanuc-mill"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:7:15: error: CYCLE/DRILL: by position, the depth and the clearance come first "
                                 "(d,c[,f,MMPM]), or the depth, the feed and the clearance (d,MMPM,f,c)"));
}

// After the holes the tool is up the last hole's axis, where the cycle returned it (G98: the
// level it started from). A FROM there says so (it was refused as a jump); a FROM elsewhere on
// that line, with a cut after it, would start the cut where the tool is not.
TEST(Cycles, AFromUpTheLastHolesAxisSaysWhereTheCycleLeftTheTool) {
  const std::string cycle = "CYCLE/DRILL,DEPTH,5,MMPM,80,CLEAR,2\nGOTO/10,10,0\nGOTO/30,10,0\nCYCLE/OFF\n";
  Compiled c = compile_text(std::string(kHead) + cycle + "FROM/30,10,20\nGOTO/30,10,5\nGOTO/40,10,-1\n",
                            machine("fanuc-mill"));
  EXPECT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N90 G80\nN100 G01 Z5. F100.\nN110 X40. Z-1.\n"));
  c = compile_text(std::string(kHead) + cycle + "FROM/30,10,30\nGOTO/30,10,5\n", machine("fanuc-mill"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:12:1: error: this cut starts at the FROM at line 11 (30, 10, 30), but the "
                                 "cycle before it returned the tool to (30, 10, 20)"));
  c = compile_text(std::string(kHead) + cycle + "FROM/30,10,30\nRAPID\nGOTO/30,10,5\n", machine("fanuc-mill"));
  EXPECT_TRUE(c.ok) << c.diags;
  // A feed on down the axis through a lower FROM holds the CL's line; a FROM between holes is
  // passed by the next one (the cycle moves across at its own level).
  c = compile_text(std::string(kHead) + cycle + "FROM/30,10,2\nGOTO/30,10,-3\n", machine("fanuc-mill"));
  EXPECT_TRUE(c.ok) << c.diags;
  c = compile_text(std::string(kHead) + "CYCLE/DRILL,DEPTH,5,MMPM,80,CLEAR,2\nGOTO/10,10,0\nFROM/10,10,30\nGOTO/30,10,0\n"
                   "CYCLE/OFF\nGOTO/30,10,-1\n", machine("fanuc-mill"));
  EXPECT_TRUE(c.ok) << c.diags;
  c = compile_text(std::string(kHead) + cycle + "FROM/31,10,20\nGOTO/30,10,5\n", machine("fanuc-mill"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:11:1: error: FROM after motion puts the tool at (31, 10, 20)"));
}

// NX writes FEDTO signed along the tool axis from the hole's top: a hole below is negative
// (its posts put the bottom at the point + FEDTO x the tool axis). In a file NX wrote (its
// TOOL PATH records say so) -12 is 12 deep; elsewhere a negative depth is still refused.
TEST(Cycles, NxNegativeFeedToIsTheDepthBelowTheTop) {
  const std::string nx = "TOOL PATH/DRILLING,TOOL,STD_DRILL_6\n";
  Compiled c = compile_text(nx + kHead + "CYCLE/DRILL,RAPTO,3.0000,FEDTO,-12.0000,RTRCTO,AUTO,MMPM,250.0000\n"
                                         "GOTO/10,10,0\nGOTO/30,10,0\nCYCLE/OFF\nEND-OF-PATH\n",
                            machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G98 G81 X10. Y10. Z-12. R3. F250.\n"));
  Compiled other = compile_text(std::string(kHead) + "CYCLE/DRILL,RAPTO,3,FEDTO,-12,MMPM,250\nGOTO/10,10,0\nCYCLE/OFF\n",
                                machine("fanuc-mill"));
  EXPECT_FALSE(other.ok);
  EXPECT_THAT(other.diags, HasSubstr(":7:27: error: CYCLE: the depth must not be negative, found -12"));
  // A positive FEDTO in NX's CL is a bottom above the top: not drilled 12 deep.
  Compiled up = compile_text(nx + kHead + "CYCLE/DRILL,RAPTO,3.0000,FEDTO,12.0000,MMPM,250.0000\nGOTO/10,10,0\n"
                                          "CYCLE/OFF\nEND-OF-PATH\n",
                             machine("fanuc-mill"));
  EXPECT_FALSE(up.ok);
  EXPECT_THAT(up.diags, HasSubstr(":8:32: error: CYCLE: in NX's CL, FEDTO is signed along the tool axis from the hole's "
                                  "top, so 12 puts the bottom above the top; a hole 12 deep is FEDTO,-12\n"));
}

TEST(Cycles, FeedFromFedratWhenTheCycleGivesNone) {
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,DEPTH,5,CLEAR,2"), "N70 G94 G98 G81 X10. Y10. Z-5. R2. F100.\nN80 X30.\nN90 G80");
}

// A cycle's own feed per revolution changes the control's mode, not the CL's: the moves after
// it go back to the FEDRAT's per-minute feed with G94. They were written F100 under the cycle's
// G95 (100 mm per revolution), and the compile was refused by verify.
TEST(Cycles, TheMovesAfterACyclesFeedPerRevolutionFeedPerMinuteAgain) {
  const std::string cl = std::string(kHead) + "CYCLE/DRILL,FEDTO,5,MMPR,0.1,RAPTO,2\nGOTO/10,10,0\nCYCLE/OFF\n"
                                              "GOTO/30,10,20\nGOTO/30,10,0\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\nN70 G95 G98 G81 X10. Y10. Z-5. R2. F0.1\nN80 G80\nN90 G94 G01 X30. F100.\nN100 Z0.\n"));
  Compiled haas = compile_text(cl, machine("haas-umc750"));
  ASSERT_TRUE(haas.ok) << haas.diags;
  EXPECT_THAT(haas.output, HasSubstr("G94 G01 X1.1811 F3.94\n"));
}

TEST(Cycles, InchFeedConvertedToAMetricProgram) {
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,DEPTH,5,IPM,10,CLEAR,2"), "N70 G94 G98 G81 X10. Y10. Z-5. R2. F254.\nN80 X30.\nN90 G80");
}

TEST(Cycles, SpotDwell) {
  EXPECT_EQ(cycle_blocks("CYCLE/CSINK,DEPTH,1,DWELL,0.5,CLEAR,2"),
            "N70 G94 G98 G82 X10. Y10. Z-1. R2. P500 F100.\nN80 X30.\nN90 G80");
  EXPECT_THAT(cycle_blocks("CYCLE/DRILL,DEPTH,1,DWELL,0.5,CLEAR,2", "haas-umc750"), HasSubstr("G82 X0.3937 Y0.3937 Z-0.0394 R0.0787 P0.5 F3.94"));
}

TEST(Cycles, PeckAndChipBreak) {
  EXPECT_EQ(cycle_blocks("CYCLE / DEEP, DEPTH, 12.0, STEP, 3.0, MMPM, 50.0, CLEAR, 1.0"),
            "N70 G94 G98 G83 X10. Y10. Z-12. R1. Q3. F50.\nN80 X30.\nN90 G80");
  EXPECT_EQ(cycle_blocks("CYCLE/BRKCHP,FEDTO,12,STEP,2,RAPTO,1"), "N70 G94 G98 G73 X10. Y10. Z-12. R1. Q2. F100.\nN80 X30.\nN90 G80");
}

// NX names the kind in a second word (CYCLE/DRILL,DEEP|BRKCHP|DWELL,...) and writes RTRCTO,AUTO
// for "back where the cycle began": the same cycles as Creo's and APT's words.
TEST(Cycles, NxKindInTheSecondWordAndRetractAuto) {
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,DEEP,FEDTO,12,INCR,3,RAPTO,1,RTRCTO,AUTO,MMPM,50"),
            "N70 G94 G98 G83 X10. Y10. Z-12. R1. Q3. F50.\nN80 X30.\nN90 G80");
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,BRKCHP,FEDTO,12,INCR,2,RAPTO,1,RTRCTO,AUTO"),
            "N70 G94 G98 G73 X10. Y10. Z-12. R1. Q2. F100.\nN80 X30.\nN90 G80");
  EXPECT_EQ(cycle_blocks("CYCLE/DRILL,DWELL,0.5,FEDTO,1,RAPTO,2,RTRCTO,AUTO"),
            "N70 G94 G98 G82 X10. Y10. Z-1. R2. P500 F100.\nN80 X30.\nN90 G80");
  // A deep drill without its increment is still refused, at the record.
  Compiled c = compile_text(std::string(kHead) + "CYCLE/DRILL,BRKCHP,FEDTO,12,RAPTO,1\nGOTO/10,10,0\nCYCLE/OFF\n",
                            machine("fanuc-mill"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":7:1: error: CYCLE/DRILL,BRKCHP: a peck cycle needs a peck depth"));
}

TEST(Cycles, TapRigidWithPitchTimesSpeed) {
  // M6 x 1: F = 1 mm x 1000 rpm.
  EXPECT_EQ(cycle_blocks("CYCLE/TAP,DEPTH,10,PITCH,1.0,CLEAR,3"),
            "N70 M29 S1000\nN80 G94 G98 G84 X10. Y10. Z-10. R3. F1000.\nN90 X30.\nN100 G80");
  // 20 threads per inch in a metric program: pitch 1.27 mm.
  EXPECT_THAT(cycle_blocks("CYCLE / TAP, DEPTH, 10, TPI, 20.0, CLEAR, 3"), HasSubstr("G84 X10. Y10. Z-10. R3. F1270."));
}

// A tap's feed per minute over the spindle's rpm is its pitch (NX writes the tap's feed so):
// 1250 mm/min at 1000 rpm is M8 x 1.25, written back as the same F at the same S.
TEST(Cycles, TapPitchFromAFeedPerMinuteAndTheSpindleSpeed) {
  EXPECT_EQ(cycle_blocks("CYCLE/TAP,FEDTO,10,RAPTO,3,RTRCTO,AUTO,MMPM,1250"),
            "N70 M29 S1000\nN80 G94 G98 G84 X10. Y10. Z-10. R3. F1250.\nN90 X30.\nN100 G80");
  Lowered l = lower_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,800,CLW\nCYCLE/TAP,FEDTO,10,RAPTO,3,MMPM,1000\nGOTO/0,0,0\nCYCLE/OFF\n");
  ASSERT_EQ(first_error(l.diags), "");
  ASSERT_EQ(l.ops.size(), 1u);
  ASSERT_EQ(l.ops[0].cycles.size(), 1u);
  EXPECT_DOUBLE_EQ(l.ops[0].cycles[0].pitch, 1.25);
  // Surface speed gives no rpm to divide by: refused at the record.
  Lowered css = lower_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/SMM,100,CLW\nCYCLE/TAP,FEDTO,10,RAPTO,3,MMPM,1000\nGOTO/0,0,0\nCYCLE/OFF\n");
  EXPECT_THAT(first_error(css.diags), HasSubstr("4:1: CYCLE/TAP: no thread pitch"));
}

TEST(Cycles, LeftHandTapWithTheSpindleCounterClockwise) {
  Machine m = machine("fanuc-mill");
  Compiled c = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,500,CCLW\nRAPID\nGOTO/0,0,10\nCYCLE/TAP,DEPTH,8,PITCH,1.25,CLEAR,2\nGOTO/0,0,0\nCYCLE/OFF\n",
      m);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G98 G74 X0. Y0. Z-8. R2. F625."));
  // The record's own hand agrees, or the CL contradicts itself (a left-hand tap record under a
  // clockwise spindle was tapped right-hand, G84).
  Compiled same = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,500,CCLW\nRAPID\nGOTO/0,0,10\nCYCLE/TAP,DEPTH,8,PITCH,1.25,CLEAR,2,CCLW\n"
      "GOTO/0,0,0\nCYCLE/OFF\n", m);
  EXPECT_THAT(same.output, HasSubstr("G98 G74 X0. Y0. Z-8. R2. F625."));
  Compiled contra = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/0,0,10\nCYCLE/TAP,DEPTH,8,PITCH,1.25,CLEAR,2,CCLW\n"
      "GOTO/0,0,0\nCYCLE/OFF\n", m);
  EXPECT_FALSE(contra.ok);
  EXPECT_THAT(contra.diags, HasSubstr("part.cls:6:38: error: CYCLE/TAP says the spindle turns counter-clockwise (a left-hand "
                                      "tap), but the SPINDL in force turns it the other way"));
}

TEST(Cycles, BoringKinds) {
  EXPECT_THAT(cycle_blocks("CYCLE/BORE,DEPTH,6,CLEAR,2"), HasSubstr("G98 G85 X10. Y10. Z-6. R2. F100."));
  EXPECT_THAT(cycle_blocks("CYCLE/REAM,DEPTH,6,CLEAR,2"), HasSubstr("G98 G85 X10. Y10. Z-6. R2. F100."));
  EXPECT_THAT(cycle_blocks("CYCLE/BORE,DEPTH,6,DWELL,1,CLEAR,2"), HasSubstr("G98 G89 X10. Y10. Z-6. R2. P1000 F100."));
  EXPECT_THAT(cycle_blocks("CYCLE/BORE,DRAG,DEPTH,6,CLEAR,2"), HasSubstr("G98 G86 X10. Y10. Z-6. R2. F100."));
  // The fine bore's shift: without Q (modal on Fanuc) the bar came out unshifted and scored
  // the bore. Back boring (G87: R at the bottom) was written as the others: refused.
  EXPECT_THAT(cycle_blocks("CYCLE/BORE,ORIENT,SHIFT,0.2,DEPTH,6,CLEAR,2"), HasSubstr("G98 G76 X10. Y10. Z-6. R2. Q0.2 F100."));
  Compiled back = compile_text(std::string(kHead) + "CYCLE/BORE,BACK,SHIFT,0.2,DEPTH,6,CLEAR,2\nGOTO/10,10,0\nCYCLE/OFF\n",
                               machine("fanuc-mill"));
  EXPECT_THAT(back.diags, HasSubstr("part.cls:7:1: error: CYCLE/BORE,BACK: back boring (G87) is not posted by clpc"));
  // A dwell the cycle does not write is said (it was dropped silently).
  Compiled peck = compile_text(std::string(kHead) + "CYCLE/DEEP,DEPTH,12,STEP,4,DWELL,0.5,CLEAR,2\nGOTO/10,10,0\nCYCLE/OFF\n",
                               machine("fanuc-mill"));
  ASSERT_TRUE(peck.ok) << peck.diags;
  EXPECT_THAT(peck.diags, HasSubstr("part.cls:7:1: warning: CYCLE/DEEP: the dwell of 0.5 s is not written: clpc writes a "
                                    "dwell with the DRILL (G82) and BORE (G89) cycles only [-Wcycle]"));
}

TEST(Cycles, ReturnToTheRPlaneWhenTheMachineSaysSo) {
  std::string extra = "[g99-mill]\ninherits = \"fanuc-mill\"\n[g99-mill.cycles]\nreturn = \"r-plane\"\n";
  EXPECT_THAT(cycle_blocks("CYCLE/DRILL,DEPTH,5,CLEAR,2", "g99-mill", extra), HasSubstr("G99 G81"));
}

TEST(Cycles, HolesAtDifferentHeightsRestateZAndR) {
  Machine m = machine("fanuc-mill");
  Compiled c = compile_text(std::string(kHead) + "CYCLE/DRILL,DEPTH,5,CLEAR,2\nGOTO/10,10,0\nGOTO/30,10,-4\nCYCLE/OFF\n", m);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N70 G94 G98 G81 X10. Y10. Z-5. R2. F100.\nN80 G80\nN90 G98 G81 X30. Y10. Z-9. R-2. F100.\nN100 G80\n"));
}

TEST(Cycles, MachineWithoutTheCycleGetsMoves) {
  std::string extra = "[no-peck]\ninherits = \"fanuc-mill\"\n[no-peck.codes]\ncycle_peck = \"\"\n[no-peck.cycles]\npeck_clearance = 0.5\n";
  Machine m = machine("no-peck", extra);
  Compiled c = compile_text(std::string(kHead) + "CYCLE/DEEP,DEPTH,7,STEP,3,CLEAR,1\nGOTO/10,10,0\nCYCLE/OFF\n", m);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N70 Z1.\nN80 G94 G01 Z-3. F100.\nN90 G00 Z1.\nN100 Z-2.5\nN110 G01 Z-6.\nN120 G00 Z1.\n"
                                  "N130 Z-5.5\nN140 G01 Z-7.\nN150 G00 Z20.\n"));
  EXPECT_EQ(c.output.find("G83"), std::string::npos);
}

TEST(Cycles, TappingCannotBeWrittenAsMoves) {
  std::string extra = "[no-tap]\ninherits = \"fanuc-mill\"\n[no-tap.codes]\ncycle_tap = \"\"\n";
  Machine m = machine("no-tap", extra);
  Compiled c = compile_text(std::string(kHead) + "CYCLE/TAP,DEPTH,7,PITCH,1,CLEAR,1\nGOTO/10,10,0\nCYCLE/OFF\n", m);
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":8:1: error: a tap cycle cannot be written as plain moves: the machine needs the canned "
                                 "cycle for it, and the machine has none (codes.cycle_tap is empty)"));
  // A lathe writes every drilling cycle as moves: a tap on the centreline is refused, saying so.
  Compiled lathe = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/0,0,10\n"
                                "CYCLE/TAP,DEPTH,20,CLEAR,5,PITCH,1.5\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n",
                                machine("fanuc-lathe"));
  EXPECT_FALSE(lathe.ok);
  EXPECT_THAT(lathe.diags, HasSubstr("part.cls:7:1: error: a tap cycle cannot be written as plain moves: the machine needs "
                                     "the canned cycle for it, and a lathe writes every drilling cycle as moves (its "
                                     "G83/G84 are live-tool cycles clpc does not post)"));
}

TEST(Cycles, ParameterRecordsInTheIr) {
  Lowered l = lower_text("UNITS/INCHES\nCYCLE/DEEP2,FEDTO,1.5,1STPECK,0.2,2NDPECK,0.1,IPM,12,RAPTO,0.1,RTRCTO,1\nGOTO/0,0,0\nCYCLE/OFF\n");
  EXPECT_EQ(first_error(l.diags), "");
  EXPECT_THAT(l.ir, HasSubstr("cycle-on peck depth 1.5 clear 0.1 retract 1 peck 0.2 then 0.1 feed 12 /min\n  3:1\tfeed (0, 0, 0)\n  4:1\tcycle-off"));
  Lowered p = lower_text("UNITS/MM\nRAPID\nGOTO/0,0,20\nCYCLE/DRILL,DEPTH,5,CLEAR,2\nGOTO/0,0,0\nGOTO/9,0,0\nCYCLE/OFF\n", {"drill-cycles"});
  EXPECT_THAT(p.ir, HasSubstr("cycle-on drill depth 5 clear 2\n  5:1\thole drill at (0, 0, 0) initial 20\n  6:1\thole drill at (9, 0, 0) initial 20\n  7:1\tcycle-off"));
}

TEST(Cycles, VariablePecksBecomeMovesOnAFanuc) {
  Machine m = machine("fanuc-mill");
  Compiled c = compile_text(std::string(kHead) + "CYCLE/DEEP2,FEDTO,10,1STPECK,4,2NDPECK,2,RAPTO,1\nGOTO/10,10,0\nCYCLE/OFF\n", m);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G01 Z-4."));
  EXPECT_THAT(c.output, HasSubstr("G01 Z-6."));
  EXPECT_THAT(c.output, HasSubstr("G01 Z-8."));
  EXPECT_THAT(c.output, HasSubstr("G01 Z-10."));
}

// --- errors --------------------------------------------------------------------------------

TEST(CycleErrors, MissingDepth) {
  EXPECT_EQ(first_error(lower_text("CYCLE/DRILL,CLEAR,2,MMPM,80\n").diags), "1:1: CYCLE/DRILL: no depth (DEPTH or FEDTO)");
}

TEST(CycleErrors, NegativePeck) {
  EXPECT_EQ(first_error(lower_text("CYCLE/DEEP,DEPTH,5,STEP,-1,CLEAR,2\n").diags),
            "1:25: CYCLE: the peck must not be negative, found -1");
}

// DEEP without a step (Creo, APT) is drilled in one go, with a warning; a chip-breaking cycle
// without one is an error.
TEST(CycleErrors, PeckCycleWithoutPeck) {
  Lowered deep = lower_text("CYCLE/DEEP,DEPTH,5,CLEAR,2\n");
  EXPECT_EQ(first_error(deep.diags), "");
  ASSERT_EQ(deep.diags.size(), 1u);
  EXPECT_EQ(deep.diags[0].message, "CYCLE/DEEP with no peck depth (STEP, 1STPECK, INCR): drilled to the depth in one go");
  EXPECT_THAT(deep.ir, HasSubstr("cycle-on drill depth 5 clear 2"));
  EXPECT_EQ(first_error(lower_text("CYCLE/BRKCHP,DEPTH,5,CLEAR,2\n").diags),
            "1:1: CYCLE/BRKCHP: a peck cycle needs a peck depth (STEP, 1STPECK or INCR) greater than zero");
}

TEST(CycleErrors, UnknownWordAndStrayNumber) {
  EXPECT_EQ(first_error(lower_text("CYCLE/DRILL,DEPTH,5,SIDEWAYS,2\n").diags), "1:21: CYCLE: unknown word 'SIDEWAYS'");
  EXPECT_EQ(first_error(lower_text("CYCLE/DRILL,DEPTH,5,2,CLEAR,2\n").diags),
            "1:21: CYCLE: the number 2 has no keyword before it");
  EXPECT_EQ(first_error(lower_text("CYCLE/SPIRAL,DEPTH,5\n").diags),
            "1:7: CYCLE: unknown cycle 'SPIRAL' (DRILL, DEEP, DEEP2, BRKCHP, TAP, BORE, REAM, CSINK, FACE, SPOT, ON, INIT "
            "or OFF)");
}

TEST(CycleErrors, CycleWithoutOffWarnsAndCancels) {
  Machine m = machine("fanuc-mill");
  std::string cl = std::string(kHead) + "CYCLE/DRILL,DEPTH,5,CLEAR,2\nGOTO/10,10,0\nEND-OF-PATH\nTOOL PATH/NEXT,TOOL,T2\nLOAD/TOOL,2\nGOTO/0,0,50\nEND-OF-PATH\n";
  Compiled d = compile_text(cl, m);
  ASSERT_TRUE(d.ok) << d.diags;
  EXPECT_THAT(d.diags, HasSubstr(":8:1: warning: CYCLE without CYCLE/OFF at the end of the operation: cancelled here"));
  EXPECT_THAT(d.output, HasSubstr("G81 X10. Y10. Z-5. R2. F100.\nN80 G80\n"));
}

// --- read back -----------------------------------------------------------------------------

TEST(Cycles, HoleBottomsReadBackFromTheGcode) {
  Machine m = machine("fanuc-mill");
  Compiled c = compile_text(std::string(kHead) + "CYCLE/DEEP,DEPTH,12,STEP,5,CLEAR,1\nGOTO/10,10,0\nGOTO/30,10,-2\nCYCLE/OFF\n", m);
  ASSERT_TRUE(c.ok) << c.diags;
  gcode::Result g = gcode::interpret(c.output, m);
  EXPECT_TRUE(g.problems.empty());
  EXPECT_EQ(g.cycles, 2);
  std::vector<ir::Vec3> bottoms;
  for (auto& s : g.segments)
    if (s.from_cycle && s.kind == gcode::Segment::Kind::Feed && s.end.z() <= -11.999) bottoms.push_back(s.end);
  ASSERT_EQ(bottoms.size(), 2u);
  EXPECT_NEAR((bottoms[0] - ir::Vec3(10, 10, -12)).norm(), 0, 1e-9);
  EXPECT_NEAR((bottoms[1] - ir::Vec3(30, 10, -14)).norm(), 0, 1e-9);
}

// An arc right after CYCLE/OFF starts, in the CL, at the last hole; the cycle left the tool at
// its return level. Found by differential fuzzing (the certificate refused the program): the
// arc was written from the return level, another arc. Now the tool feeds down to its start.
TEST(Cycles, AnArcAfterACycleStartsAtTheLastHole) {
  const std::string cl = "UNITS/MM\nLOADTL/20\nSPINDL/RPM,2000,CLW\nFEDRAT/MMPM,1430\nRAPID\nGOTO/1.6883,59.4809,40.0000\n"
                         "CYCLE/DEEP,DEPTH,8.5554,STEP,1.1854,MMPM,201,CLEAR,4.3721\nGOTO/73.5286,16.7071,-1.8423\nCYCLE/OFF\n"
                         "CIRCLE/73.5286,6.5882,-16.4502,1.0000000,0.0000000,0.0000000,17.7703\n"
                         "GOTO/73.5286,8.8397,-34.0773\nRAPID\nGOTO/70,91,24\nFINI\n";
  CompileOptions o;
  o.certify = true;
  Compiled c = compile_text(cl, machine("fanuc-mill"), o);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N70 G94 G98 G83 X73.529 Y16.707 Z-10.398 R2.53 Q1.185 F201.\nN80 G80\n"
                                  "N90 G01 Z-1.842 F1430.\nN100 G19 G03 Y8.84 Z-34.077 J-10.119 K-14.608\n"));
  EXPECT_THAT(c.diags, HasSubstr(":10:1: warning: this arc starts at the last hole of the cycle before it, where the tool "
                                 "no longer is (the cycle returned it): a feed move to the arc's start is added [-Wcycle]"));
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified "));
}

// A canned cycle crosses to each hole at the level the tool is at: a tool below the hole's R
// plane and beside it would cross there. Found by differential fuzzing (the certificate refused
// the program: the second cycle reached its hole's bottom at rapid): both cycles started below
// their R planes, the first 10 mm below its hole's top. Now drill-cycles refuses each, located.
TEST(CycleErrors, ACycleThatWouldCrossBelowTheRPlaneIsRefused) {
  const std::string cl = "UNITS/MM\nLOADTL/4\nSPINDL/RPM,1500,CLW\nRAPID\nGOTO/0,0,-10\nFEDRAT/MMPM,20\n"
                         "CIRCLE/-3.1739,0.0000,-4.1575,0,1,0,6.6489\nGOTO/2.7812,2.7345,-7.1147\n"
                         "CYCLE/DRILL,DEPTH,20.5028,MMPM,98,CLEAR,1.7584\nGOTO/3.8468,73.8231,3.2646\nCYCLE/OFF\n"
                         "CYCLE/BORE,DEPTH,1.2319,MMPM,170,CLEAR,4.0377\nGOTO/21.3642,87.3228,6.2564\nCYCLE/OFF\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":10:1: error: the tool is 12.1377 mm below this hole's R plane (CLEAR 1.7584 mm "
                                 "above the hole) when the cycle moves across to it: the canned cycle would cross at "
                                 "that level; retract above the R plane first (a GOTO, or RTRCTO)"));
  EXPECT_THAT(c.diags, HasSubstr(":13:1: error: the tool is 5.2711 mm below this hole's R plane (CLEAR 4.0377 mm"));
}

// A tool already over the first hole, below its R plane (the CAM system went to the hole's top
// before the CYCLE), rises to the R plane on the spot first: G98 then returns there, so the
// cycle crosses to the next hole at the R plane, not at the first hole's top.
// What a cycle's holes are, when the CL is not plain: a RAPID GOTO while a cycle is on (a
// hole to APT, a move between holes to some posts: a via point round a boss was drilled 2 mm
// deep), and a FEDRAT between holes of a cycle with a feed of its own (ignored: the holes were
// drilled at the record's feed). Each is refused at its record; the same feed again is nothing.
TEST(CycleErrors, ARapidOrAnotherFeedBetweenHolesIsRefused) {
  const std::string head = std::string(kHead) + "CYCLE/DRILL,DEPTH,12,MMPM,100,CLEAR,3\nGOTO/10,10,0\n";
  Compiled rapid = compile_text(head + "RAPID\nGOTO/10,30,10\nGOTO/50,10,0\nCYCLE/OFF\n", machine("fanuc-mill"));
  EXPECT_THAT(rapid.diags, HasSubstr("part.cls:10:1: error: a RAPID GOTO while CYCLE/DRILL (line 7) is on: a hole, or a move "
                                     "between holes? The CL does not say"));
  Compiled feed = compile_text(head + "FEDRAT/50,MMPM\nGOTO/30,10,0\nCYCLE/OFF\n", machine("fanuc-mill"));
  EXPECT_THAT(feed.diags, HasSubstr("part.cls:9:1: error: a FEDRAT while CYCLE/DRILL (line 7) is on, which has a feed of its "
                                    "own"));
  Compiled same = compile_text(head + "FEDRAT/100,MMPM\nGOTO/30,10,0\nCYCLE/OFF\n", machine("fanuc-mill"), {.certify = true});
  EXPECT_TRUE(same.ok) << same.diags;
}

TEST(Cycles, AToolOverTheFirstHoleBelowItsRPlaneRisesToItFirst) {
  const std::string cl = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/10,10,0\n"
                         "CYCLE/DRILL,DEPTH,5,CLEAR,2\nGOTO/10,10,0\nGOTO/30,10,0\nCYCLE/OFF\n";
  CompileOptions o;
  o.certify = true;
  Compiled c = compile_text(cl, machine("fanuc-mill"), o);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N60 G43 H01 Z0.\nN70 Z2.\nN80 G94 G98 G81 X10. Y10. Z-5. R2. F100.\nN90 X30.\nN100 G80\n"));
}

// A tap's F is the pitch times the S as written: at SPINDL 333.4 (Creo writes speeds with
// fractions) it was F416.75 at S333, 0.1 % off the pitch, and the certificate refused it
// (helper-71). A SPINDL between the holes of a tap cycle was read by verify as the speed of the
// last hole's way out, and the right program refused (helper-67, helper-70); a wrong S on the
// next hole is still caught.
TEST(Cycles, ATapIsFedForItsSpeedAsWrittenAndMayChangeSpeedBetweenHoles) {
  const std::string frac = "UNITS/MM\nLOADTL/1\nSPINDL/333.4,RPM,CLW\nRAPID\nGOTO/10,10,50\n"
                           "CYCLE/TAP,FEDTO,10,PITCH,1.25,RAPTO,5\nGOTO/10,10,0\nCYCLE/OFF\nFINI\n";
  Compiled c = compile_text(frac, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("M29 S333\nN80 G94 G98 G84 X10. Y10. Z-10. R5. F416.25\n"));
  const std::string change = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/0,0,50\n"
                             "CYCLE/TAP,DEPTH,10,PITCH,1.5,CLEAR,5\nGOTO/0,0,0\nGOTO/10,0,0\nSPINDL/RPM,300,CLW\n"
                             "GOTO/20,0,0\nCYCLE/OFF\nFINI\n";
  for (const char* name : {"fanuc-mill", "haas-umc750"}) {
    Compiled t = compile_text(change, machine(name), {.certify = true});
    EXPECT_TRUE(t.ok) << name << t.diags;
  }
  Compiled t = compile_text(change, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(t.ok) << t.diags;
  EXPECT_THAT(t.output, HasSubstr("N100 G80\nN110 S300 M03\nN120 M29 S300\nN130 G98 G84 X20. Y0. Z-10. R5. F450.\n"));
  std::string wrong = t.output;
  wrong.replace(wrong.find("N110 S300"), 9, "N110 S500");
  wrong.replace(wrong.find("M29 S300"), 8, "M29 S500");
  wrong.replace(wrong.find("F450."), 5, "F750.");
  Compiled v = verify_text(change, machine("fanuc-mill"), wrong);
  EXPECT_FALSE(v.ok);
  EXPECT_THAT(v.diags, HasSubstr(":10:1: error: the program cuts here at S500, the CL's spindle speed is 300 rpm [G-code line 19]"));
}
