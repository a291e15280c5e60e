// Rotary continuity: a winding axis that would pass its range is unwound with the tool clear
// (retract along the tool axis, unwind, re-engage at the same point), and a flip between the
// two solutions mid-cut is a retract and re-engage, never a sweep through the part. Exact
// blocks, and each program certified.
#include <cmath>

#include "readback/gcode_interp.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

// The UMC in millimetres with C winding within -400..400 and a 10 mm retract.
const char* kWindUmc =
    "[umc-wind]\ninherits = \"haas-umc750\"\nunits = \"mm\"\n[umc-wind.format]\nX = { decimals = 3 }\nY = { decimals = 3 }\n"
    "Z = { decimals = 3 }\n[umc-wind.kinematics]\nretract_distance = 10.0\n"
    "travel = { x = [-762.0, 0.0], y = [-508.0, 0.0], z = [-508.0, 0.0] }\n"
    "[[umc-wind.kinematics.axes]]\nname = \"B\"\naxis = [0.0, 1.0, 0.0]\nside = \"table\"\ndirection = -1\nmin = -35.0\n"
    "max = 120.0\nprefer = 1\n[[umc-wind.kinematics.axes]]\nname = \"C\"\naxis = [0.0, 0.0, 1.0]\nside = \"table\"\n"
    "direction = -1\ncyclic = \"wind\"\nmin = -400.0\nmax = 400.0\n";

// A helix round a 20 mm radius, the tool tilted 30 degrees outwards: C winds 45 degrees a
// point, ten points, so it would reach 405 at the tenth.
std::string spiral() {
  std::string cl = "TOOL PATH/SPIRAL,TOOL,T1\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\nMULTAX/ON\n";
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= 10; ++i) {
    double az = 45 * i * pi / 180;
    char b[200];
    std::snprintf(b, sizeof b, "GOTO/%.4f,%.4f,%.4f,%.7f,%.7f,%.7f\n", 20 * std::cos(az), 20 * std::sin(az), -0.5 * i,
                  0.5 * std::cos(az), 0.5 * std::sin(az), std::sqrt(0.75));
    cl += b;
  }
  return cl + "END-OF-PATH\n";
}

CompileOptions certified() {
  CompileOptions o;
  o.certify = true;
  return o;
}

}  // namespace

// At C360 the next point needs C405: the tool retracts 10 mm along its axis from (20, 0, -4)
// to (25, 0, 4.66), TCPC off, C turns back a whole turn to C0 (the tool's orientation is the
// same), TCPC on, back to the retract point, down to (20, 0, -4) at feed, and on.
TEST(RotaryContinuity, AWindingAxisIsUnwoundWithTheToolClear) {
  Compiled c = compile_text(spiral(), machine("umc-wind", kWindUmc), certified());
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr(":16:1: warning: C would wind to C405, past its range (-400 to 400): retracting along "
                                 "the tool axis, unwinding and re-engaging [-Wunwind]"));
  // (Each 45 degree step is split once: halfway the rotaries' own path is 1.9 degrees off the
  // CL's sweep of the tool axis, so a point on the sweep goes between, B28.076.)
  EXPECT_THAT(c.output, HasSubstr("N110 X14.142 Y-14.142 Z-3.5 B30. C315.\nN115 X17.071 Y-7.071 Z-3.75 B28.076 C337.5\n"
                                  "N120 X20. Y0. Z-4. B30. C360.\nN125 G00 X25. Z4.66\n"
                                  "N130 G49\nN135 G00 C0.\nN140 G00 G234 H01\nN145 G00 X25. Y0. Z4.66\n"
                                  "N150 G94 G01 X20. Z-4. F800.\nN155 X17.071 Y7.071 Z-4.25 B28.076 C22.5\n"
                                  "N160 X14.142 Y14.142 Z-4.5 B30. C45.\n"));
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified"));
}

// Without a retract distance there is no clear way to unwind: an error at the record, and a
// range under two turns is refused where the machine says it.
TEST(RotaryContinuity, UnwindingNeedsARetractDistanceAndARangeOfTwoTurns) {
  std::string no_retract = std::string(kWindUmc);
  no_retract.replace(no_retract.find("retract_distance = 10.0\n"), 24, "");
  Compiled c = compile_text(spiral(), machine("umc-wind", no_retract));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":16:1: error: C would wind to C405, past its range (-400 to 400): set "
                                 "kinematics.retract_distance so that clpc can retract, unwind and re-engage"));
  std::string narrow = std::string(kWindUmc);
  narrow.replace(narrow.find("max = 400.0"), 11, "max = 200.0");
  EXPECT_THAT(machine_errors(narrow, "umc-wind"),
              HasSubstr("shop.toml:26:7: error: umc-wind.kinematics.axes[1].max: a winding axis needs a range of at least two turns "
                        "(max - min >= 720), found 600"));
}

// B limited to -35: the path tilts the tool from B-20 to B-40 about Y. At the third point
// (B-34) the continuing branch runs out; the other (B+ with C half a turn round) goes on. The
// tool retracts along its axis at that point, the rotaries turn to the other branch for the
// same axis (B34 C-180), it comes back to the point and cuts on to the fourth on that branch
// (B40): the CL segment between the third and fourth points is cut, not skipped.
TEST(RotaryContinuity, ABranchFlipMidCutIsARetractAndReEngageAtThePoint) {
  const std::string machine_toml =
      "[neg-umc]\ninherits = \"haas-umc750\"\n[neg-umc.kinematics]\non_limit = \"retract\"\nretract_distance = 2.0\n"
      "[[neg-umc.kinematics.axes]]\nname = \"B\"\naxis = [0.0, 1.0, 0.0]\ndirection = -1\nmin = -35.0\nmax = 120.0\n"
      "prefer = -1\n[[neg-umc.kinematics.axes]]\nname = \"C\"\naxis = [0.0, 0.0, 1.0]\ndirection = -1\ncyclic = \"wind\"\n";
  const std::string cl =
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\nMULTAX/ON\n"
      "GOTO/0.0,0,10,-0.342020143326,0.000000000000,0.939692620786\n"
      "GOTO/1.0,0,10,-0.500000000000,0.000000000000,0.866025403784\n"
      "GOTO/2.0,0,10,-0.559192903471,0.000000000000,0.829037572555\n"
      "GOTO/3.0,0,10,-0.642787609687,0.000000000000,0.766044443119\n";
  Compiled c = compile_text(cl, machine("neg-umc", machine_toml), certified());
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr(":9:1: warning: the rotary axes must jump here: retracting, rotating and re-engaging"));
  EXPECT_THAT(c.output, HasSubstr("N50 X0.0787 B-34.\nN55 G00 X-1.0396 Z2.0518\nN60 G49\nN65 G00 B34. C-180.\n"
                                  "N70 G00 G234 H01\nN75 G00 X-1.0396 Y0. Z2.0518\nN80 G94 G01 X0.0787 Z0.3937 F19.69\n"
                                  "N85 X0.1181 B40.\nN90 G49\n"));
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified"));
}

// With codes.unwind the control renames the axis's position by whole turns (here Fanuc-style
// G92 C): no motion, so no retract; the reader follows it, and refuses a rename by other than
// whole turns (the part's angle would change).
TEST(RotaryContinuity, AnUnwindCodeRenamesTheAxisWithoutMotion) {
  const std::string toml = std::string(kWindUmc) + "[umc-wind.codes]\nunwind = \"G92 C{angle}\"\n";
  Compiled c = compile_text(spiral(), machine("umc-wind", toml), certified());
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr(":16:1: warning: C would wind to C405, past its range (-400 to 400): renamed by whole "
                                 "turns (codes.unwind) [-Wunwind]"));
  EXPECT_THAT(c.output, HasSubstr("N120 X20. Y0. Z-4. B30. C360.\nN125 G92 C0.\n"
                                  "N130 G94 G01 X17.071 Y7.071 Z-4.25 B28.076 C22.5 F800.\n"));
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified"));

  std::string off = c.output;
  off.replace(off.find("N125 G92 C0."), 12, "N125 G92 C10.");
  gcode::Result r = gcode::interpret(off, machine("umc-wind", toml));
  ASSERT_FALSE(r.problems.empty());
  EXPECT_THAT(r.problems[0].message, HasSubstr("G92 renames C360 as C10: not whole turns, so the part's angle would change"));
}
