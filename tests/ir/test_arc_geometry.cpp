// Arc geometry the verifier's certificate rests on: the distance from a point to a decided arc
// (planar, helix, spiral, either sense, whole turns) against a brute-force search along the
// arc, so a distance that comes out too small (a false pass) or too large (a false failure)
// shows here.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "ir/arc_geometry.h"

using namespace clpc;
using arcgeo::ArcProbe;
using ir::Vec3;

namespace {

// The distance by sampling the arc densely, then narrowing around every sample nearer than
// its neighbours (on whole turns of a spiral two such samples may be almost equally near).
double brute_distance(const ArcProbe& a, const Vec3& p) {
  constexpr int kSamples = 20000;
  std::vector<double> d(kSamples + 1);
  for (int i = 0; i <= kSamples; ++i) d[i] = (a.point(double(i) / kSamples) - p).norm();
  double best = INFINITY;
  for (int i = 0; i <= kSamples; ++i) {
    if ((i > 0 && d[i - 1] < d[i]) || (i < kSamples && d[i + 1] < d[i])) continue;
    double lo = std::max(0.0, double(i - 1) / kSamples), hi = std::min(1.0, double(i + 1) / kSamples);
    for (int k = 0; k < 100; ++k) {
      double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      if ((a.point(m1) - p).norm() < (a.point(m2) - p).norm()) hi = m2;
      else lo = m1;
    }
    best = std::min({best, d[i], (a.point((lo + hi) / 2) - p).norm()});
  }
  return best;
}

}  // namespace

TEST(ArcGeometry, DistanceToAnArcIsTheNearestPointOnIt) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int checked = 0;
  for (int n = 0; n < 300; ++n) {
    ir::Arc a;
    a.center = Vec3(u(rng), u(rng), u(rng)) * 50;
    a.axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double r0 = 1 + 20 * std::abs(u(rng));
    const double r1 = n % 3 == 1 ? r0 * (1 + 0.01 * u(rng)) : r0;              // a spiral, slightly
    const double rise = n % 3 == 2 ? 5 * u(rng) : 0;                            // a helix
    a.dir = n % 2 ? ir::ArcDir::Cw : ir::ArcDir::Ccw;
    a.extra_turns = n % 7 == 0 ? 1 : 0;
    const double sweep = 360.0 * a.extra_turns + 10 + 340 * std::abs(u(rng));
    a.sweep = sweep;
    const Vec3 e1 = a.axis.unitOrthogonal(), e2 = a.axis.cross(e1);
    const double phi = arcgeo::sense(a.dir) * sweep * arcgeo::kPi / 180;
    a.start = a.center + r0 * e1;
    a.end = a.center + rise * a.axis + r1 * (std::cos(phi) * e1 + std::sin(phi) * e2);
    const ArcProbe probe(a);
    EXPECT_LT((probe.point(0) - a.start).norm(), 1e-9);
    EXPECT_LT((probe.point(1) - a.end).norm(), 1e-9);
    EXPECT_DOUBLE_EQ(arcgeo::distance_to_arc(a, a.end), probe.distance(a.end));
    for (int k = 0; k < 10; ++k) {
      // Points near the arc (where the certificate's tolerance is decided) and farther off.
      const double t = std::abs(u(rng));
      const double off = k < 7 ? 0.01 * u(rng) : 3 * u(rng);
      const Vec3 p = probe.point(t) + off * Vec3(u(rng), u(rng), u(rng)).normalized();
      const double want = brute_distance(probe, p), got = probe.distance(p);
      // Never nearer than the arc is (a false pass); near the arc, where the tolerance is
      // decided, as near as it is. Far off a steep helix the search round the point's own
      // angle may stop at a farther turn: an upper bound there, which only says "missed".
      EXPECT_GE(got, want - 1e-9) << "arc " << n << " point " << k;
      if (k < 7) EXPECT_LE(got, want + 1e-6 + 1e-3 * want) << "arc " << n << " point " << k;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3000);
}
