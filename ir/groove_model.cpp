#include "ir/groove_model.h"

#include <algorithm>
#include <cmath>

namespace clpc::groove {

std::vector<Step> expand(const ir::Vec3& start, const ir::Vec3& end, const Params& p) {
  // Work in (plunge, shift) coordinates and map back: G75 plunges along x, G74 along z.
  auto pl = [&](const ir::Vec3& v) { return p.face ? v.z() : v.x(); };
  auto sh = [&](const ir::Vec3& v) { return p.face ? v.x() : v.z(); };
  auto at = [&](double plunge, double shift) {
    return p.face ? ir::Vec3(shift, 0, plunge) : ir::Vec3(plunge, 0, shift);
  };
  const double peck = p.face ? p.z_amount : p.x_amount;
  const double step = p.face ? p.x_amount : p.z_amount;
  const double p0 = pl(start), p1 = pl(end), s0 = sh(start), s1 = sh(end);
  const double dp = p1 > p0 ? 1 : -1, ds = s1 > s0 ? 1 : -1;
  const double eps = 1e-9 * std::max(1.0, std::abs(p1 - p0) + std::abs(s1 - s0));
  std::vector<Step> out;
  const double stations = step > 0 ? std::ceil(std::abs(s1 - s0) / step) + 1 : 1;
  const double pecks = peck > 0 ? std::ceil(std::abs(p1 - p0) / peck) + 1 : 1;
  if (!(stations * pecks <= kMaxSteps / 4)) return out;  // absurd P or Q: the caller says so
  double s = s0;
  for (int station = 0;; ++station) {
    double x = p0;
    for (;;) {
      double next = peck > 0 ? x + dp * std::min(peck, std::abs(p1 - x)) : p1;
      if (next == x) next = p1;  // a peck lost in the rounding of large coordinates
      out.push_back({at(next, s), true});
      x = next;
      if (std::abs(p1 - x) <= eps) break;
      if (p.retract > 0) out.push_back({at(x - dp * p.retract, s), false});
    }
    double s_here = s;
    if (p.relief > 0 && station > 0) {
      s_here = s - ds * p.relief;
      out.push_back({at(p1, s_here), false});
    }
    out.push_back({at(p0, s_here), false});
    if (std::abs(s1 - s) <= eps || step <= 0) break;
    const double moved = s + ds * std::min(step, std::abs(s1 - s));
    s = moved == s ? s1 : moved;
    out.push_back({at(p0, s), false});
  }
  out.push_back({start, false});
  return out;
}

}  // namespace clpc::groove
