#include "ir/thread_model.h"

#include <cmath>

namespace clpc::thread_model {

std::vector<double> depths(const Multi& p) {
  std::vector<double> out;
  if (!(p.height > 0) || !(p.first > 0) || !(p.allowance >= 0) || !(p.allowance < p.height) || p.finish_passes < 1 ||
      p.finish_passes > 99)
    return out;
  const double rough_bottom = p.height - p.allowance;
  double previous = 0;
  for (size_t n = 1;; ++n) {
    double d = p.first * std::sqrt(double(n));
    if (n > 1 && d - previous < p.min_step) d = previous + p.min_step;
    if (d >= rough_bottom || out.size() >= kMaxPasses) break;
    out.push_back(d);
    previous = d;
  }
  if (out.size() >= kMaxPasses) return {};
  out.push_back(rough_bottom);
  for (int i = 0; i < p.finish_passes; ++i) out.push_back(p.height);
  return out;
}

void box(const ir::Vec3& start, const ir::Vec3& end, std::vector<Step>& out) {
  out.push_back({ir::Vec3(end.x(), 0, start.z()), false});
  out.push_back({ir::Vec3(end.x(), 0, end.z()), true});
  out.push_back({ir::Vec3(start.x(), 0, end.z()), false});
  out.push_back({ir::Vec3(start.x(), 0, start.z()), false});
}

std::vector<Step> multi(const ir::Vec3& start, const ir::Vec3& end, const Multi& p) {
  std::vector<Step> out;
  const double side = start.x() >= end.x() ? 1 : -1;  // outside (OD) or inside (ID) thread
  const double crest = end.x() + side * p.height;
  for (double d : depths(p)) box(start, ir::Vec3(crest - side * d, 0, end.z()), out);
  return out;
}

}  // namespace clpc::thread_model
