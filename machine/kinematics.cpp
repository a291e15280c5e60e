#include "machine/kinematics.h"

#include <algorithm>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

namespace clpc::kin {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFreeTol = 1e-7;  // a perpendicular part this small: the axis is singular
constexpr double kLimitTol = 1e-4;  // degrees a solution may pass a rotary limit by (axis_in_limits)

double norm180(double deg) {
  deg = std::fmod(deg, 360.0);
  if (deg <= -180) deg += 360;
  if (deg > 180) deg -= 360;
  return deg;
}

// Signed angle (degrees) turning u to v about the unit axis n, both projected off n; NaN when
// either projection vanishes.
double signed_angle(const Vec3& u, const Vec3& v, const Vec3& n) {
  Vec3 a = u - u.dot(n) * n, b = v - v.dot(n) * n;
  if (a.norm() < kFreeTol || b.norm() < kFreeTol) return std::nan("");
  return std::atan2(n.dot(a.cross(b)), a.dot(b)) * 180 / kPi;
}

// Axis i of a solution at angle t; NaN (no angle determined): the axis is free, kept at 0.
void set_angle(Solution& s, size_t i, double t) {
  s.free[i] = std::isnan(t);
  s.a[i] = s.free[i] ? 0 : norm180(t);
}

// At most two solutions, without the heap: choose() runs for every five-axis move.
struct Solutions {
  Solution v[2];
  size_t n = 0;
  void push_back(const Solution& s) {
    if (n < 2) v[n++] = s;
  }
  const Solution* begin() const { return v; }
  const Solution* end() const { return v + n; }
};

// R(u1, t1) R(u2, t2) p = q, for unit u1, u2, p, q.
Solutions solve_two(const Vec3& u1, const Vec3& u2, const Vec3& p, const Vec3& q) {
  Solutions out;
  double c12 = u1.dot(u2);
  double A = q.dot(u2) - c12 * q.dot(u1);
  double B = q.dot(u1.cross(u2));
  double C = c12 * q.dot(u1);
  double D = u2.dot(p) - C;
  double R = std::sqrt(A * A + B * B);
  double t1s[2];
  size_t n1 = 0;
  bool t1_free = false;
  if (R < 1e-12) {
    if (std::abs(D) > 1e-9) return out;
    t1s[n1++] = 0;
    t1_free = true;
  } else {
    double c = D / R;
    if (std::abs(c) > 1 + 1e-9) return out;
    c = std::clamp(c, -1.0, 1.0);
    double phi = std::atan2(B, A) * 180 / kPi;
    double d = std::acos(c) * 180 / kPi;
    t1s[n1++] = phi + d;
    // The second root, unless it is the same angle (d = 0 or 180).
    if (d > 1e-9 && std::abs(norm180(2 * d)) > 1e-9) t1s[n1++] = phi - d;
  }
  for (size_t i1 = 0; i1 < n1; ++i1) {
    const double t1 = t1s[i1];
    Vec3 w = rotation(u1, -t1) * q;
    Solution s;
    s.a[0] = norm180(t1);
    s.free[0] = t1_free;
    set_angle(s, 1, signed_angle(p, w, u2));
    out.push_back(s);
  }
  return out;
}

Solutions solve_one(const Vec3& u, const Vec3& p, const Vec3& q) {
  Solutions out;
  if (std::abs(u.dot(p) - u.dot(q)) > 1e-7) return out;
  Solution s;
  set_angle(s, 0, signed_angle(p, q, u));
  out.push_back(s);
  return out;
}

}  // namespace

Mat3 rotation(const Vec3& axis, double degrees) {
  // The same few rotations come again and again (a segment starts where the last one ended;
  // each axis is undone and redone): the last eight made on this thread are kept.
  struct Kept {
    Vec3 axis;
    double degrees;
    Mat3 r;
  };
  thread_local std::array<Kept, 8> kept{};
  thread_local size_t kept_count = 0, next = 0;
  for (size_t i = 0; i < kept_count; ++i)
    if (kept[i].degrees == degrees && kept[i].axis == axis) return kept[i].r;
  // Rodrigues: R = c I + s [u]x + (1 - c) u u^T.
  const double n2 = axis.squaredNorm();
  const Vec3 u = std::abs(n2 - 1) < 1e-15 ? axis : Vec3(axis / std::sqrt(n2));
  const double t = degrees * (kPi / 180), c = std::cos(t), s = std::sin(t), k = 1 - c;
  Mat3 r;
  r << c + k * u.x() * u.x(), k * u.x() * u.y() - s * u.z(), k * u.x() * u.z() + s * u.y(),
      k * u.y() * u.x() + s * u.z(), c + k * u.y() * u.y(), k * u.y() * u.z() - s * u.x(),
      k * u.z() * u.x() - s * u.y(), k * u.z() * u.y() + s * u.x(), c + k * u.z() * u.z();
  kept[next] = {axis, degrees, r};
  next = (next + 1) % kept.size();
  kept_count = std::min(kept_count + 1, kept.size());
  return r;
}

Vec3 table_point(const KinematicsSettings& k, const Angles& a, const Vec3& p) {
  Vec3 x = p;
  for (int i = int(k.rotaries.size()) - 1; i >= 0; --i) {
    const RotaryAxis& r = k.rotaries[size_t(i)];
    if (!r.table) continue;
    x = r.center + rotation(r.effective(), a[size_t(i)]) * (x - r.center);
  }
  return x;
}

Mat3 table_rotation(const KinematicsSettings& k, const Angles& a) {
  Mat3 m = Mat3::Identity();
  for (size_t i = 0; i < k.rotaries.size(); ++i)
    if (k.rotaries[i].table) m = m * rotation(k.rotaries[i].effective(), a[i]);
  return m;
}

Vec3 head_axis(const KinematicsSettings& k, const Angles& a) {
  Mat3 m = Mat3::Identity();
  for (size_t i = 0; i < k.rotaries.size(); ++i)
    if (!k.rotaries[i].table) m = m * rotation(k.rotaries[i].effective(), a[i]);
  return m * Vec3::UnitZ();
}

Vec3 tool_axis_in_part(const KinematicsSettings& k, const Angles& a) {
  return table_rotation(k, a).transpose() * head_axis(k, a);
}

namespace {

// Where the tip goes when the head axes turn, relative to the programmed point.
Vec3 head_offset(const KinematicsSettings& k, const Angles& a, double pivot) {
  // Innermost head axis first: the tip, at the programmed point, swings about each axis.
  Vec3 tip = Vec3::Zero();
  for (int i = int(k.rotaries.size()) - 1; i >= 0; --i) {
    const RotaryAxis& r = k.rotaries[size_t(i)];
    if (r.table) continue;
    Vec3 c = r.center + Vec3::UnitZ() * pivot;
    tip = c + rotation(r.effective(), a[size_t(i)]) * (tip - c);
  }
  return tip;
}

}  // namespace

Vec3 machine_point(const KinematicsSettings& k, const Angles& a, const Vec3& tip, double pivot) {
  return table_point(k, a, tip) - head_offset(k, a, pivot);
}

Vec3 part_tip(const KinematicsSettings& k, const Angles& a, const Vec3& machine, double pivot) {
  Vec3 tip_m = machine + head_offset(k, a, pivot);
  // Undo the table axes, outermost first.
  Vec3 x = tip_m;
  for (size_t i = 0; i < k.rotaries.size(); ++i) {
    const RotaryAxis& r = k.rotaries[i];
    if (!r.table) continue;
    x = r.center + rotation(r.effective(), -a[i]) * (x - r.center);
  }
  return x;
}

namespace {

Solutions solve_fixed(const KinematicsSettings& k, const Vec3& axis) {
  const auto& r = k.rotaries;
  Vec3 v = axis.normalized(), z = Vec3::UnitZ();
  if (r.size() == 1) {
    // Table: R v = z. Head: R z = v.
    return r[0].table ? solve_one(r[0].effective(), v, z) : solve_one(r[0].effective(), z, v);
  }
  if (r.size() != 2) return {};
  bool t0 = r[0].table, t1 = r[1].table;
  if (t0 && t1) return solve_two(r[0].effective(), r[1].effective(), v, z);
  if (!t0 && !t1) return solve_two(r[0].effective(), r[1].effective(), z, v);
  // One head and one table axis: R_T v = R_H z, i.e. R_H(-t) R_T v = z.
  size_t h = t0 ? 1 : 0, t = t0 ? 0 : 1;
  Solutions s = solve_two(-r[h].effective(), r[t].effective(), v, z);
  for (size_t i = 0; i < s.n; ++i) {
    Solution& x = s.v[i];
    Solution y;
    y.a[h] = x.a[0];
    y.free[h] = x.free[0];
    y.a[t] = x.a[1];
    y.free[t] = x.free[1];
    x = y;
  }
  return s;
}

}  // namespace

std::vector<Solution> solve(const KinematicsSettings& k, const Vec3& axis) {
  Solutions s = solve_fixed(k, axis);
  return std::vector<Solution>(s.begin(), s.end());
}

namespace {

double axis_distance(const RotaryAxis& r, double a, double b) {
  double d = std::abs(a - b);
  if (r.cyclic == Cyclic::Modulo) d = std::min(d, 360 - std::fmod(d, 360.0));
  return d;
}

bool axis_in_limits(const RotaryAxis& r, double v) {
  // 1e-4 degree: a tool axis written with 7 decimals is that far off the angle it stands for
  // (0.8660254 is 30.0000002 degrees); every rotary format rounds it away.
  return r.cyclic != Cyclic::No || (v >= r.min - kLimitTol && v <= r.max + kLimitTol);
}

// The values an axis may take for a solution angle: nearest the current one for continuous
// axes, every turn within reach for limited ones.
struct Values {
  double v[9];
  size_t n = 0;
};

Values representatives(const RotaryAxis& r, double base, double current) {
  Values v;
  if (r.cyclic == Cyclic::Modulo) {
    double m = std::fmod(base, 360.0);
    v.v[v.n++] = m < 0 ? m + 360 : m;
  } else if (r.cyclic == Cyclic::Wind) {
    v.v[v.n++] = base + 360 * std::round((current - base) / 360);
  } else {
    // Every turn that could be within the limits, or within reach of a position that is
    // (the jump test looks no farther than 90 degrees).
    for (int n = -4; n <= 4; ++n) {
      double x = base + 360 * n;
      if (x >= r.min - 360 && x <= r.max + 360) v.v[v.n++] = x;
    }
  }
  return v;
}

}  // namespace

Choice choose(const KinematicsSettings& k, const Vec3& axis, const Angles* current, bool sign_first) {
  Choice best, any;
  double best_cost = 1e300, any_cost = 1e300;
  const size_t n = k.rotaries.size();
  for (const Solution& s : solve_fixed(k, axis)) {
    Values vals[kMaxRotaries];
    for (size_t i = 0; i < n; ++i) {
      double cur = current ? (*current)[i] : 0.0;
      if (s.free[i]) vals[i].v[vals[i].n++] = cur;
      else vals[i] = representatives(k.rotaries[i], s.a[i], cur);
    }
    auto consider = [&](const Angles& a) {
      double cost = 0, pref = 0;
      bool ok = true;
      for (size_t i = 0; i < n; ++i) {
        const RotaryAxis& r = k.rotaries[i];
        cost += axis_distance(r, a[i], current ? (*current)[i] : 0.0);
        if (r.prefer != 0 && a[i] * r.prefer < -1e-9) pref += 1;
        ok = ok && axis_in_limits(r, a[i]);
      }
      double total = cost + pref * (sign_first ? 1e6 : 1e-6);
      if (total < any_cost) {
        any_cost = total;
        any.a = a;
        any.found = true;
      }
      if (ok && total < best_cost) {
        best_cost = total;
        best.a = a;
        best.found = true;
      }
    };
    if (n == 1) {
      for (size_t i = 0; i < vals[0].n; ++i) consider({vals[0].v[i], 0});
    } else if (n == 2) {
      for (size_t i = 0; i < vals[0].n; ++i)
        for (size_t j = 0; j < vals[1].n; ++j) consider({vals[0].v[i], vals[1].v[j]});
    }
  }
  best.jump = best.found && current && any_cost < best_cost - 1e-6 && any_cost < 90;
  // Within the tolerance past a limit is the limit: written as solved, B30.0001 would pass B30.
  for (size_t i = 0; best.found && i < n; ++i)
    if (k.rotaries[i].cyclic == Cyclic::No) best.a[i] = std::clamp(best.a[i], k.rotaries[i].min, k.rotaries[i].max);
  return best;
}

double travel(const RotaryAxis& r, double from, double to) {
  double d = to - from;
  if (r.cyclic == Cyclic::Modulo) {
    d = std::fmod(d, 360.0);
    if (d > 180) d -= 360;
    if (d <= -180) d += 360;
  }
  return d;
}

Angles between(const KinematicsSettings& k, const Angles& a0, const Angles& a1, double t) {
  Angles a = a0;
  for (size_t i = 0; i < k.rotaries.size() && i < a.size(); ++i) a[i] = a0[i] + t * travel(k.rotaries[i], a0[i], a1[i]);
  return a;
}

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / kPi;
}

std::optional<size_t> pole_free_axis(const KinematicsSettings& k) {
  if (k.rotaries.size() != 2) return std::nullopt;
  const Vec3 s = tool_axis_in_part(k, {0, 0});
  const RotaryAxis& inner = k.rotaries[1];
  const Vec3 u = inner.table ? inner.effective() : rotation(k.rotaries[0].effective(), 0) * inner.effective();
  if (std::abs(std::abs(s.dot(u.normalized())) - 1) <= 1e-9) return 1;
  // The outer axis along the tool at zero: turning it turns the tool about itself.
  if (std::abs(std::abs(s.dot(k.rotaries[0].effective().normalized())) - 1) <= 1e-9) return 0;
  return std::nullopt;
}

double off_sweep(const Vec3& v, const Vec3& a0, const Vec3& a1) {
  const double end = std::min(angle_between(v, a0), angle_between(v, a1));
  const Vec3 n = a0.cross(a1);
  if (n.norm() < 1e-12) return end;
  const Vec3 u = n.normalized();
  const Vec3 in = v - v.dot(u) * u;  // v projected into the arc's plane
  if (in.norm() < 1e-12) return end;
  const Vec3 w = in.normalized();
  if (std::abs(angle_between(a0, w) + angle_between(w, a1) - angle_between(a0, a1)) > 1e-9) return end;
  return std::asin(std::min(1.0, std::abs(v.dot(u)))) * 180 / kPi;
}

bool RotaryIndexing::apply(const KinematicsSettings& k, const ir::RotaryIndex& ri, std::string& why) {
  int which = -1;
  for (size_t i = 0; i < k.rotaries.size(); ++i) {
    const bool named = ri.axis != '?' ? k.rotaries[i].name == std::string(1, ri.axis) : k.rotaries[i].table;
    if (!named) continue;
    if (which >= 0) {
      if (!ri.incremental && ri.angle == 0 && !on) return true;
      why = "ROTABL names no axis, and the machine turns its table about two: have the CAM system name the axis "
            "(AAXIS, BAXIS, CAXIS)";
      return false;
    }
    which = int(i);
  }
  if (which < 0 || !k.rotaries[size_t(which)].table) {
    if (!ri.incremental && ri.angle == 0 && !on) return true;  // to 0, where it is: nothing to do
    why = "the machine has no " + (ri.axis == '?' ? std::string("rotary table") : std::string(1, ri.axis) + " axis on its table") +
          " to index; post for a machine that has, or have the CAM system write the turned tool path (its tool axes, "
          "MULTAX)";
    return false;
  }
  double& at = angles[size_t(which)];
  at = ri.incremental ? at + ri.angle : ri.angle;
  Angles a{0, 0}, b{0, 0};
  a[size_t(which)] = angles[size_t(which)];
  if (k.rotaries.size() > 1) b[size_t(1 - which)] = angles[size_t(1 - which)];
  rotation = (table_rotation(k, a) * table_rotation(k, b)).transpose();
  on = (rotation - Mat3::Identity()).cwiseAbs().maxCoeff() > 1e-12;
  return true;
}

}  // namespace clpc::kin
