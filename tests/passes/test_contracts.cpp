// The passes' contracts as code (ir/stage.h, passes/pass.h): the machine loader walks a
// pipeline through them and names the missing pass; --verify-ir checks each established
// fact's invariants; `clpc passes` and docs/passes.md come from the same PassInfo.
#include <cstdlib>
#include <fstream>

#include "helpers.h"
#include "ir/verify.h"
#include "passes/describe.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

// A machine inheriting `base` with its pipeline replaced.
std::string with_pipeline(const std::string& base, const std::string& passes) {
  return "[m]\ninherits = \"" + base + "\"\npipeline = [" + passes + "]\n";
}

}  // namespace

TEST(PipelineCheck, EveryBuiltinPipelineReachesALegalProgram) {
  for (const char* name : {"haas-umc750", "fanuc-mill", "fanuc-lathe"}) EXPECT_EQ(machine_errors("", name), "") << name;
}

TEST(PipelineCheck, ALatheWithoutGrooveCyclesNamesThePass) {
  EXPECT_EQ(first_line(machine_errors(with_pipeline("fanuc-lathe", R"("arc-direction", "helix", "arc-legalise", "drill-cycles")"))),
            "shop.toml:3:12: error: m.pipeline: machine 'm' needs 'groove-cycles' in its pipeline, for the groove cycle records");
}

TEST(PipelineCheck, APassBeforeWhatItRequires) {
  EXPECT_EQ(first_line(machine_errors(with_pipeline("fanuc-mill", R"("helix", "arc-direction", "arc-legalise", "drill-cycles", "offset-table")"))),
            "shop.toml:3:12: error: m.pipeline: 'arc-direction' must come before 'helix'");
  EXPECT_EQ(first_line(machine_errors(with_pipeline("fanuc-mill", R"("arc-legalise", "drill-cycles", "offset-table")"))),
            "shop.toml:3:12: error: m.pipeline: machine 'm' needs 'arc-direction' in its pipeline, for every CIRCLE's sense");
}

// kinematics may take arcs out of the machine's planes: arc-legalise must come after it.
TEST(PipelineCheck, AFactBrokenAndNotMadeAgain) {
  EXPECT_EQ(first_line(machine_errors(with_pipeline(
                "haas-umc750", R"("arc-direction", "helix", "arc-legalise", "drill-cycles", "offset-table", "kinematics", "limits")"))),
            "shop.toml:3:12: error: m.pipeline: 'arc-legalise' must come after 'kinematics', which leaves arcs-legal undone");
}

// A machine that states its travel needs the pass that checks it.
TEST(PipelineCheck, TravelStatedButNotChecked) {
  EXPECT_EQ(first_line(machine_errors(with_pipeline(
                "haas-umc750", R"("arc-direction", "helix", "drill-cycles", "offset-table", "kinematics", "arc-legalise")"))),
            "shop.toml:3:12: error: m.pipeline: machine 'm' needs 'limits' in its pipeline, to check every position against "
            "the machine's travel");
}

// --- the IR verifier: each fact's invariants, once established ------------------------------

namespace {

ir::Operation op_with(std::vector<ir::Op> body) {
  ir::Operation op;
  op.number = 1;
  for (size_t i = 0; i < body.size(); ++i) op.body.push_back({SourceLoc{uint32_t(i + 1), 1}, std::move(body[i])});
  return op;
}

ir::Move move(ir::MoveKind kind = ir::MoveKind::Feed) {
  ir::Move m;
  m.point = ir::Vec3(1, 2, 3);
  m.axis = ir::Vec3::UnitZ();
  m.kind = kind;
  return m;
}

std::string broken(const ir::Operation& op, ir::Facts facts) {
  std::ostringstream err;
  Diagnostics d(&err);
  verify_operation(op, "the-pass", facts, d);
  return err.str();
}

}  // namespace

TEST(IrVerifier, AnUndecidedArcOnceArcsAreDecided) {
  ir::Arc a;
  a.start = ir::Vec3(1, 0, 0);
  a.end = ir::Vec3(0, 1, 0);
  a.center = ir::Vec3::Zero();
  a.axis = a.tool_axis = ir::Vec3::UnitZ();
  a.radius = 1;
  const ir::Operation op = op_with({a});
  EXPECT_EQ(broken(op, 0), "");
  EXPECT_THAT(broken(op, ir::ArcsDecided),
              HasSubstr("1:1: error: internal: IR invariant broken after pass 'the-pass': undecided arc after the arcs were decided"));
  a.dir = ir::ArcDir::Ccw;
  a.sweep = 90;
  a.extra_turns = 2;
  const ir::Operation turns = op_with({a});
  EXPECT_EQ(broken(turns, ir::ArcsDecided), "");
  EXPECT_THAT(broken(turns, ir::ArcsDecided | ir::ArcsOneTurn), HasSubstr("arc of more than one turn after the turns were split"));
}

TEST(IrVerifier, APlainMoveInsideAFormedCycle) {
  ir::Operation op = op_with({ir::CycleOn{0}, move(), ir::CycleOff{}});
  op.cycles.push_back({});
  EXPECT_EQ(broken(op, 0), "");  // as lowered: the GOTOs of the cycle
  EXPECT_THAT(broken(op, ir::CyclesFormed), HasSubstr("2:1: error: internal: IR invariant broken after pass 'the-pass': plain move inside a formed cycle"));
  ir::Operation open = op_with({ir::CycleOn{0}, ir::Hole{ir::Vec3(1, 2, 3), ir::Vec3::UnitZ(), 0, 2}});
  open.cycles.push_back({});
  EXPECT_THAT(broken(open, ir::CyclesFormed), HasSubstr("cycle still on at the end of the operation"));
  open.last_chunk = false;  // the next chunk closes it
  EXPECT_EQ(broken(open, ir::CyclesFormed), "");
}

TEST(IrVerifier, GrooveRecordsAndRotaryPositions) {
  const ir::Operation grooves = op_with({ir::GrooveMark{true}, move(), ir::GrooveMark{false}});
  EXPECT_EQ(broken(grooves, ir::CyclesFormed), "");
  EXPECT_THAT(broken(grooves, ir::GroovesFormed), HasSubstr("groove record left after the grooves were formed"));
  ir::Move placed = move();
  placed.has_rotary = true;
  const ir::Operation five = op_with({move(ir::MoveKind::From), placed, move()});
  EXPECT_THAT(first_line(broken(five, ir::Kinematic)),
              testing::EndsWith(":3:1: error: internal: IR invariant broken after pass 'the-pass': move without its rotary positions"));
}

// --- one description: the passes' own PassInfo ------------------------------------------

TEST(PassDocs, ClpcPassesPrintsEveryContract) {
  RunResult r = run_clpc("passes");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, describe_passes());
  EXPECT_THAT(r.out, StartsWith("arc-direction: decide which way each CL arc turns (CW or CCW)\n  expects:    "));
  EXPECT_THAT(r.out, HasSubstr("\n  requires:   arcs-decided, cycles-formed, offsets-assigned\n  provides:   kinematic\n"
                               "  breaks:     arcs-legal\n"));
  for (const PassInfo& p : all_passes())
    EXPECT_THAT(r.out, HasSubstr(std::string(p.name) + ": " + std::string(p.summary) + "\n  expects:    ")) << p.name;
}

// The generated section of docs/passes.md is `clpc passes --markdown`. CLPC_UPDATE_DOCS=1
// rewrites it (then review the diff).
TEST(PassDocs, TheDocsSectionIsGenerated) {
  const std::string path = std::string(CLPC_SOURCE_DIR) + "/docs/passes.md";
  const std::string begin = "<!-- generated: clpc passes --markdown -->\n", end = "<!-- end generated -->";
  std::string doc = read_file(path);
  size_t a = doc.find(begin), b = doc.find(end);
  ASSERT_NE(a, std::string::npos) << "no '" << begin << "' in " << path;
  ASSERT_NE(b, std::string::npos);
  const std::string generated = passes_markdown();
  if (std::getenv("CLPC_UPDATE_DOCS")) {
    doc.replace(a + begin.size(), b - a - begin.size(), generated);
    std::ofstream(path) << doc;
    b = doc.find(end);
  }
  EXPECT_TRUE(doc.substr(a + begin.size(), b - a - begin.size()) == generated)
      << "docs/passes.md is out of date: CLPC_UPDATE_DOCS=1 build/tests/clpc_tests --gtest_filter='PassDocs.*'";
  RunResult r = run_clpc("passes --markdown");
  EXPECT_EQ(r.out, generated);
}
