// clpc verify: every corpus file passes on every machine it is for; programs broken on
// purpose (an arc flipped, a point shifted by 0.01 mm, a block dropped, B beyond its limit)
// fail, naming the CL record; the report's counts, times and JSON form.
#include <cmath>
#include <regex>

#include "driver/readback_commands.h"
#include "helpers.h"
#include "readback/gcode_interp.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

struct Checked {
  VerifyReport report;
  std::string diags;
};

// Verifies `cl` (a path) for `m`; with `program`, that text is checked instead of clpc's own.
Checked verify(const std::string& cl, const Machine& m, const std::string& program = {}) {
  TempDir t;
  VerifyOptions o;
  if (!program.empty()) {
    o.program = t.path("edited.nc");
    write_file(o.program, program);
  }
  std::ostringstream err;
  Checked c;
  c.report = verify_file(cl, m, o, err);
  c.diags = err.str();
  return c;
}

std::string program_for(const std::string& cl, const Machine& m) {
  Compiled c = compile_path(cl, m);
  EXPECT_TRUE(c.ok) << c.diags;
  return c.output;
}

// The text with `from` (which must occur once) replaced.
std::string edit(const std::string& text, const std::string& from, const std::string& to) {
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from << " occurs twice";
  if (at == std::string::npos) return text;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

std::string first_error(const std::string& diags) {
  size_t at = diags.find(": error: ");
  if (at == std::string::npos) return {};
  size_t start = diags.rfind('\n', at);
  start = start == std::string::npos ? 0 : start + 1;
  return diags.substr(start, diags.find('\n', at) - start);
}

// A plate: a line, a counter-clockwise arc, more lines (fanuc-mill writes G03 X10. I-10. J0.).
const char* kPlate =
    "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,20\nRAPID\nGOTO/0,0,2\nFEDRAT/MMPM,300\n"
    "GOTO/0,0,-2\nFEDRAT/MMPM,800\nGOTO/30,0,-2\nGOTO/30,20,-2\nCIRCLE/20,20,-2,0,0,-1,10,0.01,0.5,10,0\n"
    "GOTO/10,20,-2\nGOTO/0,20,-2\nGOTO/0,5,-2\nRAPID\nGOTO/0,5,20\nFINI\n";

// The plate written to a fresh directory, and the machine it is verified for.
struct VerifyPlate : ::testing::Test {
  TempDir t;
  std::string cl = t.path("plate.cls");
  Machine m = machine("fanuc-mill");
  void SetUp() override { write_file(cl, kPlate); }
};

}  // namespace

TEST_F(VerifyPlate, PassesWithItsReport) {
  Checked c = verify(cl, m);
  EXPECT_TRUE(c.report.ok) << c.diags;
  EXPECT_EQ(c.report.cl_points, 8);  // and the arc's end
  EXPECT_EQ(c.report.cl_arcs, 1);
  EXPECT_EQ(c.report.program.rapids, 4);  // X Y, then Z with G43; Z2.; the retract
  EXPECT_EQ(c.report.program.feeds, 5);
  EXPECT_EQ(c.report.program.arcs, 1);
  EXPECT_EQ(c.report.program.tool_changes, 1);
  // Cutting: 4 mm at 300, then 30 + 20 + pi*10 + 10 + 15 mm at 800 mm/min.
  const double cutting = 4.0 / 300 + (30 + 20 + 3.14159265358979 * 10 + 10 + 15) / 800;
  EXPECT_NEAR(c.report.program.feed_minutes, cutting, 1e-4);
  // Rapids at 24000 mm/min, each as long as its longest axis: 20 (G43 Z20 from Z unknown is not
  // counted), 18, 22.
  EXPECT_NEAR(c.report.program.rapid_minutes, (18.0 + 22.0) / 24000, 1e-6);
  // One tool change at the machine's 4 s.
  EXPECT_NEAR(c.report.program.tool_change_minutes, 4.0 / 60, 1e-12);
  EXPECT_LT(c.report.max_deviation, 1e-9);
  std::ostringstream text;
  print_report(text, c.report);
  EXPECT_THAT(text.str(), HasSubstr("  CL path:    8 points, 1 arcs, 0 holes\n"));
  EXPECT_THAT(text.str(), HasSubstr("  cycle time: 0:13 (cutting 0:09, rapids 0:00, dwells 0:00, tool changes 0:04)\n"));
  EXPECT_THAT(text.str(), HasSubstr("  result: PASS\n"));
}

// A machine that does not say how long its tool change takes: the time is a lower bound.
TEST_F(VerifyPlate, CycleTimeWithoutAToolChangeTimeIsALowerBound) {
  Machine quiet = machine("quiet-mill", "[quiet-mill]\ninherits = \"fanuc-mill\"\ntool_change_time = 0.0\n");
  Checked c = verify(cl, quiet);
  EXPECT_TRUE(c.report.ok) << c.diags;
  EXPECT_FALSE(c.report.program.time_complete());
  std::ostringstream text, json;
  print_report(text, c.report);
  print_report_json(json, c.report);
  EXPECT_THAT(text.str(), HasSubstr("  cycle time: 0:09+ (cutting 0:09, rapids 0:00, dwells 0:00, tool changes 0:00+, tool change time "
                                    "unknown)\n"));
  EXPECT_THAT(json.str(), HasSubstr("\"tool_change\": 0, \"complete\": false, \"dynamic\": "));
}

TEST_F(VerifyPlate, FlippedArcFailsAtTheCircle) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "G03 X10. I-10. J0.", "G02 X10. I-10. J0."));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:13:1: error: the program turns this CL arc the other way (the CL arc "
                                              "turns counter-clockwise seen from +Z) [G-code line 17]"));
  // The top of the CL's half circle is sqrt(200) from the nearest point of the flipped one.
  EXPECT_NEAR(c.report.max_deviation, std::sqrt(200.0), 1e-6);
  EXPECT_EQ(c.report.max_loc.line, 13u);
}

// A full circle run the wrong way has every point on the CL circle: the direction gives it away.
TEST(Verify, FullCircleTheWrongWayFails) {
  const std::string cl = std::string(CLPC_SOURCE_DIR) + "/tests/golden/nx_mill.cls";
  const Machine m = machine("fanuc-mill");
  Checked c = verify(cl, m, edit(program_for(cl, m), "G02 I-6. J0.", "G03 I-6. J0."));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("nx_mill.cls:57:1: error: the program turns this CL arc the other way (the CL arc "
                                              "turns clockwise seen from +Z) [G-code line 44]"));
  EXPECT_LT(c.report.max_deviation, c.report.tolerance);  // the path itself is right
}

TEST_F(VerifyPlate, PointShiftedBy0_01mmFails) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "N120 G01 X0.", "N120 G01 X0.01"));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:15:1: error: CL point (0.0000, 20.0000, -2.0000) is never reached: the "
                                              "program comes within 0.01000 of it [G-code line 18]"));
  EXPECT_NEAR(c.report.max_deviation, 0.01, 1e-9);
  EXPECT_EQ(c.report.max_loc.line, 15u);
}

// A position without its point is in least input increments on a Fanuc or a Haas: X30 is
// 0.030 mm. A hand edit that lost the point was read as 30 mm and passed (helper-62).
TEST_F(VerifyPlate, APositionWithoutItsPointIsReadInIncrements) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "N90 X30. F800.", "N90 X30 F800."));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:11:1: error: CL point (30.0000, 0.0000, -2.0000) is never reached"));
}

// Register 0 is no length offset at all (G43 H00; a lathe's T0100): the tip is off by the
// tool's length. It was taken for "no register said" and passed. (helper-35)
TEST_F(VerifyPlate, NoLengthOffsetFails) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "G43 H01", "G43 H00"));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:5:1: error: no tool length offset is in force (register 0), "
                                              "tool 1's is 1 (the CL loads tool 1 at line 2)"));
  // A machine whose G43 names no register (the control takes it from the tool): none is read.
  Machine plain = machine("g43-alone", "[g43-alone]\ninherits = \"fanuc-mill\"\n[g43-alone.codes]\nlength_offset = \"G43\"\n");
  Checked alone = verify(cl, plain);
  EXPECT_TRUE(alone.report.ok) << alone.diags;
}

// The spindle turning the other way (M04 where the CL says CLW, and the machine writes M03 for
// it): the cutter rubs. It passed: only turning or not was checked. (helper-35)
TEST_F(VerifyPlate, ACutWithTheSpindleTurningTheOtherWayFails) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "S3000 M03", "S3000 M04"));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:9:1: error: the program cuts here with the spindle turning M04, "
                                              "where the CL turns it the way the machine's M03 does"));
}

// Cutter compensation the CL does not have, or none where it has some: verify takes D as no
// offset, so the path alone did not show it (a G41 inserted passed). An arc right after
// CUTCOM/OFF keeps the offset to the next straight move across, as the post writes it.
TEST_F(VerifyPlate, CutterCompensationOtherThanTheClsFails) {
  Checked on = verify(cl, m, edit(program_for(cl, m), "N90 X30. F800.", "N90 G41 D1 X30. F800."));
  EXPECT_FALSE(on.report.ok);
  EXPECT_THAT(first_error(on.diags), HasSubstr("plate.cls:11:1: error: the program cuts here with G41 (left), where the CL has "
                                               "no cutter compensation: the cut is offset by the cutter's radius from where "
                                               "the CL puts it"));
  write_file(cl, edit(kPlate, "GOTO/30,0,-2\n", "CUTCOM/RIGHT,1\nGOTO/30,0,-2\n"));
  const std::string right = program_for(cl, m);
  EXPECT_THAT(right, HasSubstr("N90 G42 D1 X30. F800.\n"));
  EXPECT_TRUE(verify(cl, m, right).report.ok);
  Checked off = verify(cl, m, edit(right, "N90 G42 D1 X30. F800.", "N90 X30. F800."));
  EXPECT_THAT(first_error(off.diags), HasSubstr("plate.cls:12:1: error: the program cuts here with no cutter compensation "
                                                "(G40), where the CL has CUTCOM/RIGHT (line 11), G42 (right)"));
  write_file(cl, edit(kPlate, "GOTO/30,0,-2\nGOTO/30,20,-2\n", "CUTCOM/LEFT,1\nGOTO/30,0,-2\nGOTO/30,20,-2\nCUTCOM/OFF\n"));
  const std::string arc_after = program_for(cl, m);
  EXPECT_THAT(arc_after, HasSubstr("N110 G17 G03 X10. I-10. J0.\nN120 G40 G01 X0.\n"));
  EXPECT_TRUE(verify(cl, m, arc_after).report.ok);
  Checked late = verify(cl, m, edit(arc_after, "N120 G40 G01 X0.", "N120 G01 X0.\nG40"));
  EXPECT_THAT(first_error(late.diags), HasSubstr("error: the program cuts here with G41 (left), where the CL has no cutter "
                                                 "compensation (CUTCOM/OFF at line 14)"));
}

TEST_F(VerifyPlate, DroppedBlockFails) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "N100 Y20.\n", ""));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:12:1: error: CL point (30.0000, 20.0000, -2.0000) is never reached"));
}

TEST_F(VerifyPlate, RapidThroughACutFails) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "N120 G01 X0.", "N120 G00 X0."));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:15:1: error: this CL feed move is made at rapid traverse (G00)"));
}

// A cut with the spindle stopped where the CL has it turning: an M00 (or M01, M05) with no M03
// after it. A raw AUXFUN/0 left the next hole drilled with the spindle stopped, certified.
TEST_F(VerifyPlate, ACutWithTheSpindleStoppedFails) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "N100 Y20.\n", "M00\nN100 Y20.\n"));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:12:1: error: the program cuts here with the spindle stopped (no "
                                              "M03/M04 since an M05, M19, M00, M01 or tool change), where the CL has it "
                                              "turning [G-code line 17]"));
  Checked oriented = verify(cl, m, edit(program_for(cl, m), "N100 Y20.\n", "M19\nN100 Y20.\n"));
  EXPECT_FALSE(oriented.report.ok);  // M19 orients, and so stops, the spindle
  Checked restarted = verify(cl, m, edit(program_for(cl, m), "N100 Y20.\n", "M00\nS3000 M03\nN100 Y20.\n"));
  EXPECT_TRUE(restarted.report.ok) << restarted.diags;
}

// A canned cycle's return up the tool axis may make the CL's feed up from the last hole; its
// other rapids may not: here a cycle with no depth (Z = R) makes the CL's fed move across to
// X20 with its positioning rapid. It passed before.
TEST(Verify, ACyclesRapidAcrossIsNoStandInForAClFeed) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nFEDRAT/100,MMPM\nRAPID\nGOTO/0,0,5\n"
                         "CYCLE/DRILL,FEDTO,2,RAPTO,0,MMPM,100\nGOTO/10,0,0\nCYCLE/OFF\nGOTO/20,0,5\nRAPID\nGOTO/20,0,50\nFINI\n";
  const std::string head = "%\nO1000\nN10 G21\nN20 G00 G17 G40 G49 G80 G90\nN30 T1 M06\nN40 S1000 M03\n"
                           "N50 G54 G00 X0. Y0.\nN60 G43 H01 Z5.\nN70 G94 G98 G81 X10. Y0. Z-2. R0. F100.\n";
  const std::string tail = "N100 G00 Z50.\nN110 M05\nN120 G91 G28 Z0.\nN130 G90\nN140 M30\n%\n";
  Compiled fed = verify_text(cl, machine("fanuc-mill"), head + "N80 G80\nN90 G01 X20. F100.\n" + tail);
  EXPECT_TRUE(fed.ok) << fed.diags;
  Compiled across = verify_text(cl, machine("fanuc-mill"), head + "N80 X20. Y0. Z5. R5.\nN90 G80\n" + tail);
  EXPECT_FALSE(across.ok);
  EXPECT_THAT(across.diags, HasSubstr("part.cl:10:1: error: this CL feed move is made at rapid traverse (G00) [G-code line 10]"));
}

// A cycle's R plane below the CL's (RAPTO 3 above the hole's top) rapids into what the CL feeds
// through: R-9. on a hole whose top is Z0 passed. A higher R only costs time; a peck cycle's
// rapids back into the hole start at R and are not counted. (helper-35)
TEST(Verify, ACycleWhoseRPlaneIsBelowTheClsFails) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nFEDRAT/100,MMPM\nRAPID\nGOTO/0,0,20\n"
                         "CYCLE/DEEP,FEDTO,10,INCR,2,RAPTO,3,MMPM,100\nGOTO/10,0,0\nCYCLE/OFF\nRAPID\nGOTO/10,0,50\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr("G83 X10. Y0. Z-10. R3. Q2. F100.\n"));
  for (const char* r : {"R-9.", "R0.", "R2.99"}) {
    Compiled low = verify_text(cl, machine("fanuc-mill"), edit(c.output, "R3.", r));
    EXPECT_FALSE(low.ok) << r;
    EXPECT_THAT(low.diags, HasSubstr("part.cl:8:1: error: the cycle rapids down to ")) << r;
    EXPECT_THAT(low.diags, HasSubstr(" above the hole's top, below the CL's R plane (3.0000 above it): a rapid into what "
                                     "the CL feeds through")) << r;
  }
  Compiled high = verify_text(cl, machine("fanuc-mill"), edit(c.output, "R3.", "R5."));
  EXPECT_TRUE(high.ok) << high.diags;
}

// A CL point where the tip already is but the tool axis is not (a tilt on the spot): the block
// that turns the rotaries reaches it. Taken as reached by the tip alone, a tilt moved into the
// next cut passed, the axis 15 degrees off at the point. (helper-35)
TEST(Verify, ATiltOnTheSpotIsReachedWithItsAxis) {
  const std::string cl = "UNITS/MM\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,2000,CLW\nRAPID\nGOTO/0,0,5,0,0,1\n"
                         "FEDRAT/MMPM,500\nGOTO/0,0,-1,0,0,1\nGOTO/20,0,-1,0,0,1\nGOTO/20,0,-1,0.2588190,0,0.9659258\n"
                         "GOTO/30,0,-1,0.2588190,0,0.9659258\nFINI\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr("X0.7874\nN55 B15.\nN60 X1.1811\n"));
  Compiled merged = verify_text(cl, machine("haas-umc750"), edit(c.output, "N55 B15.\nN60 X1.1811\n", "N60 X1.1811 B15.\n"));
  EXPECT_FALSE(merged.ok);
  EXPECT_THAT(merged.diags, HasSubstr("part.cl:10:1: error: CL point (0.7874, 0.0000, -0.0394) is never reached"));
}

// An arc of more than a turn (Fusion's MOVARC angle) passes its end at each turn: the arc's end
// is the one reached after the whole sweep. Its compile was refused at the first pass (540
// degrees: "the CL arc is not followed"); a program that stops a turn short still fails.
TEST(Verify, AnArcOfMoreThanATurnEndsAfterItsWholeSweep) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nRAPID\nGOTO/20,0,5\nFEDRAT/1000,MMPM\nGOTO/20,0,-1\n"
                         "MOVARC/0,0,-1,0,0,1,20,ANGLE,540\nGOTO/30,30,-1\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G17 G03 X-20. I-20. J0.\nN90 X20. I20. J0.\nN100 X-20. I-20. J0.\nN110 G01 X30. Y30.\n"));
  Compiled short_by_a_turn = verify_text(cl, machine("fanuc-mill"), edit(c.output, "N90 X20. I20. J0.\nN100 X-20. I-20. J0.\n", ""));
  EXPECT_FALSE(short_by_a_turn.ok);
  EXPECT_THAT(short_by_a_turn.diags, HasSubstr("part.cl:8:1: error: the end of the CL arc (-20.0000, 0.0000, -1.0000) is never reached"));
}

TEST(Verify, RotaryBeyondItsLimitFails) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus";
  const std::string cl = corpus_dir() + "/nist/b45_face.ncl";
  const Machine m = machine("haas-umc750");
  std::string program = program_for(cl, m);
  ASSERT_THAT(program, HasSubstr("N30 G00 B45. C0.\n"));
  Checked c = verify(cl, m, edit(program, "N30 G00 B45. C0.\n", "N30 G00 B125. C0.\n"));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(c.diags, HasSubstr("error: B125.000 is beyond the B axis's limits (-35 to 120) [G-code line"));
}

// Under TCPC (G234) the control moves the tip straight while B turns: each turning block is
// the CL move it carries, checked at its ends (no bow between them), so a simultaneous sweep
// is certified; a block lifted by 0.1 mm is not, nor the same blocks without TCPC (the axes
// then move the machine, not the tip).
TEST(Verify, UnderTcpcATurningBlockIsTheStraightMoveOfItsTip) {
  TempDir t;
  const std::string cl = t.path("sweep.cls");
  std::string text = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,50,0,0,1\nRAPID\nGOTO/0,0,5,0,0,1\n"
                     "FEDRAT/MMPM,500\nGOTO/0,0,0,0,0,1\n";
  for (int k = 1; k <= 8; ++k) {
    const double a = 5 * k * 3.14159265358979323846 / 180;
    text += "GOTO/" + std::to_string(5 * k) + ",0,0," + std::to_string(std::sin(a)) + ",0," + std::to_string(std::cos(a)) + "\n";
  }
  text += "RAPID\nGOTO/40,0,50,0.642788,0,0.766044\nFINI\n";
  write_file(cl, text);
  const Machine m = machine("haas-umc750");
  const std::string program = program_for(cl, m);
  ASSERT_THAT(program, HasSubstr("N30 G54 G00 G234 H01\n"));
  ASSERT_THAT(program, HasSubstr("N75 X0.9843 B25.\n"));
  Checked c = verify(cl, m, program);
  EXPECT_TRUE(c.report.ok) << c.diags;
  EXPECT_EQ(c.report.cl_points, 12);
  EXPECT_LE(c.report.max_deviation, 0.00005);

  c = verify(cl, m, edit(program, "N75 X0.9843 B25.\n", "N75 X0.9843 Z0.0039 B25.\n"));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(first_error(c.diags),
              HasSubstr("sweep.cls:14:1: error: CL point (0.9843, 0.0000, 0.0000) is never reached: the program comes within "
                        "0.00390 of it [G-code line 20]"));

  c = verify(cl, m, edit(program, "N30 G54 G00 G234 H01\n", "N30 G54 G00 G43 H01\n"));
  EXPECT_FALSE(c.report.ok);
  EXPECT_THAT(c.diags, HasSubstr("sweep.cls:10:1: error: CL point (0.1969, 0.0000, 0.0000) is never reached"));
  // On a machine whose work is written in the part's frame, a move with the table turned and
  // neither TCPC nor G254 is in machine axes about a centre the part's zero is not known from.
  EXPECT_THAT(first_error(c.diags),
              HasSubstr("sweep.cls:9:1: error: the program: the table is turned and none of TCPC (G234), a dynamic work "
                        "offset (G254) is in force: the control moves X Y Z as machine axes"));
}

TEST_F(VerifyPlate, JsonReport) {
  Checked c = verify(cl, m, edit(program_for(cl, m), "N120 G01 X0.", "N120 G01 X0.01"));
  std::ostringstream j;
  print_report_json(j, c.report);
  EXPECT_THAT(j.str(), HasSubstr("\"ok\": false,"));
  EXPECT_THAT(j.str(), HasSubstr("\"max_deviation\": {\"value\": 0.01, \"line\": 15, \"column\": 1, \"gcode_line\": 18},"));
  EXPECT_THAT(j.str(), HasSubstr("\"cl\": {\"points\": 8, \"arcs\": 1, \"holes\": 0, \"groove_cuts\": 0, \"thread_cuts\": 0},"));
  EXPECT_THAT(j.str(), HasSubstr("{\"line\": 15, \"column\": 1, \"gcode_line\": 18, \"message\": \"CL point (0.0000, 20.0000, -2.0000) "
                                 "is never reached: the program comes within 0.01000 of it\", \"deviation\": 0.01}"));
  EXPECT_THAT(j.str(), HasSubstr("\"problem_count\": 3,"));
}

// The command: exit status, report on stdout, diagnostics on stderr.
TEST_F(VerifyPlate, CommandLine) {
  RunResult ok = run_clpc("verify " + cl + " -t fanuc-mill");
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_THAT(ok.out, HasSubstr("result: PASS"));
  write_file(t.path("bad.nc"), edit(program_for(cl, m), "N100 Y20.\n", ""));
  RunResult bad = run_clpc("verify " + cl + " -t fanuc-mill --program " + t.path("bad.nc") + " --json");
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.out, HasSubstr("\"ok\": false"));
  EXPECT_THAT(bad.err, HasSubstr("plate.cls:12:1: error: CL point"));
  EXPECT_THAT(bad.err, HasSubstr("\n 12 | GOTO/30,20,-2\n"));
}


// --report: one self-contained page with the operations, the deviation map and the backplot;
// a program with a shifted point shows it red, in its operation's row.
TEST_F(VerifyPlate, HtmlReport) {
  VerifyOptions o;
  o.report = t.path("report.html");
  std::ostringstream err;
  VerifyReport r = verify_file(cl, m, o, err);
  ASSERT_TRUE(r.ok) << err.str();
  ASSERT_EQ(r.operations.size(), 1u);
  EXPECT_EQ(r.operations[0].points, 8);
  EXPECT_EQ(r.operations[0].arcs, 1);
  EXPECT_EQ(r.samples.size(), 9u);  // 8 points and the arc's end
  const std::string html = read_file(o.report);
  EXPECT_THAT(html, HasSubstr("<h1>clpc verify: " + cl + " on fanuc-mill — PASS</h1>"));
  EXPECT_THAT(html, HasSubstr("<td class=\"l\">(unnamed)</td><td>T1</td>"));
  EXPECT_THAT(html, HasSubstr("<h2>Backplot</h2>\n<svg"));
  size_t circles = 0;  // in the deviation map (the backplot marks tool changes with circles too)
  const size_t map_end = html.find("<h2>Backplot");
  for (size_t at = html.find("<circle"); at < map_end; at = html.find("<circle", at + 1)) ++circles;
  EXPECT_EQ(circles, 2 * 9u);  // top and front
  EXPECT_EQ(html.find("#d73027\"/>"), std::string::npos);  // nothing red

  o.program = t.path("edited.nc");
  write_file(o.program, edit(program_for(cl, m), "X30. F800.", "X30.01 F800."));
  o.report = t.path("bad.html");
  VerifyReport bad = verify_file(cl, m, o, err);
  EXPECT_FALSE(bad.ok);
  const std::string red = read_file(o.report);
  EXPECT_THAT(red, HasSubstr("— FAIL</h1>"));
  EXPECT_THAT(red, HasSubstr("fill=\"#d73027\"/>"));
  EXPECT_THAT(red, HasSubstr("<h2>Problems</h2>"));
}

// A macro variable set by an INSERT (#100=1, for a probing macro) moves nothing: the program
// is read past it (verify refused it: "unexpected character '#'"). A word that uses a
// variable is still no number the reader can check.
TEST(Verify, AMacroVariableSetByAnInsertIsReadPast) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,5\nINSERT/#100=1\nFEDRAT/100,MMPM\n"
                         "GOTO/0,0,0\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\n#100=1\n"));
  std::string uses = c.output;
  uses.replace(uses.find("Z0. F100."), 3, "Z#100");
  Compiled bad = verify_text(cl, machine("fanuc-mill"), uses);
  EXPECT_FALSE(bad.ok);
}

// Hand edits the reader cannot take as the CL's (helper-49): G20 on a millimetre machine (read as
// millimetres, every axis would move 25.4 times as far), a subprogram call, no M30, a canned
// cycle repeated (K0 drills nothing, K3 thrice). And a cycle's P is milliseconds: G82 P500 counted 500 s.
TEST_F(VerifyPlate, UnitsEndsAndRepeatsTheControlReadsOtherwiseFail) {
  const std::string program = program_for(cl, m);
  Checked inch = verify(cl, m, edit(program, "N10 G21", "N10 G20"));
  EXPECT_FALSE(inch.report.ok);
  EXPECT_THAT(first_error(inch.diags), HasSubstr("error: the program: G20 (inches) on a machine described in millimetres: the "
                                                 "control would read every number 25.4 times larger than the program means"));
  Checked called = verify(cl, m, edit(program, "M30\n", "M98 P9000\nM30\n"));
  EXPECT_FALSE(called.report.ok);
  EXPECT_THAT(called.diags, HasSubstr("M98 calls a subprogram the reader does not have"));
  Checked endless = verify(cl, m, edit(program, "M30\n", "\n"));
  EXPECT_FALSE(endless.report.ok);
  EXPECT_THAT(endless.diags, HasSubstr("the program has no end (M30 or M02)"));

  const std::string dcl = "UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nFEDRAT/100,MMPM\nRAPID\nGOTO/0,0,20\n"
                          "CYCLE/DRILL,FEDTO,2,RAPTO,3,MMPM,100,DWELL,0.5\nGOTO/10,0,0\nGOTO/20,0,0\nCYCLE/OFF\nRAPID\n"
                          "GOTO/20,0,50\nFINI\n";
  Compiled c = compile_text(dcl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr("G82 X10. Y0. Z-2. R3. P500 F100.\nN80 X20.\n"));
  TempDir t2;
  write_file(t2.path("d.cls"), dcl);
  Checked timed = verify(t2.path("d.cls"), m);
  ASSERT_TRUE(timed.report.ok) << timed.diags;
  EXPECT_NEAR(timed.report.program.dwell_minutes * 60, 1.0, 1e-9);  // two holes, 0.5 s each
  for (const auto& [repeat, said] : {std::pair{"K0", "stores the cycle and drills no hole"}, {"K3", "drills the hole 3 times"}}) {
    Compiled r = verify_text(dcl, machine("fanuc-mill"), edit(c.output, "N80 X20.", std::string("N80 X20. ") + repeat));
    EXPECT_FALSE(r.ok) << repeat;
    EXPECT_THAT(r.diags, HasSubstr(std::string(repeat) + " in a canned cycle: the control " + said)) << r.diags;
  }
}

// A canned cycle's code says what the spindle does at the bottom and how the tool comes out,
// which the path alone does not show. Each of these edits passed (helper-49): a tap drilled with
// G81 (fed in, rapided out turning forward) or G74 (turned backwards), a DEEP cycle made G81 or
// G73 or given a 20 mm Q, a spot-dwell made G81 (no dwell) or G86 (the spindle stopped), its
// P made 50 s. A G89 for a spot-dwell (fed out, slower) is no harm.
TEST(Verify, ACycleThatDoesOtherThanTheClsFails) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,20\n"
                         "CYCLE/DEEP,FEDTO,20,INCR,4,RAPTO,2,MMPM,100\nGOTO/10,0,0\nCYCLE/OFF\n"
                         "CYCLE/DRILL,FEDTO,2,RAPTO,2,MMPM,100,DWELL,0.5\nGOTO/20,0,0\nCYCLE/OFF\n"
                         "CYCLE/TAP,FEDTO,10,RAPTO,5,MMPR,1\nGOTO/30,0,0\nCYCLE/OFF\nRAPID\nGOTO/30,0,50\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr("G83 X10. Y0. Z-20. R2. Q4. F100.\n"));
  ASSERT_THAT(c.output, HasSubstr("G82 X20. Y0. Z-2. R2. P500 F100.\n"));
  ASSERT_THAT(c.output, HasSubstr(" G84 X30. Y0. Z-10. R5. "));
  const struct {
    const char* from;
    const char* to;
    const char* said;
  } edits[] = {
      {"G84 X30.", "G81 X30.", "part.cl:13:1: error: the hole is made with G81, not G84, the CL's cycle is tap"},
      {"G84 X30.", "G74 X30.", "part.cl:13:1: error: the hole is made with G74, not G84, the CL's cycle is tap"},
      {"G83 X10.", "G81 X10.", "part.cl:7:1: error: the drill feeds 20.0000 deeper at once (G81), its pecks are 4.0000, "
                               "the CL's cycle is peck"},
      {"Q4.", "Q20.", "part.cl:7:1: error: the drill feeds 18.0000 deeper at once (G83), its pecks are 4.0000"},
      {"G83 X10.", "G73 X10.", "part.cl:7:1: error: G73 breaks the chip without leaving the hole between pecks, the CL's "
                               "cycle is peck"},
      {"G82 X20. Y0. Z-2. R2. P500", "G81 X20. Y0. Z-2. R2.", "part.cl:10:1: error: the tool dwells 0.000 s at the bottom, "
                                                               "not 0.500 s, the CL's cycle is spot-dwell"},
      {"P500", "P50000", "part.cl:10:1: error: the tool dwells 50.000 s at the bottom, not 0.500 s"},
      {"G82 X20. Y0. Z-2. R2. P500", "G86 X20. Y0. Z-2. R2.", "part.cl:10:1: error: G86 stops the spindle at the bottom, the "
                                                               "CL's cycle is spot-dwell"},
  };
  for (const auto& e : edits) {
    Compiled v = verify_text(cl, machine("fanuc-mill"), edit(c.output, e.from, e.to));
    EXPECT_FALSE(v.ok) << e.to;
    EXPECT_THAT(v.diags, HasSubstr(e.said)) << e.to;
  }
  Compiled fed_out = verify_text(cl, machine("fanuc-mill"), edit(c.output, "G82 X20.", "G89 X20."));
  EXPECT_TRUE(fed_out.ok) << fed_out.diags;
}

// On a machine that writes its 3+2 work with a dynamic work offset and its five-axis work under
// TCPC, the work offset is the part's zero, wherever it lies from the table's centre. A move with
// the table turned and neither in force is in machine axes about a point clpc does not know:
// G254 deleted after a B90 C90 index passed, read as if the part's zero were on the centre
// (helper-49).
TEST(Verify, ATurnedTableWithoutItsDynamicWorkOffsetFails) {
  const std::string cl = "UNITS/MM\nTOOL PATH/SIDE,TOOL,EM10\nTLDATA/MILL,10,0,50,0,0\nLOAD/TOOL,1,ADJUST,1\n"
                         "SPINDL/RPM,6000,CLW\nMSYS/0,0,0,1,0,0,0,1,0\nRAPID\nGOTO/0,0,50,0,0,1\nFEDRAT/MMPM,500\n"
                         "GOTO/30,0,50\nEND-OF-PATH\nTOOL PATH/SIDE2,TOOL,EM10\n"
                         "MSYS/0,-20,-10,1,0,0,0,0,-1\nRAPID\nGOTO/0,0,50,0,0,1\nRAPID\nGOTO/0,0,2\nFEDRAT/MMPM,500\n"
                         "GOTO/0,0,0\nGOTO/30,0,0\nRAPID\nGOTO/30,0,50\nEND-OF-PATH\nFINI\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  const size_t at = c.output.find(" G254");
  ASSERT_NE(at, std::string::npos) << c.output;
  Compiled v = verify_text(cl, machine("haas-umc750"), c.output.substr(0, at) + c.output.substr(at + 5));
  EXPECT_FALSE(v.ok);
  EXPECT_THAT(v.diags, HasSubstr("error: the program: the table is turned and none of TCPC (G234), a dynamic work offset "
                                 "(G254) is in force"));
}

// A mill's S is the CL's rpm, rounded to S's increment: S3000 made S300 or S30000 passed, and a
// drill's S0 too (helper-49).
TEST_F(VerifyPlate, ACutAtAnotherSpindleSpeedFails) {
  const std::string program = program_for(cl, m);
  for (const char* s : {"S300 M03", "S30000 M03", "S0 M03"}) {
    Checked c = verify(cl, m, edit(program, "S3000 M03", s));
    EXPECT_FALSE(c.report.ok) << s;
    EXPECT_THAT(first_error(c.diags), HasSubstr("plate.cls:9:1: error: the program cuts here at " + std::string(s, std::string(s).find(' ')) +
                                                ", the CL's spindle speed is 3000 rpm")) << s;
  }
  EXPECT_TRUE(verify(cl, m, edit(program, "S3000 M03", "S3000 M03")).report.ok);
}

// A dwell's P is whole milliseconds without a point, whatever format.P's implied decimals (the
// lathe's G04 P500 was read 0.0005 s); seconds with one where the control's P takes a point
// (Haas); on a Fanuc, whose P takes none, a point is a problem (helper-50).
TEST(Verify, ADwellsPIsMillisecondsOrSecondsAsTheControlReadsIt) {
  auto dwell = [](const char* block, const char* name, std::string* problem = nullptr) {
    gcode::Result r = gcode::interpret(std::string(block) + "\nM30\n", machine(name));
    if (problem) *problem = r.problems.empty() ? "" : r.problems.front().message;
    for (const gcode::Event& e : r.events)
      if (e.kind == gcode::Event::Kind::Dwell) return e.value;
    return -1.0;
  };
  EXPECT_DOUBLE_EQ(dwell("G04 P500", "fanuc-lathe"), 0.5);
  EXPECT_DOUBLE_EQ(dwell("G04 P500", "fanuc-mill"), 0.5);
  EXPECT_DOUBLE_EQ(dwell("G04 P0.5", "haas-umc750"), 0.5);
  std::string problem;
  dwell("G04 P0.5", "fanuc-mill", &problem);
  EXPECT_EQ(problem, "P0.5 with a decimal point: this control takes a dwell's P in whole milliseconds (its P is written "
                     "without a point)");
}

// A bore on a machine without G85 is written as moves, fed out of each hole: the feed out of the
// first hole is passed over on the way to the second. It was judged against the second's axis,
// and every bore after the first was refused (helper-50).
TEST(Verify, BoresWrittenAsMovesAreFedOutOfEachHole) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,20\n"
                         "CYCLE/BORE,FEDTO,20,RAPTO,2,MMPM,100\nGOTO/10,10,0\nGOTO/30,10,0\nGOTO/30,30,0\nCYCLE/OFF\n"
                         "RAPID\nGOTO/30,30,50\nFINI\n";
  const Machine plain = machine("no-bore", "[no-bore]\ninherits = \"fanuc-mill\"\n[no-bore.codes]\ncycle_bore = \"\"\n");
  Compiled c = compile_text(cl, plain, {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, ::testing::Not(HasSubstr("G85")));
  EXPECT_THAT(c.output, HasSubstr("G01 Z-20. F100.\n"));
}

// A cut with no coolant on where the CL has it on: M08 made M09 passed (helper-49). Flood for
// mist is coolant still, and a machine whose coolant codes the reader does not know is not judged.
TEST(Verify, ACutWithTheCoolantOffWhereTheClHasItOnFails) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nCOOLNT/FLOOD\nRAPID\nGOTO/0,0,5\nFEDRAT/MMPM,200\n"
                         "GOTO/0,0,-1\nGOTO/20,0,-1\nRAPID\nGOTO/20,0,50\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr("M08\n"));
  Compiled off = verify_text(cl, machine("fanuc-mill"), edit(c.output, "M08\n", "M09\n"));
  EXPECT_FALSE(off.ok);
  EXPECT_THAT(off.diags, HasSubstr("part.cl:8:1: error: the program cuts here with the coolant off, where the CL has it on"));
  EXPECT_TRUE(verify_text(cl, machine("fanuc-mill"), edit(c.output, "M08\n", "M07\n")).ok);
  const Machine other = machine("m51", "[m51]\ninherits = \"fanuc-mill\"\n[m51.codes]\ncoolant_flood = \"M51\"\n");
  Compiled own = compile_text(cl, other, {.certify = true});
  EXPECT_TRUE(own.ok) << own.diags;
}

// A G04 dwells the CL's DELAY before the move after it: P1250 made P2500, a G04 deleted, one
// inserted mid-contour, and G04 X1250. (seconds, with the point) for 1.25 s all passed
// (helper-49, helper-52). A bore-dwell written as moves dwells with a G04 of its own.
TEST(Verify, ADwellOtherThanTheClsDelayFails) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/MMPM,200\n"
                         "GOTO/0,0,-1\nDELAY/1.25\nGOTO/20,0,-1\nGOTO/20,20,-1\nRAPID\nGOTO/20,20,50\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr(" G04 P1250\n"));
  Compiled longer = verify_text(cl, machine("fanuc-mill"), edit(c.output, "G04 P1250", "G04 P2500"));
  EXPECT_FALSE(longer.ok);
  EXPECT_THAT(longer.diags, HasSubstr("part.cl:9:1: error: the program dwells 2.500 s before this move, the CL's DELAY "
                                      "(line 8) is 1.250 s"));
  Compiled none = verify_text(cl, machine("fanuc-mill"), edit(c.output, "G04 P1250", ""));
  EXPECT_FALSE(none.ok);
  EXPECT_THAT(none.diags, HasSubstr("part.cl:9:1: error: the program dwells 0.000 s before this move, the CL's DELAY"));
  Compiled inserted = verify_text(cl, machine("fanuc-mill"), edit(c.output, " Y20.\n", " G04 P1000\nY20.\n"));
  EXPECT_FALSE(inserted.ok);
  EXPECT_THAT(inserted.diags, HasSubstr("part.cl:10:1: error: the program dwells 1.000 s before this move, the CL has no "
                                        "DELAY here"));
  // A P within the millisecond it is written in passes; 5 % off does not (helper-53).
  EXPECT_TRUE(verify_text(cl, machine("fanuc-mill"), edit(c.output, "G04 P1250", "G04 P1251")).ok);
  EXPECT_FALSE(verify_text(cl, machine("fanuc-mill"), edit(c.output, "G04 P1250", "G04 P1310")).ok);
  // The slack is the dwell word's own: a mill's unused U of one decimal let P1300 pass (helper-55).
  const Machine coarse_u = machine("coarse-u", "[coarse-u]\ninherits = \"fanuc-mill\"\n[coarse-u.format]\nU = { decimals = 1 }\n");
  EXPECT_FALSE(verify_text(cl, coarse_u, edit(c.output, "G04 P1250", "G04 P1300")).ok);
  // A machine's own codes may dwell before a rapid (a G04 in its start or tool change for the
  // spindle or the coolant): never counted against the CL (helper-53).
  const Machine waits = machine("waits", "[waits]\ninherits = \"fanuc-mill\"\n[waits.codes]\n"
                                         "tool_change = \"T{tool} M06 G04 P500\"\n");
  Compiled waited = compile_text("UNITS/MM\nLOADTL/1\n" + cl.substr(cl.find("SPINDL")) , waits, {.certify = true});
  EXPECT_TRUE(waited.ok) << waited.diags;
  // A DELAY after the last move: its G04 belongs to no move, and was never compared.
  const std::string last = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/MMPM,200\n"
                           "GOTO/0,0,-1\nRAPID\nGOTO/0,0,50\nDELAY/4\nFINI\n";
  Compiled ends = compile_text(last, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(ends.ok) << ends.diags;
  Compiled dropped = verify_text(last, machine("fanuc-mill"), edit(ends.output, " G04 P4000", ""));
  EXPECT_FALSE(dropped.ok);
  EXPECT_THAT(dropped.diags, HasSubstr("error: the program dwells 0.000 s before this move, the CL's DELAY (line 10) is 4.000 s"));
  const std::string bore = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,20\nDELAY/2\n"
                           "CYCLE/BORE,FEDTO,20,RAPTO,2,MMPM,100,DWELL,0.5\nGOTO/10,10,0\nGOTO/30,10,0\nCYCLE/OFF\n"
                           "RAPID\nGOTO/30,10,50\nFINI\n";
  const Machine plain = machine("no-g89", "[no-g89]\ninherits = \"fanuc-mill\"\n[no-g89.codes]\ncycle_bore_dwell = \"\"\n");
  Compiled moves = compile_text(bore, plain, {.certify = true});
  ASSERT_TRUE(moves.ok) << moves.diags;
  EXPECT_THAT(moves.output, HasSubstr("G04 P2000\n"));
  EXPECT_THAT(moves.output, HasSubstr("G04 P500\n"));
  // The hole's G04 is the hole's: a wrong one is caught there, not taken for a DELAY.
  std::string longer_bottom = moves.output;
  longer_bottom.replace(longer_bottom.find("G04 P500\n"), 8, "G04 P5000");
  Compiled bottom = verify_text(bore, plain, longer_bottom);
  EXPECT_FALSE(bottom.ok);
  EXPECT_THAT(bottom.diags, HasSubstr("the tool dwells 5.000 s at the bottom, not 0.500 s"));
}

// G41/G42 take the radius from the CUTCOM's register, or the tool's own: D3 made D13 passed
// (helper-49). A machine whose G41 writes no register (a lathe's T word selects it) is not judged.
TEST(Verify, CompensationFromAnotherRegisterFails) {
  const std::string cl = "UNITS/MM\nLOADTL/3\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,-10,5\nFEDRAT/MMPM,200\n"
                         "GOTO/0,-10,-1\nCUTCOM/LEFT\nGOTO/0,0,-1\nGOTO/20,0,-1\nCUTCOM/OFF\nGOTO/20,-10,-1\nRAPID\n"
                         "GOTO/20,-10,50\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr("G41 D3 "));
  Compiled other = verify_text(cl, machine("fanuc-mill"), edit(c.output, "G41 D3 ", "G41 D13 "));
  EXPECT_FALSE(other.ok);
  EXPECT_THAT(other.diags, HasSubstr("part.cl:9:1: error: the program compensates here with register D13, where the CL's "
                                     "CUTCOM (line 8) takes the radius from register 3 (the tool's own)"));
  Compiled none = verify_text(cl, machine("fanuc-mill"), edit(c.output, "G41 D3 ", "G41 "));
  EXPECT_FALSE(none.ok);
  EXPECT_THAT(none.diags, HasSubstr("with no D register"));
  // D is modal on a mill: given in a block before G41 it holds; changed mid-contour it is caught
  // (helper-53).
  EXPECT_TRUE(verify_text(cl, machine("fanuc-mill"), edit(c.output, "G41 D3 ", "D3\nG41 ")).ok);
  Compiled changed = verify_text(cl, machine("fanuc-mill"), edit(c.output, " X20.", " X20. D13"));
  EXPECT_FALSE(changed.ok);
  EXPECT_THAT(changed.diags, HasSubstr("part.cl:10:1: error: the program compensates here with register D13"));
  std::string own = cl;
  own.replace(own.find("CUTCOM/LEFT"), 11, "CUTCOM/LEFT,33");
  Compiled named = compile_text(own, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(named.ok) << named.diags;
  EXPECT_THAT(named.output, HasSubstr("G41 D33 "));
  EXPECT_FALSE(verify_text(own, machine("fanuc-mill"), edit(named.output, "G41 D33 ", "G41 D3 ")).ok);
}

// A DELAY at the bottom of a groove's last plunge: the groove's last blocks are read after it
// closes, and its G04 was taken for a dwell where the CL has none (helper-53).
TEST(Verify, ADwellAtAGroovesLastPlungeIsTheGroovesOwn) {
  const std::string cl = "MACHIN / TURN, 01\nUNITS / MM\nTURRET / 3\nSPINDL / RPM, 450, CLW\nRAPID\nGOTO / 40, 0, -20\n"
                         "$$ GRV,2.9872,-0.7794,0.100,0.025,0.000,0.000,0.008,0.000,0\nFEDRAT / 0.1, MMPR\n"
                         "GOTO / 36, 0, -20\nGOTO / 30, 0, -20\nGOTO / 36, 0, -20\nRAPID\nGOTO / 36, 0, -22\n"
                         "FEDRAT / 0.1, MMPR\nGOTO / 30, 0, -22\nDELAY / 0.5\nGOTO / 36, 0, -22\n$$ GRV END\nRAPID\n"
                         "GOTO / 50, 0, 5\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G04 U0.5\n"));
  EXPECT_FALSE(verify_text(cl, machine("fanuc-lathe"), edit(c.output, "G04 U0.5\n", "G04 U5.\n")).ok);
}

// A G00 that leaves a CL cut (through the stock) followed by a feed back to the cut's end was
// passed: rapids were taken for the post's own positioning anywhere (helper-57). They are only
// where the tool comes from no point of this tool's, or where the program comes back to the
// last point before it cuts on (RotaryContinuity's retract and re-engage).
TEST(Verify, ARapidThatLeavesACutFails) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,50\nFEDRAT/MMPM,300\n"
                         "GOTO/0,0,-2\nGOTO/50,0,-2\nGOTO/50,50,-2\nRAPID\nGOTO/50,50,50\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  Compiled detour = verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N80 G00 X25. Z-30.\nN85 G01 X50. Z-2.\n"));
  EXPECT_FALSE(detour.ok);
  EXPECT_THAT(first_error(detour.diags),
              HasSubstr("part.cl:8:1: error: the program leaves the CL's cut from (0.0000, 0.0000, -2.0000) to (50.0000, 0.0000, "
                        "-2.0000) at rapid traverse (G00), 28.0000 off its path: that cut is not made [G-code line 14]"));
  // Out and back to the point the cut starts from, then the cut: the cut is made.
  EXPECT_TRUE(verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N76 G00 Z10.\nN78 G01 Z-2.\nN80 X50.\n")).ok);
  // Up in machine coordinates and down over the cut's end: the same cut not made.
  Compiled up = verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N76 G53 G00 Z0.\nN78 X50.\nN80 G01 Z-2.\n"));
  EXPECT_FALSE(up.ok);
  EXPECT_THAT(first_error(up.diags), HasSubstr("part.cl:8:1: error: the program leaves the CL's cut from (0.0000, 0.0000, -2.0000) to "
                                              "(50.0000, 0.0000, -2.0000) at rapid traverse (G00), in machine coordinates: that "
                                              "cut is not made"));
  // G53 in G91 is ignored by the control: read so, not as a move up (helper-71).
  Compiled g91 = verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N76 G91 G53 Z0.\nN77 G90\nN80 X50.\n"));
  EXPECT_FALSE(g91.ok);
  EXPECT_THAT(g91.diags, HasSubstr("G53 in G91: the control ignores machine coordinates in incremental mode, so the tool does "
                                   "not move; G90 G53"));
}

// An operation whose first move is a cut from where the last one left the tool, at another
// tilt: the post retracts, re-tilts and plunges over the cut's end, so the cut is not made
// (certified before; helper-57). The certificate refuses it.
TEST(Verify, AReTiltInPlaceOfAnOperationsFirstCutIsRefused) {
  const std::string cl =
      "TOOL PATH/OP1,TOOL,EM\nTLDATA/MILL,0.5,0,4,0\nUNITS/INCHES\nLOAD/TOOL,1\nSPINDL/RPM,3000,CLW\nRAPID\n"
      "GOTO/1,1,3,0.5,0,0.8660254\nFEDRAT/IPM,20\nGOTO/1,1,0,0.5,0,0.8660254\nGOTO/2,1,0,0.5,0,0.8660254\nEND-OF-PATH\n"
      "TOOL PATH/OP2,TOOL,EM\nFEDRAT/IPM,20\nGOTO/2,2,0,0,0,1\nGOTO/3,2,0,0,0,1\nRAPID\nGOTO/3,2,3,0,0,1\nEND-OF-PATH\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("part.cls:14:1: error: the program leaves the CL's cut from (2.0000, 1.0000, 0.0000) to (2.0000, "
                                 "2.0000, 0.0000) at rapid traverse (G00), in machine coordinates: that cut is not made"));
}

// A DELAY after the last move, its G04 deleted, passed where the program drills with a dwell
// at the bottom: the holes' dwells were counted as the missing G04 (helper-55).
TEST(Verify, ADelayAfterTheLastMoveIsNotMadeByTheHolesDwells) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,20\n"
                         "CYCLE/DRILL,FEDTO,5,RAPTO,2,MMPM,100,DWELL,2\nGOTO/10,10,0\nGOTO/30,10,0\nCYCLE/OFF\n"
                         "RAPID\nGOTO/30,10,50\nDELAY/4\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  Compiled gone = verify_text(cl, machine("fanuc-mill"), edit(c.output, "G04 P4000\n", ""));
  EXPECT_FALSE(gone.ok);
  EXPECT_THAT(first_error(gone.diags), HasSubstr("error: the program dwells 0.000 s before this move, the CL's DELAY (line 12) is 4.000 s"));
}

// Between two CL rapids a G00 down into the stock and across, and a dive in a new tool's
// approach, passed (helper-60). An out-and-back excursion down into the cut too (helper-58).
TEST(Verify, ARapidBelowTheClsRapidFails) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,50\nFEDRAT/MMPM,300\n"
                         "GOTO/0,0,-2\nGOTO/50,0,-2\nRAPID\nGOTO/50,0,50\nRAPID\nGOTO/80,5,50\nGOTO/80,5,-2\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr("N100 X80. Y5.\n"));
  Compiled dive = verify_text(cl, machine("fanuc-mill"), edit(c.output, "N100 X80. Y5.\n", "N96 Z-30.\nN98 X80. Y5.\nN100 Z50.\n"));
  EXPECT_FALSE(dive.ok);
  EXPECT_THAT(first_error(dive.diags), HasSubstr("part.cl:12:1: error: the program's rapid goes 80.0000 lower along the tool axis "
                                                 "than the CL's rapid from (50.0000, 0.0000, 50.0000) to (80.0000, 5.0000, 50.0000), "
                                                 "to (50.0000, 0.0000, -30.0000)"));
  Compiled back = verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N80 X50.\nN82 G00 Z-30.\nN84 Z-2.\n"));
  EXPECT_FALSE(back.ok);
}

// A lathe program with no T word cuts with the station and offset the last program left: a CL
// with no tool is refused like a mill's, and a T0101 deleted from a program fails (helper-59).
TEST(Verify, ALatheCutWithNoToolSelectedFails) {
  const std::string cut = "SPINDL/RPM,1000,CLW\nFEDRAT/MMPR,0.2\nRAPID\nGOTO/22,0,2\nGOTO/10,0,2\nGOTO/10,0,-20\nGOTO/22,0,-20\nFINI\n";
  Compiled bare = compile_text("UNITS/MM\n" + cut, machine("fanuc-lathe"));
  EXPECT_FALSE(bare.ok);
  EXPECT_THAT(bare.diags, HasSubstr("part.cls:6:1: error: cutting with no tool loaded: the CL loads none before this move "
                                    "(LOADTL, LOAD/TOOL, TURRET), so the program would select no turret station and no "
                                    "offset (no T word) and cut with whatever the last program left"));
  const std::string cl = "UNITS/MM\nTURRET/1\n" + cut;
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr("N30 T0101 (T1)\n"));
  Compiled gone = verify_text(cl, machine("fanuc-lathe"), edit(c.output, "N30 T0101 (T1)\n", ""));
  EXPECT_FALSE(gone.ok);
  EXPECT_THAT(first_error(gone.diags), HasSubstr("error: this is cut with no tool selected (no T word) (the CL loads tool 1 at line 2)"));
}

// A lathe never turns faster than the CL asks where it cuts: a G50 clamp deleted (the spindle
// runs up facing to the centre), G96 S raised, G97 S1000 made S3000 passed (helper-59, helper-60).
TEST(Verify, ALatheSpindleFasterThanTheClsFails) {
  const std::string face = "UNITS/MM\nTURRET/1\nSPINDL/SMM,200,MAXRPM,1500,CLW\nFEDRAT/MMPR,0.1\nRAPID\nGOTO/22,0,0.5\n"
                           "GOTO/22,0,0\nGOTO/0,0,0\nRAPID\nGOTO/0,0,5\nFINI\n";
  Compiled c = compile_text(face, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  ASSERT_THAT(c.output, HasSubstr(" G50 S1500\n"));
  Compiled unclamped = verify_text(face, machine("fanuc-lathe"), edit(c.output, " G50 S1500\n", " G50 S3000\n"));
  EXPECT_FALSE(unclamped.ok);
  EXPECT_THAT(first_error(unclamped.diags), HasSubstr("error: the program turns the spindle at "));
  EXPECT_THAT(first_error(unclamped.diags), HasSubstr("faster than the CL's surface speed within its clamp makes it at this radius"));
  EXPECT_FALSE(verify_text(face, machine("fanuc-lathe"), edit(c.output, " G96 S200 ", " G96 S250 ")).ok);
  const std::string rpm = "UNITS/MM\nTURRET/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPR,0.1\nRAPID\nGOTO/22,0,2\nGOTO/20,0,2\n"
                          "GOTO/20,0,-10\nRAPID\nGOTO/30,0,5\nFINI\n";
  Compiled r = compile_text(rpm, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(r.ok) << r.diags;
  Compiled faster = verify_text(rpm, machine("fanuc-lathe"), edit(r.output, " G97 S1000 ", " G97 S3000 "));
  EXPECT_FALSE(faster.ok);
  EXPECT_THAT(first_error(faster.diags), HasSubstr("error: the program turns the spindle at 3000 rpm here, faster than the CL's "
                                                   "speed (1000 rpm)"));
}

// Where the CL sets no work offset the registers are the operator's: a G10 L2 P1 inserted moved
// G54, and the whole part was cut elsewhere, passed (helper-60).
TEST(Verify, AWorkOffsetTheClDoesNotSetFails) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,50\nFEDRAT/MMPM,300\n"
                         "GOTO/0,0,-2\nGOTO/50,0,-2\nRAPID\nGOTO/50,0,50\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  Compiled moved = verify_text(cl, machine("fanuc-mill"), edit(c.output, "N30 T1 M06", "N25 G10 L2 P1 X100. Y50. Z-20.\nN30 T1 M06"));
  EXPECT_FALSE(moved.ok);
  EXPECT_THAT(moved.diags, HasSubstr("G10 sets work offset register 1, which the operator sets up: the CL gives it no value, so "
                                     "the part's zero would move"));
}

// '/' before a block: the operator's Block Delete switch may skip it. A stop so written is a
// routine shop edit, read as run; a block that moves or changes a state would make two
// programs, one unchecked, and is refused (helper-70: "/M01" was an unexpected character).
TEST(Verify, ABlockDeleteStopIsReadAndOtherSkippableBlocksAreRefused) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10\nFEDRAT/MMPM,100\n"
                         "GOTO/0,0,-2\nGOTO/50,0,-2\nRAPID\nGOTO/50,0,10\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_TRUE(verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N80 X50.\n/M01\n")).ok);
  EXPECT_TRUE(verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N80 X50.\n / N85 M00\n")).ok);
  EXPECT_TRUE(verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N80 X50.\nN85 /M01\n/2 M01\n")).ok);
  Compiled moved = verify_text(cl, machine("fanuc-mill"), edit(c.output, "N80 X50.\n", "N80 X50.\n/G00 Z10.\n"));
  EXPECT_FALSE(moved.ok);
  EXPECT_THAT(moved.diags, HasSubstr("a block the Block Delete switch may skip ('/') holds G0: the program runs two ways, "
                                     "and only one could be checked; only a stop (M00, M01) may be written so"));
}
