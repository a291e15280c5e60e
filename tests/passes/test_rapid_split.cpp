// rapid-split: on a control whose rapids are not interpolated (motion.rapids_linear = false)
// a rapid that goes along and across the tool axis is written as two, never below the CL's
// straight line; where rapids are linear nothing changes.
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

// A Fanuc mill whose builder set parameter 1401#1 (linear rapids), without the pass.
const char* kLinearMill =
    "[linear-mill]\ninherits = \"fanuc-mill\"\n"
    "pipeline = [\"arc-direction\", \"helix\", \"arc-legalise\", \"drill-cycles\", \"offset-table\"]\n"
    "[linear-mill.motion]\nrapids_linear = true\n";

// Up and across, down and across, up alone, across alone, a feed down and across, and an arc.
const char* kRapids =
    "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/10,10,50\nFEDRAT/MMPM,100\nGOTO/10,10,0\n"
    "RAPID\nGOTO/40,30,20\nRAPID\nGOTO/60,30,2\nRAPID\nGOTO/60,30,30\nRAPID\nGOTO/90,30,30\n"
    "GOTO/90,40,-1\nCIRCLE/90,50,-1,0,0,1,10\nGOTO/100,50,-1\nRAPID\nGOTO/80,50,10\n";

// The blocks from the first feed to the end of the motion.
std::string motion(const std::string& out) {
  size_t from = out.find("G01 Z0.");
  size_t to = out.find("M05", from);
  if (from == std::string::npos || to == std::string::npos) return out;
  from = out.rfind('N', from);
  to = out.rfind('\n', to);
  return out.substr(from, to - from + 1);
}

}  // namespace

// fanuc-mill: a Fanuc control's rapids are non-linear unless its builder says otherwise.
TEST(RapidSplit, UpFirstOrAcrossFirstWhereRapidsAreNotLinear) {
  Compiled c = compile_text(kRapids, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(motion(c.output),
            "N70 G94 G01 Z0. F100.\n"
            "N80 G00 Z20.\n"   // up first...
            "N90 X40. Y30.\n"  // ...then across at the end's height
            "N100 X60.\n"      // across at the start's height...
            "N110 Z2.\n"       // ...then down
            "N120 Z30.\n"      // along the axis alone: as it is
            "N130 X90.\n"      // across alone: as it is
            "N140 G01 Y40. Z-1.\n"  // a feed is interpolated: as it is
            "N150 G17 G03 X100. Y50. I0. J10.\n"
            "N160 G00 Z10.\n"  // after an arc: up first
            "N170 X80.\n");
}

// A canned cycle leaves the tool over its last hole at the return level: the initial level
// (G98) or the R plane (G99). The rapid after CYCLE/OFF went up and across at once from there
// (helper-44); it goes up first, as after any move. Down and across, it crosses first.
TEST(RapidSplit, AfterACannedCycleFromItsReturnLevel) {
  const std::string cl = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,50,20\n"
                         "CYCLE/DRILL,10,2,100,MMPM\nGOTO/10,10,0\nGOTO/20,10,0\nCYCLE/OFF\nRAPID\nGOTO/0,0,50\n"
                         "RAPID\nGOTO/40,40,5\n";
  Compiled g98 = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(g98.ok) << g98.diags;
  EXPECT_THAT(g98.output, HasSubstr("N80 X20.\nN90 G80\nN100 G00 Z50.\nN110 X0. Y0.\nN120 X40. Y40.\nN130 Z5.\n"));
  Compiled g99 = compile_text(cl, machine("g99", "[g99]\ninherits = \"fanuc-mill\"\n[g99.cycles]\nreturn = \"r-plane\"\n"),
                              {.certify = true});
  ASSERT_TRUE(g99.ok) << g99.diags;
  EXPECT_THAT(g99.output, HasSubstr(" G99 G81 X10. Y10. Z-10. R2. F100.\nN80 X20.\nN90 G80\nN100 G00 Z50.\nN110 X0. Y0.\n"));
}

TEST(RapidSplit, NothingChangesWhereRapidsAreLinear) {
  Compiled c = compile_text(kRapids, machine("linear-mill", kLinearMill), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N80 G00 X40. Y30. Z20.\nN90 X60. Z2.\n"));
  EXPECT_THAT(c.output, HasSubstr("N140 G00 X80. Z10.\n"));
}

TEST(RapidSplit, NotAfterAToolChangeNorWithCutterCompensationOn) {
  Compiled c = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/10,10,50\nFEDRAT/MMPM,100\nGOTO/10,10,0\n"
      "LOAD/TOOL,2\nRAPID\nGOTO/50,50,5\nCUTCOM/LEFT\nRAPID\nGOTO/60,50,20\nCUTCOM/OFF\nRAPID\nGOTO/70,50,30\n",
      machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  // After the tool change: X Y, then Z with the length offset (the backend's), not split again.
  // The moves that start and cancel compensation carry G41 and G40: not split (a corner more in
  // the compensated path), but fed at the machine's fastest, along the CL's line (as G00 they
  // went up and across at once, off the line).
  EXPECT_THAT(c.output, HasSubstr("N100 G90 G54 G00 X50. Y50.\nN110 G43 H02 Z5.\nN120 S1000 M03\n"
                                  "N130 G41 D2 G94 G01 X60. Z20. F10000.\nN140 G40 X70. Z30. F10000.\nN150 M05\n"));
  // With compensation on, the feed in force before is said again after it.
  Compiled on = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/100,0,30\nCUTCOM/LEFT,1\nFEDRAT/500\n"
      "GOTO/100,10,30\nRAPID\nGOTO/0,10,2\nGOTO/0,10,-1\nGOTO/0,30,-1\nCUTCOM/OFF\nGOTO/0,40,-1\n",
      machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(on.ok) << on.diags;
  EXPECT_THAT(on.output, HasSubstr("N70 G41 D1 G94 G01 Y10. F500.\nN80 X0. Z2. F10000.\nN90 Z-1. F500.\nN100 Y30.\n"));
  // A FEDRAT before the next cut gives the feed after it.
  Compiled lead_in = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,30\nCUTCOM/LEFT,1\nRAPID\nGOTO/0,-10,-5\n"
      "FEDRAT/MMPM,200\nGOTO/50,-10,-5\nGOTO/50,-10,20\n",
      machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(lead_in.ok) << lead_in.diags;
  EXPECT_THAT(lead_in.output, HasSubstr("G41 D1 G94 G01 Y-10. Z-5. F10000.\nN80 X50. F200.\n"));
  // With no FEDRAT before it there is no feed to return to (the cuts after it ran at 10000).
  Compiled no_feed = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,30\nCUTCOM/LEFT,1\nRAPID\nGOTO/0,-10,-5\n"
      "GOTO/50,-10,-5\n",
      machine("fanuc-mill"));
  EXPECT_THAT(no_feed.diags, HasSubstr("part.cls:8:1: error: a rapid along and across the tool axis with cutter "
                                       "compensation on: the control's G00 is not interpolated (motion.rapids_linear = "
                                       "false), so it would leave the CL's line, and split it would change the compensated "
                                       "path; it is written as a feed at the machine's fastest, and with no FEDRAT before "
                                       "it there is no feed to return to"));
  // A machine with no max_feed has no fastest feed to give it: an error at the rapid.
  Compiled none = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/100,0,30\nCUTCOM/LEFT,1\nFEDRAT/500\n"
      "GOTO/100,10,30\nRAPID\nGOTO/0,10,2\n",
      machine("slow-mill", "[slow-mill]\ninherits = \"fanuc-mill\"\nmax_feed = 0.0\n"));
  EXPECT_THAT(none.diags, HasSubstr("part.cls:10:1: error: a rapid along and across the tool axis with cutter compensation "
                                    "on: the control's G00 is not interpolated (motion.rapids_linear = false), so it "
                                    "would leave the CL's line, and split it would change the compensated path; it is "
                                    "written as a feed at the machine's fastest, which machine 'slow-mill' does not give "
                                    "(max_feed)"));
}

TEST(RapidSplit, AlongATiltedToolAxisOnTheFiveAxis) {
  // The Haas's G00 is not interpolated unless configured (CONTROLLERS.md); one whose is:
  const char* toml = "[linear-umc]\ninherits = \"haas-umc750\"\n[linear-umc.motion]\nrapids_linear = true\n";
  // Tool axis tilted 30 degrees about X; the second rapid goes down the axis and across it.
  const std::string cl =
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nMULTAX/ON\nRAPID\nGOTO/0,-25,43.30127,0,-0.5,0.8660254\n"
      "RAPID\nGOTO/20,-5,8.660254,0,-0.5,0.8660254\nFEDRAT/MMPM,100\nGOTO/20,-4,6.928203,0,-0.5,0.8660254\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  Compiled plain = compile_text(cl, machine("linear-umc", toml), {.certify = true});
  ASSERT_TRUE(plain.ok) << plain.diags;
  // One block more: the corner, across at the start's height (on the table, the tool axis is Z).
  EXPECT_EQ(std::count(c.output.begin(), c.output.end(), '\n'), std::count(plain.output.begin(), plain.output.end(), '\n') + 1);
  EXPECT_THAT(c.output, HasSubstr("N55 Y0.7874\nN60 Z0.3937\n"));
  EXPECT_THAT(plain.output, HasSubstr("N55 Y0.7874 Z0.3937\n"));
}

TEST(RapidSplit, TheMachineMustRunThePassAndBeAMill) {
  const std::string without = "[m]\ninherits = \"fanuc-mill\"\npipeline = [\"arc-direction\", \"helix\", \"arc-legalise\", "
                              "\"drill-cycles\", \"offset-table\"]\n";
  EXPECT_EQ(machine_errors(without),
            "shop.toml:3:12: error: m.pipeline: machine 'm' needs 'rapid-split' in its pipeline, where "
            "motion.rapids_linear is false: each axis rapids at its own rate, so a rapid down and across would reach "
            "the depth before it has crossed (a control whose G00 moves in a straight line: motion.rapids_linear = "
            "true)\n 3 | pipeline = [\"arc-direction\", \"helix\", \"arc-legalise\", "
            "\"drill-cycles\", \"offset-table\"]\n   |            ^\n");
  EXPECT_EQ(machine_errors(without + "[m.motion]\nrapids_linear = true\n"), "");
  EXPECT_THAT(machine_errors("[l]\ninherits = \"fanuc-lathe\"\n[l.motion]\nrapids_linear = false\n"),
              HasSubstr("rapids_linear: false is for mills"));
}

// NX writes MSYS and LOAD/TOOL at every operation: the same frame and the same tool again are
// no motion, so the move from one operation to the next is split like any other.
TEST(RapidSplit, FromOneOperationToTheNextWithTheSameToolAndFrame) {
  const std::string op = "MSYS/0,0,0,1,0,0,0,1,0\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\n";
  Compiled c = compile_text("UNITS/MM\nTOOL PATH/A,TOOL,EM\n" + op +
                                "RAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nGOTO/10,0,-1\nEND-OF-PATH\nTOOL PATH/B,TOOL,EM\n" + op +
                                "RAPID\nGOTO/50,50,2\nGOTO/50,50,-1\nEND-OF-PATH\nTOOL PATH/C,TOOL,EM2\n"
                                "LOAD/TOOL,2\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,5\nEND-OF-PATH\n",
                            machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("(B)\nN90 S1000 M03\nN100 G00 Z2.\nN110 X50. Y50.\nN120 G01 Z-1.\n"));  // up first
  // Another tool: the backend's own X Y, then Z with the length offset.
  EXPECT_THAT(c.output, HasSubstr("G00 X0. Y0.\nN170 G43 H02 Z5.\n"));
}

// A raw block that can move no axis (a G08, an M08, a message) leaves the tool where it stood:
// the rapid after it is split like any other (it went down and across in one G00, certified).
// One that may move axes (G28 with an axis, G53, an axis word, a pallet change) leaves the
// position unknown: the backend writes the next rapid by the CL's direction from its last point,
// down as across and then down (from G53 Z0. it came down and across at once into the part), up
// as Z first and then across, on any control (Haas's rapids are linear).
TEST(RapidSplit, AfterARawBlockThatMovesNoAxis) {
  const std::string start = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,50\n"
                            "GOTO/0,0,-1\nRAPID\nGOTO/20,10,5\n";
  for (const char* raw : {"INSERT/G08 P1", "AUXFUN/8", "INSERT/(HELLO)", "PREFUN/61"}) {
    Compiled c = compile_text(start + raw + "\nRAPID\nGOTO/40,40,-3\n", machine("fanuc-mill"), {.certify = true});
    ASSERT_TRUE(c.ok) << raw << c.diags;
    EXPECT_THAT(c.output, HasSubstr("\nN100 G00 X40. Y40. Z5.\nN110 Z-3.\n")) << raw;
  }
  for (const char* raw : {"INSERT/G53 Z0.", "INSERT/M60", "AUXFUN/60"}) {  // M60: a pallet change
    Compiled moved = compile_text(start + raw + "\nRAPID\nGOTO/40,40,-3\n", machine("fanuc-mill"));
    EXPECT_THAT(moved.output, HasSubstr("\nN100 G00 X40. Y40.\nN110 Z-3.\n")) << raw;
  }
  // Up: where the block moves Z alone, X Y stand over the CL's last point and the rapid goes up
  // first; after a pallet change or a G28 with X Y, where the tool stands is not known: across
  // first (up first went down at an unknown X Y).
  Compiled up = compile_text(start + "INSERT/G53 Z0.\nRAPID\nGOTO/40,40,30\n", machine("fanuc-mill"));
  EXPECT_THAT(up.output, HasSubstr("\nN100 G00 Z30.\nN110 X40. Y40.\n"));
  // (Z alone to somewhere else, G00 Z-5. or G53 Z-100., is not up; and a pallet change before
  // a G53 Z0. leaves X Y unknown all the same.)
  for (const char* raw : {"INSERT/M60", "INSERT/G91 G28 X0. Y0. Z0.\nINSERT/G90", "INSERT/G65 P9000 Z0.",
                          "INSERT/M60\nINSERT/G53 Z0.", "INSERT/G53 Z-100."}) {
    Compiled moved = compile_text(start + raw + "\nRAPID\nGOTO/40,40,30\n", machine("fanuc-mill"));
    EXPECT_THAT(moved.output, HasSubstr(" G00 X40. Y40.\nN110 Z30.\n")) << raw;
  }
  Compiled haas = compile_text(start + "INSERT/G53 Z0.\nRAPID\nGOTO/40,40,-3\n", machine("haas-umc750"));
  EXPECT_THAT(haas.output, HasSubstr("G53 Z0.\nN65 M11 M13\nN70 G00 B0. C0.\nN75 M10 M12\nN80 X1.5748 Y1.5748\nN85 Z-0.1181\n"));
  // CUTCOM/OFF with compensation off switches nothing: the rapid after it is split too.
  Compiled off = compile_text(start + "CUTCOM/OFF\nRAPID\nGOTO/40,40,-3\n", machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(off.ok) << off.diags;
  EXPECT_THAT(off.output, HasSubstr("\nN100 G40 X40. Y40.\nN110 Z-3.\n"));
}

// G40 is written on the first straight move after CUTCOM/OFF, not on an arc: a rapid after
// such an arc carries it and is not split, but fed along the CL's line at the fastest feed.
TEST(RapidSplit, NotTheMoveThatCarriesG40AfterAnArc) {
  Compiled c = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\n"
      "CUTCOM/LEFT\nGOTO/10,0,-1\nCUTCOM/OFF\nCIRCLE/10,10,-1,0,0,1,10\nGOTO/20,10,-1\nRAPID\nGOTO/40,10,20\n",
      machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N100 G40 G01 X40. Z20. F10000.\n"));
}

// G41/G42 and G40 come on a move in the plane: on a plunge or a retract along Z alone the
// control starts or cancels the offset during it, sideways by the radius beside the wall (the
// plunge after CUTCOM/LEFT carried G41, the retract after CUTCOM/OFF G40, certified). The
// plunge and retract are made on the CL's points, the offset comes on and off across.
TEST(CutterComp, StartsAndEndsOnAMoveInThePlane) {
  Compiled c = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nCUTCOM/LEFT,1\n"
      "GOTO/0,0,-1\nGOTO/10,0,-1\nGOTO/10,20,-1\nCUTCOM/OFF\nGOTO/10,20,5\nRAPID\nGOTO/30,30,5\n",
      machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N60 G43 H01 Z5.\nN70 G94 G01 Z-1. F100.\nN80 G41 D1 X10.\nN90 Y20.\nN100 Z5.\n"
                                  "N110 G40 G00 X30. Y30.\n"));
  // A plunge after CUTCOM/OFF carries the G40: the CL has the tool down there without the
  // offset, and the arc after it, which cannot carry G40, was cut still offset.
  Compiled ramp = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,-10,5\nGOTO/0,-10,-5\n"
      "CUTCOM/LEFT,1\nGOTO/50,-10,-5\nCUTCOM/OFF\nGOTO/50,-10,-8\nCIRCLE/50,0,-8,0,0,1,10\nGOTO/60,0,-8\nGOTO/60,0,20\n",
      machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(ramp.ok) << ramp.diags;
  EXPECT_THAT(ramp.output, HasSubstr("N80 G41 D1 X50.\nN90 G40 Z-8.\nN100 G17 G03 X60. Y0. I0. J10.\n"));
  // After CUTCOM/OFF and a retract (which does not carry the G40), an arc cannot end the
  // compensation: refused (it was cut offset, certified).
  Compiled up_arc = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,-10,5\nGOTO/0,-10,-5\n"
      "CUTCOM/LEFT,1\nGOTO/50,-10,-5\nCUTCOM/OFF\nGOTO/50,-10,2\nCIRCLE/50,0,2,0,0,1,10\nGOTO/60,0,2\n",
      machine("fanuc-mill"));
  EXPECT_THAT(up_arc.diags, HasSubstr("part.cls:12:1: error: cutter compensation is to end (CUTCOM/OFF) before this arc, "
                                      "with only a move along the tool axis between"));
  // With no move across after it, the G40 comes before the program's end.
  Compiled end = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\n"
      "CUTCOM/LEFT,1\nGOTO/10,0,-1\nCUTCOM/OFF\nGOTO/10,0,5\n",
      machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(end.ok) << end.diags;
  EXPECT_THAT(end.output, HasSubstr("N80 G41 D1 X10.\nN90 Z5.\nN100 G40\nN110 M05\n"));
}

// Cutter compensation the control cannot make as the CL asks: refused, where it was written
// on the line after the arc (the arc cut on the tool's centre), or in G17 for a ZX profile.
TEST(CutterComp, WhatTheControlCannotMakeAsTheClAsksIsRefused) {
  // Turned on just before an arc.
  Compiled on = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nGOTO/10,0,-1\n"
      "CUTCOM/LEFT\nCIRCLE/10,10,-1,0,0,1,10\nGOTO/20,10,-1\nGOTO/40,10,-1\n",
      machine("fanuc-mill"));
  EXPECT_THAT(on.diags, HasSubstr("part.cls:9:1: error: cutter compensation (CUTCOM) starts on an arc: the control "
                                  "starts G41/G42 only on a straight move (G00/G01), and clpc only on one across the "
                                  "tool axis (not on a plunge); have the CAM system turn it on before a line across (a "
                                  "lead-in)"));
  // In another plane than the mill's XY (the plane word was dropped: G42 in G17).
  Compiled zx = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nCUTCOM/RIGHT,2,ZXPLAN\n"
      "GOTO/10,0,-1\n",
      machine("fanuc-mill"));
  EXPECT_THAT(zx.diags, HasSubstr("part.cls:7:1: error: CUTCOM in the ZX plane, which is not square to the tool axis: a "
                                  "mill's cutter compensation is taken in the plane square to the tool, so the offset "
                                  "would be taken in another plane than the CL asks"));
  // A plane named alone is the plane of the compensation turned on after it (it was refused).
  const std::string to_5 = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\n";
  Compiled alone = compile_text(to_5 + "CUTCOM/ZXPLAN\nCUTCOM/RIGHT,2\nGOTO/10,0,-1\n", machine("fanuc-mill"));
  EXPECT_THAT(alone.diags, HasSubstr("part.cls:8:1: error: CUTCOM in the ZX plane, which is not square to the tool axis"));
  Compiled plane_xy = compile_text(to_5 + "CUTCOM/XYPLAN\nCUTCOM/RIGHT,2\nGOTO/10,0,-1\nGOTO/20,0,-1\nCUTCOM/OFF\nGOTO/20,0,5\n",
                                   machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(plane_xy.ok) << plane_xy.diags;
  EXPECT_THAT(plane_xy.output, HasSubstr("G42 D2 "));
  // A 3+2 side face is the CL's ZX plane: square to the tool, posted.
  Compiled side = compile_text(
      "UNITS/MM\nMULTAX/ON\nLOADTL/1\nSPINDL/8000,RPM,CLW\nRAPID\nGOTO/0,-50,10,0,-1,0\nFEDRAT/500,MMPM\n"
      "GOTO/0,-10,10,0,-1,0\nCUTCOM/LEFT,ZXPLAN\nGOTO/10,-10,10,0,-1,0\nGOTO/10,-10,20,0,-1,0\nCUTCOM/OFF\n"
      "GOTO/0,-10,30,0,-1,0\nRAPID\nGOTO/0,-50,30,0,-1,0\nFINI\n",
      machine("haas-umc750"), {.certify = true});
  EXPECT_TRUE(side.ok) << side.diags;
  // A point repeated between the CUTCOM and the arc: G41 on a block with no motion came on at
  // the arc (certified); it waits for a move, and the arc refuses it.
  Compiled still = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/10,0,5\nGOTO/10,0,-1\n"
      "CUTCOM/LEFT\nGOTO/10,0,-1\nCIRCLE/10,10,-1,0,0,1,10\nGOTO/20,10,-1\n",
      machine("fanuc-mill"));
  EXPECT_THAT(still.diags, HasSubstr("part.cls:10:1: error: cutter compensation (CUTCOM) starts on an arc"));
  // CUTCOM/LEFT again, with compensation on that side: nothing starts.
  Compiled again = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nCUTCOM/LEFT\n"
      "GOTO/0,0,-1\nGOTO/10,0,-1\nCIRCLE/10,10,-1,0,0,1,10\nGOTO/20,10,-1\nCUTCOM/LEFT\nCIRCLE/20,20,-1,0,0,1,10\n"
      "GOTO/30,20,-1\nGOTO/40,20,-1\nCUTCOM/OFF\nGOTO/50,30,-1\n",
      machine("fanuc-mill"), {.certify = true});
  EXPECT_TRUE(again.ok) << again.diags;
  Compiled xy = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nCUTCOM/RIGHT,2,XYPLAN\n"
      "GOTO/10,0,-1\nCUTCOM/OFF\nGOTO/20,0,-1\n",
      machine("fanuc-mill"));
  EXPECT_TRUE(xy.ok) << xy.diags;
}

// On a machine whose head tilts, a piece along a tilted tool axis moves several axes at their
// own rates: only rapids with the tool along Z are split there.
TEST(RapidSplit, OnAHeadMachineOnlyWithTheToolAlongZ) {
  // examples/head_table_bc.toml: a B head over a C table.
  const Machine m = machine("head-table-bc", read_file(source_path("examples/head_table_bc.toml")));
  Compiled c = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nMULTAX/ON\nRAPID\nGOTO/0,0,50,0,0,1\nRAPID\nGOTO/20,0,10,0,0,1\n"
      "RAPID\nGOTO/20,0,40,0.5,0,0.8660254\nRAPID\nGOTO/40,0,10,0.5,0,0.8660254\n",
      m, {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  // Along Z: across first, then down; tilted 30 degrees: one block, as the CL gives it.
  EXPECT_THAT(c.output, HasSubstr("N60 G43 H01 Z50.\nN70 X20.\nN80 Z10.\nN90 X145. Z6.506 B30.\nN100 X165. Z-23.494\n"));
}

// G41/G42 under TCPC (G234) offset in the part's XY plane. With the tool tilted (simultaneous
// five-axis, or 3+2 in the "tcp" mode) that plane is not square to the tool: it was written
// (G41 D11 X1. C30.) and certified. In the default 3+2 mode (G254) the frame is turned and the
// compensation is square to the tool.
TEST(CutterComp, CompensationWithATiltedToolUnderTcpcIsRefused) {
  const std::string cl =
      "UNITS/INCHES\nLOAD/TOOL,1,ADJUST,1\nMULTAX/ON\nSPINDL/RPM,5000,CLW\nRAPID\n"
      "GOTO/0,0,3,0.5,0,0.8660254\nRAPID\nGOTO/0,0,0.1\nFEDRAT/IPM,20\nGOTO/0,0,0\nCUTCOM/LEFT,11\n"
      "GOTO/1,0,0,0.4330127,0.25,0.8660254\nGOTO/2,0,0,0.25,0.4330127,0.8660254\nCUTCOM/OFF\nGOTO/2,0.5,0\n";
  Compiled c = compile_text(cl, machine("haas-umc750"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("part.cls:12:1: error: cutter compensation (CUTCOM) with the tool tilted under TCPC: "
                                 "G41/G42 offset in the part's XY plane, which is not square to the tool"));
  const std::string indexed = "UNITS/INCHES\nLOAD/TOOL,1,ADJUST,1\nMULTAX/ON\nSPINDL/RPM,5000,CLW\nRAPID\n"
                              "GOTO/0,0,3,0.5,0,0.8660254\nFEDRAT/IPM,20\nGOTO/0,0,0\nCUTCOM/LEFT,11\nGOTO/1,0,0\n"
                              "GOTO/1,1,0\nCUTCOM/OFF\nGOTO/0,1,0\n";
  Compiled dwo = compile_text(indexed, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(dwo.ok) << dwo.diags;
  EXPECT_THAT(dwo.output, HasSubstr("G254"));
  EXPECT_THAT(dwo.output, HasSubstr("G41 D11"));
  // A head that tilts the tool leaves it tilted in the machine's coordinates, TCPC or not.
  const std::string head =
      "[bhead]\ninherits = \"haas-umc750\"\n[bhead.kinematics]\nsimultaneous = \"transform\"\nindexed = \"transform\"\ndegrees_per_minute = true\n"
      "[[bhead.kinematics.axes]]\nname = \"B\"\naxis = [0.0, 1.0, 0.0]\nside = \"head\"\nmin = -120.0\nmax = 120.0\n"
      "[[bhead.kinematics.axes]]\nname = \"C\"\naxis = [0.0, 0.0, 1.0]\nside = \"table\"\ncyclic = \"wind\"\n";
  Compiled side = compile_text("UNITS/INCHES\nLOAD/TOOL,1,ADJUST,1\nSPINDL/RPM,5000,CLW\nRAPID\nGOTO/3,-1,-1,1,0,0\n"
                               "FEDRAT/IPM,20\nGOTO/2,-1,-1\nCUTCOM/LEFT,1\nGOTO/2,0,-1\nGOTO/2,1,-1\nCUTCOM/OFF\nGOTO/2,2,-1\n",
                               machine("bhead", head));
  EXPECT_FALSE(side.ok);
  EXPECT_THAT(side.diags, HasSubstr("part.cls:9:1: error: cutter compensation (CUTCOM) with the tool tilted by the head: "
                                    "G41/G42 offset in the machine's XY plane"));
  // The block that cancels compensation may tilt: it ends the offset.
  const std::string vertical = "UNITS/INCHES\nLOAD/TOOL,1,ADJUST,1\nMULTAX/ON\nSPINDL/RPM,5000,CLW\nRAPID\n"
                               "GOTO/0,-1,1,0,0,1\nFEDRAT/IPM,20\nGOTO/0,-1,0\nCUTCOM/LEFT,1\nGOTO/1,-1,0\nGOTO/2,-1,0\n"
                               "CUTCOM/OFF\nGOTO/2,-1,0.1,0.258819,0,0.9659258\n";
  Compiled off = compile_text(vertical, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(off.ok) << off.diags;
  EXPECT_THAT(off.output, HasSubstr("G40"));
}
