#include "ir/arc_geometry.h"

#include <algorithm>
#include <cmath>

namespace clpc::arcgeo {

Vec3 radial(const Arc& a, const Vec3& p) {
  Vec3 v = p - a.center;
  return v - v.dot(a.axis) * a.axis;
}

double axial(const Arc& a, const Vec3& p) { return (p - a.center).dot(a.axis); }

double ccw_angle(const Vec3& u, const Vec3& v, const Vec3& n) {
  double ang = std::atan2(n.dot(u.cross(v)), u.dot(v));
  if (ang < 0) ang += 2 * kPi;
  return ang;
}

bool closes(const Arc& a, double tol) { return (radial(a, a.end) - radial(a, a.start)).norm() <= tol; }

double sweep_deg(const Arc& a, ir::ArcDir dir, double close_tol) {
  double turns = 360.0 * a.extra_turns;
  if (closes(a, close_tol)) return 360.0 + turns;
  double ccw = ccw_angle(radial(a, a.start), radial(a, a.end), a.axis) * 180 / kPi;
  return (dir == ir::ArcDir::Cw ? 360.0 - ccw : ccw) + turns;
}

ArcProbe::ArcProbe(const Arc& a)
    : start_(a.start), end_(a.end), center_(a.center), axis_(a.axis), rs_(radial(a, a.start)) {
  const Vec3 re = radial(a, a.end);
  r0_ = rs_.norm();
  r1_ = re.norm();
  u_ = r0_ > 0 ? Vec3(rs_ / r0_) : Vec3(a.axis.unitOrthogonal());
  w_ = a.axis.cross(u_);
  h0_ = axial(a, a.start);
  h1_ = axial(a, a.end);
  sweep_deg_ = a.sweep;
  phi_total_ = sense(a.dir) * a.sweep * kPi / 180;
  cw_ = a.dir == ir::ArcDir::Cw;
}

Vec3 ArcProbe::point(double t) const {
  const double phi = phi_total_ * t;
  const double r = r0_ + (r1_ - r0_) * t;
  const double h = h0_ + (h1_ - h0_) * t;
  return center_ + h * axis_ + r * (std::cos(phi) * u_ + std::sin(phi) * w_);
}

void ArcProbe::interior_points(int n, std::vector<Vec3>& out) const {
  out.resize(n > 1 ? size_t(n - 1) : 0);
  if (n <= 1) return;
  const double step = phi_total_ / n, cs = std::cos(step), sn = std::sin(step);
  double c = 1, s = 0;
  for (int i = 1; i < n; ++i) {
    const double c1 = c * cs - s * sn;
    s = s * cs + c * sn;
    c = c1;
    const double t = double(i) / n;
    const double r = r0_ + (r1_ - r0_) * t;
    const double h = h0_ + (h1_ - h0_) * t;
    out[size_t(i - 1)] = center_ + h * axis_ + r * (c * u_ + s * w_);
  }
}

Vec3 point_at(const Arc& a, double t) { return ArcProbe(a).point(t); }

Vec3 tangent_at(const Arc& a, double t) {
  Vec3 p = point_at(a, t);
  Vec3 rv = radial(a, p);
  Vec3 tan = a.axis.cross(rv) * sense(a.dir);
  double n = tan.norm();
  return n > 0 ? Vec3(tan / n) : Vec3::Zero();
}

double ArcProbe::distance(const Vec3& p) const {
  const Vec3 v = p - center_;
  const double hp = v.dot(axis_);
  const Vec3 rp = v - hp * axis_;
  double phi = std::atan2(axis_.dot(rs_.cross(rp)), rs_.dot(rp));
  if (phi < 0) phi += 2 * kPi;
  phi *= 180 / kPi;
  if (cw_ && phi > 0) phi = 360 - phi;
  double best = std::min((p - start_).norm(), (p - end_).norm());
  const double rpn = rp.norm();
  // On a helix the nearest point is not at p's own angle: a steep one rises so fast that a
  // point a hair round the turn is nearer. Searched for around that angle, within the
  // parameter span the distance found there allows.
  const double rise = std::abs(h1_ - h0_);
  const double run = r0_ * sweep_deg_ * kPi / 180;
  const double length = std::sqrt(run * run + rise * rise);
  auto at = [&](double t) { return (point(std::clamp(t, 0.0, 1.0)) - p).norm(); };
  // The angle may be reached on any turn of a multi-turn arc.
  for (double turn = 0; turn * 360 <= sweep_deg_ + 1e-9; ++turn) {
    double t = (phi + 360 * turn) / sweep_deg_;
    if (t < -1e-9 || t > 1 + 1e-9) continue;
    // The arc's point at p's own angle lies in p's half-plane through the axis: no sine needed.
    const double tc = std::clamp(t, 0.0, 1.0);
    const double dr = rpn - (r0_ + (r1_ - r0_) * tc), dh = hp - (h0_ + (h1_ - h0_) * tc);
    double d = std::sqrt(dr * dr + dh * dh);
    if (rise > 1e-12 && length > 0 && d > 0) {
      // Golden-section search (the distance is unimodal this near the curve), until the span
      // left is a thousandth of the distance: the minimum is then known to a millionth of it.
      constexpr double g = 0.6180339887498949;
      double lo = std::max(0.0, t - 2 * d / length), hi = std::min(1.0, t + 2 * d / length);
      double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      double f1 = at(x1), f2 = at(x2);
      for (int k = 0; k < 60 && (hi - lo) * length > 1e-3 * d; ++k) {
        if (f1 < f2) {
          hi = x2;
          x2 = x1;
          f2 = f1;
          x1 = hi - g * (hi - lo);
          f1 = at(x1);
        } else {
          lo = x1;
          x1 = x2;
          f1 = f2;
          x2 = lo + g * (hi - lo);
          f2 = at(x2);
        }
      }
      d = std::min({d, f1, f2});
    }
    best = std::min(best, d);
  }
  return best;
}

double distance_to_arc(const Arc& a, const Vec3& p) { return ArcProbe(a).distance(p); }

double sweep_for_chord_error(double r, double tol) {
  if (r <= tol) return 360;
  double half = std::acos(std::clamp(1 - tol / r, -1.0, 1.0));
  return std::max(2 * half * 180 / kPi, 1e-6);
}

}  // namespace clpc::arcgeo
