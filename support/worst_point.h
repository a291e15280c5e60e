// The largest value of a smooth function on [0, 1] with one or two bumps, such as how far a
// tool tip bows off its line while the rotaries turn (the control interpolates the axes, not
// the tip): sampled at eighths, then the largest sample's neighbourhood searched by golden
// section to a ten-thousandth. The kinematics pass (where it splits a move) and verify (what it
// proves) ask the same question this same way, so what one passes the other passes.
#pragma once

#include <algorithm>

namespace clpc {

template <class F>
double worst_point(F f) {
  double worst = f(0.5), at = 0.5;
  for (int k = 1; k < 8; ++k) {
    if (k == 4) continue;
    const double t = k / 8.0, v = f(t);
    if (v > worst) worst = v, at = t;
  }
  constexpr double g = 0.6180339887498949;
  double lo = std::max(0.0, at - 0.125), hi = std::min(1.0, at + 0.125);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  while (hi - lo > 1e-4) {
    if (f1 > f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = f(x2);
    }
  }
  return std::max({worst, f1, f2});
}

}  // namespace clpc
