// Lathe: tool nose radius compensation; threading: Fanuc's G76 pass model against hand-worked depths, THREAD sections posted
// as G76, G92 per pass or G32 moves as the machine allows (exact blocks), constant surface
// speed held at one speed while threading, the lead's rounding refused, the reader running
// G32/G92/G76, and verify refusing a thread the program cuts wrong.
#include <cmath>
#include <cstdio>

#include "helpers.h"
#include "thread_cl.h"
#include "ir/thread_model.h"
#include "readback/gcode_interp.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

std::string blocks(const std::string& program, const std::string& from, const std::string& to = "N") {
  size_t a = program.find(from);
  if (a == std::string::npos) return program;
  size_t e = program.find("M05", a);
  return program.substr(a, e == std::string::npos ? std::string::npos : e - a);
}

}  // namespace

TEST(ThreadModel, G76DepthsAreFanucsSquareRootInfeed) {
  thread_model::Multi p{0.92, 0.3, 0, 0.05, 2};
  std::vector<double> d = thread_model::depths(p);
  ASSERT_EQ(d.size(), 11u);
  // 0.3·√n while below k − d = 0.87: n = 1..8 (0.3·√9 = 0.9 is not), then 0.87, then 0.92 twice.
  const double want[] = {0.3, 0.424264, 0.519615, 0.6, 0.670820, 0.734847, 0.793725, 0.848528, 0.87, 0.92, 0.92};
  for (size_t i = 0; i < d.size(); ++i) EXPECT_NEAR(d[i], want[i], 1e-6) << i;
  // The smallest step: 0.5196 − 0.4243 = 0.095 < 0.1, so from the third pass on it steps by 0.1.
  p.min_step = 0.1;
  d = thread_model::depths(p);
  const double clamped[] = {0.3, 0.424264, 0.524264, 0.624264, 0.724264, 0.824264, 0.87, 0.92, 0.92};
  ASSERT_EQ(d.size(), 9u);
  for (size_t i = 0; i < d.size(); ++i) EXPECT_NEAR(d[i], clamped[i], 1e-6) << i;
  EXPECT_TRUE(thread_model::depths({0.5, 0.6, 0, 0.6, 1}).empty());  // allowance not below the height
  EXPECT_TRUE(thread_model::depths({1, 1e-9, 0, 0.1, 1}).empty());   // more than 10000 passes
}

TEST(ThreadModel, G76RunsEachPassAsABoxFromTheStart) {
  const auto steps = thread_model::multi({15, 0, 5}, {9.08, 0, -20}, {0.92, 0.6, 0, 0.1, 1});
  // Depths 0.6, 0.82 (k − d), 0.92; crest 10.
  ASSERT_EQ(steps.size(), 12u);
  EXPECT_EQ(steps[0].to, ir::Vec3(9.4, 0, 5));
  EXPECT_FALSE(steps[0].cut);
  EXPECT_EQ(steps[1].to, ir::Vec3(9.4, 0, -20));
  EXPECT_TRUE(steps[1].cut);
  EXPECT_EQ(steps[2].to, ir::Vec3(15, 0, -20));
  EXPECT_EQ(steps[3].to, ir::Vec3(15, 0, 5));
  EXPECT_NEAR(steps[5].to.x(), 9.18, 1e-12);
  EXPECT_NEAR(steps[9].to.x(), 9.08, 1e-12);
}

TEST(Threads, PassesOfFanucsModelBecomeOneG76) {
  Compiled c = compile_text(thread_cl(g76_depths()), machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(blocks(c.output, "N50 "),
            "N50 G00 X30. Z5.\n"
            "N60 G76 P020000 Q1 R0.05\n"
            "N70 G76 X18.16 Z-20. P920 Q300 F1.5\n"
            "N80 G00 X60. Z30.\n"
            "N90 ");
  EXPECT_THAT(c.diags, HasSubstr("11 thread cuts checked"));
}

TEST(Threads, WithoutG76EachPassIsAG92) {
  Compiled c = compile_text(thread_cl({0.3, 0.6, 0.8, 0.92}), machine("my-lathe", "[my-lathe]\ninherits = \"fanuc-lathe\"\n[my-lathe.codes]\nthread_multi = \"\"\n"),
                            {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(blocks(c.output, "N50 "),
            "N50 G00 X30. Z5.\n"
            "N60 G92 X19.4 Z-20. F1.5\n"
            "N70 G92 X18.8 Z-20. F1.5\n"
            "N80 G92 X18.4 Z-20. F1.5\n"
            "N90 G92 X18.16 Z-20. F1.5\n"
            "N100 G00 X60. Z30.\n"
            "N110 ");
}

TEST(Threads, PassesThatAreNotFanucsModelBecomeG92) {
  // Constant depth per pass is not G76's √n infeed: G92 per pass, not a G76 that cuts otherwise.
  Compiled c = compile_text(thread_cl({0.2, 0.4, 0.6, 0.8, 0.92}), machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N60 G92 X19.6 Z-20. F1.5\nN70 G92 X19.2 Z-20. F1.5\n"));
  EXPECT_THAT(c.output, Not(HasSubstr("G76")));
}

TEST(Threads, FlankInfeedIsG92FromEachPassesStart) {
  // Each pass starts further along Z (an infeed along the flank): G76 with radial infeed would
  // cut otherwise, so each pass is a G92 from its own start.
  Compiled c = compile_text(thread_cl({0.3, 0.6, 0.92}, "SPINDL/RPM,800,CLW", {5, 4.85, 4.6}), machine("fanuc-lathe"),
                            {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(blocks(c.output, "N50 "),
            "N50 G00 X30. Z5.\n"
            "N60 G92 X19.4 Z-20. F1.5\n"
            "N70 G00 Z4.85\n"
            "N80 G92 X18.8 Z-20. F1.5\n"
            "N90 G00 Z4.6\n"
            "N100 G92 X18.16 Z-20. F1.5\n"
            "N110 G00 X60. Z30.\n"
            "N120 ");
}

// A pass that feeds out of the thread (it may touch) is no G92 box, which pulls out at rapid:
// the box made the fed pull-out a rapid. The passes stay G32 and G01, and verify takes each
// pull-out as the one after its own pass (all lie on one line: the first pass's is not the last's).
TEST(Threads, APassThatFeedsOutIsNoBox) {
  std::string cl = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/12,0,5\nTHREAD/TURN,LEAD,1.5,MMPR\n";
  for (const char* x : {"9.7", "9.4", "9.08"})
    cl += std::string("RAPID\nGOTO/") + x + ",0,5\nFEDRAT/1.5,MMPR\nGOTO/" + x + ",0,-20\nGOTO/12,0,-20\nRAPID\nGOTO/12,0,5\n";
  cl += "THREAD/OFF\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr("3 groove cuts, 3 thread cuts checked"));
  EXPECT_THAT(c.output, HasSubstr("N60 X19.4\nN70 G32 Z-20. F1.5\nN80 G99 G01 X24. F1.5\nN90 G00 Z5.\n"));
  // The last pass's pull-out made at rapid is caught, though the first pass's lies on it.
  std::string rapid_out = c.output;
  const size_t last = rapid_out.rfind("G01 X24.");
  rapid_out.replace(last, 3, "G00");
  Compiled rapid = verify_text(cl, machine("fanuc-lathe"), rapid_out);
  EXPECT_FALSE(rapid.ok);
  EXPECT_THAT(rapid.diags, HasSubstr("is made at rapid traverse (G00)"));
  EXPECT_EQ(c.output.find("G92"), std::string::npos);
  EXPECT_EQ(c.output.find("G76"), std::string::npos);
}

TEST(Threads, WithoutCyclesEachCutIsG32) {
  Compiled c = compile_text(thread_cl({0.3, 0.92}),
                            machine("my-lathe", "[my-lathe]\ninherits = \"fanuc-lathe\"\n[my-lathe.codes]\nthread_multi = \"\"\nthread_box = \"\"\n"),
                            {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(blocks(c.output, "N50 "),
            "N50 G00 X30. Z5.\n"
            "N60 X19.4\n"
            "N70 G32 Z-20. F1.5\n"
            "N80 G00 X30.\n"
            "N90 Z5.\n"
            "N100 X18.16\n"
            "N110 G32 Z-20. F1.5\n"
            "N120 G00 X30.\n"
            "N130 Z5.\n"
            "N140 X60. Z30.\n"
            "N150 ");
}

TEST(Threads, SurfaceSpeedIsHeldAtOneSpeedWhileThreading) {
  // 120 m/min at the crest (20 mm): 1909.86 rpm, written 1909; G96 again after THREAD/OFF.
  Compiled c = compile_text(thread_cl(g76_depths(), "SPINDL/SMM,120,CLW,MAXRPM,2000"), machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(blocks(c.output, "N40 "),
            "N40 G50 S2000\n"
            "N50 G96 S120 M03\n"
            "N60 G00 X30. Z5.\n"
            "N70 G97 S1909 M03\n"
            "N80 G76 P020000 Q1 R0.05\n"
            "N90 G76 X18.16 Z-20. P920 Q300 F1.5\n"
            "N100 G96 S120 M03\n"
            "N110 G00 X60. Z30.\n"
            "N120 ");
  // The clamp caps it: 60 m/min at 20 mm is 954 rpm, under a 500 rpm clamp 500.
  Compiled low = compile_text(thread_cl(g76_depths(), "SPINDL/SMM,60,CLW,MAXRPM,500"), machine("fanuc-lathe"));
  EXPECT_THAT(low.output, HasSubstr("G97 S500 M03\n"));
}

TEST(Threads, ALeadThatRoundingWouldChangeIsRefused) {
  // 13 threads per inch, 0.0769231 in, written with 3 decimals: F0.077, 0.0000769 a turn,
  // 25 mm (0.98425 in, 12.8 turns) end 0.000984 in off: more than the path tolerance (arcs.tolerance,
  // 0.0002 in).
  std::string cl = thread_cl({0.3, 0.92});
  cl.replace(cl.find("THREAD/TURN,1.5"), 15, "THREAD/TURN,0.0769231,IPR");
  Compiled c = compile_text(cl, machine("my-lathe", "[my-lathe]\ninherits = \"fanuc-lathe\"\nunits = \"inch\"\n[my-lathe.feeds]\nlead = { decimals = 3 }\n"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("error: the thread's lead of 0.0769231 in would be written F0.077 (feeds.lead: 3 decimals): "
                                 "the thread would end 0.000984 off; give feeds.lead more decimals"));
  // The default (6 decimals in inches) keeps it.
  Compiled ok = compile_text(cl, machine("my-lathe", "[my-lathe]\ninherits = \"fanuc-lathe\"\nunits = \"inch\"\n"), {.certify = true});
  EXPECT_TRUE(ok.ok) << ok.diags;
  EXPECT_THAT(ok.output, HasSubstr("F0.076923\n"));
  // On the metric lathe (4 decimals) it is F1.9538, 0.0006 mm off over 25 mm: within its path
  // tolerance (0.005 mm), as any post writes it.
  Compiled metric = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  EXPECT_TRUE(metric.ok) << metric.diags;
  EXPECT_THAT(metric.output, HasSubstr(" F1.9538\n"));
}

TEST(Threads, TheReaderRunsG32G92AndG76) {
  Machine m = machine("fanuc-lathe");
  gcode::Result r = gcode::interpret(
      "G97 S800 M03\nG00 X30. Z5.\nG92 X19.4 Z-20. F1.5\nX19.\nG76 P010000 Q1 R0.1\nG76 X18.16 Z-20. P920 Q600 F1.5\n"
      "G00 X19.4\nG32 Z-20. F1.5\n",
      m);
  EXPECT_TRUE(r.problems.empty()) << r.problems[0].message;
  std::vector<std::pair<double, double>> cuts;  // (diameter, lead) of each synchronised cut
  for (const auto& s : r.segments)
    if (s.thread) cuts.emplace_back(std::round(s.end.x() * 2 * 1000) / 1000, s.feed);
  // G92 twice; G76: depths 0.6, 0.82 (k − d), 0.92 below the crest at 20 mm; G32 once.
  ASSERT_EQ(cuts.size(), 6u);
  const double want[] = {19.4, 19.0, 18.8, 18.36, 18.16, 19.4};
  for (size_t i = 0; i < cuts.size(); ++i) {
    EXPECT_DOUBLE_EQ(cuts[i].first, want[i]) << i;
    EXPECT_DOUBLE_EQ(cuts[i].second, 1.5) << i;
  }
  gcode::Result css = gcode::interpret("G50 S2000\nG96 S120 M03\nG00 X30. Z5.\nG92 X19.4 Z-20. F1.5\n", m);
  ASSERT_EQ(css.problems.size(), 1u);
  EXPECT_EQ(css.problems[0].message, "thread cut under constant surface speed (G96): the passes would not meet; G97 first");
  gcode::Result flank = gcode::interpret("G97 S800 M03\nG00 X30. Z5.\nG76 P010060 Q1 R0.1\n", m);
  ASSERT_EQ(flank.problems.size(), 1u);
  EXPECT_EQ(flank.problems[0].message, "G76 with a tool angle (P....aa, flank infeed): clpc's reader runs radial infeed only");
}

TEST(Threads, VerifyRefusesAThreadCutWrong) {
  TempDir t;
  write_file(t.path("thread.cls"), thread_cl(g76_depths()));
  ASSERT_EQ(run_clpc("compile " + t.path("thread.cls") + " -t fanuc-lathe -o " + t.path("good.nc")).status, 0);
  const std::string good = read_file(t.path("good.nc"));
  auto verify = [&](const std::string& program) {
    write_file(t.path("bad.nc"), program);
    return run_clpc("verify " + t.path("thread.cls") + " -t fanuc-lathe --program " + t.path("bad.nc"));
  };
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string p = good;
    p.replace(p.find(from), from.size(), to);
    return p;
  };
  EXPECT_EQ(verify(good).status, 0);
  // The thread 0.02 mm too deep (k 0.94): every pass deeper than the CL's.
  RunResult deep = verify(replaced("P920 Q300", "P940 Q300"));
  EXPECT_NE(deep.status, 0);
  EXPECT_THAT(deep.err, HasSubstr("is not made: the program's nearest thread cut passes 0.02000 from it"));
  // Another lead.
  RunResult lead = verify(replaced("Q300 F1.5", "Q300 F1.25"));
  EXPECT_NE(lead.status, 0);
  EXPECT_THAT(lead.err, HasSubstr("at a lead of F1.250000 where the CL's is 1.500000"));
  // A plain feed where the CL threads.
  std::string g01 = compile_text(thread_cl({0.3, 0.92}), machine("my-lathe", "[my-lathe]\ninherits = \"fanuc-lathe\"\n[my-lathe.codes]\nthread_multi = \"\"\nthread_box = \"\"\n")).output;
  write_file(t.path("thread.cls"), thread_cl({0.3, 0.92}));
  g01.replace(g01.find("G32 Z-20. F1.5"), 14, "G01 Z-20. F1.5");
  RunResult plain = verify(g01);
  EXPECT_NE(plain.status, 0);
  EXPECT_THAT(plain.err, HasSubstr("is made by a block not synchronised with the spindle (not G32/G92/G76)"));
}

TEST(Threads, DifferentialFindingsAreCertified) {
  // Found by the differential sweep (fuzz/cl_generator.h threads): a thread cut 0.003 mm long
  // that verify skipped as "no move" while the program cut it (G32 Z-19.054 from Z-19.057),
  // and a face thread's last rapid whose two ends lie on the CIRCLE after THREAD/OFF, taken
  // for that arc cut at rapid.
  for (const char* f : {"thread_cut_shorter_than_tolerance.cls", "thread_rapid_ends_on_next_arc.cls",
                        "thread_rapid_ends_on_next_arc_2.cls"}) {
    Compiled c = compile_path(std::string(CLPC_SOURCE_DIR) + "/tests/fuzz_regressions/" + f, machine("fanuc-lathe"),
                              {.certify = true});
    EXPECT_TRUE(c.ok) << f << "\n" << c.diags;
    EXPECT_THAT(c.diags, HasSubstr("thread cuts checked")) << f;
  }
}

TEST(NoseRadius, CutcomIsG41G42OnTheNextStraightMove) {
  const std::string head = "UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,1\nSPINDL/RPM,800,CLW\nFEDRAT/MMPR,0.2\nRAPID\nGOTO/30,0,5\n";
  Compiled c = compile_text(head + "CUTCOM/RIGHT\nGOTO/20,0,2\nGOTO/20,0,-20\nCUTCOM/OFF\nGOTO/30,0,-20\nFINI\n", machine("fanuc-lathe"),
                            {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(blocks(c.output, "N50 "),
            "N50 G00 X60. Z5.\n"
            "N60 G42 G99 G01 X40. Z2. F0.2\n"
            "N70 Z-20.\n"
            "N80 G40 X60.\n"
            "N90 ");
  Compiled arc = compile_text(head + "CUTCOM/LEFT\nCIRCLE/20,0,5,0,1,0,10\nGOTO/20,0,-5\nFINI\n", machine("fanuc-lathe"));
  EXPECT_FALSE(arc.ok);
  EXPECT_THAT(arc.diags, HasSubstr(":9:1: error: tool nose radius compensation (CUTCOM) starts or ends on an arc: the control "
                                   "needs a straight move (G00/G01) for it; have the CAM system turn it on or off before a line"));
}

// A control that views the ZX plane from -Y (lathe.arcs_seen_from = "-Y") turns G02 and G03 the
// other way, and left and right of the path with them. The G42 was kept (the nose radius
// offset to the wrong side with --no-verify), and verify read G03 as +Y's, refusing every arc.
TEST(NoseRadius, SeenFromMinusYArcsAndSidesSwapAndReadBack) {
  const std::string cl = "UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,1\nSPINDL/RPM,800,CLW\nFEDRAT/MMPR,0.2\nRAPID\nGOTO/10,0,2\n"
                         "CUTCOM/RIGHT\nGOTO/10,0,-20\nCIRCLE/15,0,-20,0,-1,0,5\nGOTO/15,0,-25\nGOTO/20,0,-25\nCUTCOM/OFF\n"
                         "RAPID\nGOTO/50,0,5\nFINI\n";
  Compiled plus = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(plus.ok) << plus.diags;
  EXPECT_THAT(plus.output, HasSubstr("G42 G99 G01 Z-20. F0.2\nN70 G02 X30. Z-25. I5. K0.\n"));
  Compiled minus = compile_text(cl, machine("rear-lathe", "[rear-lathe]\ninherits = \"fanuc-lathe\"\n[rear-lathe.lathe]\narcs_seen_from = \"-Y\"\n"), {.certify = true});
  ASSERT_TRUE(minus.ok) << minus.diags;
  EXPECT_THAT(minus.output, HasSubstr("G41 G99 G01 Z-20. F0.2\nN70 G03 X30. Z-25. I5. K0.\n"));
}

TEST(Threads, AFeedAndACommentAmongThePassesOutliveTheCycle) {
  // A FEDRAT among the passes the G76 replaced still sets the feed in force after the thread,
  // and a comment there is still written (both were dropped with the moves).
  std::string cl = thread_cl(g76_depths());
  cl.replace(cl.find("GOTO/9.7000,0,-20\n"), 0, "FEDRAT/MMPR,0.15\nPPRINT FIRST PASS\n");
  cl.replace(cl.find("THREAD/OFF\nRAPID\n"), 17, "THREAD/OFF\n");
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(blocks(c.output, "N50 "),
            "N50 G00 X30. Z5.\n"
            "N60 G76 P020000 Q1 R0.05\n"
            "N70 G76 X18.16 Z-20. P920 Q300 F1.5\n"
            "(FIRST PASS)\n"
            "N80 G99 G01 X60. Z30. F0.15\n"
            "N90 ");
}

TEST(Threads, AThreadWithoutOffEndsWhereTheNextBegins) {
  // Two threads, the first without THREAD/OFF: a warning, and each section is read on its own
  // (the first's passes one G76, the second's too), the program certified.
  std::string one = thread_cl(g76_depths());
  const std::string passes = one.substr(one.find("THREAD/TURN"), one.find("THREAD/OFF") - one.find("THREAD/TURN"));
  std::string cl = one;
  cl.replace(cl.find("THREAD/OFF"), 0, "RAPID\nGOTO/15,0,5\n" + passes);
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr("warning: THREAD replaces a thread still on (no THREAD/OFF before it)"));
  EXPECT_THAT(c.output, HasSubstr("N70 G76 X18.16 Z-20. P920 Q300 F1.5\nN80 G76 P020000 Q1 R0.05\nN90 G76 X18.16 Z-20. P920 Q300 F1.5\n"));
  EXPECT_THAT(c.diags, HasSubstr("22 thread cuts checked"));
}

// A lathe's tool works on one side of the spindle axis (that of its first position off it): a
// feed that ends further past it than a facing cut's nose radius is refused (1 mm for a drill,
// 13 mm or the corner radius and 1 mm for other tools: round inserts reach R12). An NX file
// with the XM-YM lathe work plane gives a centre drill's plunge along its X: it was fed through
// the centre to X-50, certified (helper-45). A facing cut that ends a nose radius past the centre,
// tools that work at minus X (a gang-tool lathe), one on each side, and arcs are judged so too
// (helper-46).
TEST(LatheMotion, AFeedFarPastTheSpindleAxisIsRefused) {
  const std::string head = "UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,2\nSPINDL/RPM,800,CLW\nFEDRAT/MMPR,0.1\nRAPID\n";
  const std::string drill = "UNITS/MM\nMACHIN/TURN\nTLDATA/DRILL,10,0,50,118,0\nLOAD/TOOL,2\nSPINDL/RPM,800,CLW\n"
                            "FEDRAT/MMPR,0.1\nRAPID\n";
  for (const std::string& cl : {head + "GOTO/50,0,0\nRAPID\nGOTO/3,0,0\nGOTO/-25,0,0\n",
                                head + "GOTO/2,0,0\nGOTO/-25,0,0\n",
                                head + "GOTO/10,0,2\nGOTO/20,0,0\nCIRCLE/0,0,0,0,1,0,20\nGOTO/-20,0,0\n"}) {
    Compiled c = compile_text(cl, machine("fanuc-lathe"));
    EXPECT_FALSE(c.ok) << cl;
    EXPECT_THAT(c.diags, HasSubstr(" past the spindle axis from the side this tool works on: a lathe's tool cuts on one "
                                   "side of it")) << cl;
  }
  // A tool that cuts along the axis is never fed along X, through the centre or not (the part's
  // face off X0 in an XM-YM file; helper-47).
  for (const char* kind : {"DRILL", "CENTER", "SPOT", "TAP"})
    for (const char* moves : {"GOTO/2,0,0\nGOTO/-3,0,0\n", "GOTO/103,0,0\nGOTO/80,0,0\n"}) {
      std::string cl = drill + moves;
      cl.replace(cl.find("DRILL"), 5, kind);
      Compiled c = compile_text(cl, machine("fanuc-lathe"));
      EXPECT_FALSE(c.ok) << cl;
      EXPECT_THAT(c.diags, HasSubstr(":9:1: error: a " + std::string(kind) + " tool fed along X, from radius ")) << cl;
    }
  Compiled at = compile_text(head + "GOTO/50,0,0\nRAPID\nGOTO/3,0,0\nGOTO/-25,0,0\n", machine("fanuc-lathe"));
  EXPECT_THAT(at.diags, HasSubstr(":10:1: error: a feed to radius -25, 25 past the spindle axis"));
  // An arc whose end is on the tool's side, over a circle centred past the axis: judged by its
  // end alone it went 38 past, certified (helper-54). Its furthest reach counts.
  Compiled over = compile_text(head + "GOTO/10,0,8.2462\nGOTO/1,0,6.2450\nCIRCLE/-18,0,0,0,-1,0,20\nGOTO/1,0,-6.2450\n",
                               machine("fanuc-lathe"));
  EXPECT_THAT(over.diags, HasSubstr(":9:1: error: an arc reaching radius -38, 38 past the spindle axis"));
  // The same circle the short way round, under it, stays on the tool's side.
  Compiled under = compile_text(head + "GOTO/10,0,8.2462\nGOTO/1,0,6.2450\nCIRCLE/-18,0,0,0,1,0,20\nGOTO/1,0,-6.2450\n"
                                "GOTO/30,0,-6.2450\n",
                                machine("fanuc-lathe"), {.certify = true});
  EXPECT_TRUE(under.ok) << under.diags;
  for (const std::string& cl :
       {head + "GOTO/30,0,2\nGOTO/30,0,0\nGOTO/-0.8,0,0\nGOTO/-0.8,0,2\nRAPID\nGOTO/0,0,1\nGOTO/0,0,-1\nGOTO/12,0,-1\n",
        head + "GOTO/60,0,2\nGOTO/60,0,0\nGOTO/-6,0,0\nGOTO/-6,0,2\n",  // a round insert's R6
        head + "GOTO/-30,0,2\nGOTO/-30,0,0\nGOTO/0.8,0,0\nGOTO/-20,0,0\n",
        head + "GOTO/-30,0,2\nGOTO/-30,0,0\nGOTO/-10,0,0\nRAPID\nGOTO/-40,0,5\nLOAD/TOOL,4\nRAPID\nGOTO/30,0,2\n"
               "GOTO/30,0,-5\nGOTO/20,0,-5\nGOTO/30,0,-5\n",
        drill + "GOTO/0,0,5\nGOTO/0,0,-20\n",
        head + "GOTO/-0.8,0,2\nGOTO/-0.8,0,0\nGOTO/30,0,0\nGOTO/30,0,2\n"}) {  // a face cut from just past the centre
    Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
    EXPECT_TRUE(c.ok) << cl << c.diags;
  }
}

// Turning motion outside the XZ plane (an NX lathe work plane other than ZM-XM, a mill file
// posted for a lathe) is refused at each record, with the rule and where to set it.
TEST(LatheMotion, OutsideTheXzPlaneIsRefusedWithTheRule) {
  Compiled c = compile_text("UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,1\nSPINDL/RPM,800,CLW\nFEDRAT/MMPR,0.2\nRAPID\nGOTO/10,30,0\n",
                            machine("fanuc-lathe"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":7:1: error: lathe motion must lie in the XZ plane (Y = 0), found Y = 30: the CL must "
                                 "give turning motion with X the radius and Z along the spindle (in NX, the lathe work "
                                 "plane ZM-XM)\n"));
  // Once per record: an arc from a point off the plane is cut in pieces, each off it (18 errors).
  Compiled arc = compile_text("UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,1\nSPINDL/RPM,800,CLW\nFEDRAT/MMPR,0.2\nGOTO/10,3,-20\n"
                              "CIRCLE/15,0,-20,0,-1,0,5\nGOTO/15,0,-25\n",
                              machine("fanuc-lathe"));
  size_t errors = 0;
  for (size_t at = arc.diags.find("error: lathe motion must lie"); at != std::string::npos;
       at = arc.diags.find("error: lathe motion must lie", at + 1))
    ++errors;
  EXPECT_EQ(errors, 2u) << arc.diags;  // the GOTO, and the arc
}

// A lathe of Fanuc's G-code system B (G33/G78 thread, G92 clamp, G94/G95 feeds), described in
// TOML: the program uses its codes, and verify reads them as that control runs them (the reader
// knew system A only and refused every such program).
TEST(Threads, ALatheOfGCodeSystemBIsWrittenAndReadInItsOwnCodes) {
  const std::string toml =
      "[lathe-b]\ninherits = \"fanuc-lathe\"\n[lathe-b.program]\nsafe_start = [\"G00 G18 G40 G80 G95\"]\n"
      "[lathe-b.codes]\nfeed_per_minute = \"G94\"\nfeed_per_rev = \"G95\"\nthread = \"G33\"\nthread_box = \"G78\"\n"
      "thread_multi = \"\"\nspindle_clamp = \"G92 S{max}\"\n";
  std::string cl = thread_cl({0.3, 0.92}, "SPINDL/SMM,120,CLW,MAXRPM,2000");
  cl.replace(cl.find("RAPID\nGOTO/15,0,5\n"), 18, "RAPID\nGOTO/15,0,5\nGOTO/10,0,2\nGOTO/10,0,-10\nFEDRAT/100,MMPM\nGOTO/14,0,-10\nRAPID\nGOTO/15,0,5\n");
  Compiled c = compile_text(cl, machine("lathe-b", toml), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(blocks(c.output, "N40 "),
            "N40 G92 S2000\n"
            "N50 G96 S120 M03\n"
            "N60 G00 X30. Z5.\n"
            "N70 G95 G01 X20. Z2. F0.2\n"
            "N80 Z-10.\n"
            "N90 G94 X28. F100.\n"
            "N100 G00 X30. Z5.\n"
            "N110 G97 S1968 M03\n"  // 120 m/min at the first pass's 19.4 mm
            "N120 G78 X19.4 Z-20. F1.5\n"
            "N130 G78 X18.16 Z-20. F1.5\n"
            "N140 G96 S120 M03\n"
            "N150 G00 X60. Z30.\n"
            "N160 ");
  EXPECT_THAT(c.diags, HasSubstr("2 thread cuts checked"));
  // Read as system A, G95 was an unknown code; read as system B, a feed per minute written
  // where the CL feeds per revolution is still caught.
  std::string wrong = c.output;
  wrong.replace(wrong.find("G95 G01"), 3, "G94");
  Compiled bad = verify_text(cl, machine("lathe-b", toml), wrong);
  EXPECT_FALSE(bad.ok);
  EXPECT_THAT(bad.diags, HasSubstr("the block feeds per minute, the CL's FEDRAT"));
}

// A dwell's X is seconds, whatever the X of a diameter lathe is scaled by: G04 X{seconds}
// wrote X1. for a 0.5 s dwell (twice as long), and verify refused its own program.
TEST(LatheMotion, ADwellWrittenWithXIsSecondsOnADiameterLathe) {
  const std::string toml = "[lathe-x]\ninherits = \"fanuc-lathe\"\n[lathe-x.codes]\ndwell = \"G04 X{seconds}\"\n";
  const std::string cl =
      "PARTNO/DWELL\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/15,0,5\n"
      "GOTO/10,0,1\nGOTO/10,0,-10\nDELAY/0.5\nGOTO/14,0,-10\nEND\nFINI\n";
  Compiled c = compile_text(cl, machine("lathe-x", toml), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr(" G04 X0.5\n"));
  EXPECT_THAT(c.output, Not(HasSubstr("G04 X1.")));
  EXPECT_THAT(c.diags, HasSubstr("certified"));
}

// DELAY/REV under constant surface speed: the control holds 100 m/min at the groove's bottom,
// 32 mm across: 994.7 rpm, so 3 turns take 0.181 s. It was refused (helper-54).
TEST(LatheMotion, ADwellInRevolutionsUnderSurfaceSpeed) {
  const std::string cl = "UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,1\nSPINDL/SMM,100,MAXRPM,1500,CLW\nFEDRAT/MMPR,0.1\nRAPID\n"
                         "GOTO/20,0,-15\nGOTO/16,0,-15\nDELAY/REV,3\nGOTO/20,0,-15\nRAPID\nGOTO/30,0,5\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr(" G04 U0.181\n"));
  // Near the axis the clamp holds: 1500 rpm, 0.12 s.
  std::string near = cl;
  near.replace(near.find("GOTO/16,0,-15"), 13, "GOTO/5,0,-15");
  Compiled clamped = compile_text(near, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(clamped.ok) << clamped.diags;
  EXPECT_THAT(clamped.output, HasSubstr(" G04 U0.12\n"));
  // Drilling on centre the speed is fixed (G97 S1909 for 60 m/min on the 10 mm drill): 3 turns
  // take 0.094 s. It was refused, the dwell timed at the S of no SPINDL/RPM (helper-55).
  const std::string drill = "UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,1\nTLDATA/DRILL,10,0,50\nSPINDL/SMM,60,MAXRPM,3000,CLW\n"
                            "FEDRAT/MMPR,0.1\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-20\nDELAY/REV,3\nGOTO/0,0,5\nRAPID\nGOTO/50,0,50\nFINI\n";
  Compiled fixed = compile_text(drill, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(fixed.ok) << fixed.diags;
  EXPECT_THAT(fixed.output, HasSubstr(" G97 S1909 M03\n"));
  EXPECT_THAT(fixed.output, HasSubstr(" G04 U0.094\n"));
}

// A MAXRPM holds until another is given: a later SPINDL/SMM without one raised G50 S1500 to the
// machine's S3000 with only a warning (helper-59).
TEST(LatheMotion, AClampHoldsUntilAnotherIsGiven) {
  const std::string cl = "UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,2\nSPINDL/SMM,200,CLW,MAXRPM,1500\nRAPID\nGOTO/22,0,2\n"
                         "FEDRAT/MMPR,0.1\nGOTO/10,0,2\nSPINDL/SMM,150,CLW\nGOTO/10,0,-20\nGOTO/22,0,-20\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N80 G50 S1500\nN90 G96 S150 M03\n"));
  EXPECT_THAT(c.output, Not(HasSubstr("S3000")));
}

// The retract home (G28 U0. W0.) goes out in X and Z at once. After a cut toward the axis or
// the chuck that left the tool short of its cuts' reach in both, it drags the tool through the
// part: a face down a shoulder, then LOADTL, was certified (helper-59). Refused at the record
// that retracts; the program's end is reported at the cut that left the tool there.
TEST(LatheRetract, AToolLeftInThePartIsNotSentHomeDiagonally) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/31,0,2\nFEDRAT/0.2,MMPR\n"
                           "GOTO/31,0,-20\nGOTO/20,0,-20\n";
  const std::string next = "LOADTL/2\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/40,0,5\nEND\n";
  Compiled change = compile_text(head + next, machine("fanuc-lathe"));
  EXPECT_FALSE(change.ok);
  EXPECT_THAT(change.diags,
              HasSubstr("part.cls:9:1: error: the tool change finds the tool at X40 Z-20 after a cut toward the spindle "
                        "axis or the chuck, inside the reach of its cuts (out to X62, forward to Z2): the machine's "
                        "retract G28 U0. W0. goes home in X and Z at once and would drag it through the part; the CL "
                        "must retract the tool clear of the part (a GOTO out of the groove, bore or shoulder) first\n"
                        " 9 | LOADTL/2\n"));
  Compiled ends = compile_text(head + "END\n", machine("fanuc-lathe"));
  EXPECT_FALSE(ends.ok);
  EXPECT_THAT(ends.diags, HasSubstr("part.cls:8:1: error: the program ends at X40 Z-20 after a cut toward the spindle "
                                    "axis or the chuck"));
  // A bore finished down to its floor: the tool stands below its pass's start in Z and inside
  // the bore's largest radius.
  Compiled bore = compile_text("UNITS/MM\nLOADTL/3\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/12,0,2\nFEDRAT/0.1,MMPR\n"
                               "GOTO/12,0,-30\nGOTO/8,0,-30\n" + next, machine("fanuc-lathe"));
  EXPECT_THAT(bore.diags, HasSubstr("part.cls:9:1: error: the tool change finds the tool at X16 Z-30 after a cut"));
  // Clear: the CL's own retract (a rapid, or a feed out of the groove), and a facing pass that
  // ends going out (NIST turn_op10.ncl.4 changes tool at the bar's diameter).
  for (const std::string& out : {std::string("RAPID\nGOTO/33,0,-20\n"), std::string("GOTO/33,0,-20\n"),
                                 std::string("GOTO/20,0,0\nGOTO/32,0,0\n")}) {
    Compiled c = compile_text(head + out + next, machine("fanuc-lathe"), {.certify = true});
    EXPECT_TRUE(c.ok) << out << c.diags;
    EXPECT_THAT(c.output, HasSubstr("G28 U0. W0.\nN")) << out;
  }
  // A face cut to the centre: the face is behind the tool (helper-65 R1). A tool on the minus-X
  // side is judged on its own side's terms, not reset before (helper-65 R2).
  for (const std::string& cl : {std::string("UNITS/MM\nLOADTL/1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/32,0,2\nFEDRAT/0.2,MMPR\n"
                                            "GOTO/32,0,0\nGOTO/-0.8,0,0\n"),
                                std::string("UNITS/MM\nLOADTL/1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/-2,0,2\nFEDRAT/0.2,MMPR\n"
                                            "GOTO/-2,0,0\nGOTO/-32,0,0\n")}) {
    Compiled c = compile_text(cl + next, machine("fanuc-lathe"), {.certify = true});
    EXPECT_TRUE(c.ok) << cl << c.diags;
  }
}
