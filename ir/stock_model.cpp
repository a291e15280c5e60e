#include "ir/stock_model.h"

#include <algorithm>
#include <cmath>

namespace clpc::stock {

namespace {

constexpr double kPi = 3.14159265358979323846;

double wrap(double a) {  // to [0, 2π)
  a = std::fmod(a, 2 * kPi);
  return a < 0 ? a + 2 * kPi : a;
}

std::string at_line(int line) { return line > 0 ? " (G-code line " + std::to_string(line) + ")" : ""; }

}  // namespace

Params params_of(const ir::RoughMark& m, double scale, bool infeed_rapid) {
  Params p;
  p.facing = m.facing;
  p.depth = m.depth * scale;
  p.retract = m.retract * scale;
  p.allow_x = m.allow_x * scale;
  p.allow_z = m.allow_z * scale;
  p.infeed_rapid = infeed_rapid;
  return p;
}

std::vector<Step> expand(const ir::Vec3& start, const std::vector<Element>& profile, const Params& p, std::string& why) {
  // Work in (level, cut) coordinates and map back: G71 steps its levels along x and cuts along
  // z, G72 the other way round. Swapping the axes mirrors the plane, so an arc's sense flips.
  auto L = [&](const ir::Vec3& v) { return p.facing ? v.z() : v.x(); };
  auto C = [&](const ir::Vec3& v) { return p.facing ? v.x() : v.z(); };
  auto at = [&](double l, double c) { return p.facing ? ir::Vec3(c, 0, l) : ir::Vec3(l, 0, c); };
  const char* lname = p.facing ? "Z" : "X";
  const char* cname = p.facing ? "X" : "Z";
  const double al = p.facing ? p.allow_z : p.allow_x, ac = p.facing ? p.allow_x : p.allow_z;
  why.clear();
  if (!(p.depth > 0)) {
    why = "the depth of cut is not above zero";
    return {};
  }
  if (profile.empty()) {
    why = "the profile has no blocks";
    return {};
  }
  double size = std::abs(L(start)) + std::abs(C(start));
  for (const Element& e : profile) size = std::max(size, std::abs(L(e.end)) + std::abs(C(e.end)));
  const double eps = 1e-9 * std::max(1.0, size);

  const Element& first = profile.front();
  if (first.arc || std::abs(C(first.end) - C(first.start)) > eps) {
    why = std::string("its first block") + at_line(first.line) + " moves along " + cname + ": a type I cycle's first block moves along " +
          lname + " alone";
    return {};
  }
  const double l0 = L(start), c0 = C(start), la = L(first.end);
  const double sl = l0 > la + eps ? 1 : l0 < la - eps ? -1 : 0;
  if (sl == 0) {
    why = std::string("it starts on the profile's first ") + lname + ": no stock lies between the start point and the profile";
    return {};
  }
  const double cb = C(profile.back().end);
  const double sc = cb > C(first.end) + eps ? 1 : cb < C(first.end) - eps ? -1 : 0;
  if (sc == 0 || profile.size() < 2) {
    why = std::string("the profile does not move along ") + cname;
    return {};
  }
  // Type I: the profile only ever moves towards the stock along the level axis and one way
  // along the cut axis (a pocket would need type II), arcs included (no arc passes a quadrant
  // point, where it would turn back).
  for (size_t i = 1; i < profile.size(); ++i) {
    const Element& e = profile[i];
    const double dl = L(e.end) - L(e.start), dc = C(e.end) - C(e.start);
    bool monotonic = sl * dl >= -eps && sc * dc >= -eps;
    if (monotonic && e.arc) {
      const bool ccw = p.facing ? !e.ccw : e.ccw;
      const double lc = L(e.center), cc = C(e.center);
      const double t0 = std::atan2(L(e.start) - lc, C(e.start) - cc), t1 = std::atan2(L(e.end) - lc, C(e.end) - cc);
      const double sweep = ccw ? wrap(t1 - t0) : wrap(t0 - t1);
      const double aeps = 1e-9;
      if (sweep < aeps) monotonic = false;  // a full circle
      for (int k = -1; k <= 2 && monotonic; ++k) {
        const double off = ccw ? wrap(k * kPi / 2 - t0) : wrap(t0 - k * kPi / 2);
        if (off > aeps && off < sweep - aeps) monotonic = false;
      }
    }
    if (!monotonic) {
      why = std::string("the profile turns back along ") + (sl * dl >= -eps && sc * dc >= -eps ? "X or Z within an arc" : sl * dl < -eps ? lname : cname) +
            at_line(e.line) + ": a pocket, which a type I cycle does not cut";
      return {};
    }
  }

  // The profile shifted by the allowances; the level cuts end where they meet it.
  const double la_s = la + al;
  auto cut_end = [&](double lk) {
    for (size_t i = 1; i < profile.size(); ++i) {
      const Element& e = profile[i];
      const double ls = L(e.start) + al, le = L(e.end) + al, cs = C(e.start) + ac, ce = C(e.end) + ac;
      if (sl * (le - lk) < 0) continue;   // still short of the level
      if (sl * (ls - lk) >= 0) return cs;  // a step along the level axis reached it at its start
      if (!e.arc) return cs + (ce - cs) * (lk - ls) / (le - ls);
      const double lc = L(e.center) + al, cc = C(e.center) + ac;
      const double r = std::hypot(ls - lc, cs - cc);
      const double h = std::sqrt(std::max(0.0, r * r - (lk - lc) * (lk - lc)));
      const double c1 = cc + h, c2 = cc - h;
      auto inside = [&](double c) { return sc * (c - cs) >= -eps && sc * (ce - c) >= -eps; };
      if (inside(c1) && !inside(c2)) return c1;
      if (inside(c2) && !inside(c1)) return c2;
      return std::abs(c1 - (cs + ce) / 2) < std::abs(c2 - (cs + ce) / 2) ? c1 : c2;
    }
    return cb + ac;  // the profile ends short of the level: the cut ends at B's
  };

  const double levels = std::floor((sl * (l0 - la_s) - eps) / p.depth);
  if (!(levels * 4 + profile.size() + 2 <= kMaxSteps)) {
    why = "the depth of cut is so small the cycle would make more than a million moves";
    return {};
  }
  std::vector<Step> out;
  out.reserve(size_t(std::max(0.0, levels)) * 4 + profile.size() + 2);
  const Step::Kind in = p.infeed_rapid ? Step::Kind::Rapid : Step::Kind::Feed;
  // A move of no length (a level that meets the profile where it starts) is no move.
  ir::Vec3 last = start;
  auto push = [&](Step::Kind k, const ir::Vec3& to) {
    if ((to - last).norm() <= 1e-12) return;
    out.push_back({k, to, ir::Vec3::Zero(), false});
    last = to;
  };
  for (double k = 1; k <= levels; ++k) {
    const double lk = l0 - sl * k * p.depth;
    double ck = cut_end(lk);
    if (sc * (ck - c0) < 0) ck = c0;  // the shifted profile stands before the start: nothing to cut
    push(in, at(lk, c0));
    push(Step::Kind::Feed, at(lk, ck));
    if (p.retract > 0) push(Step::Kind::Feed, at(lk + sl * p.retract, ck - sc * p.retract));
    push(Step::Kind::Rapid, at(lk + sl * std::max(p.retract, 0.0), c0));
  }
  // The last cut: along the shifted profile, entered as the levels are.
  push(in, at(la_s, C(first.end) + ac));
  for (size_t i = 1; i < profile.size(); ++i) {
    const Element& e = profile[i];
    const ir::Vec3 shift = at(al, ac);
    if (!e.arc) {
      push(Step::Kind::Feed, e.end + shift);
      continue;
    }
    out.push_back({Step::Kind::Arc, e.end + shift, ir::Vec3(e.center + shift), e.ccw});
    last = e.end + shift;
  }
  push(Step::Kind::Rapid, start);
  return out;
}

}  // namespace clpc::stock
