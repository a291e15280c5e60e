#include "machine/tilted_plane.h"

#include <algorithm>
#include <cmath>

namespace clpc::plane {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180;

ir::Mat3 about(int axis, double deg) {
  return ir::Mat3(Eigen::AngleAxisd(deg * kDeg, ir::Vec3::Unit(axis)));
}

// Angles that differ from a round value by rounding noise alone are written as that value.
double tidy(double deg) {
  double r = std::round(deg * 1e9) / 1e9;
  if (r <= -180) r += 360;
  return r == 0 ? 0 : r;  // no -0
}

}  // namespace

ir::Mat3 rotation(const ir::Vec3& a, EulerOrder order) {
  if (order == EulerOrder::Zxz) return about(2, a.x()) * about(0, a.y()) * about(2, a.z());
  return about(0, a.x()) * about(1, a.y()) * about(2, a.z());
}

ir::Vec3 angles(const ir::Mat3& r, EulerOrder order) {
  double i, j, k;
  if (order == EulerOrder::Zxz) {
    // Third column (sin I sin J, -cos I sin J, cos J), third row (sin J sin K, sin J cos K, cos J).
    j = std::acos(std::clamp(r(2, 2), -1.0, 1.0));
    if (std::abs(std::sin(j)) < 1e-12) {
      k = 0;  // I and K turn about the same axis: all of it in I
      i = std::atan2(r(1, 0), r(0, 0));
    } else {
      i = std::atan2(r(0, 2), -r(1, 2));
      k = std::atan2(r(2, 0), r(2, 1));
    }
  } else {
    // First row (cos J cos K, -cos J sin K, sin J), third column (sin J, -sin I cos J, cos I cos J).
    j = std::asin(std::clamp(r(0, 2), -1.0, 1.0));
    if (std::abs(std::cos(j)) < 1e-12) {
      k = 0;
      i = std::atan2(r(2, 1), r(1, 1));
    } else {
      i = std::atan2(-r(1, 2), r(2, 2));
      k = std::atan2(-r(0, 1), r(0, 0));
    }
  }
  return {tidy(i / kDeg), tidy(j / kDeg), tidy(k / kDeg)};
}

ir::Mat3 least_tilt(const ir::Vec3& n0) {
  const ir::Vec3 z = ir::Vec3::UnitZ(), n = n0.normalized();
  ir::Vec3 axis = z.cross(n);
  double s = axis.norm(), c = z.dot(n);
  if (s < 1e-15) return c > 0 ? ir::Mat3::Identity() : about(0, 180);
  return ir::Mat3(Eigen::AngleAxisd(std::atan2(s, c), axis / s));
}

}  // namespace clpc::plane
