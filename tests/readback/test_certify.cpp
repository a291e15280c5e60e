// Certified output: clpc compile reads every program back and compares it with the CL before
// it puts it in place. A compile made wrong on purpose (a test double of a pass: arcs turned
// the other way, points shifted) exits 1 and writes nothing, the old program untouched; the
// certificate line and its JSON; --no-verify; a five-axis path in steps smaller than the
// tolerance certifies.
#include <cmath>

#include "driver/driver.h"
#include "helpers.h"
#include "passes/pass.h"
#include "support/threads.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// The test doubles: passes that are wrong on purpose, run after arc-direction.
class FlipArcs : public Pass {
 public:
  void run(ir::Operation& op, PassContext&) override {
    for (ir::Instr& in : op.body)
      if (auto* a = std::get_if<ir::Arc>(&in.op)) {
        a->dir = a->dir == ir::ArcDir::Cw ? ir::ArcDir::Ccw : ir::ArcDir::Cw;
        a->sweep = 360 - a->sweep;
      }
  }
};

class ShiftX : public Pass {  // every cutting point 0.05 mm along X
 public:
  void run(ir::Operation& op, PassContext&) override {
    for (ir::Instr& in : op.body)
      if (auto* m = std::get_if<ir::Move>(&in.op); m && m->kind == ir::MoveKind::Feed) m->point.x() += 0.05;
  }
};

void register_doubles() {
  register_extra_pass(PassInfo{.name = "test-flip-arcs",
                               .summary = "test double: every arc turned the other way",
                               .needs = ir::ArcsDecided,
                               .make = [] { return std::unique_ptr<Pass>(std::make_unique<FlipArcs>()); }});
  register_extra_pass(PassInfo{.name = "test-shift-x",
                               .summary = "test double: every cutting point 0.05 mm along X",
                               .make = [] { return std::unique_ptr<Pass>(std::make_unique<ShiftX>()); }});
}

// fanuc-mill with the double right after arc-direction.
Machine with_double(const std::string& pass) {
  register_doubles();
  Machine m = machine("fanuc-mill");
  auto at = std::find(m.pipeline.begin(), m.pipeline.end(), "arc-direction");
  m.pipeline.insert(at == m.pipeline.end() ? at : at + 1, pass);
  return m;
}

// A plate: a line, a counter-clockwise arc (line 13), more lines.
const char* kPlate =
    "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,20\nRAPID\nGOTO/0,0,2\nFEDRAT/MMPM,300\n"
    "GOTO/0,0,-2\nFEDRAT/MMPM,800\nGOTO/30,0,-2\nGOTO/30,20,-2\nCIRCLE/20,20,-2,0,0,-1,10,0.01,0.5,10,0\n"
    "GOTO/10,20,-2\nGOTO/0,20,-2\nGOTO/0,5,-2\nRAPID\nGOTO/0,5,20\nFINI\n";

struct Result {
  CompileResult r;
  std::string diags;
};

Result certified_compile(const std::string& in, const std::string& out, const Machine& m, bool certify = true) {
  CompileOptions o;
  o.certify = certify;
  std::ostringstream err;
  Result x;
  x.r = compile_file(in, out, m, o, err);
  x.diags = err.str();
  return x;
}

}  // namespace

TEST(Certify, ACorrectCompileEndsWithItsCertificate) {
  TempDir t;
  write_file(t.path("plate.cls"), kPlate);
  Result x = certified_compile(t.path("plate.cls"), t.path("plate.nc"), machine("fanuc-mill"));
  ASSERT_TRUE(x.r.ok) << x.diags;
  ASSERT_TRUE(x.r.certificate.has_value());
  EXPECT_TRUE(x.r.certificate->ok);
  EXPECT_EQ(x.diags, "clpc: certified " + t.path("plate.nc") +
                         ": 8 points, 1 arcs, 0 holes checked; max deviation 0.0000 mm at " + t.path("plate.cls") +
                         ":13 (G-code line 17); tolerance 0.0060 mm\n");
  EXPECT_THAT(read_file(t.path("plate.nc")), HasSubstr("G03 X10. I-10. J0."));
}

// Arcs turned the other way by a wrong pass: the compile fails at the CIRCLE, writes nothing,
// and leaves the program of an earlier run as it was.
TEST(Certify, AWrongArcDirectionIsNeverWritten) {
  TempDir t;
  write_file(t.path("plate.cls"), kPlate);
  write_file(t.path("plate.nc"), "the earlier program\n");
  const Machine m = with_double("test-flip-arcs");
  Result x = certified_compile(t.path("plate.cls"), t.path("plate.nc"), m);
  EXPECT_FALSE(x.r.ok);
  EXPECT_GE(x.r.errors, 2u);
  EXPECT_THAT(x.diags, HasSubstr(t.path("plate.cls") + ":13:1: error: the program turns this CL arc the other way (the CL arc "
                                 "turns counter-clockwise seen from +Z) [G-code line 17]\n"));
  EXPECT_THAT(x.diags, HasSubstr("clpc: NOT certified " + t.path("plate.nc") + ": 8 points, 1 arcs, 0 holes checked;"));
  EXPECT_THAT(x.diags, HasSubstr("error: the program does not follow the CL within the tolerance: it is not written "
                                 "(--no-verify writes it unchecked)\n"));
  EXPECT_EQ(read_file(t.path("plate.nc")), "the earlier program\n");
  // The double is really wrong: unchecked, its program is written with the arc reversed.
  Result unchecked = certified_compile(t.path("plate.cls"), t.path("plate.nc"), m, false);
  EXPECT_TRUE(unchecked.r.ok) << unchecked.diags;
  EXPECT_THAT(read_file(t.path("plate.nc")), HasSubstr("G02 X10. I-10. J0."));
}

TEST(Certify, AShiftedPathIsNeverWritten) {
  TempDir t;
  write_file(t.path("plate.cls"), kPlate);
  Result x = certified_compile(t.path("plate.cls"), t.path("plate.nc"), with_double("test-shift-x"));
  EXPECT_FALSE(x.r.ok);
  // The first cutting point, GOTO/0,0,-2, is made at X0.05.
  EXPECT_THAT(x.diags, HasSubstr(t.path("plate.cls") + ":9:1: error: CL point (0.0000, 0.0000, -2.0000) is never reached: the "
                                 "program comes within 0.05000 of it"));
  EXPECT_FALSE(std::filesystem::exists(t.path("plate.nc")));
}

// The command line: the certificate on standard error, --json whole, --no-verify none; a
// program to standard output is certified before a byte of it is written.
TEST(Certify, CommandLine) {
  TempDir t;
  write_file(t.path("plate.cls"), kPlate);
  RunResult r = run_clpc("compile " + t.path("plate.cls") + " -t fanuc-mill -o -");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("G03 X10. I-10. J0."));
  EXPECT_EQ(r.err, "clpc: certified (standard output): 8 points, 1 arcs, 0 holes checked; max deviation 0.0000 mm at " +
                       t.path("plate.cls") + ":13 (G-code line 17); tolerance 0.0060 mm\n");
  RunResult json = run_clpc("compile " + t.path("plate.cls") + " -t fanuc-mill -o " + t.path("a.nc") + " --json");
  EXPECT_EQ(json.status, 0) << json.err;
  EXPECT_THAT(json.err, HasSubstr("\"ok\": true,"));
  EXPECT_THAT(json.err, HasSubstr("\"cl\": {\"points\": 8, \"arcs\": 1, \"holes\": 0, \"groove_cuts\": 0, \"thread_cuts\": 0},"));
  RunResult none = run_clpc("compile " + t.path("plate.cls") + " -t fanuc-mill -o " + t.path("b.nc") + " --no-verify");
  EXPECT_EQ(none.status, 0) << none.err;
  EXPECT_EQ(none.err, "");
  EXPECT_EQ(read_file(t.path("a.nc")), read_file(t.path("b.nc")));
  RunResult tight = run_clpc("compile " + t.path("plate.cls") + " -t fanuc-mill -o " + t.path("c.nc") + " --tolerance 0.0001");
  EXPECT_EQ(tight.status, 0) << tight.err;
  EXPECT_THAT(tight.err, HasSubstr("; tolerance 0.0001 mm\n"));
}

// A five-axis finish in steps of 0.002 mm, the tool axis turning 0.002 degrees a step: every
// block end lies within the tolerance (0.0076 mm) of several CL points. Each CL point is
// matched to its own block (the nearest, axis agreeing), not the first within the tolerance.
TEST(Certify, FiveAxisStepsSmallerThanTheToleranceCertify) {
  TempDir t;
  std::string cl = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nMULTAX/ON\nRAPID\nGOTO/0,0,50,0,0,1\nFEDRAT/MMPM,500\n";
  char line[160];
  for (int i = 0; i <= 3000; ++i) {
    const double a = (i * 0.002) * M_PI / 180;  // about Y
    std::snprintf(line, sizeof line, "GOTO/%.4f,%.4f,%.4f,%.7f,%.7f,%.7f\n", i * 0.002, 0.001 * std::sin(i * 0.01), 10.0,
                  std::sin(a), 0.0, std::cos(a));
    cl += line;
  }
  cl += "RAPID\nGOTO/6,0,50,0.1045285,0,0.9945219\nFINI\n";
  write_file(t.path("fine.cls"), cl);
  Result x = certified_compile(t.path("fine.cls"), t.path("fine.nc"), machine("haas-umc750"));
  ASSERT_TRUE(x.r.ok) << x.diags.substr(0, 2000);
  ASSERT_TRUE(x.r.certificate.has_value());
  EXPECT_EQ(x.r.certificate->cl_points, 3003);
  EXPECT_LE(x.r.certificate->max_deviation, x.r.certificate->tolerance);
  EXPECT_LE(x.r.certificate->max_axis_deviation, 0.01);
  EXPECT_THAT(x.diags, HasSubstr("clpc: certified "));
  EXPECT_THAT(x.diags, Not(HasSubstr("error")));
}

// A CL that contradicts itself: the move into the NX arc (line 14) runs down -Y, against the
// arc's counter-clockwise start. The compile warns, cuts the convention, and the certificate
// says the CL is ambiguous there.
TEST(Certify, AnArcAgainstItsConventionIsReportedAmbiguous) {
  TempDir t;
  std::string cl = kPlate;
  const std::string from = "GOTO/30,20,-2\n";
  cl.replace(cl.find(from), from.size(), "GOTO/30,40,-2\nGOTO/30,20,-2\n");
  write_file(t.path("plate.cls"), cl);
  Result x = certified_compile(t.path("plate.cls"), t.path("plate.nc"), machine("fanuc-mill"));
  ASSERT_TRUE(x.r.ok) << x.diags;
  EXPECT_THAT(x.diags, HasSubstr(t.path("plate.cls") + ":14:1: warning: arc: the NX CLSF convention"));
  EXPECT_EQ(x.r.certificate->ambiguous_arcs, 1);
  EXPECT_THAT(x.diags, HasSubstr("; tolerance 0.0060 mm; 1 arc where the CL's convention and its geometry disagree (first at " +
                                 t.path("plate.cls") + ":14)\n"));
}

// Found by fuzz_certify: the CL dithers about a point by less than the tolerance (15.8824,
// 15.8799, 15.8824), each step written; the walk took the first as the point already reached
// and stuck on the small move after it, failing every record after. Such blocks go with the
// point.
TEST(Certify, StepsWithinTheToleranceOfAPointGoWithIt) {
  TempDir t;
  write_file(t.path("dither.cls"),
             "UNITS/MM\nLOADTL/7\nSPINDL/RPM,1500,CLW\nFEDRAT/MMPM,1070\nRAPID\nGOTO/64.7059,64.7059,40\n"
             "GOTO/64.7059,64.7059,15.8824\nGOTO/64.7059,64.7059,15.8824\nGOTO/64.7059,64.7059,15.8799\n"
             "GOTO/64.7059,64.7059,15.8824\nCYCLE/DEEP,DEPTH,29.5827,STEP,7.1705,MMPM,94,CLEAR,3.4015\n"
             "GOTO/35.4467,98.7747,9.3225\nGOTO/65.7374,78.2513,9.3225\nCYCLE/OFF\nRAPID\nGOTO/65.7374,78.2513,40\nFINI\n");
  Result x = certified_compile(t.path("dither.cls"), t.path("dither.nc"), machine("fanuc-mill"));
  ASSERT_TRUE(x.r.ok) << x.diags;
  EXPECT_THAT(read_file(t.path("dither.nc")), HasSubstr("Z15.882 F1070.\nN80 Z15.88\nN90 Z15.882\n"));
  EXPECT_EQ(x.r.certificate->cl_holes, 2);
}

// Found by fuzz_certify: a steep helix (5 mm down over 10 degrees of a 2 mm radius). Its
// ends rounded to 0.0001 in turn it by a hair, and at a point's own angle the heights differ
// by 0.0005 in; the nearest point of the helix is a hair round the turn. Verify measured at
// the same angle and failed a correct program.
TEST(Certify, ASteepHelixIsMeasuredToItsNearestPoint) {
  TempDir t;
  write_file(t.path("helix.cls"),
             "UNITS/MM\nLOADTL/14\nSPINDL/RPM,1100,CLW\nFEDRAT/MMPM,680\nRAPID\nGOTO/35.6841,45.8833,40.0000\n"
             "CIRCLE/35.9473,45.8833,47.4048,0.0000000,-1.0000000,0.0000000,7.4094\nGOTO/36.9740,40.9101,40.0668\n"
             "CIRCLE/34.9740,40.9101,40.0668,0.0000000,0.0000000,-1.0000000,2.0000\nGOTO/36.9436,40.5628,35.0668\n"
             "RAPID\nGOTO/36.9436,40.5628,50.0000\nFINI\n");
  Result x = certified_compile(t.path("helix.cls"), t.path("helix.nc"), machine("haas-umc750"));
  ASSERT_TRUE(x.r.ok) << x.diags;
  EXPECT_THAT(read_file(t.path("helix.nc")), HasSubstr("G17 X1.4545 Y1.597 Z1.3806 I-0.0788 J0.0001\n"));
  EXPECT_LE(x.r.certificate->max_deviation, 0.0001);
}

// Found by fuzz_certify: after CYCLE/OFF the CL feeds up from the last hole to the level the
// cycle started at; the G98 return has put the tool there already, at rapid, so the move is
// not written. The cycle's own return reaching a CL feed point is no feed made rapid.
TEST(Certify, ACycleReturnMayReachTheNextFeedPoint) {
  TempDir t;
  write_file(t.path("ret.cls"),
             "UNITS/MM\nLOADTL/4\nSPINDL/RPM,1500,CLW\nFEDRAT/MMPM,1000\nRAPID\nGOTO/21.5686,54.3816,11.8039\nFEDRAT/MMPM,1000\n"
             "GOTO/21.5686,54.3816,11.8039\nCYCLE/BORE,DEPTH,16.8078,MMPM,173,CLEAR,3.1804\nGOTO/54.5098,54.5098,3.1765\n"
             "GOTO/21.5686,21.5686,3.1765\nCYCLE/OFF\nGOTO/21.5686,21.5686,11.8039\nRAPID\nGOTO/21.5686,21.5686,40\nFINI\n");
  Result x = certified_compile(t.path("ret.cls"), t.path("ret.nc"), machine("fanuc-mill"));
  ASSERT_TRUE(x.r.ok) << x.diags;
  EXPECT_THAT(read_file(t.path("ret.nc")), HasSubstr("N80 X21.569 Y21.569\nN90 G80\nN100 G00 Z40.\n"));
}

// Found by fuzz_certify: a helix of nearly a whole turn (349.6 degrees, radius 0.744 in) whose
// chord is 0.135 in. Written as one G03, its centre placed for the rounded ends left the far
// side of the arc 0.00042 in off (tolerance 0.0003 in); arc-legalise now splits it in two.
TEST(Certify, ANearlyWholeHelixWithAShortChordIsSplit) {
  TempDir t;
  write_file(t.path("turn.cls"),
             "UNITS/MM\nLOADTL/1\nSPINDL/RPM,5000,CLW\nFEDRAT/MMPM,1540\nGOTO/103.3081,41.9109,-8.8609\n"
             "CIRCLE/85.4071,41.9109,-14.9345,0.0000000,1.0000000,0.0000000,18.9034\n"
             "GOTO/101.9119,39.4108,-5.7188\nFINI\n");
  Result x = certified_compile(t.path("turn.cls"), t.path("turn.nc"), machine("haas-umc750"));
  ASSERT_TRUE(x.r.ok) << x.diags;
  EXPECT_THAT(read_file(t.path("turn.nc")),
              HasSubstr("G18 G03 X2.6824 Y1.6008 Z-0.8902 K-0.2391 I-0.7047\nN55 X4.0123 Y1.5516 Z-0.2251 K0.3022 I0.6801\n"));
  EXPECT_LE(x.r.certificate->max_deviation, 0.0001);
}

// Found on the 200 MB benchmark: a 3-axis operation under G254 with the table still turned
// from the five-axis one before ends on a retract point; the next tool's first block (under
// G234, after G53 and the tool change) returns to that very point, its coordinates exactly as
// the CL's where the turned ones are rounded. The nearer block end was taken, so the retract
// was "cut with tool 5". The search for a nearer end stops at a tool change and at a block
// the reader cannot place. (The kinematics pass no longer writes that block: a turn of the free
// axis "on the spot" after a tool change brought the new tool back down to the old retract
// point at the old feed. The program as it was is checked with --program.)
TEST(Certify, ANearerBlockEndAfterAToolChangeIsNotThisPointsOwn) {
  TempDir t;
  write_file(t.path("ops.cls"),
             "UNITS/MM\n"
             "TOOL PATH/CONTOUR_1,TOOL,BALL6\n"
             "LOAD/TOOL,6,ADJUST,6\n"
             "SPINDL/RPM,7500,CLW\n"
             "RAPID\n"
             "GOTO/40.0000,30.0000,-4.8607,0.4624384,0.0622863,0.8844609\n"
             "FEDRAT/MMPM,3407.2360\n"
             "GOTO/40.2389,30.0000,-4.8697,0.4623385,0.0618584,0.8845432\n"
             "GOTO/40.4777,30.0000,-4.8781,0.4622336,0.0614339,0.8846276\n"
             "RAPID\n"
             "GOTO/40.4777,30.0000,50.0000,0.0000000,0.0000000,1.0000000\n"
             "END-OF-PATH\n"
             "TOOL PATH/ROUGH_2,TOOL,EM12\n"
             "LOAD/TOOL,3,ADJUST,3\n"
             "SPINDL/RPM,6000,CLW\n"
             "RAPID\n"
             "GOTO/70.0939,35.6920,50.0000,0.0000000,0.0000000,1.0000000\n"
             "GOTO/70.0939,35.6920,3.0000\n"
             "FEDRAT/MMPM,1256.8139\n"
             "GOTO/70.0939,35.6920,0.0000\n"
             "GOTO/90.0939,35.6920,0.0000\n"
             "RAPID\n"
             "GOTO/70.0939,35.6920,50.0000\n"
             "END-OF-PATH\n"
             "TOOL PATH/CONTOUR_3,TOOL,BALL6\n"
             "LOAD/TOOL,5,ADJUST,5\n"
             "SPINDL/RPM,7000,CLW\n"
             "RAPID\n"
             "GOTO/40.0000,30.0000,2.1262,0.2860252,0.3686712,0.8844609\n"
             "FEDRAT/MMPM,3013.5509\n"
             "GOTO/40.2389,30.0000,2.1300,0.2855252,0.3691712,0.8844114\n"
             "GOTO/40.4777,30.0000,2.1350,0.2850252,0.3696712,0.8843609\n"
             "END-OF-PATH\n"
             "FINI\n");
  Result x = certified_compile(t.path("ops.cls"), t.path("ops.nc"), machine("haas-umc750"));
  ASSERT_TRUE(x.r.ok) << x.diags;
  const std::string nc = read_file(t.path("ops.nc"));
  EXPECT_THAT(nc, HasSubstr("N120 G00 Z1.9685\nN125 X2.9207 Y1.0294\nN130 G255\n"));  // up first: rapid-split
  // The new tool goes straight to its operation's first point.
  EXPECT_THAT(nc, HasSubstr("N150 G54 G00 G234 H05\nN155 M11 M13\nN160 G00 X1.5748 Y1.1811 B27.815 C52.195\n"));
  // The program as it was written before: the next tool's first block at the retract point.
  std::string was = nc;
  const std::string at = "N155 M11 M13\n";
  was.insert(was.find(at) + at.size(), "N157 G94 G01 X2.7596 Y1.4052 Z1.9685 C52.195 F49.48\n");
  write_file(t.path("was.nc"), was);
  RunResult r = run_clpc("verify " + t.path("ops.cls") + " --program " + t.path("was.nc") + " -t haas-umc750");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("result: PASS"));
}

// Found by helper-41 (a Lissajous curve): the path turns back on itself at a cusp, and the
// blocks past the turn lie within the tolerance of the points before it. A point the tool
// already stood at took every block after it within the tolerance, past the turn, and the
// turn's own point and all after it were "never reached" (a correct program refused). It takes
// only the blocks that come nearer.
TEST(Certify, APathThatTurnsBackOnItselfCertifies) {
  const std::string cl =
      "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/30.2,69.7,28\nFEDRAT/MMPM,250\nGOTO/30.1712,69.7110,20\n"
      "GOTO/30.1461,69.7533,20\nGOTO/30.1229,69.7924,20\nGOTO/30.1018,69.8281,20\nGOTO/30.0826,69.8604,20\n"
      "GOTO/30.0655,69.8894,20\nGOTO/30.0503,69.9150,20\nGOTO/30.0371,69.9373,20\nGOTO/30.0259,69.9562,20\n"
      "GOTO/30.0168,69.9717,20\nGOTO/30.0096,69.9838,20\nGOTO/30.0044,69.9926,20\nGOTO/30.0012,69.9980,20\n"
      "GOTO/30.0000,70.0000,20\nGOTO/30.0008,69.9986,20\nGOTO/30.0036,69.9939,20\nGOTO/30.0084,69.9857,20\n"
      "GOTO/30.0153,69.9742,20\nGOTO/30.0241,69.9593,20\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr("clpc: certified"));
  EXPECT_THAT(c.output, HasSubstr("N190 X30.001 Y69.998\nN200 X30. Y70.\nN210 X30.001 Y69.999\n"));
}

// A machine with no retract before the tool change (codes.safe_retract = ""): the new tool's
// first block, X Y before its G43, ends at the last tool's height, which is the new tool's
// first CL point. That block was taken as the point's own and failed as "no tool length offset
// in force (register 0)" (the NIST drilling file b270_alldrill, refused); the next block,
// there with the tool's own H, is the point's.
TEST(Certify, ABlockThereWithoutTheToolsLengthOffsetIsNotThePointsOwn) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,50\nFEDRAT/MMPM,100\nGOTO/0,0,-1\n"
                         "RAPID\nGOTO/0,0,50\nLOADTL/2\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/20,0,50\nGOTO/20,0,5\n"
                         "GOTO/20,0,-1\nFINI\n";
  const char* toml = "[no-retract]\ninherits = \"fanuc-mill\"\n[no-retract.codes]\nsafe_retract = \"\"\n";
  Compiled c = compile_text(cl, machine("no-retract", toml), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N90 T2 M06 (T2)\nN100 S1000 M03\nN110 G54 G00 X20. Y0.\nN120 G43 H02 Z50.\n"));
  // With no block there under H02, the point is still refused.
  Compiled plain = compile_text(cl, machine("no-retract", toml));
  std::string wrong = plain.output;
  wrong.replace(wrong.find("N120 G43 H02 Z50.\n"), 19, "N120 Z50.\n");
  EXPECT_THAT(verify_text(cl, machine("no-retract", toml), wrong).diags,
              HasSubstr("error: no tool length offset is in force (register 0), tool 2's is 2"));
}

// Found by the differential test (head-table-bc, seed 837): a move to a tool axis 0.43 degrees
// from the pole. The transform splits it by the turn of C, so its last dozen blocks move the
// tip some thousandths each, and the angles' rounding times the tool's length shakes the tip
// by as much: one block end sat just outside the tolerance between block ends inside it. The
// walk stopped there and took a block whose tool axis was 0.087 degrees off, then lost every
// point after. It goes on past such a block and takes the end nearest in tip and axis.
TEST(Certify, NearThePoleTheBlockNearestInTipAndAxisIsThePointsOwn) {
  TempDir t;
  write_file(t.path("pole.cls"),
             "UNITS/MM\nLOADTL/11\nSPINDL/RPM,2800,CLW\nFEDRAT/MMPM,2040\nMULTAX/ON\nRAPID\n"
             "GOTO/18.6099,77.7087,40.0000,0.0000000,0.0000000,1.0000000\n"
             "GOTO/39.9281,48.0017,19.5242,0.0182441,0.7241995,0.6893492\n"
             "GOTO/41.1323,45.6973,20.1919,0.0871286,0.7427815,0.6638405\n"
             "GOTO/3.5233,77.8759,29.1785,-0.0190441,0.5905282,0.8067923\n"
             "GOTO/1.1971,78.6723,29.8057,-0.0044230,0.0061184,0.9999715\n"
             "GOTO/0.0000,81.0977,29.6370,-0.0228153,0.0315964,0.9992403\n"
             "GOTO/1.6078,79.2325,30.0000,-0.0093416,0.0132029,0.9998692\n"
             "GOTO/4.2760,78.8607,30.0000,-0.0000000,0.0000000,1.0000000\n"
             "RAPID\nGOTO/1.6078,79.2325,50.0000,0,0,1\nFINI\n");
  RunResult r = run_clpc("compile " + t.path("pole.cls") + " -o " + t.path("pole.nc") + " -t head-table-bc --machines " +
                         source_path("examples/head_table_bc.toml"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("clpc: certified " + t.path("pole.nc") + ": 9 points, 0 arcs, 0 holes checked; max deviation "));
  // The block that reaches line 11 ends at its tool axis (B 0.433 = 0.4326 rounded, C
  // 125.863), not at the first block within the tolerance of its tip (B 0.507).
  EXPECT_THAT(r.err, HasSubstr(", tool axis 0.0005 deg at " + t.path("pole.cls") + ":9 "));
  EXPECT_THAT(read_file(t.path("pole.nc")), HasSubstr(" C125.863 B0.433 F10000.\n"));  // held at max_feed near the pole
  EXPECT_THAT(r.err, HasSubstr("warning: the rotaries turn too fast for the CL's feed here: F over all the axes would be "));
}

// Without threads (the browser build, support/threads.h) every stage runs in turn and the
// program is read back once written: the same programs, the same certificates, and a wrong
// compile still never written.
TEST(Certify, WithoutThreadsTheSameProgramsAndCertificates) {
  TempDir t;
  const std::string golden = std::string(CLPC_SOURCE_DIR) + "/tests/golden/";
  for (const auto& [cl, name] : std::vector<std::pair<std::string, std::string>>{
           {"nx_mill.cls", "haas-umc750"}, {"creo_lathe.ncl", "fanuc-lathe"}, {"creo_mill.ncl", "fanuc-mill"}}) {
    const Machine m = machine(name);
    Result threaded = certified_compile(golden + cl, t.path("a.nc"), m);
    set_threads_available(false);
    Result single = certified_compile(golden + cl, t.path("b.nc"), m);
    set_threads_available(true);
    ASSERT_TRUE(single.r.ok) << cl << ": " << single.diags;
    EXPECT_THAT(single.diags, HasSubstr("clpc: certified "));
    EXPECT_EQ(read_file(t.path("b.nc")), read_file(t.path("a.nc"))) << cl;
    std::string diags = threaded.diags;
    diags.replace(diags.find(t.path("a.nc")), t.path("a.nc").size(), t.path("b.nc"));
    EXPECT_EQ(single.diags, diags) << cl;
  }
  write_file(t.path("plate.cls"), kPlate);
  set_threads_available(false);
  Result x = certified_compile(t.path("plate.cls"), t.path("plate.nc"), with_double("test-flip-arcs"));
  set_threads_available(true);
  EXPECT_FALSE(x.r.ok);
  EXPECT_THAT(x.diags, HasSubstr(t.path("plate.cls") + ":13:1: error: the program turns this CL arc the other way"));
  EXPECT_FALSE(std::filesystem::exists(t.path("plate.nc")));
}
