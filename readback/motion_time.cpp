#include "readback/motion_time.h"

#include <algorithm>
#include <cmath>

namespace clpc {

namespace {

constexpr size_t kWindow = 256;
constexpr double kPi = 3.14159265358979323846;

bool finite(const ir::Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// The most a move along unit `u` may go (per second) and speed up, from each axis's own.
void along(const MotionSettings& m, const ir::Vec3& u, double& v, double& a) {
  v = a = INFINITY;
  for (int i = 0; i < 3; ++i) {
    const double c = std::abs(u[i]);
    if (c < 1e-12) continue;
    v = std::min(v, m.velocity[i] / 60 / c);
    a = std::min(a, m.acceleration[i] / c);
  }
}

}  // namespace

double MotionTimer::trapezoid(double length, double v0, double v1, double v_max, double a) {
  if (length <= 0) return 0;
  v_max = std::max(v_max, std::max(v0, v1));
  const double d_up = (v_max * v_max - v0 * v0) / (2 * a), d_down = (v_max * v_max - v1 * v1) / (2 * a);
  if (d_up + d_down <= length) return (v_max - v0) / a + (v_max - v1) / a + (length - d_up - d_down) / v_max;
  // No time at full speed: up to the peak the length allows, and down.
  const double peak = std::sqrt((2 * a * length + v0 * v0 + v1 * v1) / 2);
  return (peak - v0) / a + (peak - v1) / a;
}

void MotionTimer::add(const gcode::Segment& s) {
  if (!known()) return;
  if (!finite(s.start) || !finite(s.end)) {
    stop();
    return;
  }
  double rotary_seconds = 0;
  for (int i = 0; i < 3; ++i) {
    const double turn = std::abs(s.rotary[size_t(i)] - s.rotary_start[size_t(i)]);
    if (turn > 0 && std::isfinite(turn) && m_.rotary_velocity[i] > 0) rotary_seconds = std::max(rotary_seconds, turn / m_.rotary_velocity[i]);
  }
  const ir::Vec3 d = s.end - s.start;
  if (s.kind == gcode::Segment::Kind::Rapid) {
    // Each axis on its own, from rest to rest, at its own top speed.
    stop();
    double t = rotary_seconds;
    for (int i = 0; i < 3; ++i) t = std::max(t, trapezoid(std::abs(d[i]), 0, 0, m_.velocity[i] / 60, m_.acceleration[i]));
    seconds_ += t;
    return;
  }
  Block b;
  b.min_seconds = rotary_seconds;
  double feed = s.per_rev ? s.feed * s.rpm : s.feed;  // units per minute
  if (s.kind == gcode::Segment::Kind::Arc) {
    const double rise = d.dot(s.normal);
    const double arc = s.start_radius * s.sweep * kPi / 180;
    b.length = std::hypot(arc, rise);
    if (!(b.length > 0)) return;
    // Tangents at the ends: about the normal, the arc's way.
    const ir::Vec3 n = s.normal.normalized();
    ir::Vec3 rs = s.start - s.center, re = s.end - s.center;
    rs -= rs.dot(n) * n;
    re -= re.dot(n) * n;
    const double sense = s.ccw ? 1 : -1;
    const ir::Vec3 lift = n * (rise / b.length);
    b.dir_in = (sense * n.cross(rs).normalized() * (arc / b.length) + lift).normalized();
    b.dir_out = (sense * n.cross(re).normalized() * (arc / b.length) + lift).normalized();
    // The in-plane axes set the pace; the centripetal acceleration bounds the speed.
    double v = INFINITY, a = INFINITY;
    for (int i = 0; i < 3; ++i) {
      if (std::abs(n[i]) > 0.999) continue;
      v = std::min(v, m_.velocity[i] / 60);
      a = std::min(a, m_.acceleration[i]);
    }
    b.accel = a;
    b.v_max = std::min(v, std::sqrt(a * std::max(s.start_radius, 1e-9)));
  } else {
    b.length = d.norm();
    if (!(b.length > 0)) {
      if (rotary_seconds > 0) {  // the rotaries alone
        stop();
        seconds_ += rotary_seconds;
      }
      return;
    }
    b.dir_in = b.dir_out = d / b.length;
    along(m_, b.dir_in, b.v_max, b.accel);
  }
  if (s.inverse_time) {
    if (s.feed > 0) b.min_seconds = std::max(b.min_seconds, 60 / s.feed);
  } else if (dpm_ && gcode::feeds_combined(s)) {
    if (s.feed > 0) b.min_seconds = std::max(b.min_seconds, 60 * gcode::combined_length(s, kinematics_) / s.feed);
  } else if (feed > 0) {
    b.v_max = std::min(b.v_max, feed / 60);
  }
  push(b);
}

void MotionTimer::push(Block b) {
  // The corner with the block before: how fast the path may turn it within the junction
  // deviation (0 when the machine gives none: exact stop).
  b.v_corner = 0;
  if (!window_.empty()) {
    const Block& p = window_.back();
    const double cos_theta = -p.dir_out.dot(b.dir_in);  // 1: a reversal, -1: straight on
    double v = std::min(p.v_max, b.v_max);
    if (cos_theta > 0.999999) {
      v = 0;
    } else if (cos_theta > -0.999999) {
      const double sin_half = std::sqrt(0.5 * (1 - cos_theta));
      const double a = std::min(p.accel, b.accel);
      v = std::min(v, std::sqrt(a * m_.junction_deviation * sin_half / (1 - sin_half)));
    }
    b.v_corner = v;
  }
  window_.push_back(b);
  if (window_.size() >= kWindow) plan(kWindow / 2);
}

void MotionTimer::plan(size_t retire) {
  const size_t n = window_.size();
  if (n == 0) return;
  // Backward: each block must be able to slow down to what the next may enter with (the
  // last stops).
  std::vector<double> entry(n + 1, 0.0);
  entry[n] = 0;
  for (size_t i = n; i-- > 0;) {
    const Block& b = window_[i];
    const double limit = i == 0 ? entry_ : b.v_corner;
    entry[i] = std::min({limit, b.v_max, std::sqrt(entry[i + 1] * entry[i + 1] + 2 * b.accel * b.length)});
  }
  // Forward: and speed up no faster than it can.
  entry[0] = std::min(entry[0], entry_);
  for (size_t i = 0; i < n; ++i) {
    const Block& b = window_[i];
    entry[i + 1] = std::min(entry[i + 1], std::sqrt(entry[i] * entry[i] + 2 * b.accel * b.length));
    if (i < retire) {
      double t = trapezoid(b.length, entry[i], entry[i + 1], b.v_max, b.accel);
      seconds_ += std::max(t, b.min_seconds);
    }
  }
  retire = std::min(retire, n);
  entry_ = entry[retire];
  window_.erase(window_.begin(), window_.begin() + std::ptrdiff_t(retire));
}

void MotionTimer::stop() {
  plan(window_.size());
  entry_ = 0;
}

double MotionTimer::minutes() {
  stop();
  return seconds_ / 60;
}

}  // namespace clpc
