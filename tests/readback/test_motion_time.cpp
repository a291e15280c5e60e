// verify's dynamic cycle time (readback/motion_time.h): trapezoidal profiles, the slowdown at
// a corner, rapids axis by axis, an arc's centripetal limit; each against the time worked out
// by hand.
#include <cmath>

#include "helpers.h"
#include "readback/motion_time.h"
#include "readback/verify.h"

using namespace clpc;
using namespace clpc::test;
using ir::Vec3;

namespace {

// 100 mm/s (6000 mm/min) on every axis, 1000 mm/s^2, corners within 0.01 mm.
MotionSettings limits() {
  MotionSettings m;
  m.velocity = Vec3(24000, 24000, 24000);
  m.acceleration = Vec3(1000, 1000, 1000);
  m.junction_deviation = 0.01;
  return m;
}

gcode::Segment feed(const Vec3& a, const Vec3& b, double f = 6000) {
  gcode::Segment s;
  s.kind = gcode::Segment::Kind::Feed;
  s.start = a;
  s.end = b;
  s.feed = f;
  return s;
}

double seconds(MotionTimer& t) { return t.minutes() * 60; }

}  // namespace

// 100 mm at 100 mm/s: 0.1 s up to speed (5 mm), 0.9 s at it, 0.1 s down.
TEST(MotionTime, ALineSpeedsUpCruisesAndSlowsDown) {
  MotionTimer t(limits());
  t.add(feed({0, 0, 0}, {100, 0, 0}));
  EXPECT_NEAR(seconds(t), 1.1, 1e-9);
}

// 4 mm never reaches 100 mm/s: up to sqrt(1000 * 4) and down again.
TEST(MotionTime, AShortLineNeverReachesItsFeed) {
  MotionTimer t(limits());
  t.add(feed({0, 0, 0}, {4, 0, 0}));
  EXPECT_NEAR(seconds(t), 2 * std::sqrt(4000.0) / 1000, 1e-9);
}

// Two lines straight on take the time of one: no slowdown between them.
TEST(MotionTime, StraightOnThereIsNoCorner) {
  MotionTimer t(limits());
  t.add(feed({0, 0, 0}, {50, 0, 0}));
  t.add(feed({50, 0, 0}, {100, 0, 0}));
  EXPECT_NEAR(seconds(t), 1.1, 1e-9);
}

// A square corner: v^2 = a * 0.01 * sin45 / (1 - sin45) at the corner; each 50 mm leg speeds
// up to 100 mm/s and slows to it (or from it).
TEST(MotionTime, ASquareCornerSlowsTheTool) {
  MotionTimer t(limits());
  t.add(feed({0, 0, 0}, {50, 0, 0}));
  t.add(feed({50, 0, 0}, {50, 50, 0}));
  const double s = std::sqrt(0.5), vc = std::sqrt(1000 * 0.01 * s / (1 - s));
  const double leg = 0.1 + (100 - vc) / 1000 + (50 - 5 - (10000 - vc * vc) / 2000) / 100;
  EXPECT_NEAR(seconds(t), 2 * leg, 1e-9);
  EXPECT_GT(seconds(t), 1.1);  // slower than straight on
}

// A reversal stops the tool.
TEST(MotionTime, AReversalStops) {
  MotionTimer t(limits());
  t.add(feed({0, 0, 0}, {100, 0, 0}));
  t.add(feed({100, 0, 0}, {0, 0, 0}));
  EXPECT_NEAR(seconds(t), 2.2, 1e-9);
}

// Rapids move each axis on its own, from rest to rest: the slowest axis sets the time.
TEST(MotionTime, RapidsAxisByAxis) {
  MotionSettings m = limits();
  m.velocity = Vec3(24000, 12000, 24000);  // Y at 200 mm/s
  MotionTimer t(m);
  gcode::Segment r = feed({0, 0, 0}, {100, 60, 0});
  r.kind = gcode::Segment::Kind::Rapid;
  t.add(r);
  // X: 400 mm/s needs 80 mm up and 80 down: never reached in 100 mm, peak sqrt(1000 * 100).
  // Y: 200 mm/s after 20 mm, 20 mm at speed, 20 mm down: 0.2 + 0.1 + 0.2.
  const double x = 2 * std::sqrt(1000 * 100.0) / 1000, y = 0.2 + 0.1 + 0.2;
  EXPECT_NEAR(seconds(t), std::max(x, y), 1e-9);
}

// A small arc is limited by the acceleration that turns the tool round it: v = sqrt(a r).
TEST(MotionTime, ATightArcIsSlowerThanItsFeed) {
  MotionTimer t(limits());
  gcode::Segment a = feed({1, 0, 0}, {1, 0, 0});
  a.kind = gcode::Segment::Kind::Arc;
  a.center = Vec3(0, 0, 0);
  a.normal = Vec3::UnitZ();
  a.ccw = true;
  a.sweep = 360;
  a.start_radius = a.end_radius = 1;
  t.add(a);
  const double v = std::sqrt(1000.0), length = 2 * M_PI;
  const double expected = 2 * v / 1000 + (length - v * v / 1000) / v;
  EXPECT_NEAR(seconds(t), expected, 1e-9);
}

// The built-ins give their limits; the report prints both estimates, the dynamic one no less.
TEST(MotionTime, TheReportShowsBothEstimates) {
  TempDir d;
  write_file(d.path("plate.cls"), "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,20\nFEDRAT/MMPM,3000\n"
                                  "GOTO/0,0,-2\nGOTO/30,0,-2\nGOTO/30,20,-2\nGOTO/0,20,-2\nGOTO/0,0,-2\nRAPID\nGOTO/0,0,20\nFINI\n");
  VerifyReport r;
  {
    CompileOptions o;
    o.certify = true;
    std::ostringstream err;
    CompileResult plain = compile_file(d.path("plate.cls"), d.path("plate.nc"), machine("fanuc-mill"), o, err);
    ASSERT_TRUE(plain.ok && plain.certificate) << err.str();
    EXPECT_FALSE(plain.certificate->program.dynamic_known);  // the one line shows no cycle time: not planned
    o.certificate_cycle_time = true;
    CompileResult c = compile_file(d.path("plate.cls"), d.path("plate.nc"), machine("fanuc-mill"), o, err);
    ASSERT_TRUE(c.ok && c.certificate) << err.str();
    r = *c.certificate;
  }
  ASSERT_TRUE(r.program.dynamic_known);
  EXPECT_GT(r.program.dynamic_minutes, r.program.total_minutes());
  std::ostringstream text;
  print_report(text, r);
  EXPECT_THAT(text.str(), ::testing::HasSubstr("  dynamic:    0:"));
  MotionSettings none;
  EXPECT_FALSE(none.known());
}
