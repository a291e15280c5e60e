// Shop-floor safety and the per-job options (issue 18): every case that once wrote a program
// that looked right and would break a tool is now a correct program (exact blocks) or an
// error (exact text); every per-job option by the blocks it writes.
#include <cstdlib>

#include "helpers.h"
#include "thread_cl.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

namespace {

// Three tools, flood coolant from the first; on fanuc-mill (docs/machines.md).
const char* kThreeTools =
    "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nCOOLNT/ON\nRAPID\nGOTO/0,0,10\nFEDRAT/MMPM,500\nGOTO/10,0,-1\n"
    "LOADTL/2\nSPINDL/RPM,4000,CLW\nRAPID\nGOTO/20,0,10\nGOTO/20,10,-1\n"
    "LOADTL/3\nSPINDL/RPM,4000,CLW\nRAPID\nGOTO/30,0,10\nGOTO/30,10,-1\nFINI\n";

// Two NX operations with one tool.
const char* kTwoOperations =
    "UNITS/MM\nTOOL PATH/ROUGH,TOOL,MILL_10\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,10\nFEDRAT/MMPM,500\n"
    "GOTO/10,0,-1\nGOTO/10,0,10\nEND-OF-PATH\nTOOL PATH/FINISH,TOOL,MILL_10\nSPINDL/RPM,3500,CLW\nRAPID\nGOTO/20,0,10\n"
    "FEDRAT/MMPM,400\nGOTO/20,10,-1\nEND-OF-PATH\nFINI\n";

// clpc compile of `cl` from standard input to standard output.
RunResult post(const std::string& cl, const std::string& args) { return run_clpc("compile - -o - " + args, cl); }

}  // namespace

// --- The cases of issue 18 -------------------------------------------------------------

TEST(ShopFloor, FeedPerRevolutionOnTheHaasKeepsItsDecimals) {
  RunResult r = post("UNITS/INCHES\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,0.1\nFEDRAT/IPR,0.004\nGOTO/0,0,-0.5\nFINI\n",
                     "-t haas-umc750");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("N45 G43 H01 Z0.1\nN50 G95 G01 Z-0.5 F0.004\n"));
}

TEST(ShopFloor, MillimetresPerRevolutionOnTheFanucMill) {
  RunResult r = post("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/0.15,MMPR\nGOTO/0,0,-10\nFINI\n",
                     "-t fanuc-mill");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("N70 G95 G01 Z-10. F0.15\n"));
}

TEST(ShopFloor, AFeedThatRoundsToZeroIsAnErrorNamingItsFedrat) {
  RunResult r = post("UNITS/INCHES\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,0.1\nFEDRAT/IPR,0.004\nGOTO/0,0,-0.5\nFINI\n",
                     "-t haas-umc750 --set 'feeds.per_rev={decimals=2}'");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, StartsWith("<stdin>:6:1: error: the feed of 0.004 in/rev would be written F0. (feeds.per_rev: 2 decimals): it "
                                "rounds to zero; give feeds.per_rev more decimals\n"));
  EXPECT_EQ(r.out, "");
}

const char* kTapM8 =
    "UNITS/MM\nLOADTL/1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/0,0,10\nCYCLE/TAP,DEPTH,12,PITCH,1.25,CLEAR,2\nGOTO/0,0,0\n"
    "CYCLE/OFF\nFINI\n";

TEST(ShopFloor, RigidTapM8x1_25KeepsItsPitch) {
  RunResult per_rev = post(kTapM8, "-t fanuc-mill --set cycles.tap_feed=per-rev");
  EXPECT_EQ(per_rev.status, 0) << per_rev.err;
  EXPECT_THAT(per_rev.out, HasSubstr("N70 M29 S500\nN80 G95 G98 G84 X0. Y0. Z-12. R2. F1.25\nN90 G80\n"));
  RunResult per_minute = post(kTapM8, "-t fanuc-mill");  // F = pitch x S = 625 mm/min
  EXPECT_EQ(per_minute.status, 0) << per_minute.err;
  EXPECT_THAT(per_minute.out, HasSubstr("N70 M29 S500\nN80 G94 G98 G84 X0. Y0. Z-12. R2. F625.\n"));
  // A tap format that cannot hold the pitch: refused at the hole, never F1.3.
  RunResult coarse = post(kTapM8, "-t fanuc-mill --set cycles.tap_feed=per-rev --set 'feeds.tap={decimals=1}'");
  EXPECT_EQ(coarse.status, 1);
  EXPECT_THAT(coarse.err, StartsWith("<stdin>:7:1: error: the tap's pitch of 1.25 mm would be written F1.3 (feeds.tap: 1 decimal): "
                                     "the tap would advance 1.3 a turn and be 0.48 off its thread at the bottom; give "
                                     "feeds.tap more decimals\n"));
}

TEST(ShopFloor, VerifyChecksTheTapsPitch) {
  TempDir t;
  write_file(t.path("tap.cls"), kTapM8);
  RunResult r = run_clpc("verify " + t.path("tap.cls") + " -t fanuc-mill --set cycles.tap_feed=per-rev");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("result: PASS"));
}

TEST(ShopFloor, ThreadOnAMillIsALocatedError) {
  RunResult r = post("UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/20,0,5\nTHREAD/TURN,1.5\nFEDRAT/MMPM,100\nGOTO/20,0,-20\nTHREAD/OFF\nFINI\n",
                     "-t fanuc-mill");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "<stdin>:6:1: error: machine 'fanuc-mill' is a mill: THREAD (a thread cut synchronised with the spindle) needs a "
            "lathe\n 6 | THREAD/TURN,1.5\n   | ^\nclpc: 1 error, 0 warnings\n");
  EXPECT_EQ(r.out, "");
}

const char* kLatheFile = "UNITS/MM\nMACHIN/TURN\nTURRET/1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/20,0,5\nFEDRAT/0.2,MMPR\nGOTO/20,0,-20\nFINI\n";

TEST(ShopFloor, ALatheFileForAMillIsAnErrorUnlessForced) {
  RunResult r = post(kLatheFile, "-t fanuc-mill");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "<stdin>:2:1: error: the CL data is for a lathe (MACHIN/TURN) but machine 'fanuc-mill' is a mill; --force-family posts it "
            "anyway\n 2 | MACHIN/TURN\n   | ^\nclpc: 1 error, 0 warnings\n");
  EXPECT_EQ(r.out, "");
  RunResult forced = post(kLatheFile, "-t fanuc-mill --force-family");
  EXPECT_EQ(forced.status, 0) << forced.err;
  EXPECT_THAT(forced.err, HasSubstr("<stdin>:2:1: warning: the CL data is for a lathe (MACHIN/TURN) but machine 'fanuc-mill' is a mill"));
}

TEST(ShopFloor, AMillFileForALatheIsAnError) {
  RunResult r = post("UNITS/MM\nMACHIN/MILL\nLOADTL/1\nRAPID\nGOTO/0,0,5\nFINI\n", "-t fanuc-lathe");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, StartsWith("<stdin>:2:1: error: the CL data is for a mill (MACHIN/MILL) but machine 'fanuc-lathe' is a lathe"));
}

TEST(ShopFloor, TwoInputsToOneOutputAreRefusedBeforeAnythingIsWritten) {
  TempDir t;
  write_file(t.path("a.ncl.1"), kThreeTools);
  write_file(t.path("a.ncl.2"), kThreeTools);
  RunResult r = run_clpc("compile " + t.path("a.ncl.1") + " " + t.path("a.ncl.2") + " -t fanuc-mill");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "clpc: error: '" + t.path("a.ncl.1") + "' and '" + t.path("a.ncl.2") + "' would both be written to '" +
                       t.path("a.nc") + "': compile them one at a time with -o, or into other folders with --output-dir\n");
  EXPECT_FALSE(std::filesystem::exists(t.path("a.nc")));
  // One at a time, into another folder: written, and the second run says what it replaced.
  std::filesystem::create_directory(t.path("out"));
  RunResult first = run_clpc("compile " + t.path("a.ncl.1") + " -t fanuc-mill --output-dir " + t.path("out"));
  EXPECT_EQ(first.status, 0) << first.err;
  EXPECT_THAT(read_file(t.path("out/a.nc")), HasSubstr("M30"));
  RunResult again = run_clpc("compile " + t.path("a.ncl.2") + " -t fanuc-mill --output-dir " + t.path("out"));
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_THAT(again.err, HasSubstr("clpc: note: replaced '" + t.path("out/a.nc") + "', the program an earlier run wrote there\n"));
}

TEST(ShopFloor, AnInchMachineDerivedFromAMetricOneHasItsNumbersConverted) {
  const char* toml = "[inch-mill]\ninherits = \"fanuc-mill\"\nunits = \"inch\"\n";
  Machine m = machine("inch-mill", toml);
  EXPECT_EQ(m.units, ir::Units::Inch);
  EXPECT_NEAR(m.rapid_rate, 24000 / 25.4, 1e-9);    // mm/min -> in/min
  EXPECT_NEAR(m.max_feed, 10000 / 25.4, 1e-9);
  EXPECT_NEAR(m.arcs.tolerance, 0.005 / 25.4, 1e-12);
  EXPECT_EQ(m.format('X').decimals, 4);              // 3 in mm: one more in inches
  EXPECT_EQ(m.format('F').decimals, 2);              // 1 in mm
  Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/0.15,MMPR\nGOTO/0,0,-10\nFINI\n", m);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N10 G20\n"));
  EXPECT_THAT(c.output, HasSubstr("N60 G43 H01 Z0.1969\nN70 G95 G01 Z-0.3937 F0.0059\n"));
}

TEST(ShopFloor, EmptyAxesRemoveInheritedRotaries) {
  const char* toml =
      "[three]\ninherits = \"haas-umc750\"\npipeline = [\"arc-direction\", \"helix\", \"drill-cycles\", \"rapid-split\", \"offset-table\", "
      "\"arc-legalise\", \"limits\"]\n[three.kinematics]\naxes = []\n";
  Machine m = machine("three", toml);
  EXPECT_FALSE(m.kinematics.has_rotaries());
  Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/MMPM,100\nGOTO/0,0,-1\nFINI\n", m);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, Not(HasSubstr("B0.")));
}

namespace {
std::string load_error(const std::string& toml) { return machine_errors(toml); }
}  // namespace

// point = "if-fraction" on a position wrote G43 H01 Z10 and X50: a Fanuc reads them in least
// input increments, 0.010 and 0.050 mm (helper-62). Refused at the key.
TEST(ShopFloor, APositionWrittenWithoutItsPointWhenWholeIsRefused) {
  EXPECT_EQ(load_error("[iff]\ninherits = \"fanuc-mill\"\n[iff.format]\nY = { point = \"if-fraction\" }\n"),
            "shop.toml:4:1: error: iff.format.Y.point: \"if-fraction\" writes a whole Y without its point (Y50), which a "
            "control reads in least input increments (0.050 mm, 0.0050 in) unless it is set for calculator-type input: "
            "say point = \"always\"\n 4 | Y = { point = \"if-fraction\" }\n   | ^\n");
  EXPECT_EQ(load_error("[iff]\ninherits = \"fanuc-mill\"\n[iff.format]\nF = { point = \"if-fraction\" }\n"), "");
  // A peck or a lathe's P/Q, a feed per revolution, a lead, a tap fed per revolution: G83 Q5
  // pecked 0.005 mm and a rigid tap's F1 fed 0.001 mm a turn (helper-71: certified).
  EXPECT_THAT(load_error("[q]\ninherits = \"fanuc-mill\"\n[q.format]\nQ = { decimals = 3, point = \"if-fraction\" }\n"),
              HasSubstr("q.format.Q.point: \"if-fraction\" writes a whole Q without its point (Q50)"));
  EXPECT_THAT(load_error("[t]\ninherits = \"fanuc-mill\"\n[t.cycles]\ntap_feed = \"per-rev\"\n[t.feeds]\n"
                         "tap = { decimals = 3, point = \"if-fraction\" }\n"),
              HasSubstr("shop.toml:6:7: error: t.feeds.tap: \"if-fraction\" writes a whole feed per revolution or lead "
                        "without its point (F1 for 1 a turn), which the control reads in its least increments"));
  EXPECT_EQ(load_error("[t]\ninherits = \"fanuc-mill\"\n[t.feeds]\ntap = { decimals = 0, point = \"if-fraction\" }\n"), "");
  for (const char* k : {"lead", "per_rev"})
    EXPECT_THAT(load_error("[l]\ninherits = \"fanuc-lathe\"\n[l.feeds]\n" + std::string(k) +
                           " = { decimals = 4, point = \"if-fraction\" }\n"),
                HasSubstr("l.feeds." + std::string(k) + ": \"if-fraction\" writes a whole feed per revolution"));
  EXPECT_THAT(load_error("[l]\ninherits = \"fanuc-lathe\"\n[l.format]\nP = { decimals = 3, point = \"if-fraction\" }\n"),
              HasSubstr("say point = \"never\" in the axes' decimals (a lathe's cycles take P and Q without a point)"));
  // So is one in whole units without a point: Y20 is 0.020 mm (helper-65).
  EXPECT_THAT(load_error("[d0]\ninherits = \"fanuc-mill\"\n[d0.format]\nY = { decimals = 0, point = \"never\" }\n"),
              HasSubstr("shop.toml:4:1: error: d0.format.Y: written without a point in whole units (Y20), which a control "
                        "reads in least input increments (0.020 mm)"));
}

// A whole number written without a point in decimals is multiplied: S3000 was S30000, H1 H10,
// G54.1 P{number} P10 for P1; all certified (helper-67). Refused at the key.
TEST(ShopFloor, AWholeNumberWrittenWithoutAPointInDecimalsIsRefused) {
  EXPECT_EQ(load_error("[s1]\ninherits = \"fanuc-mill\"\n[s1.format]\nS = { decimals = 1, point = \"never\" }\n"),
            "shop.toml:4:1: error: s1.format.S: S is a whole number (a speed, a tool, a register, a program number, a "
            "count), and without a point in 1 decimals S1 would be written S10, which the control reads as that number: "
            "say decimals = 0\n 4 | S = { decimals = 1, point = \"never\" }\n   | ^\n");
  for (const char* k : {"T", "H", "D"})
    EXPECT_THAT(load_error("[w]\ninherits = \"fanuc-mill\"\n[w.format]\n" + std::string(k) +
                           " = { decimals = 2, point = \"never\" }\n"),
                HasSubstr("shop.toml:4:1: error: w.format." + std::string(k) + ": " + k + " is a whole number"))
        << k;
  EXPECT_EQ(load_error("[p1]\ninherits = \"fanuc-mill\"\n[p1.format]\nP = { decimals = 1, point = \"never\" }\n"
                       "[p1.codes]\nwork_offset_extended = \"G54.1 P{number}\"\n"),
            "shop.toml:6:24: error: p1.codes.work_offset_extended: P{number} is a whole number, and format.P writes it "
            "without a point in 1 decimals: 1 would be P10, which the control reads as 10; write P{number:1} (a plain "
            "whole number)\n 6 | work_offset_extended = \"G54.1 P{number}\"\n   |                        ^\n");
  // A width makes it a plain whole number whatever format.P says; with a point it is no other number.
  EXPECT_EQ(load_error("[p2]\ninherits = \"fanuc-mill\"\n[p2.format]\nP = { decimals = 1, point = \"never\" }\n"
                       "[p2.codes]\nwork_offset_extended = \"G54.1 P{number:1}\"\n"),
            "");
  EXPECT_EQ(load_error("[s2]\ninherits = \"fanuc-mill\"\n[s2.format]\nS = { decimals = 0, point = \"never\" }\n"), "");
}

// R and Q are lengths counted in the control's increment when written without a point: with
// 2 decimals R3.2 was R320 (0.32 mm: the R plane inside the boss), Q3 with 4 was Q30000 (one
// 30 mm peck), certified (helper-67).
TEST(ShopFloor, AnRorQWithoutAPointInAnotherIncrementIsRefused) {
  EXPECT_EQ(load_error("[r2]\ninherits = \"fanuc-mill\"\n[r2.format]\nR = { decimals = 2, point = \"never\" }\n"),
            "shop.toml:4:5: error: r2.format.R: R is a length written without a point in 2 decimals, and the control "
            "counts it in its least input increment (3 decimals, the usual 0.001 mm; a control in finer increments says "
            "so by writing its axes without a point): every R would be off by a power of ten; give it 3 decimals, or "
            "point = \"always\" where the control takes one\n 4 | R = { decimals = 2, point = \"never\" "
            "}\n   |     ^\n");
  EXPECT_THAT(load_error("[q4]\ninherits = \"fanuc-mill\"\n[q4.format]\nQ = { decimals = 4, point = \"never\" }\n"),
              HasSubstr("shop.toml:4:5: error: q4.format.Q: Q is a length written without a point in 4 decimals"));
  // The increment is the axes' where they are written without a point (0.0001 mm here).
  EXPECT_EQ(load_error("[isc]\ninherits = \"fanuc-mill\"\n[isc.format]\nX = { decimals = 4, point = \"never\" }\n"
                       "Y = { decimals = 4, point = \"never\" }\nZ = { decimals = 4, point = \"never\" }\n"
                       "I = { decimals = 4, point = \"never\" }\nJ = { decimals = 4, point = \"never\" }\n"
                       "K = { decimals = 4, point = \"never\" }\nR = { decimals = 4, point = \"never\" }\n"),
            "");
  EXPECT_THAT(load_error("[lq]\ninherits = \"fanuc-lathe\"\n[lq.format]\nP = { decimals = 2, point = \"never\" }\n"),
              HasSubstr("shop.toml:4:5: error: lq.format.P: P is a length written without a point in 2 decimals"));
  // An inherited P and Q made wrong by the axes given here are said at the axis (helper-68).
  EXPECT_EQ(load_error("[l4]\ninherits = \"fanuc-lathe\"\n[l4.format]\nX = { decimals = 4, point = \"never\", scale = 2.0 }\n"
                       "Z = { decimals = 4, point = \"never\" }\n"),
            "shop.toml:4:5: error: l4.format.P: P is a length written without a point in 3 decimals, and the control "
            "counts it in its least input increment (4 decimals, as format.X says): every P would be off by a power of "
            "ten; give it 4 decimals\n 4 | X = { decimals = 4, point = \"never\", scale = 2.0 }\n   |     ^\n"
            "shop.toml:4:5: error: l4.format.Q: Q is a length written without a point in 3 decimals, and the control "
            "counts it in its least input increment (4 decimals, as format.X says): every Q would be off by a power of "
            "ten; give it 4 decimals, or point = \"always\" where the control takes one\n 4 | X = { decimals = 4, "
            "point = \"never\", scale = 2.0 }\n   |     ^\n");
}

// A machine's fixed blocks run wherever the CL left the tool: "G28 Z0." (G90) as the retract
// rapided from Z100 down to the part's Z0 before going home, "G00 X0. Y0. Z-20." in the finish
// went into the part; both certified (helper-67). Only G53 and a home return from where the
// tool is (G91 G28 Z0., a lathe's G28 U0. W0.) load.
TEST(ShopFloor, AFixedBlockThatGoesToAPartPositionIsRefused) {
  EXPECT_EQ(load_error("[g28]\ninherits = \"fanuc-mill\"\n[g28.codes]\nsafe_retract = \"G28 Z0.\"\n"),
            "shop.toml:4:16: error: g28.codes.safe_retract: 'G28 Z0.' goes home through an intermediate point in the "
            "part's coordinates (G90: Z0 of the part, at rapid): it runs wherever the tool stands, so it must clear the "
            "part whatever it is; move in machine coordinates (G53 G00 Z0.) or straight home (G91 G28 Z0.)\n"
            " 4 | safe_retract = \"G28 Z0.\"\n   |                ^\n");
  EXPECT_THAT(load_error("[f]\ninherits = \"fanuc-mill\"\n[f.program]\nfinish = [\"M05\", \"G00 X0. Y0. Z-20.\", \"M30\"]\n"),
              HasSubstr("shop.toml:4:18: error: f.program.finish: 'G00 X0. Y0. Z-20.' moves X to a position in the "
                        "part's coordinates (X0): a fixed block must clear the part"));
  EXPECT_THAT(load_error("[g]\ninherits = \"fanuc-mill\"\n[g.codes]\nsafe_retract = \"G91 G28 Z-5.\"\n"),
              HasSubstr("'G91 G28 Z-5.' goes home through an intermediate point away from where the tool is"));
  // A Fanuc ignores G53 in G91: "G91 G53 Z0." moved nothing, and the tool change after it came
  // with the tool in the part (helper-71: certified).
  for (const char* g91 : {"G91 G53 Z0.", "G53 G91 G00 Z0."})
    EXPECT_THAT(load_error("[g]\ninherits = \"fanuc-mill\"\n[g.codes]\nsafe_retract = \"" + std::string(g91) + "\"\n"),
                HasSubstr("g.codes.safe_retract: '" + std::string(g91) + "' gives machine coordinates (G53) in G91, where "
                          "the control ignores them (the tool stays where it is): it runs wherever the tool stands"));
  // A mill's G41 with no D takes the D in force, D00 after a reset: the cut on the tool's
  // centre (helper-71: certified). Siemens selects it with the tool (D{offset}).
  EXPECT_EQ(load_error("[c]\ninherits = \"fanuc-mill\"\n[c.codes]\ncomp_left = \"G41\"\n"),
            "shop.toml:4:13: error: c.codes.comp_left: 'G41' names no radius register: a mill's control takes the one in "
            "force, D00 (radius 0) after a reset, and cuts on the tool's centre; write \"G41 D{register}\" (or select it "
            "with the tool: tool_change = \"T{tool} M06 D{offset}\")\n 4 | comp_left = \"G41\"\n   |             ^\n");
  EXPECT_EQ(load_error("[s]\ninherits = \"fanuc-mill\"\n[s.codes]\ncomp_left = \"G41\"\ncomp_right = \"G42\"\n"
                       "tool_change = \"T{tool} M06 D{offset}\"\n"), "");
  // Z alone first, where the tool may be down in the part: Y or X with Z, or before it, starts
  // across at the depth (a Fanuc's rapids are not interpolated; helper-74: certified).
  for (const char* across : {"G28 G91 Z0. Y0.", "G91 G28 X0. Y0. Z0.", "G53 G00 X0. Y0. Z0."})
    EXPECT_THAT(load_error("[a]\ninherits = \"fanuc-mill\"\n[a.codes]\nsafe_retract = \"" + std::string(across) + "\"\n"),
                HasSubstr("with Z while the tool may still be down in the part: it would cross at the depth it stands; "
                          "send Z home in a block of its own first (G91 G28 Z0., G53 G00 Z0.)"))
        << across;
  EXPECT_THAT(load_error("[a]\ninherits = \"fanuc-mill\"\n[a.program]\nfinish = [\"M05\", \"G53 G00 Y0.\", \"G53 G00 Z0.\", \"M30\"]\n"),
              HasSubstr("a.program.finish: 'G53 G00 Y0.' moves Y before Z while the tool may still be down in the part"));
  EXPECT_THAT(load_error("[a]\ninherits = \"fanuc-mill\"\n[a.program]\nfinish = [\"M05\", \"M30\"]\npark = true\n"
                         "park_blocks = [\"G53 G00 X-500. Y0.\"]\n"),
              HasSubstr("a.program.park_blocks: 'G53 G00 X-500. Y0.' moves XY before Z"));
  for (const char* ok : {"G91G28Z0.", "G53 G00 Z0.", "G90 G53 Z0.", "M05"})
    EXPECT_EQ(load_error("[ok]\ninherits = \"fanuc-mill\"\n[ok.codes]\nsafe_retract = \"" + std::string(ok) + "\"\n"), "")
        << ok;
  EXPECT_THAT(load_error("[l]\ninherits = \"fanuc-lathe\"\n[l.codes]\nsafe_retract = \"G28 X0. Z0.\"\n"),
              HasSubstr("'G28 X0. Z0.' goes home through an intermediate point in the part's coordinates"));
  // After a finish that has gone home, a park position is where the tool goes from there: a
  // lathe's anywhere, a mill's across, not down (helper-68: G00 X0. Y0. Z-50. was certified).
  EXPECT_EQ(load_error("[p]\ninherits = \"fanuc-lathe\"\n[p.program]\npark_blocks = [\"G00 X200. Z100.\"]\n"), "");
  EXPECT_EQ(load_error("[p]\ninherits = \"fanuc-mill\"\n[p.program]\npark_blocks = [\"G00 X0. Y200.\"]\n"), "");
  EXPECT_THAT(load_error("[p]\ninherits = \"fanuc-mill\"\n[p.program]\npark_blocks = [\"G00 X0. Y0. Z-50.\"]\n"),
              HasSubstr("'G00 X0. Y0. Z-50.' moves Z to a position in the part's coordinates (Z-50)"));
  // Read as the control reads words: any case, blanks, a G91 of its own block before, a
  // negative value; program.start too (helper-68).
  for (const char* bad : {"g00 x0. y0. z-20.", "G 28 Z 0.", "G91 G28 Z0. G90 Z-20.", "G91 G28 Z-5."})
    EXPECT_THAT(load_error("[c]\ninherits = \"fanuc-mill\"\n[c.program]\nfinish = [\"" + std::string(bad) + "\"]\n"),
                HasSubstr("c.program.finish: '" + std::string(bad) + "'"))
        << bad;
  EXPECT_THAT(load_error("[s]\ninherits = \"fanuc-mill\"\n[s.program]\nstart = [\"%\", \"G00 Z-50.\"]\n"),
              HasSubstr("s.program.start: 'G00 Z-50.' moves Z"));
  for (const char* ok : {"[\"M05\", \"G91\", \"G28 Z0.\", \"G90\", \"M30\"]", "[\"G28 W0\", \"G28 U0 V0\"]", "[\"G0 SUPA Z0 D0\"]",
                         "[\"G153 Z0\"]", "[\"L Z-0.5 R0 FMAX M91\"]"})
    EXPECT_EQ(load_error("[ok]\ninherits = \"fanuc-mill\"\n[ok.program]\nfinish = " + std::string(ok) + "\n"), "") << ok;
  // A lathe's tool change at a position in the part's coordinates is refused as a mill's: G00
  // X0. Z-40. was certified (helper-69); G30 U0. W0. is the control's tool change position.
  EXPECT_THAT(load_error("[t]\ninherits = \"fanuc-lathe\"\n[t.codes]\ntool_change = \"G00 X0. Z-40. T{tool:2}{offset:2}\"\n"),
              HasSubstr("t.codes.tool_change: 'G00 X0. Z-40. T{tool:2}{offset:2}' moves X to a position in the part's"));
  EXPECT_EQ(load_error("[t]\ninherits = \"fanuc-lathe\"\n[t.codes]\ntool_change = \"G30 U0. W0. T{tool:2}{offset:2}\"\n"
                       "safe_retract = \"G00 U0 W0\"\n"),
            "");
  // A park after the finish's blocks but its last (M30 with them: helper-69), and not back in Z.
  EXPECT_THAT(load_error("[p]\ninherits = \"fanuc-mill\"\n[p.program]\nfinish = [\"M05\", \"G91 G28 Z0. M30\"]\n"
                         "park_blocks = [\"G90 G00 X0. Y0.\"]\n"),
              HasSubstr("p.program.park_blocks: 'G90 G00 X0. Y0.' moves X"));
  EXPECT_THAT(load_error("[p]\ninherits = \"fanuc-lathe\"\n[p.program]\npark_blocks = [\"G00 X0. Z-40.\"]\n"),
              HasSubstr("p.program.park_blocks: 'G00 X0. Z-40.' moves Z"));
}

// spindle_cw = "M04" ran every right-hand cutter backwards, certified: verify holds a program
// to the machine's own codes (helper-67). On a mill M03 is clockwise whatever the file says.
TEST(ShopFloor, ASpindleDirectionCodeTheOtherWayIsRefused) {
  EXPECT_EQ(load_error("[m4]\ninherits = \"fanuc-mill\"\n[m4.codes]\nspindle_cw = \"M04\"\nspindle_ccw = \"M03\"\n"),
            "shop.toml:4:14: error: m4.codes.spindle_cw: M04 turns a mill's spindle counter-clockwise (ISO 6983), the "
            "other way than spindle_cw says: every cutter would run backwards\n 4 | spindle_cw = \"M04\"\n   |           "
            "   ^\nshop.toml:5:15: error: m4.codes.spindle_ccw: M03 turns a mill's spindle clockwise (ISO 6983), the "
            "other way than spindle_ccw says: every cutter would run backwards\n 5 | spindle_ccw = \"M03\"\n   |       "
            "        ^\n");
  EXPECT_EQ(load_error("[m13]\ninherits = \"fanuc-mill\"\n[m13.codes]\nspindle_cw = \"M13\"\n"), "");
}

// From the machine's own keys, what a control reads otherwise reached the program: a '%' (the
// tape's end) as a comment's replacement or a block end, a program number longer than format.O
// (helper-67).
TEST(ShopFloor, TapeMarksAndOverlongProgramNumbersAreRefused) {
  EXPECT_EQ(load_error("[c]\ninherits = \"fanuc-mill\"\n[c.comments]\nreplacement = \"%\"\n"),
            "shop.toml:4:15: error: c.comments.replacement: '%' would stand in the program's blocks, where a control "
            "reads '%' as the end of the tape and '(' ')' as a comment's ends\n 4 | replacement = \"%\"\n   |         "
            "      ^\n");
  EXPECT_THAT(load_error("[w]\ninherits = \"fanuc-mill\"\n[w.words]\nblock_end = \" %\"\n"),
              HasSubstr("w.words.block_end: '%' would stand in the program's blocks"));
  EXPECT_THAT(load_error("[n]\ninherits = \"fanuc-mill\"\n[n.program]\nnumber = 12345\n"),
              HasSubstr("shop.toml:4:10: error: n.program.number: 12345 has more digits than format.O's 4"));
  EXPECT_EQ(load_error("[n]\ninherits = \"haas-umc750\"\n[n.program]\nnumber = 12345\n"), "");
}

TEST(ShopFloor, ARotaryMachineWithoutKinematicsIsOneErrorInItsFile) {
  EXPECT_EQ(load_error("[rot]\ninherits = \"haas-umc750\"\npipeline = [\"arc-direction\", \"helix\", \"drill-cycles\", "
                       "\"rapid-split\", \"offset-table\", \"arc-legalise\"]\n"),
            "shop.toml:3:12: error: rot.pipeline: machine 'rot' needs 'kinematics' in its pipeline, to turn tool axes into "
            "rotary positions\n 3 | pipeline = [\"arc-direction\", \"helix\", \"drill-cycles\", \"rapid-split\", \"offset-table\", "
            "\"arc-legalise\"]\n   |            ^\n");
}

TEST(ShopFloor, AMillWithoutDrillCyclesIsOneErrorInItsFile) {
  EXPECT_EQ(load_error("[nodrill]\ninherits = \"fanuc-mill\"\npipeline = [\"arc-direction\", \"helix\", \"arc-legalise\", "
                       "\"offset-table\"]\n"),
            "shop.toml:3:12: error: nodrill.pipeline: machine 'nodrill' needs 'drill-cycles' in its pipeline, for CYCLE "
            "records: without it their holes would be cut as moves to their tops\n 3 | pipeline = [\"arc-direction\", "
            "\"helix\", \"arc-legalise\", \"offset-table\"]\n   |            ^\n");
}

// Travel added to a machine whose inherited pipeline has no 'limits': said in the user's file,
// at the machine (it was located at the parent's pipeline in the built-in machines.toml).
TEST(ShopFloor, AnInheritedPipelineThatDoesNotFitIsSaidAtTheMachine) {
  EXPECT_EQ(load_error("[tm]\ninherits = \"fanuc-mill\"\n[tm.kinematics]\ntravel = { x = [0.0, 500.0], y = [0.0, 400.0], "
                       "z = [-400.0, 0.0] }\n"),
            "shop.toml:1:1: error: tm: machine 'tm' needs 'limits' in its pipeline, to check every position against the "
            "machine's travel (its pipeline is inherited: give the machine its own)\n 1 | [tm]\n   | ^\n");
}

// Inverse time asked for with no G93 to write it: one error where it is asked (it was several
// per record, at every move that turned a rotary).
TEST(ShopFloor, InverseTimeWithoutItsCodeIsOneErrorInItsFile) {
  EXPECT_EQ(load_error("[inv]\ninherits = \"haas-umc750\"\n[inv.kinematics]\nsimultaneous = \"transform\"\n"
                       "inverse_time = true\n[inv.codes]\ninverse_time = \"\"\n"),
            "shop.toml:5:16: error: inv.kinematics.inverse_time: machine 'inv' has no codes.inverse_time (say, \"G93\") "
            "to write it with\n 5 | inverse_time = true\n   |                ^\n");
}

TEST(ShopFloor, PassesOutOfOrderAreAnError) {
  EXPECT_THAT(load_error("[late]\ninherits = \"haas-umc750\"\npipeline = [\"arc-direction\", \"helix\", \"offset-table\", "
                         "\"kinematics\", \"drill-cycles\", \"arc-legalise\"]\n"),
              StartsWith("shop.toml:3:12: error: late.pipeline: 'drill-cycles' must come before 'kinematics'\n"));
}

// A machine's TOML that leaves a code empty lacks the function. A tool change, a spindle
// start, a stop, a dwell, cutter compensation or a feed per revolution were written as nothing
// and the program certified (tool 1 cutting tool 2's operation, the spindle never started,
// the cut on the tool's centre); a COOLNT/OFF was written as flood coolant on.
TEST(ShopFloor, ACodeTheMachineLacksRefusesWhatTheClCannotDoWithout) {
  const std::string toml =
      "[router]\ninherits = \"fanuc-mill\"\n[router.codes]\ncomp_left = \"\"\ntool_change = \"\"\ncoolant_off = \"\"\n"
      "spindle_ccw = \"\"\ndwell = \"\"\nstop = \"\"\noptional_stop = \"\"\nfeed_per_rev = \"\"\n";
  const Machine m = machine("router", toml);
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/10,10,10\nGOTO/10,10,0\n";
  auto first_error = [&](const std::string& tail) {
    Compiled c = compile_text(head + tail, m);
    EXPECT_FALSE(c.ok);
    const size_t e = c.diags.find("error: ");
    if (e == std::string::npos) return c.diags;
    const size_t start = c.diags.rfind("part.cls", e);
    return c.diags.substr(start, c.diags.find('\n', e) - start);
  };
  EXPECT_EQ(first_error("LOADTL/2\nGOTO/20,10,0\n"),
            "part.cls:8:1: error: machine 'router' has no code to change the tool (codes.tool_change is empty): tool 1 would "
            "cut on for tool 2; post each tool's operations as a program of its own");
  EXPECT_EQ(first_error("CUTCOM/LEFT\nGOTO/20,10,0\n"),
            "part.cls:8:1: error: machine 'router' has no code to offset the cutter to the left of the path "
            "(codes.comp_left is empty): the cut would run on the tool's centre");
  EXPECT_EQ(first_error("SPINDL/RPM,1000,CCLW\nGOTO/20,10,0\n"),
            "part.cls:8:1: error: machine 'router' has no code to start the spindle counter-clockwise (codes.spindle_ccw is "
            "empty): the tool would cut with the spindle stopped");
  EXPECT_EQ(first_error("DELAY/2\n"), "part.cls:8:1: error: machine 'router' has no code to dwell (codes.dwell is empty)");
  EXPECT_EQ(first_error("STOP\n"), "part.cls:8:1: error: machine 'router' has no code to stop the program (codes.stop is empty)");
  EXPECT_EQ(first_error("FEDRAT/0.1,MMPR\nGOTO/20,10,0\n"),
            "part.cls:8:1: error: machine 'router' has no code to feed per revolution (codes.feed_per_rev is empty): its F "
            "would be read per minute; have the CAM system write the feed per minute");
  // The first tool is the one the operator loads; an OPSTOP and a coolant are said, not written.
  Compiled ok = compile_text(head + "OPSTOP\nCOOLNT/FLOOD\nCOOLNT/OFF\nGOTO/20,10,0\n", m, {.certify = true});
  ASSERT_TRUE(ok.ok) << ok.diags;
  EXPECT_THAT(ok.diags, HasSubstr("part.cls:8:1: warning: machine 'router' has no optional stop (codes.optional_stop is "
                                  "empty): OPSTOP is not written [-Wmachine-code]"));
  EXPECT_THAT(ok.diags, HasSubstr("part.cls:10:1: warning: machine 'router' has no code to turn the coolant off "
                                  "(codes.coolant_off): nothing is written [-Wcoolant]"));
  EXPECT_THAT(ok.output, HasSubstr("M08"));
  EXPECT_EQ(ok.output.find("M08", ok.output.find("M08") + 1), std::string::npos);
  EXPECT_THAT(ok.output, Not(HasSubstr("M01")));
}

// max_feed held only feeds per minute of moves. A tap above it (pitch x rpm) is refused: held
// to the limit it strips its thread. A feed per revolution above it at a fixed speed is said;
// a cycle's feed per minute is written at the limit, as a move's is (it was written as the CL's
// and verify, holding it to the limit, refused the program).
TEST(ShopFloor, FeedsAboveTheMachinesLimit) {
  const Machine m = machine("old-vmc", "[old-vmc]\ninherits = \"fanuc-mill\"\nmax_feed = 2000.0\n");
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/20,10,10\n";
  Compiled tap = compile_text(head + "CYCLE/TAP,DEPTH,10,PITCH,2.5,CLEAR,2\nGOTO/20,10,0\nCYCLE/OFF\n", m);
  EXPECT_FALSE(tap.ok);
  EXPECT_THAT(tap.diags, HasSubstr("part.cls:7:1: error: the tap feeds 2500 mm/min (pitch 2.5 at 1000 rpm), above machine "
                                   "'old-vmc''s max_feed 2000: give the tap a lower speed"));
  Compiled drill = compile_text(head + "CYCLE/DRILL,DEPTH,20,MMPM,2500,CLEAR,2\nGOTO/20,10,0\nGOTO/40,10,0\nCYCLE/OFF\n"
                                       "FEDRAT/2.5,MMPR\nGOTO/40,10,-1\n",
                                m, {.certify = true});
  ASSERT_TRUE(drill.ok) << drill.diags;
  EXPECT_THAT(drill.output, HasSubstr("G81 X20. Y10. Z-20. R2. F2000.\n"));
  EXPECT_THAT(drill.diags, HasSubstr("part.cls:7:1: warning: feed 2500 is above machine 'old-vmc''s max_feed 2000: written "
                                     "as 2000, slower than the CL asks [-Wfeed-clamped]\n"));
  EXPECT_THAT(drill.diags, HasSubstr("part.cls:10:1: warning: feed 2.5 mm/rev at 1000 rpm is 2500 mm/min, above machine "
                                     "'old-vmc''s max_feed 2000: the control cuts it slower than the CL asks [-Wfeed-clamped]\n"));
  Compiled per_rev = compile_text(head + "CYCLE/DRILL,DEPTH,10,CLEAR,2,MMPR,2.5\nGOTO/20,10,0\nCYCLE/OFF\n", m);
  ASSERT_TRUE(per_rev.ok) << per_rev.diags;
  EXPECT_THAT(per_rev.diags, HasSubstr("part.cls:7:1: warning: feed 2.5 mm/rev at 1000 rpm is 2500 mm/min, above machine "
                                       "'old-vmc''s max_feed 2000: the control drills it slower than the CL asks"));
  size_t warnings = 0;  // once for the cycle's two holes
  for (size_t at = drill.diags.find("warning:"); at != std::string::npos; at = drill.diags.find("warning:", at + 1)) ++warnings;
  EXPECT_EQ(warnings, 2u);
}

// SPINDL/RPM,0.4 was written S0 M03 and the cuts after it certified: a spindle that does not turn.
TEST(ShopFloor, ASpindleSpeedThatRoundsToZeroIsRefused) {
  for (const char* name : {"fanuc-mill", "fanuc-lathe"}) {
    Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,0.4,CLW\nFEDRAT/100\nRAPID\nGOTO/0,0,5\nGOTO/0,0,0\n",
                              machine(name));
    EXPECT_FALSE(c.ok) << name;
    EXPECT_THAT(c.diags, HasSubstr("part.cls:3:1: error: SPINDL: 0.4 rpm would be written S0 (format.S), a spindle that "
                                   "does not turn"))
        << name;
  }
  // Under constant surface speed: G96 S0, or a clamp G50 S0; and a lathe with no clamp code
  // would run to its top speed near the axis.
  Compiled css = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/SMM,0.4,CLW,MAXRPM,2000\nFEDRAT/0.1,MMPR\nRAPID\nGOTO/20,0,5\n",
                              machine("fanuc-lathe"));
  EXPECT_THAT(css.diags, HasSubstr("part.cls:3:1: error: SPINDL: the surface speed of 0.4 would be written S0 (format.S)"));
  Compiled clamp = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/SMM,200,CLW,MAXRPM,0.4\nFEDRAT/0.1,MMPR\nRAPID\nGOTO/20,0,5\n",
                                machine("fanuc-lathe"));
  EXPECT_THAT(clamp.diags, HasSubstr("part.cls:3:1: error: SPINDL: the clamp of 0.4 rpm would be written S0 (format.S)"));
  Compiled no_clamp = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/SMM,200,CLW,MAXRPM,2000\nFEDRAT/0.1,MMPR\nRAPID\nGOTO/20,0,5\n",
                                   machine("l2", "[l2]\ninherits = \"fanuc-lathe\"\n[l2.codes]\nspindle_clamp = \"\"\n"));
  EXPECT_THAT(no_clamp.diags, HasSubstr("part.cls:3:1: error: machine 'l2' has no code to clamp the spindle under constant "
                                        "surface speed (codes.spindle_clamp is empty)"));
}

// --- Per-job options -------------------------------------------------------------------

TEST(JobOptions, ProgramNumberFromTheFileName) {
  TempDir t;
  auto second_line = [&](const std::string& name, const std::string& args = "-t fanuc-mill") {
    write_file(t.path(name), kThreeTools);
    RunResult r = run_clpc("compile '" + t.path(name) + "' -o - " + args);
    EXPECT_EQ(r.status, 0) << r.err;
    return r.out.substr(2, r.out.find('\n', 2) - 2);
  };
  EXPECT_EQ(second_line("1234_pocket.cls"), "O1234");
  EXPECT_EQ(second_line("O0042.cls"), "O0042");
  EXPECT_EQ(second_line("o77 rev B.cls"), "O0077");
  EXPECT_EQ(second_line("O1234.cls", "-t haas-umc750"), "O01234");
  EXPECT_EQ(second_line("3axis.cls"), "O1000");           // a name, not a number: the machine's
  EXPECT_EQ(second_line("20231105_part.cls"), "O1000");   // beyond O9999
  EXPECT_EQ(second_line("plate.cls"), "O1000");
  EXPECT_EQ(second_line("9001_part.cls"), "O1000");  // O8000-O9999: the control's macros (helper-67)
  EXPECT_EQ(second_line("1234_pocket.cls", "-t fanuc-mill --set program.number=55"), "O0055");  // the job's number wins
  EXPECT_EQ(second_line("1234_pocket.cls", "-t fanuc-mill --set program.number_from_name=false"), "O1000");
}

TEST(JobOptions, OutputUnitsWhateverTheMachinesDefault) {
  RunResult r = post(kThreeTools, "-t fanuc-mill --set units=inch");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("(UNITS: INCH)\n"));
  EXPECT_THAT(r.out, HasSubstr("N10 G20\n"));
  EXPECT_THAT(r.out, HasSubstr("N70 G43 H01 Z0.3937\nN80 G94 G01 X0.3937 Z-0.0394 F19.69\n"));
  RunResult mm = post(kThreeTools, "-t haas-umc750 --set units=mm");
  EXPECT_EQ(mm.status, 0) << mm.err;
  EXPECT_THAT(mm.out, HasSubstr("N10 G21\n"));
  EXPECT_THAT(mm.out, HasSubstr("G01 X10. Z-1. F500.\n"));
}

TEST(JobOptions, OptionalStopBeforeEachToolChange) {
  RunResult r = post(kThreeTools, "-t fanuc-mill --set program.optional_stop=tool-change");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("N30 T1 M06 (T1)\n"));  // none before the first tool
  EXPECT_THAT(r.out, HasSubstr("N90 G91 G28 Z0.\nN100 M01\nN110 T2 M06 (T2)\n"));
  // M01 stops the coolant (and the spindle): T3's SPINDL starts its spindle, and the coolant,
  // which the CL left on (no COOLNT for T3), is started again before its first move.
  EXPECT_THAT(r.out, HasSubstr("N170 G91 G28 Z0.\nN180 M01\nN190 T3 M06 (T3)\nN200 S4000 M03\nN210 M08\n"
                               "N220 G90 G54 G00 X30. Y0.\n"));
}

TEST(JobOptions, OptionalStopBetweenOperations) {
  RunResult r = post(kTwoOperations, "-t fanuc-mill --set program.optional_stop=operation");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("N80 Z10.\n(FINISH)\nN90 G91 G28 Z0.\nN100 M01\nN110 S3500 M03\nN120 G90 G00 X20. Y0.\n"));
  // "operation" stops at tool changes too (a plain APT file marks no operations).
  RunResult tools = post(kThreeTools, "-t fanuc-mill --set program.optional_stop=operation");
  EXPECT_THAT(tools.out, HasSubstr("N90 G91 G28 Z0.\nN100 M01\nN110 T2 M06 (T2)\n"));
  RunResult off = post(kTwoOperations, "-t fanuc-mill");
  EXPECT_THAT(off.out, Not(HasSubstr("M01")));
}

TEST(JobOptions, PreselectTheNextTool) {
  RunResult r = post(kThreeTools, "-t fanuc-mill --set program.preselect=true");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("N30 T1 M06 (T1)\nN40 T2\nN50 S3000 M03\n"));
  EXPECT_THAT(r.out, HasSubstr("N110 T2 M06 (T2)\nN120 T3\nN130 S4000 M03\nN140 M08\n"));
  EXPECT_THAT(r.out, HasSubstr("N190 T3 M06 (T3)\nN200 S4000 M03\nN210 M08\n"));  // the last tool: nothing to preselect
  RunResult lathe = post(kLatheFile, "-t fanuc-lathe --set program.preselect=true");
  EXPECT_EQ(lathe.status, 1);
  EXPECT_EQ(lathe.err, "--set:1:21: error: fanuc-lathe.program.preselect: a lathe's turret indexes the tool it cuts with: there "
                       "is no next tool to preselect\n 1 | program.preselect = true\n   |                     ^\n");
}

TEST(JobOptions, CoolantOffBeforeAndOnAfterEachToolChange) {
  RunResult r = post(kThreeTools, "-t fanuc-mill --set program.coolant_around_tool_change=true");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("N90 G91 G28 Z0.\nN100 M09\nN110 T2 M06 (T2)\nN120 S4000 M03\nN130 M08\nN140 G90 G54 G00 X20. Y0.\n"));
  // With the optional stop: the coolant is off when the machine stops.
  RunResult both = post(kThreeTools, "-t fanuc-mill --set program.coolant_around_tool_change=true --set program.optional_stop=tool-change");
  EXPECT_THAT(both.out, HasSubstr("N90 G91 G28 Z0.\nN100 M09\nN110 M01\nN120 T2 M06 (T2)\n"));
  // A lathe too.
  RunResult lathe = post(
      "UNITS/MM\nMACHIN/TURN\nTURRET/1\nSPINDL/RPM,800,CLW\nCOOLNT/ON\nRAPID\nGOTO/30,0,5\nFEDRAT/0.2,MMPR\nGOTO/30,0,-20\n"
      "TURRET/2\nSPINDL/RPM,900,CLW\nRAPID\nGOTO/20,0,5\nFEDRAT/0.1,MMPR\nGOTO/20,0,-10\nFINI\n",
      "-t fanuc-lathe --set program.coolant_around_tool_change=true");
  EXPECT_EQ(lathe.status, 0) << lathe.err;
  EXPECT_THAT(lathe.out, HasSubstr("N80 G28 U0. W0.\nN90 M09\nN100 T0202 (T2)\nN110 G97 S900 M03\nN120 M08\nN130 G00 X40. Z5.\n"));
}

TEST(JobOptions, SmoothingOnTheHaasAndTheFanuc) {
  RunResult haas = post(kThreeTools, "-t haas-umc750 --set program.smoothing=finish --set program.smoothing_tolerance=0.0005");
  EXPECT_EQ(haas.status, 0) << haas.err;
  EXPECT_THAT(haas.out, HasSubstr("N15 G00 G17 G40 G49 G80 G90\nN20 G187 P3 E0.0005\nN25 T1 M06 (T1)\n"));
  EXPECT_THAT(haas.out, HasSubstr("N165 G187\nN170 M05\n"));
  RunResult own = post(kThreeTools, "-t haas-umc750 --set program.smoothing=rough");  // the control's tolerance
  EXPECT_THAT(own.out, HasSubstr("N20 G187 P1\n"));
  RunResult fanuc = post(kThreeTools, "-t fanuc-mill --set program.smoothing=medium");
  EXPECT_EQ(fanuc.status, 0) << fanuc.err;
  EXPECT_THAT(fanuc.out, HasSubstr("N20 G00 G17 G40 G49 G80 G90\nN30 G05.1 Q1\n"));
  EXPECT_THAT(fanuc.out, HasSubstr("N240 G05.1 Q0\nN250 M05\n"));
  RunResult tol = post(kThreeTools, "-t fanuc-mill --set program.smoothing=medium --set program.smoothing_tolerance=0.01");
  EXPECT_EQ(tol.status, 1);
  EXPECT_EQ(tol.err,
            "--set:2:31: error: fanuc-mill.program.smoothing_tolerance: machine 'fanuc-mill''s codes.smoothing_on (\"G05.1 Q1\") "
            "has no {tolerance}: the control takes its tolerance from its parameters\n 2 | program.smoothing_tolerance = 0.01\n"
            "   |                               ^\n");
  RunResult lathe = post(kLatheFile, "-t fanuc-lathe --set program.smoothing=finish");
  EXPECT_EQ(lathe.status, 1);
  EXPECT_THAT(lathe.err, StartsWith("--set:1:21: error: fanuc-lathe.program.smoothing: machine 'fanuc-lathe' has no "
                                    "codes.smoothing_on to switch its smoothing on with\n"));
}

TEST(JobOptions, SpindleSpeedLimit) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,9000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/MMPM,100\nGOTO/0,0,-1\nFINI\n";
  RunResult r = post(cl, "-t haas-umc750");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "<stdin>:3:1: error: SPINDL: 9000 rpm is above machine 'haas-umc750''s spindle limit of 8100 rpm (max_rpm)\n"
                   " 3 | SPINDL/RPM,9000,CLW\n   | ^\nclpc: 1 error, 0 warnings\n");
  EXPECT_EQ(post(cl, "-t haas-umc750 --set max_rpm=12000").status, 0);  // the 12,000 rpm spindle option
  EXPECT_EQ(post(cl, "-t fanuc-mill").status, 0);                         // a generic control: no limit of its own
  EXPECT_EQ(post(cl, "-t fanuc-mill --set max_rpm=6000").status, 1);
}

TEST(JobOptions, ParkAtTheEnd) {
  RunResult haas = post(kThreeTools, "-t haas-umc750 --set program.park=true");
  EXPECT_EQ(haas.status, 0) << haas.err;
  EXPECT_THAT(haas.out, HasSubstr("N170 G53 G00 Z0.\nN175 G53 G00 Y0.\nN180 G28 G91 B0. C0.\nN185 G90\nN190 M30\n%\n"));
  RunResult fanuc = post(kThreeTools, "-t fanuc-mill --set program.park=true");
  EXPECT_THAT(fanuc.out, HasSubstr("N250 G91 G28 Z0.\nN260 G90\nN270 G91 G28 Y0.\nN280 G90\nN290 M30\n"));
  RunResult lathe = post(kLatheFile, "-t fanuc-lathe --set program.park=true");
  EXPECT_EQ(lathe.status, 1);
  EXPECT_THAT(lathe.err, StartsWith("--set:1:16: error: fanuc-lathe.program.park: machine 'fanuc-lathe' has no park_blocks to "
                                    "park with (say, park_blocks = [\"G53 G00 Y0.\"])\n"));
  RunResult own = post(kLatheFile, "-t fanuc-lathe --set program.park=true --set 'program.park_blocks=[\"G00 X200. Z100.\"]'");
  EXPECT_EQ(own.status, 0) << own.err;
  EXPECT_THAT(own.out, HasSubstr("G28 U0. W0.\nN90 G00 X200. Z100.\nN100 M30\n"));
}

TEST(JobOptions, HeaderWithDateProgrammerAndStock) {
  setenv("SOURCE_DATE_EPOCH", "1795392000", 1);  // 2026-11-23, for a reproducible "today"
  RunResult r = post(kThreeTools, "-t fanuc-mill --set program.date=today --set 'program.programmer=J. Smith' "
                                  "--set 'program.stock=100 x 50 x 25 AlMg3'");
  unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, StartsWith("%\nO1000\n(MACHINE: FANUC-MILL - FANUC 0I-MF STYLE 3-AXIS VERTICAL MILL, METRIC)\n(SOURCE: <STDIN>)\n"
                                "(DATE: 2026-11-23)\n(PROGRAMMER: J. SMITH)\n(STOCK: 100 X 50 X 25 ALMG3)\n(UNITS: MM)\n"));
  RunResult fixed = post(kThreeTools, "-t fanuc-mill --set program.header=false --set 'program.date=23 NOV 2026'");
  EXPECT_THAT(fixed.out, StartsWith("%\nO1000\n(DATE: 23 NOV 2026)\nN10 G21\n"));
}

TEST(JobOptions, SequenceNumbersOff) {
  RunResult r = post(kThreeTools, "-t fanuc-mill --set sequence.enabled=false");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("\nG21\nG00 G17 G40 G49 G80 G90\nT1 M06 (T1)\n"));
  EXPECT_THAT(r.out, Not(HasSubstr("N10")));
}

TEST(JobOptions, AJobFile) {
  TempDir t;
  write_file(t.path("job.toml"), "[job]\nunits = \"mm\"\n[job.program]\noptional_stop = \"tool-change\"\nnumber = 77\n");
  RunResult r = post(kThreeTools, "-t haas-umc750 --job " + t.path("job.toml") + " --set program.number=78");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, StartsWith("%\nO00078\n"));  // --set comes after --job
  EXPECT_THAT(r.out, HasSubstr("N10 G21\n"));
  EXPECT_THAT(r.out, HasSubstr("N60 G53 G00 Z0.\nN65 M01\nN70 T2 M06 (T2)\n"));
  // explain shows the machine as the job has it.
  RunResult e = run_clpc("explain haas-umc750 --job " + t.path("job.toml"));
  EXPECT_THAT(e.out, HasSubstr("optional_stop = \"tool-change\"\n"));
  EXPECT_THAT(e.out, HasSubstr("units = \"mm\"\n"));

  write_file(t.path("bad.toml"), "[job]\nfamily = \"lathe\"\n");
  RunResult bad = post(kThreeTools, "-t fanuc-mill --job " + t.path("bad.toml"));
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(bad.err, t.path("bad.toml") + ":2:10: error: family: a job cannot change the machine's family; name another "
                                          "machine with -t\n 2 | family = \"lathe\"\n   |          ^\n");
  write_file(t.path("stray.toml"), "[job]\nunits = \"mm\"\n[haas]\nunits = \"inch\"\n");
  RunResult stray = post(kThreeTools, "-t fanuc-mill --job " + t.path("stray.toml"));
  EXPECT_EQ(stray.status, 1);
  EXPECT_THAT(stray.err, StartsWith(t.path("stray.toml") + ":3:2: error: 'haas': a job file holds one [job] table of machine keys"));
}

TEST(JobOptions, SetErrorsAreLocatedAndSuggest) {
  RunResult typo = post(kThreeTools, "-t fanuc-mill --set program.optionl_stop=operation");
  EXPECT_EQ(typo.status, 1);
  EXPECT_EQ(typo.err, "--set:1:9: error: unknown key 'optionl_stop' in fanuc-mill.program; did you mean 'optional_stop'?\n"
                      " 1 | program.optionl_stop = \"operation\"\n   |         ^\n");
  RunResult value = post(kThreeTools, "-t fanuc-mill --set program.smoothing=ultra");
  EXPECT_EQ(value.status, 1);
  EXPECT_THAT(value.err, StartsWith("--set:1:21: error: fanuc-mill.program.smoothing: expected one of \"off\", \"rough\", "
                                    "\"medium\", \"finish\", found \"ultra\"\n"));
  RunResult malformed = post(kThreeTools, "-t fanuc-mill --set program.park");
  EXPECT_EQ(malformed.status, 1);
  EXPECT_EQ(malformed.err, "clpc: error: --set program.park: expected KEY=VALUE, KEY a machine key such as "
                           "program.optional_stop or units\n");
  RunResult no_machine = run_clpc("check - --set units=inch", kThreeTools);
  EXPECT_EQ(no_machine.status, 2);
  EXPECT_EQ(no_machine.err, "clpc: error: --set and --job change a machine: name it with -t\n");
  // A later --set of one key replaces an earlier one.
  EXPECT_EQ(post(kThreeTools, "-t fanuc-mill --set program.number=5 --set program.number=6").out.substr(0, 8), "%\nO0006\n");
}

// --- The command line -------------------------------------------------------------------

TEST(CommandLine, DidYouMeanForOptionCommandAndMachine) {
  RunResult option = run_clpc("compile x.cls -t haas-umc750 --outptu x.nc");
  EXPECT_EQ(option.status, 2);
  EXPECT_EQ(option.err, "clpc: error: unknown option '--outptu'; did you mean '--output'?\nRun 'clpc compile --help' for the options.\n");
  RunResult command = run_clpc("compil x.cls");
  EXPECT_EQ(command.status, 2);
  EXPECT_EQ(command.err, "clpc: error: unknown command 'compil'; did you mean 'compile'?\nRun 'clpc --help' for the options.\n");
  RunResult machine = run_clpc("compile - -t haas-umc75", kThreeTools);
  EXPECT_EQ(machine.status, 1);
  EXPECT_EQ(machine.err, "clpc: error: no machine named 'haas-umc75'; did you mean 'haas-umc750'? (known: fanuc-lathe, "
                         "fanuc-mill, haas-umc750; see 'clpc machines')\n");
  RunResult value = run_clpc("compile - -t fanuc-mill --emit gcod", kThreeTools);
  EXPECT_EQ(value.status, 2);
  EXPECT_THAT(value.err, StartsWith("clpc: error: --emit: 'gcod' is not one of gcode, ir; did you mean 'gcode'?\n"));
  RunResult warning = run_clpc("compile - -t fanuc-mill -Wno-spindle-stoped", kThreeTools);
  EXPECT_EQ(warning.status, 2);
  EXPECT_EQ(warning.err, "clpc: error: -Wno-spindle-stoped: no such warning switch (-Wno-NAME, -Werror); did you mean "
                         "'-Wno-spindle-stopped'?\n");
}

TEST(CommandLine, ClpcAloneGivesTheShortHelp) {
  RunResult r = run_clpc("");
  EXPECT_EQ(r.status, 2);
  EXPECT_THAT(r.out, StartsWith("clpc - a CNC postprocessor: CL data (APT/CLSF) in, G-code out\n\nusage: clpc COMMAND [OPTIONS]\n"));
  EXPECT_THAT(r.out, HasSubstr("  clpc compile part.cls -t haas-umc750     the main job\n"));
}

namespace {
// Five cutting moves with the spindle stopped: five warnings of one name.
const char* kNoSpindle = "UNITS/MM\nLOADTL/1\nRAPID\nGOTO/0,0,5\nFEDRAT/MMPM,100\nGOTO/1,0,0\nGOTO/2,0,0\nGOTO/3,0,0\n"
                         "GOTO/4,0,0\nGOTO/5,0,0\nFINI\n";
}  // namespace

TEST(CommandLine, RepeatedWarningsAreSummarisedAfterThree) {
  RunResult r = post(kNoSpindle, "-t fanuc-mill");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("<stdin>:8:1: warning: cutting move with the spindle stopped [-Wspindle-stopped]\n"));
  EXPECT_THAT(r.err, Not(HasSubstr("<stdin>:9:1")));
  EXPECT_THAT(r.err, HasSubstr("<stdin>: note: 2 more warnings like these not shown (spindle-stopped; -Wno-spindle-stopped silences "
                               "them)\nclpc: 0 errors, 5 warnings\n"));
}

TEST(CommandLine, WarningsSilencedByName) {
  RunResult r = post(kNoSpindle, "-t fanuc-mill -Wno-spindle-stopped");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err,
            "clpc: certified (standard output): 6 points, 0 arcs, 0 holes checked; max deviation 0.0000 mm; tolerance 0.0060 mm\n");
  RunResult werror = post(kNoSpindle, "-t fanuc-mill -Werror");
  EXPECT_EQ(werror.status, 1);
}

TEST(CommandLine, ASubroutinesDiagnosticNamesTheCall) {
  RunResult r = post("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nDEFSUB/1\nGOTO/1,2,3,4\nENDSUB\nRAPID\nGOTO/0,0,5\nCALSUB/1\nFINI\n",
                     "-t fanuc-mill");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("<stdin>:5:12: error: GOTO needs 3 or 6 values (x,y,z[,i,j,k]), found 4\n"));
  EXPECT_THAT(r.err, HasSubstr("<stdin>:9:1: note: called from line 9"));
}

// docs/reliability.md lists every warning name (the -W option's help points there).
TEST(CommandLine, EveryWarningNameIsDocumented) {
  const std::string doc = read_file(std::string(CLPC_SOURCE_DIR) + "/docs/reliability.md");
  for (const WarningName& w : warning_names()) EXPECT_THAT(doc, HasSubstr("| `" + std::string(w.name) + "` |")) << w.name;
}

// A dwell keeps its meaning after formatting, as a feed does: with a whole-seconds P, 0.4 s was
// written P0 and 1.5 s P2, certified (so was a cycle's dwell).
TEST(ShopFloor, ADwellThatRoundingWouldChangeIsAnError) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/10,0,5\nFEDRAT/MMPM,250\nGOTO/10,0,-2\n"
                         "DELAY/0.4\nGOTO/20,0,-2\nDELAY/1.5\nFINI\n";
  Compiled c = compile_text(cl, machine("my-mill", "[my-mill]\ninherits = \"fanuc-mill\"\n[my-mill.codes]\ndwell = \"G04 P{seconds}\"\n"
                                                   "[my-mill.format]\nP = { point = \"always\" }\n"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("part.cls:8:1: error: the dwell of 0.4 s would be written as 0 s: no dwell at all"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:10:1: error: the dwell of 1.5 s would be written as 2 s: rounding changes it by "
                                 "more than 5%"));
  Compiled ok = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(ok.ok) << ok.diags;
  EXPECT_THAT(ok.output, HasSubstr("G04 P400\n"));
  // A dwell's word the control would read in other units is refused at load: without a point
  // P is milliseconds (G04 P{seconds} wrote P1 for 1 s), with one seconds (G04 X{milliseconds}
  // wrote X1250. for 1.25 s; helper-52).
  EXPECT_THAT(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.codes]\ndwell = \"G04 P{seconds}\"\n"),
              HasSubstr("shop.toml:4:9: error: m.codes.dwell: P{seconds} may be written without a point (format.P), and "
                        "the control reads a dwell's P without a point in milliseconds: 1 s would be read as 1 ms; write "
                        "P{milliseconds:1} or X{seconds} (a Fanuc's P takes no point), or give format.P point = "
                        "\"always\" where the control takes one (Haas)"));
  EXPECT_THAT(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.codes]\ndwell = \"G04 X{milliseconds}\"\n"),
              HasSubstr("shop.toml:4:9: error: m.codes.dwell: X{milliseconds} is written with a point (format.X), and the "
                        "control reads a dwell's X with a point in seconds, without one in milliseconds"));
  EXPECT_THAT(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.codes]\ncycle_dwell_word = \"P{seconds:1}\"\n"),
              HasSubstr("m.codes.cycle_dwell_word: P{seconds:1} may be written without a point (a whole number)"));
  EXPECT_EQ(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.codes]\ndwell = \"G04 X{seconds}\"\n"), "");
  // Made wrong by this file's format of an inherited code's word: said at the format.
  EXPECT_THAT(load_error("[h]\ninherits = \"haas-umc750\"\n[h.format]\nP = { decimals = 0, point = \"never\" }\n"),
              HasSubstr("shop.toml:4:5: error: h.codes.dwell: P{seconds} may be written without a point (format.P)"));
  // A number that is no position in an axis address: the offset number became a Z to move to.
  EXPECT_THAT(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.codes]\nlength_offset = \"G43 Z{offset} H{tool}\"\n"),
              HasSubstr("shop.toml:4:17: error: m.codes.length_offset: placeholder {offset} in the axis address Z: the "
                        "control would move the axis to it; give it its own address (H{offset}, D{register})"));
}

// Formats a control cannot read as meant, refused at load: a scale on a mill's axis (X
// stretched or mirrored while I, J, K and the arcs' directions stay: scale = -1 wrote a 90
// degree G03 cut as 270, certified), and two axes without a point in other decimals (X in
// 0.001 mm, Y in 0.0001 mm: one 10 times off, certified).
TEST(ShopFloor, FormatsTheControlWouldReadOtherwiseAreRefusedAtLoad) {
  EXPECT_THAT(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.format]\nX = { scale = -1.0 }\n"),
              HasSubstr("shop.toml:4:1: error: m.format.X.scale: -1 would stretch or mirror X while the arcs' centres and "
                        "directions stay the CL's"));
  EXPECT_THAT(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.format]\nX = { point = \"never\" }\nY = { point = \"never\", decimals = 4 }\n"),
              HasSubstr("shop.toml:5:1: error: m.format.Y: written without a point in 4 decimals, while X is in 3"));
  EXPECT_EQ(load_error("[m]\ninherits = \"fanuc-lathe\"\n[m.format]\nX = { scale = 2.0 }\n"), "");
  EXPECT_EQ(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.format]\nX = { point = \"never\" }\nY = { point = \"never\" }\n"), "");
  EXPECT_THAT(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.format]\nN = { decimals = 2 }\n"),
              HasSubstr("shop.toml:4:1: error: m.format.N: a block number is a whole number, written as counted "
                        "([sequence] start and step): only digits (zero-padding) applies"));
}

// A feed per minute written without a point in decimals (format.F, feeds.per_minute, a tap fed
// per minute) is refused where it is asked: a control reads it in whole units, so F5000 for
// 500.0 mm/min was cut ten times too fast and certified (verify read it in clpc's own
// increments; helper-44). Feeds per revolution and leads without a point count the control's
// own increment (a Fanuc lathe's 0.0001 mm/rev), and are read back so.
TEST(ShopFloor, FeedsPerMinuteWithoutAPointInDecimalsAreRefused) {
  EXPECT_EQ(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.format]\nF = { decimals = 1, point = \"never\" }\n"),
            "shop.toml:4:5: error: m.format.F: F is written without a point in 1 decimals: a control reads a feed per "
            "minute without a point in whole units, so every feed would be read 10 times too fast; say point = "
            "\"always\" (or decimals = 0)\n 4 | F = { decimals = 1, point = \"never\" }\n   |     ^\n");
  EXPECT_THAT(load_error("[tap3]\ninherits = \"fanuc-mill\"\n[tap3.feeds]\ntap = { decimals = 3, point = \"never\" }\n"),
              HasSubstr("shop.toml:4:7: error: tap3.feeds.tap: the feed is written without a point in 3 decimals"));
  // Whole units without a point stay allowed: F500 is 500 mm/min on every control.
  const Machine whole = machine("f0", "[f0]\ninherits = \"fanuc-mill\"\n[f0.format]\nF = { decimals = 0, point = \"never\" }\n");
  Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10\nFEDRAT/500,MMPM\nGOTO/0,0,-2\n", whole,
                            {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr(" G01 Z-2. F500\n"));
  // Per revolution and leads: the control's increment, written and read back so.
  const Machine lathe = machine("lathe4", "[lathe4]\ninherits = \"fanuc-lathe\"\n[lathe4.feeds]\n"
                                          "per_rev = { decimals = 4, point = \"never\" }\nlead = { decimals = 4, point = \"never\" }\n");
  Compiled turn = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/30,0,2\nFEDRAT/0.2032,MMPR\n"
                               "GOTO/30,0,-20\nGOTO/40,0,-20\n", lathe, {.certify = true});
  ASSERT_TRUE(turn.ok) << turn.diags;
  EXPECT_THAT(turn.output, HasSubstr(" G01 Z-20. F2032\n"));
  Compiled thread = compile_text(test::thread_cl({0.3, 0.6, 0.8, 0.92}), lathe, {.certify = true});
  ASSERT_TRUE(thread.ok) << thread.diags;
  EXPECT_THAT(thread.output, HasSubstr("F15000"));
}

// Two rotaries of one name, and a mode switched on with no code to switch it off (G43.4 kept
// through G28 and M06 for the next tool), are refused at their key.
TEST(ShopFloor, AxesOfOneNameAndModesThatCannotBeCancelledAreRefused) {
  EXPECT_THAT(load_error("[dupa]\ninherits = \"haas-umc750\"\n[[dupa.kinematics.axes]]\nname = \"A\"\naxis = [1.0, 0.0, 0.0]\n"
                         "[[dupa.kinematics.axes]]\nname = \"A\"\naxis = [0.0, 0.0, 1.0]\n"),
              HasSubstr("shop.toml:7:8: error: dupa.kinematics.axes[1].name: a second axis named \"A\""));
  EXPECT_THAT(load_error("[hermle]\ninherits = \"haas-umc750\"\n[hermle.codes]\ntcp_off = \"\"\n"),
              HasSubstr("shop.toml:4:11: error: hermle.codes.tcp_off: machine 'hermle' switches tool centre point control "
                        "on with \"G00 G234 H{offset}\" and has no code to switch it off"));
  EXPECT_THAT(load_error("[dwo]\ninherits = \"haas-umc750\"\n[dwo.codes]\ndwo_off = \"\"\n"),
              HasSubstr("error: dwo.codes.dwo_off: machine 'dwo' switches its dynamic work offset on with"));
  // A 3-axis machine that never uses TCPC may leave its codes empty.
  EXPECT_EQ(load_error("[plain]\ninherits = \"fanuc-mill\"\n[plain.codes]\ntcp_off = \"\"\n"), "");
  // Limits on a modulo axis were dropped (C270 certified on an axis declared 0 to 90), and two
  // parallel axes loaded, to fail every tilt with a word about limits (helper-52).
  const std::string ac = "[ac]\ninherits = \"haas-umc750\"\n[ac.kinematics]\nsimultaneous = \"transform\"\n"
                         "[[ac.kinematics.axes]]\nname = \"A\"\naxis = [1.0, 0.0, 0.0]\nmin = -30.0\nmax = 110.0\n"
                         "[[ac.kinematics.axes]]\nname = \"C\"\naxis = [0.0, 0.0, 1.0]\ncyclic = \"modulo\"\n";
  EXPECT_EQ(load_error(ac), "");
  EXPECT_THAT(load_error(ac + "min = 0.0\nmax = 90.0\n"),
              HasSubstr("shop.toml:15:7: error: ac.kinematics.axes[1].max: a modulo axis (cyclic = \"modulo\") turns to any "
                        "angle the short way: limits narrower than a turn cannot be kept; an axis that stops within a "
                        "range is cyclic = \"no\""));
  EXPECT_EQ(load_error(ac + "min = 0.0\nmax = 360.0\n"), "");
  EXPECT_EQ(load_error(ac + "min = 0.0\nmax = 359.999\n"), "");
  // A degree short of a turn is no turn: C359.6 was written past max = 359 (helper-55).
  EXPECT_THAT(load_error(ac + "min = 0.0\nmax = 359.0\n"), HasSubstr("shop.toml:15:7: error: ac.kinematics.axes[1].max: a modulo axis"));
  std::string parallel = ac;
  parallel.replace(parallel.find("axis = [1.0, 0.0, 0.0]"), 22, "axis = [0.0, 0.0, -1.0]");
  EXPECT_THAT(load_error(parallel), HasSubstr("shop.toml:12:8: error: ac.kinematics.axes[1].axis: parallel to A's axis"));
  // A pivot on a machine with no head axis changed nothing, without a word (helper-52).
  EXPECT_THAT(load_error("[tt]\ninherits = \"haas-umc750\"\n[tt.kinematics]\npivot = 150.0\n"),
              HasSubstr("shop.toml:4:9: error: tt.kinematics.pivot: a pivot is the distance from a tilting head's axes to "
                        "the tool: this machine has no head axis (side = \"head\"), so it would change nothing"));
  // A scale on what is no length: F with scale 2 fed twice as fast.
  EXPECT_THAT(load_error("[f2]\ninherits = \"fanuc-mill\"\n[f2.format]\nF = { scale = 2.0 }\n"),
              HasSubstr("shop.toml:4:15: error: f2.format.F.scale: 2 on F, which is no length"));
}

// format.N's digits pads the block numbers (N00010); it was read and then ignored.
TEST(ShopFloor, BlockNumbersArePaddedToTheirDigits) {
  Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,50\nFEDRAT/100,MMPM\nGOTO/0,0,10\n",
                            machine("n5", "[n5]\ninherits = \"fanuc-mill\"\n[n5.format]\nN = { digits = 5 }\n"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\nN00010 G21\nN00020 G00 G17 G40 G49 G80 G90\n"));
}

// A machine with no G43 and no offset in its tool change ran T2 at T1's length: the second
// tool's plunge certified (helper-62). A control that applies the length with the tool
// (Siemens' D) says so with {offset} in the tool change.
TEST(ShopFloor, ASecondToolWithNoLengthOffsetIsRefused) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10\nFEDRAT/MMPM,200\nGOTO/0,0,-5\n"
                         "RAPID\nGOTO/0,0,10\nLOADTL/2\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/20,0,5\nFEDRAT/MMPM,200\n"
                         "GOTO/20,0,-3\nRAPID\nGOTO/20,0,10\nFINI\n";
  Compiled none = compile_text(cl, machine("nog43", "[nog43]\ninherits = \"fanuc-mill\"\n[nog43.codes]\nlength_offset = \"\"\n"));
  EXPECT_FALSE(none.ok);
  EXPECT_THAT(none.diags, HasSubstr("part.cls:10:1: error: machine 'nog43' has no length offset (codes.length_offset) and "
                                    "its tool change (T{tool} M06) selects none: tool 2 would cut at tool 1's length; give "
                                    "codes.length_offset (G43 H{offset}), or {offset} in codes.tool_change where the control "
                                    "applies the length with it\n"));
  Compiled d = compile_text(cl, machine("sie", "[sie]\ninherits = \"fanuc-mill\"\n[sie.codes]\nlength_offset = \"\"\n"
                                               "tool_change = \"T{tool} M06 D{offset}\"\n"));
  ASSERT_TRUE(d.ok) << d.diags;
  EXPECT_THAT(d.output, HasSubstr("N100 T2 M06 D2 (T2)\n"));
  // The same tool reloaded with another register: no block for it (helper-65).
  Compiled reload = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10\nLOADTL/1,OSETNO,2\n"
                                 "RAPID\nGOTO/0,0,5\nFINI\n",
                                 machine("sie", "[sie]\ninherits = \"fanuc-mill\"\n[sie.codes]\nlength_offset = \"\"\n"
                                                "tool_change = \"T{tool} M06 D{offset}\"\n"));
  EXPECT_THAT(reload.diags, HasSubstr("part.cls:6:1: error: machine 'sie' has no length offset (codes.length_offset): the "
                                      "change of tool 1's offset from 1 to 2 cannot be written"));
}

// A fixed list is checked from G90 when the machine loads; one of the post's own blocks left
// G91 (G91 G28 Z0. before the last tool change) and a finish's "G53 G00 Z0." ran in G91, where
// a Fanuc ignores it (helper-72): G90 first. A G41 with a D of its own, or a D in a comment of
// the tool change, is no register of the tool's.
TEST(ShopFloor, FixedBlocksRunFromG90AndCompensationTakesTheToolsRegister) {
  TempDir t;
  write_file(t.path("shop.toml"), "[my]\ninherits = \"fanuc-mill\"\n[my.program]\n"
                                  "finish = [\"M05\", \"M09\", \"G53 G00 Z0.\", \"G53 X0. Y0.\", \"M30\"]\n");
  write_file(t.path("p.cls"), "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10\nFEDRAT/MMPM,100\n"
                              "GOTO/0,0,-2\nGOTO/50,0,-2\nRAPID\nGOTO/50,0,10\nLOADTL/2\nFINI\n");
  RunResult r = run_clpc("compile " + t.path("p.cls") + " -t my --machines " + t.path("shop.toml") + " -o " + t.path("p.nc"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(read_file(t.path("p.nc")), HasSubstr("N100 G91 G28 Z0.\nN110 T2 M06 (T2)\nN120 G90\nN130 G53 G00 Z0.\n"));
  // Once before the list, never between its blocks: "G91" then "G28 Z0." is a home from where
  // the tool is, and G90 between them sent it to the part's Z0 first (helper-74: certified).
  write_file(t.path("list.toml"), "[my]\ninherits = \"fanuc-mill\"\n[my.program]\n"
                                  "finish = [\"M05\", \"G91\", \"G28 Z0.\", \"G28 X0. Y0.\", \"G90\", \"M30\"]\n"
                                  "[my.codes]\ntool_change = \"G53 G00 X-500. Y0. T{tool} M06\"\n");
  r = run_clpc("compile " + t.path("p.cls") + " -t my --machines " + t.path("list.toml") + " -o " + t.path("l.nc"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(read_file(t.path("l.nc")), HasSubstr("N100 G91 G28 Z0.\nN110 G90 G53 G00 X-500. Y0. T2 M06 (T2)\n"
                                                    "N120 G91\nN130 G28 Z0.\nN140 G28 X0. Y0.\nN150 G90\nN160 M30\n"));
  EXPECT_THAT(load_error("[c]\ninherits = \"fanuc-mill\"\n[c.codes]\ncomp_left = \"G41 D99\"\n"),
              HasSubstr("c.codes.comp_left: 'G41 D99' names one radius register for every tool, not the tool's ({register})"));
  EXPECT_THAT(load_error("[c]\ninherits = \"fanuc-mill\"\n[c.codes]\ncomp_left = \"G41\"\ntool_change = \"T{tool} M06 (LOAD{tool})\"\n"),
              HasSubstr("c.codes.comp_left: 'G41' names no radius register"));
}

// A macro call's words are its arguments: "G65 P9832 X0. Y0. Z100." was refused as a move to
// the part's X0, while "G65 P9000" loaded (helper-68, helper-69).
TEST(ShopFloor, AMacroCallInAFixedBlockIsTheShopsOwn) {
  EXPECT_EQ(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.program]\nstart = [\"G65 P9832 X0. Y0. Z100.\"]\n"), "");
  EXPECT_THAT(load_error("[m]\ninherits = \"fanuc-mill\"\n[m.program]\nstart = [\"G00 X0. Y0. Z100.\"]\n"),
              HasSubstr("'G00 X0. Y0. Z100.' moves X to a position in the part's coordinates (X0)"));
}
