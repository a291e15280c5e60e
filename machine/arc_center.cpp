#include "machine/arc_center.h"

#include <cmath>

#include "machine/format.h"

namespace clpc {

namespace {

// The midpoint of the arc the control cuts about (pu, pv), from the true midpoint. Without
// trigonometry: the midpoint's direction bisects the start and end directions, and for any
// sweep the bisector is perpendicular to the chord between the two unit directions (on the
// chord's right for a counter-clockwise arc); the radius is the start's.
double midpoint_deviation(const ArcCenterInput& in, double pu, double pv) {
  const double au = in.su - pu, av = in.sv - pv, bu = in.eu - pu, bv = in.ev - pv;
  const double ra = std::sqrt(au * au + av * av), rb = std::sqrt(bu * bu + bv * bv);
  if (ra == 0 || rb == 0) return std::sqrt((pu - in.mu) * (pu - in.mu) + (pv - in.mv) * (pv - in.mv));
  const double cu = bu / rb - au / ra, cv = bv / rb - av / ra;
  double du, dv;
  if (in.full) {
    du = -au;
    dv = -av;
  } else if (cu * cu + cv * cv > 1e-12) {
    du = in.ccw ? cv : -cv;
    dv = in.ccw ? -cu : cu;
  } else {
    // Start and end in one direction: no turn, or a whole one.
    const double cross = au * bv - av * bu;
    const bool whole = in.ccw ? cross < 0 : cross > 0;
    du = whole ? -au : au;
    dv = whole ? -av : av;
  }
  const double dl = std::sqrt(du * du + dv * dv);
  const double xu = pu + ra * du / dl - in.mu, xv = pv + ra * dv / dl - in.mv;
  return std::sqrt(xu * xu + xv * xv);
}

}  // namespace

ArcCenterChoice choose_arc_center(const ArcCenterInput& in, const AddressFormat& fu, const AddressFormat& fv,
                                  bool incremental) {
  double du = in.eu - in.su, dv = in.ev - in.sv, len = std::hypot(du, dv);
  double iu = in.cu, iv = in.cv;
  if (len > 1e-12) {
    double mu = (in.su + in.eu) / 2, mv = (in.sv + in.ev) / 2;
    double nu = -dv / len, nv = du / len;
    double t = (in.cu - mu) * nu + (in.cv - mv) * nv;
    iu = mu + t * nu;
    iv = mv + t * nv;
  }
  double ou = incremental ? in.su : 0, ov = incremental ? in.sv : 0;
  int64_t qu0, qv0;
  if (!quantize(iu - ou, fu, qu0) || !quantize(iv - ov, fv, qv0)) return {iu, iv, 0, 0};
  double unit = std::min(std::abs(dequantize(1, fu)), std::abs(dequantize(1, fv)));
  // Rings of candidates outwards from the ideal centre; within a ring the radius mismatch
  // first (cheap) and the midpoint only for centres the control accepts, since any of those
  // beats any it would not. Once an accepted centre puts the midpoint within an increment of
  // the true one, the outer rings (farther off) need not be tried.
  constexpr int W = 3;
  const double limit = unit * (1 + 1e-9);
  ArcCenterChoice best{0, 0, 1e300, 1e300};
  bool best_ok = false;
  auto consider = [&](int a, int b) {
    const double pu = ou + dequantize(qu0 + a, fu), pv = ov + dequantize(qv0 + b, fv);
    const double su = in.su - pu, sv = in.sv - pv, eu = in.eu - pu, ev = in.ev - pv;
    const double mis = std::abs(std::sqrt(su * su + sv * sv) - std::sqrt(eu * eu + ev * ev));
    if (mis <= limit) {
      const double dev = midpoint_deviation(in, pu, pv);
      if (!best_ok || dev < best.deviation) best = {pu, pv, mis, dev};
      best_ok = true;
    } else if (!best_ok && mis < best.mismatch) {
      best = {pu, pv, mis, 1e300};
    }
  };
  for (int ring = 0; ring <= W; ++ring) {
    if (ring == 0) {
      consider(0, 0);
      if (best_ok && best.deviation <= unit) break;
      continue;
    }
    for (int a = -ring; a <= ring; ++a) {
      consider(a, -ring);
      consider(a, ring);
    }
    for (int b = -ring + 1; b <= ring - 1; ++b) {
      consider(-ring, b);
      consider(ring, b);
    }
    if (best_ok && best.deviation <= unit) break;
  }
  if (!best_ok) best.deviation = midpoint_deviation(in, best.cu, best.cv);
  return best;
}

}  // namespace clpc
