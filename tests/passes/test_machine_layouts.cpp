// The example five-axis machines (examples/): a head-head gantry (A/C fork head, G43.4), a
// head-table machine (B head over a C table, no TCP: points through the chain) and an A/C
// trunnion (G43.4, G68.2). Each compiles and certifies a generated five-axis finish and a 3+2
// file; the exact blocks of a short program; and, where the control has no TCP, verify proves
// each move at its worst point.
#include <cmath>

#include "readback/gcode_interp.h"
#include "helpers.h"
#include "three_plus_two.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {


struct Example {
  const char* name;
  const char* file;
};
const Example kExamples[] = {{"fanuc-ac-plane", "examples/fanuc_ac_plane.toml"},
                             {"gantry-ac-head", "examples/gantry_ac_head.toml"},
                             {"head-table-bc", "examples/head_table_bc.toml"}};

Machine example(const Example& e) { return machine(e.name, read_file(source_path(e.file))); }

// A five-axis finish: 41 points along a wave, the tool tilting from 5 to 30 degrees while its
// azimuth turns a quarter turn.
std::string five_axis_finish() {
  std::string cl = "TOOL PATH/SWARF,TOOL,T1\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,6000,CLW\nRAPID\nGOTO/0,0,60,0,0,1\n"
                   "FEDRAT/MMPM,800\nMULTAX/ON\n";
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= 40; ++i) {
    double t = i / 40.0, tilt = (5 + 25 * t) * pi / 180, az = 90 * t * pi / 180;
    char b[200];
    std::snprintf(b, sizeof b, "GOTO/%.4f,%.4f,%.4f,%.7f,%.7f,%.7f\n", 40 * t, 10 * std::sin(pi * t), 5 - 3 * t,
                  std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt));
    cl += b;
  }
  return cl + "RAPID\nGOTO/40,30,60,0,0,1\nEND-OF-PATH\n";
}


// Down vertical, then along X tilting to 30 degrees towards +X, then along Y turning the tilt
// towards +Y.
const char* kShortFive =
    "TOOL PATH/SWARF,TOOL,T1\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,6000,CLW\nRAPID\nGOTO/0,0,60,0,0,1\nFEDRAT/MMPM,800\n"
    "GOTO/0,0,5,0,0,1\nGOTO/20,0,5,0.5,0,0.8660254\nGOTO/20,20,5,0,0.5,0.8660254\nRAPID\nGOTO/20,20,60,0,0,1\n"
    "END-OF-PATH\n";

CompileOptions certified() {
  CompileOptions o;
  o.certify = true;
  return o;
}

}  // namespace

TEST(MachineLayouts, EveryExampleCertifiesAFiveAxisFinishAndA3Plus2File) {
  const std::string finish = five_axis_finish();
  for (const Example& e : kExamples) {
    Machine m = example(e);
    Compiled five = compile_text(finish, m, certified());
    EXPECT_TRUE(five.ok) << e.name << "\n" << five.diags;
    EXPECT_THAT(five.diags, HasSubstr("out.nc: 43 points, 0 arcs, 0 holes checked")) << e.name;
    Compiled indexed = compile_text(kThreePlusTwo, m, certified());
    EXPECT_TRUE(indexed.ok) << e.name << "\n" << indexed.diags;
    EXPECT_THAT(indexed.diags, HasSubstr("out.nc: 8 points, 0 arcs, 0 holes checked")) << e.name;
  }
}

// The fork head under G43.4: the tip in the part frame with the head's angles. By hand: the
// tool along Rz(C) Rx(A) Z; (0.5, 0, 0.866) is C90 A30 (Rx(30) Z = (0, -0.5, 0.866), a
// quarter turn about Z takes it to (0.5, 0, 0.866)); (0, 0.5, 0.866) is C180 A30.
TEST(MachineLayouts, HeadHeadGantryUnderTcpExactBlocks) {
  Compiled c = compile_text(kShortFive, example(kExamples[1]), certified());
  ASSERT_TRUE(c.ok) << c.diags;
  // At the vertical C is free: it turns first, on the spot (C is the axis along the tool at A0).
  // The quarter turn of C at A30 from (0.5, 0, 0.866) to (0, 0.5, 0.866): the head's own path
  // keeps A30 and is 7.6 degrees off the CL's sweep of the axis halfway, so points on the sweep
  // go between (A dips to 22.208 halfway, the tip on the CL line).
  EXPECT_THAT(c.output, HasSubstr("N50 G54 G43.4 H01\nN60 G00 X0. Y0. C0. A0.\nN70 Z60.\nN80 G94 G01 Z5. F800.\n"
                                  "N90 C90.\nN100 X20. A30.\nN110 Y2.5 C98.678 A26.871\nN120 Y5. C109.205 A24.391\n"
                                  "N130 Y7.5 C121.522 A22.773\nN140 Y10. C135. A22.208\nN150 Y12.5 C148.478 A22.773\n"
                                  "N160 Y15. C160.795 A24.391\nN170 Y17.5 C171.322 A26.871\nN180 Y20. C180. A30.\n"
                                  "N190 G00 Z60. A0.\nN200 G49\n"));
}

// Without TCP the B head swings the tool about its pivot (250 mm above the gauge line): the
// pivot's path is written, and the control, interpolating X Z B linearly, would bow the tip off
// the CL line; the move is split until each block's worst point is within 0.003 mm (half the
// tolerance: the rest is for the rounding of the written axes). By hand:
// tip (20, 0, 5) at B30 puts the pivot at (20 + 250 sin 30, 0, 5 + 250 cos 30 - 250) = (145,
// 0, -28.494). Dropping the split blocks makes verify name the bow at its worst point.
TEST(MachineLayouts, HeadTableWithoutTcpSplitsMovesAndVerifyProvesTheWorstPoint) {
  Compiled c = compile_text(kShortFive, example(kExamples[2]), certified());
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N60 G43 H01 Z60.\nN70 G94 G01 Z5. F800.\nN80 X2.358 Z4.992 B0.469 F6154.1\n"));
  EXPECT_THAT(c.output, HasSubstr("N700 X142.912 Z-27.478 B29.531 F6066.4\nN710 X145. Z-28.494 B30. F6063.6\n"));
  EXPECT_THAT(c.output, HasSubstr("N1170 X145. Y-20. Z-28.494 C90. B30. F5453.\nN1180 G00 X20. Z60. B0.\n"));

  // The same program with the tilting move in one block.
  std::string one = c.output;
  size_t from = one.find("N80 "), to = one.find("N710 ");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  one.erase(from, to - from);
  TempDir t;
  write_file(t.path("p.cls"), kShortFive);
  write_file(t.path("one.nc"), one);
  RunResult r = run_clpc("verify " + t.path("p.cls") + " --program " + t.path("one.nc") + " -t head-table-bc --machines " +
                         source_path("examples/head_table_bc.toml"));
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.out + r.err, HasSubstr("while the rotaries turn the tool tip leaves the CL line by "));
  EXPECT_THAT(r.out + r.err, HasSubstr(" at its worst point [G-code line "));
}

// Degrees per minute (no G93, no TCPC): F over all the block's axes at once, so the block
// takes the tip's time at the CL feed. By hand for N80: the tip goes 20/64 mm (the tilting move
// split in 64) in 0.3125 / 800 min; the block moves X 2.358, Z -0.008, B 0.469: sqrt(5.5602 +
// 0.0001 + 0.2200) = 2.4042 in 3.906e-4 min, F6154.1. A block that turns no rotary keeps the
// CL's F. verify checks F this way (every block of a split move, not only the last), and refuses
// the CL feed written instead (its 6172.0 is measured from the written, rounded coordinates).
TEST(MachineLayouts, DegreesPerMinuteFeedIsTheCombinedLengthOverTheTipsTime) {
  const std::string toml = read_file(source_path("examples/head_table_bc.toml")) +
                           "\n[bc-dpm]\ninherits = \"head-table-bc\"\n[bc-dpm.kinematics]\ndegrees_per_minute = true\n";
  Compiled c = compile_text(kShortFive, machine("bc-dpm", toml), certified());
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N70 G94 G01 Z5. F800.\nN80 X2.358 Z4.992 B0.469 F6154.1\nN90 X4.715 Z4.967 B0.938 F6154.1\n"));
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified"));

  std::string slow = c.output;
  size_t at = slow.find("B0.469 F6154.1");
  ASSERT_NE(at, std::string::npos);
  slow.replace(at, 14, "B0.469 F800.");
  TempDir t;
  write_file(t.path("p.cls"), kShortFive);
  write_file(t.path("bc.toml"), toml);
  write_file(t.path("slow.nc"), slow);
  RunResult r = run_clpc("verify " + t.path("p.cls") + " --program " + t.path("slow.nc") + " -t bc-dpm --machines " + t.path("bc.toml"));
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.out + r.err, HasSubstr(":9:1: error: the block's F is 800.0000 (degrees per minute: over X Y Z and the rotaries); the CL's feed along the tip's path makes it 6172.0490 [G-code line 15]"));

  EXPECT_THAT(machine_errors(toml + "inverse_time = true\n", "bc-dpm"),
              HasSubstr("error: bc-dpm.kinematics.degrees_per_minute: a control feeds rotary moves one way: inverse_time or "
                        "degrees_per_minute, not both"));
}

// Degrees per minute across C's zero (a modulo axis turns the short way): C359 to C0 is one
// degree, so the block's F is its neighbours' (1635.3, not 514514 from a raw 359-degree
// difference, which verify used to expect and so refused the right program).
TEST(MachineLayouts, DegreesPerMinuteAcrossAModuloAxissZeroTakesTheShortWay) {
  const std::string toml = read_file(source_path("examples/head_table_bc.toml")) +
                           "\n[bc-dpm]\ninherits = \"head-table-bc\"\n[bc-dpm.kinematics]\ndegrees_per_minute = true\n";
  std::string cl = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,6000,CLW\nMULTAX/ON\nRAPID\nGOTO/0,0,60,0,0,1\nFEDRAT/MMPM,800\nRAPID\n";
  char line[160];
  for (int i = 0; i <= 10; ++i) {  // tilt 20 degrees, azimuth -10 to 10
    const double az = (-10 + 2 * i) * M_PI / 180, b = 20 * M_PI / 180;
    std::snprintf(line, sizeof line, "GOTO/%.4f,%.4f,5,%.7f,%.7f,%.7f\n", 10.0 + i, 0.5 * i, std::sin(b) * std::cos(az),
                  std::sin(b) * std::sin(az), std::cos(b));
    cl += line;
  }
  cl += "RAPID\nGOTO/20,5,60,0,0,1\nFINI\n";
  Compiled c = compile_text(cl, machine("bc-dpm", toml), certified());
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("X99.952 Y2.503 Z-10.073 C359. B19.997 F1616.7\nN180 X100.505 Y2.5 Z-10.077 C0. B20. F1635.3\n"));
}

// Found by differential fuzzing on head-table-bc: a CL arc in YZ with the table turned is made
// into lines (no such plane on the machine) within the tolerance, but the rounding of the written
// C (0.0005 degrees, 0.001 mm at 115 mm) came on top: 0.00611 against 0.006. On machines whose
// points clpc turns through the chain, arcs become lines within half the tolerance.
TEST(MachineLayouts, ArcsMadeLinesLeaveRoomForTheRotariesRounding) {
  Compiled c = compile_path(source_path("tests/fuzz_regressions/arc_lines_rotary_rounding.cls"),
                            machine("head-table-bc", read_file(source_path("examples/head_table_bc.toml"))), certified());
  EXPECT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified"));
}

// With kinematics.work_zero the limits pass checks each position of the chain in machine
// coordinates, the head's pivot included: the fork head's gauge line is 150 mm from A, so with
// the tool horizontal at tip Z -60 over a part zero at machine Z -700 the head sits at
// -700 - 60 - 150 = -910, past Z's -900; vertical it is at -760, at 45 degrees -803.9.
TEST(MachineLayouts, TravelInMachineCoordinatesCountsTheHeadsPivot) {
  const std::string toml = read_file(source_path("examples/gantry_ac_head.toml")) +
                           "\n[gz]\ninherits = \"gantry-ac-head\"\n[gz.kinematics]\nwork_zero = [500.0, 500.0, -700.0]\n";
  const std::string cl = "TOOL PATH/SIDE,TOOL,T1\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,500\nRAPID\n"
                         "GOTO/100,100,-60,0,0,1\nMULTAX/ON\nGOTO/100,120,-60,0,-0.7071068,0.7071068\n"
                         "GOTO/100,140,-60,0,-1,0\nEND-OF-PATH\n";
  Compiled c = compile_text(cl, machine("gz", toml));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":10:1: error: Z reaches -910 mm in machine coordinates, beyond the travel (-900 to 0)"));
  EXPECT_THAT(c.diags, ::testing::Not(HasSubstr(":9:1: error")));
}

// Under TCPC a CL arc in a five-axis operation is written as lines (the control is given
// part-frame points): every chord's worst point, its middle, lies within arcs.tolerance
// (0.006 mm) of the circle, and the chords are not needlessly short (the worst is over half
// of it). Read back from the program: the quarter circle of radius 30 about the origin.
TEST(MachineLayouts, AnArcUnderTcpIsLinearisedWithinTheToleranceAtEachChordsWorstPoint) {
  const std::string cl = "TOOL PATH/ARC5,TOOL,T1\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\nMULTAX/ON\n"
                         "GOTO/30,0,0,0,0,1\nGOTO/30,0,0,0.1,0,0.99498744\nCIRCLE/0,0,0,0,0,1,30\n"
                         "GOTO/0,30,0,0.1,0,0.99498744\nGOTO/0,40,0,0,0,1\nEND-OF-PATH\n";
  const Machine m = example(kExamples[0]);
  Compiled c = compile_text(cl, m, certified());
  ASSERT_TRUE(c.ok) << c.diags;
  gcode::Result r = gcode::interpret(c.output, m);
  ASSERT_TRUE(r.problems.empty());
  double worst = 0;
  int chords = 0;
  for (const gcode::Segment& s : r.segments) {
    if (s.kind != gcode::Segment::Kind::Feed || !s.tcp) continue;
    const double r0 = s.start.head<2>().norm(), r1 = s.end.head<2>().norm();
    if (std::abs(r0 - 30) > 0.001 || std::abs(r1 - 30) > 0.001 || (s.end - s.start).norm() < 1e-9) continue;
    worst = std::max(worst, 30 - ((s.start + s.end) / 2).head<2>().norm());
    ++chords;
  }
  EXPECT_GT(chords, 40);
  EXPECT_LE(worst, 0.006 + 0.0005);  // the ends are rounded to 0.001 mm
  EXPECT_GE(worst, 0.003);
}

// Drilling in a 3+2 operation: a canned cycle where the tool is the machine's Z (table axes, or
// the tilted plane's Z), its holes written in the plane; moves without the cycle records where
// it is not (a head tilts the tool off Z without TCPC; under TCPC) — before, the cycle records
// stayed around the moves and the program was refused ("a canned cycle's hole reached the
// program as a plain move").
TEST(MachineLayouts, ThreePlusTwoDrillingIsCannedWhereTheToolIsZAndMovesElsewhere) {
  const std::string cl = "TOOL PATH/HOLES,TOOL,T2\nUNITS/MM\nLOADTL/2\nSPINDL/RPM,2000,CLW\nRAPID\n"
                         "GOTO/10,0,60,0.5,0,0.8660254\nCYCLE/DRILL,DEPTH,8,MMPM,120,CLEAR,3\n"
                         "GOTO/10,0,20,0.5,0,0.8660254\nGOTO/15,10,20,0.5,0,0.8660254\nCYCLE/OFF\nRAPID\n"
                         "GOTO/15,10,60,0.5,0,0.8660254\nEND-OF-PATH\n";
  for (const Example& e : kExamples) {
    Compiled c = compile_text(cl, example(e), certified());
    EXPECT_TRUE(c.ok) << e.name << "\n" << c.diags;
    EXPECT_THAT(c.diags, HasSubstr("out.nc: 2 points, 0 arcs, 2 holes checked")) << e.name;
    const bool canned = c.output.find("G81") != std::string::npos;
    EXPECT_EQ(canned, std::string(e.name) != "head-table-bc") << e.name;
  }
  // In the plane: (10, 0, 20) turned by Ry(30)^T is (-1.340, 0, 21.321): bottom 8 below, R 3 above.
  Compiled p = compile_text(cl, example(kExamples[0]), certified());
  EXPECT_THAT(p.output, HasSubstr("N80 G68.2 X0. Y0. Z0. I90. J30. K-90.\nN90 G53.1\nN100 G00 X-21.34 Y0.\n"
                                  "N110 G43 H02 Z56.962\nN120 G94 G98 G81 X-1.34 Y0. Z14.321 R25.321 F120.\n"));
  Compiled tcp = compile_text(
      cl, machine("umc-tcp", "[umc-tcp]\ninherits = \"haas-umc750\"\n[umc-tcp.kinematics]\nindexed = \"tcp\"\n"), certified());
  EXPECT_TRUE(tcp.ok) << tcp.diags;
  EXPECT_EQ(tcp.output.find("G81"), std::string::npos);
}
