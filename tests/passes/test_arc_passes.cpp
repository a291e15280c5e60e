// Unit tests of arc-direction, helix and arc-legalise on IR built directly.
#include <cmath>

#include "helpers.h"
#include "ir/arc_geometry.h"
#include "passes/pass_manager.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

constexpr double kPi = 3.14159265358979323846;

// In-plane unit vectors (u, v) right-handed about `axis`.
void plane_basis(const ir::Vec3& axis, ir::Vec3& u, ir::Vec3& v) {
  if (std::abs(axis.z()) > 0.5) u = ir::Vec3::UnitX();
  else if (std::abs(axis.y()) > 0.5) u = ir::Vec3::UnitZ();
  else u = ir::Vec3::UnitY();
  v = axis.cross(u);
}

struct ArcCase {
  ir::Vec3 axis = ir::Vec3::UnitZ();
  double r = 10;
  double deg = 90;                   // signed: + ccw about axis, - cw
  ir::ArcDir hint = ir::ArcDir::Unknown;
  bool tangent_in = true;            // an incoming cutting move tangent to the true direction
  ir::ArcLayout layout = ir::ArcLayout::NoRadius6;
  double rise = 0;                   // helix: end height above start along the axis
  int extra_turns = 0;
};

ir::Operation make_op(const ArcCase& c) {
  ir::Vec3 u, v;
  plane_basis(c.axis, u, v);
  ir::Vec3 center(5, 6, 7);
  ir::Vec3 start = center + c.r * u;
  double a = c.deg * kPi / 180;
  ir::Vec3 end = center + c.r * (std::cos(a) * u + std::sin(a) * v) + c.rise * c.axis;
  ir::Operation op;
  op.number = 1;
  ir::Move m;
  m.axis = ir::Vec3::UnitZ();
  ir::Vec3 tangent = (c.deg >= 0 ? 1.0 : -1.0) * v;  // at the start (angle 0)
  m.point = c.tangent_in ? ir::Vec3(start - 20 * tangent) : ir::Vec3(start + 20 * c.axis);
  m.kind = ir::MoveKind::Feed;
  op.body.push_back({{1, 1}, m});
  m.point = start;
  op.body.push_back({{2, 1}, m});
  ir::Arc arc;
  arc.start = start;
  arc.end = end;
  arc.center = center;
  arc.axis = c.axis;
  arc.radius = c.r;
  arc.hint = c.hint;
  arc.layout = c.layout;
  arc.tool_axis = ir::Vec3::UnitZ();
  arc.extra_turns = uint16_t(c.extra_turns);
  op.body.push_back({{3, 1}, arc});
  return op;
}

struct Ran {
  ir::Operation op;
  std::vector<Diagnostic> diags;
};

Ran run(ir::Operation op, const std::vector<std::string>& passes, const Machine& m) {
  Ran r;
  Diagnostics d(nullptr);
  d.set_keep(true);
  ir::ProgramInfo info;
  PassContext ctx{info, m, d};
  auto verify_ir = make_verify_ir();
  PassManager pm(ctx, passes, {verify_ir.get()});
  pm.begin();
  pm.run(op);
  r.op = std::move(op);
  r.diags = d.all();
  return r;
}

Machine mill() {
  Machine m = default_machine(Family::Mill, ir::Units::Mm);
  return m;
}

const ir::Arc* arc_at(const ir::Operation& op, size_t i) { return std::get_if<ir::Arc>(&op.body.at(i).op); }

std::vector<const ir::Arc*> arcs(const ir::Operation& op) {
  std::vector<const ir::Arc*> out;
  for (auto& in : op.body)
    if (auto* a = std::get_if<ir::Arc>(&in.op)) out.push_back(a);
  return out;
}

size_t moves(const ir::Operation& op) {
  size_t n = 0;
  for (auto& in : op.body) n += std::holds_alternative<ir::Move>(in.op);
  return n;
}

}  // namespace

// CW and CCW arcs of 10, 179, 181 and 359 degrees in each of the three planes, decided by
// the tangent of the move entering them (no convention to lean on).
TEST(ArcDirection, SweepsInEachPlaneFromGeometry) {
  for (ir::Vec3 axis : std::vector<ir::Vec3>{ir::Vec3::UnitZ(), ir::Vec3::UnitY(), ir::Vec3::UnitX(), -ir::Vec3::UnitZ()}) {
    for (double deg : {10.0, 179.0, 181.0, 359.0}) {
      for (double sign : {1.0, -1.0}) {
        ArcCase c;
        c.axis = axis;
        c.deg = sign * deg;
        Ran r = run(make_op(c), {"arc-direction"}, mill());
        SCOPED_TRACE("axis " + std::to_string(axis.x()) + "," + std::to_string(axis.y()) + "," +
                     std::to_string(axis.z()) + " deg " + std::to_string(c.deg));
        ASSERT_EQ(first_error(r.diags), "");
        const ir::Arc* a = arc_at(r.op, 2);
        ASSERT_NE(a, nullptr);
        EXPECT_EQ(a->dir, sign > 0 ? ir::ArcDir::Ccw : ir::ArcDir::Cw);
        EXPECT_NEAR(a->sweep, deg, 1e-9);
      }
    }
  }
}

// The same arcs with no tangent move: the CAM convention decides (NX: the axis of clockwise
// rotation; Creo: right-hand rule).
TEST(ArcDirection, ConventionDecidesWithoutGeometry) {
  for (double deg : {10.0, 181.0, 359.0}) {
    ArcCase nx;
    nx.tangent_in = false;
    nx.deg = -deg;  // clockwise about +Z
    nx.hint = ir::ArcDir::Cw;
    nx.layout = ir::ArcLayout::Nx11;
    Ran r = run(make_op(nx), {"arc-direction"}, mill());
    EXPECT_TRUE(r.diags.empty());
    EXPECT_EQ(arc_at(r.op, 2)->dir, ir::ArcDir::Cw);
    EXPECT_NEAR(arc_at(r.op, 2)->sweep, deg, 1e-9);

    ArcCase creo = nx;
    creo.deg = deg;
    creo.hint = ir::ArcDir::Ccw;
    creo.layout = ir::ArcLayout::Creo7;
    Ran q = run(make_op(creo), {"arc-direction"}, mill());
    EXPECT_EQ(arc_at(q.op, 2)->dir, ir::ArcDir::Ccw);
    EXPECT_NEAR(arc_at(q.op, 2)->sweep, deg, 1e-9);
  }
}

TEST(ArcDirection, FullCircle) {
  ArcCase c;
  c.deg = 360;
  c.tangent_in = false;
  c.hint = ir::ArcDir::Cw;
  c.layout = ir::ArcLayout::Nx11;
  Ran r = run(make_op(c), {"arc-direction"}, mill());
  EXPECT_EQ(arc_at(r.op, 2)->dir, ir::ArcDir::Cw);
  EXPECT_DOUBLE_EQ(arc_at(r.op, 2)->sweep, 360);
}

// The CL's convention decides; geometry only confirms it, and where it disagrees (a cusp, a
// plunge onto the arc) a warning names both readings. (A tangency guess once turned a short
// clockwise arc into a 326-degree counter-clockwise one.)
TEST(ArcDirection, ConventionWinsOverGeometryWithAWarning) {
  ArcCase c;
  c.deg = 90;  // tangent says ccw
  c.hint = ir::ArcDir::Cw;
  c.layout = ir::ArcLayout::Nx11;
  Ran r = run(make_op(c), {"arc-direction"}, mill());
  EXPECT_EQ(arc_at(r.op, 2)->dir, ir::ArcDir::Cw);
  EXPECT_NEAR(arc_at(r.op, 2)->sweep, 270, 1e-9);
  ASSERT_EQ(r.diags.size(), 1u);
  EXPECT_EQ(r.diags[0].severity, Severity::Warning);
  EXPECT_EQ(r.diags[0].loc, (SourceLoc{3, 1}));
  EXPECT_EQ(r.diags[0].message,
            "arc: the NX CLSF convention (the axis of clockwise rotation) says clockwise, and it is cut clockwise; but "
            "the arc is tangent to the move entering it only if it turns counter-clockwise (a cusp or a plunge onto the "
            "arc?)");
}

// A file that does not say which CAM system wrote it: the right-hand rule is clpc's guess. Where
// more than a tangent says otherwise (the move after the arc goes on round its circle), the two
// readings are a 45-degree arc and a 315-degree one through the pocket (cut with a warning,
// certified): refused. A tangent alone may be a cusp: the guess is cut, with the warning.
TEST(ArcDirection, AnUnknownSystemsAxisAgainstTheGeometryIsRefused) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nRAPID\nGOTO/-20,20,5\nFEDRAT/100,MMPM\nGOTO/-20,20,-2\n"
                           "GOTO/0,20,-2\nCIRCLE/0,0,-2,0,0,1,20\nGOTO/14.142136,14.142136,-2\n";
  Compiled c = compile_text(head + "GOTO/20,0,-2\nGOTO/0,-20,-2\n", machine("fanuc-mill"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:9:1: error: arc: the right-hand rule about the CIRCLE's axis (an unknown CAM "
                                 "system) says counter-clockwise, but the arc is tangent to the move entering it only "
                                 "if it turns clockwise, and the move after it goes on round its circle that way: the "
                                 "file does not say which CAM system wrote it"));
  Compiled cusp = compile_text(head + "GOTO/30,30,-2\n", machine("fanuc-mill"));
  EXPECT_TRUE(cusp.ok) << cusp.diags;
  EXPECT_THAT(cusp.diags, HasSubstr("part.cls:9:1: warning: arc: the right-hand rule"));
  // Named (Creo's header): its convention is documented, and the corpus bears it out.
  Compiled creo = compile_text("$$* Pro/CLfile Version Wildfire 5.0 - M060\n" + head + "GOTO/20,0,-2\n", machine("fanuc-mill"));
  EXPECT_TRUE(creo.ok) << creo.diags;
  // The same for NX's eleven values in a file that does not name NX: its convention was taken
  // on trust, and a 270-degree arc cut where both tangents said 90 the other way (helper-61).
  const std::string eleven = "UNITS/MM\nLOADTL/1\nSPINDL/2000,RPM,CLW\nRAPID\nGOTO/0,-10,20\nFEDRAT/200,MMPM\n"
                             "GOTO/0,-10,-1\nGOTO/20,-10,-1\nCIRCLE/20,0,-1,0,0,1,10,0.01,0.5,10,0\nGOTO/30,0,-1\n"
                             "GOTO/30,20,-1\nFINI\n";
  Compiled nx = compile_text(eleven, machine("fanuc-mill"));
  EXPECT_THAT(nx.diags, HasSubstr("part.cls:9:1: error: arc: the NX CLSF convention (the axis of clockwise rotation) says "
                                  "clockwise, but the arc is tangent to the move entering it only if it turns "
                                  "counter-clockwise, and so is the move leaving it: the file does not say which CAM "
                                  "system wrote it"));
}

// Creo points that run against the CIRCLE's convention. The first GOTO is the arc's end, and
// the arc turns the convention's way however far (here 315 degrees counter-clockwise, not the
// short way clockwise); later points behind it in that sense are straight moves. They were
// joined into a clockwise arc by the first step's short way round, which a 270-degree CIRCLE
// with one GOTO then a straight chord also took for clockwise.
TEST(ArcDirection, TheFirstGotoEndsTheArcTheConventionsWayRound) {
  const std::string cl = "$$-> MFGNO / T\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,0,10\n"
                         "FEDRAT/200,MMPM\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/7.0710678,-7.0710678,0\n"
                         "GOTO/0,-10,0\nGOTO/-7.0710678,-7.0710678,0\nGOTO/-10,0,0\nGOTO/-20,0,0\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G03 X7.071 Y-7.071 I-10. J0.\nN90 G01 X0. Y-10.\n"));
  // With the axis the points agree with, it is one clockwise arc through them.
  std::string agree = cl;
  agree.replace(agree.find("0,0,1,10"), 8, "0,0,-1,10");
  Compiled a = compile_text(agree, machine("fanuc-mill"));
  ASSERT_TRUE(a.ok) << a.diags;
  EXPECT_THAT(a.output, HasSubstr("G02 X-10. I-10. J0.\n"));
  // 270 degrees counter-clockwise with one GOTO, then a straight chord back across.
  Compiled r = compile_text("$$-> MFGNO / T\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,0,10\n"
                            "FEDRAT/200,MMPM\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,-10,0\nGOTO/-10,0,0\nFINI\n",
                            machine("fanuc-mill"));
  ASSERT_TRUE(r.ok) << r.diags;
  EXPECT_THAT(r.output, HasSubstr("G03 X0. Y-10. I-10. J0.\nN90 G01 X-10. Y0.\n"));
}

TEST(ArcDirection, NothingDecidesIsAnError) {
  ArcCase c;
  c.tangent_in = false;
  c.layout = ir::ArcLayout::NoRadius6;
  Ran r = run(make_op(c), {"arc-direction"}, mill());
  EXPECT_EQ(first_error(r.diags),
            "3:1: cannot decide which way this arc turns: this CIRCLE layout (no radius) has no axis convention and no "
            "tangent move or point on the arc tells");
}

TEST(ArcDirection, OutgoingMoveAndIntermediatePointsDecide) {
  // No incoming tangent; the move leaving the end is tangent for a clockwise arc.
  ArcCase c;
  c.deg = -90;
  c.tangent_in = false;
  ir::Operation op = make_op(c);
  const ir::Arc a = *arc_at(op, 2);
  ir::Vec3 out_dir = a.axis.cross(arcgeo::radial(a, a.end)) * -1;  // cw tangent at the end
  ir::Move m;
  m.point = a.end + 15 * out_dir;
  m.axis = ir::Vec3::UnitZ();
  op.body.push_back({{4, 1}, m});
  Ran r = run(op, {"arc-direction"}, mill());
  EXPECT_EQ(arc_at(r.op, 2)->dir, ir::ArcDir::Cw);

  // A point on the arc at -45 degrees says clockwise too.
  ir::Operation op2 = make_op(c);
  auto* arc = std::get_if<ir::Arc>(&op2.body[2].op);
  ir::Vec3 u, v;
  plane_basis(arc->axis, u, v);
  op2.points.push_back(arc->center + 10 * (std::cos(-kPi / 4) * u + std::sin(-kPi / 4) * v));
  arc->via_begin = 0;
  arc->via_count = 1;
  Ran r2 = run(op2, {"arc-direction"}, mill());
  EXPECT_EQ(arc_at(r2.op, 2)->dir, ir::ArcDir::Cw);
  EXPECT_NEAR(arc_at(r2.op, 2)->sweep, 90, 1e-9);
}

// --- helix ---------------------------------------------------------------------------------

namespace {
ArcCase helix_case() {
  ArcCase c;
  c.deg = 180;  // 2.5 turns: two extra turns and a half
  c.extra_turns = 2;
  c.rise = -5;
  c.hint = ir::ArcDir::Ccw;
  c.layout = ir::ArcLayout::Nx11;
  c.tangent_in = false;
  return c;
}
}  // namespace

// Half turns at most, whatever the machine allows: a piece of nearly a whole turn has a chord too
// short to place its centre within an increment once its ends are rounded (APT_Project2.cls,
// TIMES,7, was off its helix by three increments in 315-degree pieces).
TEST(Helix, TwoAndAHalfTurnsKeptAsHelicalBlocksOfAtMostHalfATurn) {
  Machine m = mill();
  m.arcs.helix_max_sweep = 360;
  Ran r = run(make_op(helix_case()), {"arc-direction", "helix"}, m);
  ASSERT_EQ(first_error(r.diags), "");
  auto as = arcs(r.op);
  ASSERT_EQ(as.size(), 5u);
  for (auto* a : as) {
    EXPECT_NEAR(a->sweep, 180, 1e-9);
    EXPECT_EQ(a->extra_turns, 0);
  }
  EXPECT_NEAR(as.back()->end.z() - as.front()->start.z(), -5, 1e-9);
  // Each piece starts where the previous one ended, on the helix.
  for (size_t i = 1; i < as.size(); ++i) EXPECT_NEAR((as[i]->start - as[i - 1]->end).norm(), 0, 1e-12);
}

TEST(Helix, SplitIntoQuarterTurns) {
  Machine m = mill();
  m.arcs.helix_max_sweep = 90;
  Ran r = run(make_op(helix_case()), {"arc-direction", "helix"}, m);
  auto as = arcs(r.op);
  ASSERT_EQ(as.size(), 10u);
  for (auto* a : as) EXPECT_NEAR(a->sweep, 90, 1e-9);
}

TEST(Helix, LinearisedWithinToleranceWithoutHelicalArcs) {
  Machine m = mill();
  m.arcs.helical = false;
  m.arcs.tolerance = 0.01;
  ir::Operation op = make_op(helix_case());
  Ran r = run(op, {"arc-direction", "helix"}, m);
  EXPECT_TRUE(arcs(r.op).empty());
  // Chord error: every chord's midpoint within 0.01 of the helix axis distance r.
  double step = arcgeo::sweep_for_chord_error(10, 0.01);
  EXPECT_EQ(moves(r.op), 2 + size_t(std::ceil(900 / step)));
  ir::Vec3 prev = std::get<ir::Move>(r.op.body[1].op).point;
  for (size_t i = 2; i < r.op.body.size(); ++i) {
    ir::Vec3 p = std::get<ir::Move>(r.op.body[i].op).point;
    ir::Vec3 mid = (p + prev) / 2 - ir::Vec3(5, 6, 7);
    EXPECT_LE(10 - std::hypot(mid.x(), mid.y()), 0.01 + 1e-9);
    prev = p;
  }
  EXPECT_NEAR((prev - ir::Vec3(5 - 10, 6, 7 - 5)).norm(), 0, 1e-9);  // ends at the CL end
}

TEST(Helix, PlanarArcWithinLimitsIsKept) {
  ArcCase c;
  c.deg = 270;
  Ran r = run(make_op(c), {"arc-direction", "helix"}, mill());
  ASSERT_EQ(arcs(r.op).size(), 1u);
  EXPECT_NEAR(arcs(r.op)[0]->sweep, 270, 1e-9);
}

// --- arc-legalise --------------------------------------------------------------------------

TEST(ArcLegalise, PlaneTheMachineLacksIsLinearised) {
  Machine m = mill();
  m.arcs.yz = false;
  ArcCase c;
  c.axis = ir::Vec3::UnitX();
  Ran r = run(make_op(c), {"arc-direction", "arc-legalise"}, m);
  EXPECT_TRUE(arcs(r.op).empty());
  EXPECT_GT(moves(r.op), 3u);
}

TEST(ArcLegalise, ArbitraryPlaneIsLinearised) {
  ArcCase c;
  c.axis = ir::Vec3(0, 0.6, 0.8);
  Ran r = run(make_op(c), {"arc-direction", "arc-legalise"}, mill());
  EXPECT_TRUE(arcs(r.op).empty());
}

TEST(ArcLegalise, RadiusOutsideLimitsIsLinearised) {
  Machine m = mill();
  m.arcs.max_radius = 5;
  Ran r = run(make_op(ArcCase{}), {"arc-direction", "arc-legalise"}, m);
  EXPECT_TRUE(arcs(r.op).empty());
  Machine n = mill();
  n.arcs.min_radius = 20;
  Ran q = run(make_op(ArcCase{}), {"arc-direction", "arc-legalise"}, n);
  EXPECT_TRUE(arcs(q.op).empty());
}

TEST(ArcLegalise, SweepOverTheMaximumIsSplit) {
  Machine m = mill();
  m.arcs.max_sweep = 90;
  ArcCase c;
  c.deg = -359;
  Ran r = run(make_op(c), {"arc-direction", "arc-legalise"}, m);
  auto as = arcs(r.op);
  ASSERT_EQ(as.size(), 4u);
  for (auto* a : as) EXPECT_NEAR(a->sweep, 359.0 / 4, 1e-9);
}

// Over half a turn the centre lies beyond the chord; a short chord makes it move R/chord
// increments per increment of rounding at the ends. 359.1 degrees of 10 mm radius (chord
// 0.16 mm) as one G03 would pass 0.024 mm from the arc's midpoint: split in two. Three
// quarters of a turn (chord 14 mm) stays one arc.
TEST(ArcLegalise, AShortChordOverHalfATurnIsSplitWhereRoundingWouldMoveTheCentre) {
  Machine m = mill();
  ArcCase c;
  c.deg = 359.1;
  Ran r = run(make_op(c), {"arc-direction", "arc-legalise"}, m);
  auto as = arcs(r.op);
  ASSERT_EQ(as.size(), 2u);
  EXPECT_NEAR(as[0]->sweep, 359.1 / 2, 1e-9);
  EXPECT_NEAR(as[1]->sweep, 359.1 / 2, 1e-9);
  c.deg = 270.0123;
  Ran q = run(make_op(c), {"arc-direction", "arc-legalise"}, m);
  EXPECT_EQ(arcs(q.op).size(), 1u);
}

TEST(ArcLegalise, RFormatNeverGetsAFullCircle) {
  Machine m = mill();
  m.arcs.center = ArcCenter::Radius;
  ArcCase c;
  c.deg = 360;
  c.tangent_in = false;
  c.hint = ir::ArcDir::Ccw;
  c.layout = ir::ArcLayout::Creo7;
  Ran r = run(make_op(c), {"arc-direction", "arc-legalise"}, m);
  auto as = arcs(r.op);
  ASSERT_EQ(as.size(), 2u);
  EXPECT_NEAR(as[0]->sweep, 180, 1e-9);
  EXPECT_GT((as[0]->end - as[0]->start).norm(), 19.9);
}

// A zero-length arc: its ends (nearly) meet but it is not a circle. A control reading those
// ends would cut a full circle; clpc writes a straight move instead.
TEST(ArcLegalise, ZeroLengthArcBecomesAStraightMove) {
  ArcCase c;
  c.deg = 0.000001;
  c.hint = ir::ArcDir::Ccw;
  c.layout = ir::ArcLayout::Creo7;
  c.tangent_in = false;
  Ran r = run(make_op(c), {"arc-direction", "helix", "arc-legalise"}, mill());
  EXPECT_TRUE(arcs(r.op).empty());
  EXPECT_EQ(moves(r.op), 3u);
}

TEST(ArcLegalise, CircleSmallerThanTheResolutionIsDropped) {
  ArcCase c;
  c.r = 0.0001;
  c.deg = 360;
  c.hint = ir::ArcDir::Ccw;
  c.layout = ir::ArcLayout::Creo7;
  c.tangent_in = false;
  Ran r = run(make_op(c), {"arc-direction", "arc-legalise"}, mill());
  EXPECT_TRUE(arcs(r.op).empty());
  EXPECT_EQ(moves(r.op), 2u);
}

// The whole chain through the mill backend: an R-format machine writes negative R over 180.
TEST(ArcLegalise, RFormatOutputSignsTheRadius) {
  Machine m = machine("fanuc-mill", "[r-mill]\ninherits = \"fanuc-mill\"\n[r-mill.arcs]\ncenter = \"radius\"\n");
  Machine rm = machine("r-mill", "[r-mill]\ninherits = \"fanuc-mill\"\n[r-mill.arcs]\ncenter = \"radius\"\n");
  Compiled c = compile_text(
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/100\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,-10,0\n"
      "CIRCLE/0,0,0,0,0,1,10\nGOTO/10,0,0\n",
      rm);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_NE(c.output.find("G03 X0. Y-10. R-10."), std::string::npos) << c.output;  // 270 degrees
  EXPECT_NE(c.output.find("X10. Y0. R10."), std::string::npos) << c.output;        // 90 degrees
}

// Near half a turn the centre an R-format control finds for the rounded R lies R/distance
// increments off for each increment of R (179.5 degrees of R10 was cut 0.044 off and refused
// by verify, unlocated): such an arc is split into the fewest pieces whose centres hold.
TEST(ArcLegalise, AnRFormatArcNearHalfATurnIsSplitWhereItsCentreWouldNotHold) {
  Machine rm = machine("r-mill", "[r-mill]\ninherits = \"fanuc-mill\"\n[r-mill.arcs]\ncenter = \"radius\"\n");
  const std::string head = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/100\nGOTO/10,0,0\nINDIRV/0,1,0\nCIRCLE/0,0,0,0,0,1,10\n";
  Compiled near_half = compile_text(head + "GOTO/-9.9996,0.0873,0\n", rm, {.certify = true});  // 179.5 degrees
  ASSERT_TRUE(near_half.ok) << near_half.diags;
  EXPECT_THAT(near_half.output, HasSubstr(" G03 X0.044 Y10. R10.\nN"));
  EXPECT_THAT(near_half.output, HasSubstr(" X-10. Y0.087 R10.\n"));
  Compiled near_full = compile_text(head + "GOTO/9.9998,-0.0175,0\n", rm, {.certify = true});  // 359.9 degrees
  ASSERT_TRUE(near_full.ok) << near_full.diags;
  size_t pieces = 0;
  for (size_t at = near_full.output.find(" R10.\n"); at != std::string::npos; at = near_full.output.find(" R10.\n", at + 1))
    ++pieces;
  EXPECT_EQ(pieces, 3u) << near_full.output;
  Compiled quarter = compile_text(head + "GOTO/0,10,0\n", rm, {.certify = true});
  ASSERT_TRUE(quarter.ok) << quarter.diags;
  EXPECT_THAT(quarter.output, HasSubstr(" G03 X0. Y10. R10.\n"));
  // Held on the path, not at the centre: a short arc's centre moves far with its rounded ends
  // while its path hardly moves (a first version split 0.5 degrees of R5 into pieces under an
  // increment, refused, and 3 degrees of R10 into 64 blocks).
  Compiled short_arc = compile_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/100\nGOTO/5,0,0\nINDIRV/0,1,0\n"
                                    "CIRCLE/0,0,0,0,0,1,5\nGOTO/4.999810,0.043633,0\n", rm, {.certify = true});
  ASSERT_TRUE(short_arc.ok) << short_arc.diags;
  EXPECT_THAT(short_arc.output, HasSubstr(" G03 Y0.044 R5.\nN80 M05\n"));
  // A full circle off the grid: its halves' centres did not hold (0.1 mm off, refused).
  Compiled circle = compile_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/100\nGOTO/10.0007,0.0003,0\nINDIRV/0,1,0\n"
                                 "CIRCLE/0.0003,0.0003,0,0,0,1,10.0004\nGOTO/10.0007,0.0003,0\n", rm, {.certify = true});
  EXPECT_TRUE(circle.ok) << circle.diags;
  // A helix: the centre off turns the heights too (its angles about the centre move), which the
  // plane alone did not count: 0.0064 off against 0.006, refused.
  Compiled helix = compile_text("UNITS/MM\nLOAD/TOOL,1\nSPINDL/1000\nFEDRAT/300\nGOTO/278.910809,-13.238466,-3.568\n"
                                "INDIRV/0,1,0\nCIRCLE/278.5,-12.552,-3.568,0,0,1,0.8\nGOTO/278.858769,-13.267042,-7.452\n",
                                rm, {.certify = true});
  EXPECT_TRUE(helix.ok) << helix.diags;
}
