#include "backends/arc_center.h"

#include <cmath>

#include "backends/format.h"

namespace clpc {

namespace {

constexpr double kPi = 3.14159265358979323846;

double midpoint_deviation(const ArcCenterInput& in, double pu, double pv) {
  double r = std::hypot(in.su - pu, in.sv - pv);
  double a0 = std::atan2(in.sv - pv, in.su - pu);
  double a1 = std::atan2(in.ev - pv, in.eu - pu);
  double ccw = a1 - a0;
  while (ccw < 0) ccw += 2 * kPi;
  while (ccw >= 2 * kPi) ccw -= 2 * kPi;
  double sweep = in.full ? 2 * kPi : in.ccw ? ccw : 2 * kPi - ccw;
  double mid = a0 + (in.ccw ? 1 : -1) * sweep / 2;
  return std::hypot(pu + r * std::cos(mid) - in.mu, pv + r * std::sin(mid) - in.mv);
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
  ArcCenterChoice best{0, 0, 1e300, 1e300};
  constexpr int W = 3;
  for (int a = -W; a <= W; ++a)
    for (int b = -W; b <= W; ++b) {
      double pu = ou + dequantize(qu0 + a, fu), pv = ov + dequantize(qv0 + b, fv);
      double mis = std::abs(std::hypot(in.su - pu, in.sv - pv) - std::hypot(in.eu - pu, in.ev - pv));
      double dev = midpoint_deviation(in, pu, pv);
      bool ok = mis <= unit * (1 + 1e-9), best_ok = best.mismatch <= unit * (1 + 1e-9);
      bool take = ok != best_ok ? ok : ok ? dev < best.deviation : mis < best.mismatch;
      if (take) best = {pu, pv, mis, dev};
    }
  return best;
}

}  // namespace clpc
