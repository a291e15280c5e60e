// Lathe grooving: the G74/G75 model, the groove-cycles pass on IR built directly, the
// CYCLE/FACE|RADIUS records, P/Q scaling, and every collapse the corpus produces read back
// and compared with the CL motion it replaced.
#include "readback/gcode_interp.h"
#include "helpers.h"
#include "ir/groove_model.h"
#include "support/text.h"
#include "ir/printer.h"
#include "passes/pass_manager.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

std::string steps_text(const std::vector<groove::Step>& steps) {
  std::string s;
  for (const auto& st : steps)
    s += std::string(st.cut ? "cut " : "rapid ") + num_text(st.to.x()) + "," + num_text(st.to.z()) + "\n";
  return s;
}

// An operation of lathe moves: (x, z, rapid?) in order.
ir::Operation lathe_op(const std::vector<std::tuple<double, double, bool>>& pts, double feed = 0.1) {
  ir::Operation op;
  op.number = 1;
  ir::Feed f;
  f.value = feed;
  f.mode = ir::FeedMode::PerRev;
  op.body.push_back({{1, 1}, f});
  uint32_t line = 2;
  for (auto [x, z, rapid] : pts) {
    ir::Move m;
    m.point = ir::Vec3(x, 0, z);
    m.axis = ir::Vec3::UnitZ();
    m.kind = rapid ? ir::MoveKind::Rapid : ir::MoveKind::Feed;
    op.body.push_back({{line++, 1}, m});
  }
  return op;
}

struct Ran {
  ir::Operation op;
  std::vector<Diagnostic> diags;
  std::string ir;
};

Ran run_pass(ir::Operation op) {
  Machine m = machine("fanuc-lathe");
  Ran r;
  Diagnostics d(nullptr);
  d.set_keep(true);
  ir::ProgramInfo info;
  PassContext ctx{info, m, d};
  auto verify_ir = make_verify_ir();
  PassManager pm(ctx, {"groove-cycles"}, {verify_ir.get()});
  pm.begin();
  pm.run(op);
  std::ostringstream o;
  ir::print_operation(o, op);
  r.ir = o.str();
  r.op = std::move(op);
  r.diags = d.all();
  return r;
}

// Plunges from x = 30 to x = 25 at the given z stations, each in and out along X, with
// rapid shifts at x = 30 between them.
std::vector<std::tuple<double, double, bool>> plunges(const std::vector<double>& zs, double bottom = 25) {
  std::vector<std::tuple<double, double, bool>> p{{32, zs[0], true}, {30, zs[0], false}};
  for (size_t i = 0; i < zs.size(); ++i) {
    if (i) p.emplace_back(30, zs[i], true);
    p.emplace_back(bottom, zs[i], false);
    p.emplace_back(30, zs[i], false);
  }
  return p;
}

size_t count_of(const ir::Operation& op, auto pred) {
  size_t n = 0;
  for (auto& in : op.body) n += pred(in) ? 1 : 0;
  return n;
}

}  // namespace

TEST(GrooveModel, RadialPecksAndShifts) {
  groove::Params p;
  p.retract = 0.5;
  p.x_amount = 2;  // peck along X
  p.z_amount = 3;  // shift along Z
  auto steps = groove::expand(ir::Vec3(30, 0, -10), ir::Vec3(25, 0, -15), p);
  EXPECT_EQ(steps_text(steps),
            "cut 28,-10\nrapid 28.5,-10\ncut 26,-10\nrapid 26.5,-10\ncut 25,-10\nrapid 30,-10\nrapid 30,-13\n"
            "cut 28,-13\nrapid 28.5,-13\ncut 26,-13\nrapid 26.5,-13\ncut 25,-13\nrapid 30,-13\nrapid 30,-15\n"
            "cut 28,-15\nrapid 28.5,-15\ncut 26,-15\nrapid 26.5,-15\ncut 25,-15\nrapid 30,-15\nrapid 30,-10\n");
}

TEST(GrooveModel, FacePlungesAlongZ) {
  groove::Params p;
  p.face = true;
  p.z_amount = 0;  // in one go
  p.x_amount = 2;  // shift along X
  auto steps = groove::expand(ir::Vec3(10, 0, 1), ir::Vec3(14, 0, -3), p);
  EXPECT_EQ(steps_text(steps), "cut 10,-3\nrapid 10,1\nrapid 12,1\ncut 12,-3\nrapid 12,1\nrapid 14,1\ncut 14,-3\nrapid 14,1\nrapid 10,1\n");
}

TEST(GrooveCycles, WiderThanTheToolBecomesOneG75) {
  Ran r = run_pass(lathe_op(plunges({-10, -12, -14, -16})));
  EXPECT_TRUE(r.diags.empty());
  EXPECT_THAT(r.ir, HasSubstr("groove G75 from (30, 0, -10) to (25, 0, -16) retract 0 x 5 z 2 feed 0.1"));
  EXPECT_EQ(count_of(r.op, [](auto& in) { return std::holds_alternative<ir::Move>(in.op); }), 2u);  // approach
}

TEST(GrooveCycles, PlungesInAnyOrderAndPeckedPlunges) {
  // Creo's order: the middle first, then alternating outwards.
  Ran r = run_pass(lathe_op(plunges({-13, -12, -14, -11, -15})));
  EXPECT_THAT(r.ir, HasSubstr("groove G75 from (30, 0, -15) to (25, 0, -11) retract 0 x 5 z 1"));
  // Pecks of 2 with a 0.5 pull-out.
  std::vector<std::tuple<double, double, bool>> p{{32, -10, true}, {30, -10, false}};
  for (double z : {-10.0, -13.0, -16.0}) {
    if (z != -10.0) p.emplace_back(30, z, true);
    p.insert(p.end(), {{28, z, false}, {28.5, z, true}, {26, z, false}, {26.5, z, true}, {25, z, false}, {30, z, true}});
  }
  Ran q = run_pass(lathe_op(p));
  EXPECT_THAT(q.ir, HasSubstr("groove G75 from (30, 0, -10) to (25, 0, -16) retract 0.5 x 2 z 3"));
}

TEST(GrooveCycles, FaceGroove) {
  std::vector<std::tuple<double, double, bool>> p{{10, 3, true}, {10, 1, false}};
  for (double x : {10.0, 11.0, 12.0}) {
    if (x != 10.0) p.emplace_back(x, 1, true);
    p.emplace_back(x, -4, false);
    p.emplace_back(x, 1, true);
  }
  Ran r = run_pass(lathe_op(p));
  EXPECT_THAT(r.ir, HasSubstr("groove G74 from (10, 0, 1) to (12, 0, -4) retract 0 x 1 z 5"));
}

TEST(GrooveCycles, MotionThatIsNoCycleIsLeftAlone) {
  // Uneven spacing.
  Ran a = run_pass(lathe_op(plunges({-10, -12, -15})));
  EXPECT_THAT(a.ir, ::testing::Not(HasSubstr("groove")));
  // Different bottoms: at most two at one depth, not enough for a cycle of plain motion.
  std::vector<std::tuple<double, double, bool>> p = plunges({-10, -12});
  auto more = plunges({-14}, 24);
  p.insert(p.end(), more.begin() + 1, more.end());
  Ran b = run_pass(lathe_op(p));
  EXPECT_THAT(b.ir, ::testing::Not(HasSubstr("groove")));
  // A turning pass (along Z, then away diagonally) is no groove.
  Ran c = run_pass(lathe_op({{30, 2, true}, {25, 2, false}, {25, -20, false}, {30, -18, false}, {30, 2, true},
                             {24, 2, false}, {24, -20, false}, {30, -18, false}}));
  EXPECT_THAT(c.ir, ::testing::Not(HasSubstr("groove")));
  EXPECT_EQ(c.op.body.size(), 9u);
}

TEST(GrooveCycles, AShiftTheClFeedsIsNotMadeARapid) {
  // The cycle shifts at rapid; plain motion that feeds its shifts (at the level, maybe on the
  // stock) keeps them.
  std::vector<std::tuple<double, double, bool>> p = plunges({-10, -12, -14, -16});
  for (auto& [x, z, rapid] : p)
    if (x == 30 && rapid) rapid = false;
  Ran r = run_pass(lathe_op(p));
  EXPECT_THAT(r.ir, ::testing::Not(HasSubstr("groove")));
  EXPECT_EQ(r.op.body.size(), p.size() + 1);  // the feed and every move
}

TEST(GrooveCycles, OnlyStationsWithTheCommonBottomCollapse) {
  std::vector<std::tuple<double, double, bool>> p = plunges({-10, -11, -12, -13});
  auto shallow = plunges({-9}, 27);
  p.insert(p.end(), shallow.begin() + 1, shallow.end());
  Ran r = run_pass(lathe_op(p));
  EXPECT_THAT(r.ir, HasSubstr("groove G75 from (30, 0, -10) to (25, 0, -13)"));
  EXPECT_THAT(r.ir, HasSubstr("feed (27, 0, -9)"));  // the shallow one stays motion
}

// --- records -------------------------------------------------------------------------------

namespace {
const char* kLatheHead = "UNITS/MM\nMACHIN/TURN,1\nTURRET/1\nSPINDL/RPM,600,CLW\nFEDRAT/0.1,MMPR\nRAPID\nGOTO/32,0,-10\n";

std::string groove_blocks(const std::string& cl, const std::string& machine_name = "fanuc-lathe", const std::string& extra = {}) {
  Compiled c = compile_text(cl, machine(machine_name, extra));
  EXPECT_TRUE(c.ok) << c.diags;
  size_t a = c.output.find("G75 R");
  if (a == std::string::npos) a = c.output.find("G74 R");
  if (a == std::string::npos) return c.output;
  size_t b = c.output.find('\n', c.output.find('\n', a) + 1);
  return c.output.substr(a, b - a);
}
}  // namespace

TEST(GrooveRecords, RadiusMetric) {
  std::string cl = std::string(kLatheHead) + "CYCLE/RADIUS,RETRACT,0.5,XAXIS,2,ZAXIS,3,FEED,0.05\nGOTO/30,0,-10\n";
  for (double z : {-10.0, -13.0, -16.0}) {
    if (z != -10.0) cl += "GOTO/30,0," + num_text(z) + "\n";
    cl += "GOTO/25,0," + num_text(z) + "\nGOTO/30,0," + num_text(z) + "\n";
  }
  cl += "CYCLE/OFF\n";
  // X as a diameter; P (X peck) and Q (Z shift) in 0.001 mm without a point.
  EXPECT_EQ(groove_blocks(cl), "G75 R0.5\nN80 G75 X50. Z-16. P2000 Q3000 F0.05");
}

// The seed paper's records are written under the FEDRAT in force: the shifts between plunges
// are feeds in the CL. The record asks for the cycle, which shifts at rapid along its start
// level: verify takes a fed CL shift made by the cycle's own rapid shift, and nothing else.
TEST(GrooveRecords, ARecordsFedShiftsAreMadeByTheCyclesRapidShifts) {
  std::string cl = std::string(kLatheHead) + "CYCLE/RADIUS,RETRACT,0.5,XAXIS,2,ZAXIS,3,FEED,0.05\nGOTO/30,0,-10\n";
  for (double z : {-10.0, -13.0, -16.0}) {
    if (z != -10.0) cl += "GOTO/30,0," + num_text(z) + "\n";  // fed: no RAPID before it
    cl += "GOTO/25,0," + num_text(z) + "\nGOTO/30,0," + num_text(z) + "\n";
  }
  cl += "CYCLE/OFF\nFINI\n";
  Compiled r = verify_text(cl, machine("fanuc-lathe"));
  EXPECT_TRUE(r.ok) << r.diags;
  EXPECT_EQ(groove_blocks(cl), "G75 R0.5\nN80 G75 X50. Z-16. P2000 Q3000 F0.05");
  // The same shifts made by plain G00 blocks (no cycle) are feeds made at rapid.
  Compiled plain = verify_text(cl, machine("fanuc-lathe"),
                               "%\nO2000\nN10 G21\nN20 G00 G18 G40 G80 G99\nN30 T0101\nN40 G97 S600 M03\nN50 G00 X64. Z-10.\n"
                               "N60 G01 X60. F0.1\nN70 X50. F0.05\nN80 X60.\nN90 G00 Z-13.\nN100 G01 X50.\nN110 X60.\n"
                               "N120 G00 Z-16.\nN130 G01 X50.\nN140 X60.\nN150 M05\nN160 M30\n%\n");
  EXPECT_FALSE(plain.ok);
  EXPECT_THAT(plain.diags, HasSubstr("part.cl:12:1: error: groove cut to (30.0000, 0.0000, -13.0000) is made at rapid "
                                     "traverse (G00) [G-code line 11]"));
}

TEST(GrooveRecords, FaceInchKeywordsInAnotherOrder) {
  std::string cl = "UNITS/INCHES\nMACHIN/TURN,1\nTURRET/1\nSPINDL/RPM,600,CLW\nFEDRAT/0.004,IPR\nRAPID\nGOTO/1,0,0.1\n"
                   "CYCLE/FACE,ZAXIS,0.1,FEED,0.002,XAXIS,0.05,RETRACT,0.02\nGOTO/1,0,0.04\n";
  for (double x : {1.0, 1.05, 1.1}) {
    if (x != 1.0) cl += "GOTO/" + num_text(x) + ",0,0.04\n";
    cl += "GOTO/" + num_text(x) + ",0,-0.2\nGOTO/" + num_text(x) + ",0,0.04\n";
  }
  cl += "CYCLE/OFF\n";
  // Metric output from inch data: Q = 0.1 in = 2.54 mm -> Q2540; P = 0.05 in -> P1270.
  EXPECT_EQ(groove_blocks(cl), "G74 R0.508\nN80 G74 X55.88 Z-5.08 P1270 Q2540 F0.0508");
  // An inch machine: least input increment 0.0001 in.
  std::string inch = "[inch-lathe]\ninherits = \"fanuc-lathe\"\nunits = \"inch\"\n[inch-lathe.format]\nX = { decimals = 4, scale = 2.0 }\n"
                     "Z = { decimals = 4 }\nR = { decimals = 4 }\nP = { decimals = 4, point = \"never\" }\nQ = { decimals = 4, point = \"never\" }\n";
  EXPECT_EQ(groove_blocks(cl, "inch-lathe", inch), "G74 R0.02\nN80 G74 X2.2 Z-0.2 P500 Q1000 F0.002");
}

TEST(GrooveRecords, SinglePlunge) {
  std::string cl = std::string(kLatheHead) + "CYCLE/RADIUS,RETRACT,0.3,XAXIS,1.5,ZAXIS,2,FEED,0.05\nGOTO/30,0,-10\n"
                   "GOTO/24,0,-10\nGOTO/30,0,-10\nCYCLE/OFF\n";
  EXPECT_EQ(groove_blocks(cl), "G75 R0.3\nN80 G75 X48. Z-10. P1500 Q2000 F0.05");
}

TEST(GrooveRecords, MotionTheRecordCannotReproduceStaysWithAWarning) {
  // Two bottoms: one cycle cannot cut both.
  std::string cl = std::string(kLatheHead) + "CYCLE/RADIUS,RETRACT,0.3,XAXIS,1.5,ZAXIS,2,FEED,0.05\nGOTO/30,0,-10\n"
                   "GOTO/24,0,-10\nGOTO/30,0,-10\nGOTO/30,0,-12\nGOTO/26,0,-12\nGOTO/30,0,-12\nCYCLE/OFF\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr(":8:1: warning: CYCLE/RADIUS: the motion is not a groove the cycle reproduces; it is written as motion"));
  EXPECT_EQ(c.output.find("G75"), std::string::npos);
  EXPECT_THAT(c.output, HasSubstr("N90 Z-12.\nN100 X52.\nN110 X60.\n"));  // the motion, as it was
}

TEST(GrooveRecords, MalformedRecordsAreErrorsWithTheirLocation) {
  EXPECT_EQ(first_error(lower_text("CYCLE/RADIUS,RETRACT,0.5,XAXIS,2,FEED,0.05\n").diags), "1:1: CYCLE/RADIUS: missing ZAXIS");
  EXPECT_EQ(first_error(lower_text("CYCLE/FACE,RETRACT,0.5,XAXIS,-2,ZAXIS,3\n").diags),
            "1:30: CYCLE: XAXIS must be greater than zero, found -2");
  EXPECT_EQ(first_error(lower_text("CYCLE/RADIUS,RETRACT,0.5,XAXIS,2,ZAXIS,3,SIDEWAYS,1\n").diags),
            "1:42: CYCLE: unknown word 'SIDEWAYS' in a groove cycle");
  EXPECT_EQ(first_error(lower_text("CYCLE/RADIUS,RETRACT,XAXIS,2\n").diags), "1:22: CYCLE: a number must follow RETRACT");
}

// --- the corpus: every collapse read back and compared with the CL it replaced ------------

TEST(GrooveCorpus, EveryCollapseMatchesTheMotionItReplaced) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR;
  Machine m = machine("fanuc-lathe");
  int collapses = 0, cuts_checked = 0;
  for (const std::string& f : corpus_files()) {
    if (!is_lathe_file(f) || f.find("basic_turning") != std::string::npos) continue;  // (loads no tool: refused)
    SCOPED_TRACE(f);
    Compiled c = compile_path(f, m);
    ASSERT_TRUE(c.ok) << c.diags;
    gcode::Result g = gcode::interpret(c.output, m);
    for (auto& p : g.problems) ADD_FAILURE() << "line " << p.line << ": " << p.message;
    // The CL's feed moves (without the groove pass), in mm, as segments.
    Lowered l = lower_text(read_file(f));
    const double k = ir::mm_per_unit(l.info.units) / ir::mm_per_unit(m.units);
    std::vector<std::pair<ir::Vec3, ir::Vec3>> cl_feeds;
    ir::Vec3 at(0, 0, 0);
    for (auto& op : l.ops)
      for (auto& in : op.body)
        if (auto* mv = std::get_if<ir::Move>(&in.op)) {
          if (mv->kind == ir::MoveKind::Feed) cl_feeds.emplace_back(at * k, mv->point * k);
          at = mv->point;
        } else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
          at = a->end;
        }
    auto on_cl = [&](const ir::Vec3& a, const ir::Vec3& b) {
      for (auto& [p, q] : cl_feeds) {
        ir::Vec3 d = q - p;
        double len = d.norm();
        if (len < 1e-12) continue;
        auto dist = [&](const ir::Vec3& x) {
          double t = std::clamp((x - p).dot(d) / (len * len), 0.0, 1.0);
          return (p + t * d - x).norm();
        };
        if (dist(a) <= 0.0011 && dist(b) <= 0.0011) return true;
      }
      return false;
    };
    collapses += g.cycles;
    for (const auto& s : g.segments) {
      if (!s.from_cycle || s.kind != gcode::Segment::Kind::Feed) continue;
      ++cuts_checked;
      EXPECT_TRUE(on_cl(s.start, s.end)) << "cycle cut at G-code line " << s.line << " from " << s.start.transpose() << " to "
                                         << s.end.transpose() << " is no cut of the CL";
    }
    // And every CL cut is made: by a cycle cut or by a feed the program writes.
    for (auto& [p, q] : cl_feeds) {
      bool made = false;
      for (const auto& s : g.segments) {
        if (s.kind == gcode::Segment::Kind::Rapid) continue;
        ir::Vec3 d = s.end - s.start;
        double len = d.norm();
        auto dist = [&](const ir::Vec3& x) {
          if (len < 1e-12) return (x - s.start).norm();
          double t = std::clamp((x - s.start).dot(d) / (len * len), 0.0, 1.0);
          return (s.start + t * d - x).norm();
        };
        if (dist(p) <= 0.0011 && dist(q) <= 0.0011) made = true;
        if (s.kind == gcode::Segment::Kind::Arc && ((s.end - q).norm() <= 0.0011)) made = true;
      }
      EXPECT_TRUE(made) << "CL cut to " << q.transpose() << " is not made";
    }
  }
  std::printf("groove cycles in the corpus: %d, their cuts checked: %d\n", collapses, cuts_checked);
  EXPECT_GE(collapses, 1);
}

// A record's FEED has no unit word. Against plunges fed per minute it was cut per revolution
// (F0.12 where every plunge was 50 mm/min, certified): the motion stays, with the reason. The
// same mode at another value is the cycle's (the seed paper's form), said. A record pecking by
// other than the motion's pecks keeps the motion too.
TEST(GrooveRecords, ARecordThatContradictsItsMotionKeepsTheMotion) {
  auto plunges = [](const std::string& record, const std::string& feed) {
    std::string cl = "UNITS/MM\nMACHIN/TURN,1\nTURRET/1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/12,0,-10\n" + record + "\n" + feed + "\n";
    for (double z : {-10.0, -11.5, -13.0}) {
      cl += "RAPID\nGOTO/12,0," + num_text(z) + "\nGOTO/8,0," + num_text(z) + "\nRAPID\nGOTO/12,0," + num_text(z) + "\n";
    }
    return cl + "CYCLE/OFF\nFINI\n";
  };
  Compiled per_min = compile_text(plunges("CYCLE/RADIUS,RETRACT,0,XAXIS,4,ZAXIS,1.5,FEED,0.12", "FEDRAT/50,MMPM"),
                                  machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(per_min.ok) << per_min.diags;
  EXPECT_THAT(per_min.diags, HasSubstr("part.cls:7:1: warning: CYCLE/RADIUS: the motion is not a groove the cycle reproduces "
                                       "(its FEED is per revolution, and the motion plunges per minute); it is written as motion"));
  EXPECT_EQ(per_min.output.find("G75"), std::string::npos);
  Compiled other = compile_text(plunges("CYCLE/RADIUS,RETRACT,0,XAXIS,4,ZAXIS,1.5,FEED,0.12", "FEDRAT/0.08,MMPR"),
                                machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(other.ok) << other.diags;
  EXPECT_THAT(other.diags, HasSubstr("part.cls:7:1: warning: CYCLE/RADIUS: the cycle cuts at its FEED 0.12, not at the feed "
                                     "the motion plunges at (0.08)"));
  EXPECT_THAT(other.output, HasSubstr("G75 X16. Z-13. P4000 Q1500 F0.12"));
}

// An inch lathe that inherits the metric fanuc-lathe: G75's P (the peck, in least input
// increments) is a length like Q. It kept the metric 3 decimals, and P59 (0.0059 in) pecked
// 10 times too little where the CL asks 1.5 mm (0.0591 in).
TEST(GrooveRecords, AnInchLatheInheritingTheMetricOneWritesThePeckInItsIncrements) {
  const std::string cl = "UNITS/MM\nMACHIN/TURN,1\nTURRET/1\nSPINDL/RPM,600,CLW\nFEDRAT/0.1,MMPR\nRAPID\nGOTO/32,0,-10\n"
                         "CYCLE/RADIUS,RETRACT,0.3,XAXIS,1.5,ZAXIS,2,FEED,0.05\nGOTO/30,0,-10\nGOTO/24,0,-10\nGOTO/30,0,-10\n"
                         "CYCLE/OFF\nFINI\n";
  Compiled c = compile_text(cl, machine("inch-lathe", "[inch-lathe]\ninherits = \"fanuc-lathe\"\nunits = \"inch\"\n"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G75 X1.8898 Z-0.3937 P591 Q787 F0.00197\n"));
}
