#include "lower/frame_records.h"

#include <Eigen/SVD>
#include <cmath>

#include "lower/params.h"

namespace clpc {

namespace {

// Values are printed to ~1e-10: the rotation must be orthonormal and right-handed within 1e-4,
// and is then made exactly so.
bool orthonormalise(ir::Mat3& m, std::string& why) {
  ir::Mat3 g = m.transpose() * m - ir::Mat3::Identity();
  if (g.cwiseAbs().maxCoeff() > 1e-4) {
    why = "its axes are not unit length and perpendicular";
    return false;
  }
  if (m.determinant() < 0) {
    why = "it is left-handed";
    return false;
  }
  Eigen::JacobiSVD<ir::Mat3> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  m = svd.matrixU() * svd.matrixV().transpose();
  return true;
}

}  // namespace

bool read_frame(const Record& r, Diagnostics* d, ir::Frame& f, ir::FrameSource& source) {
  auto fail = [&](SourceLoc loc, const std::string& msg) {
    if (d) d->error(loc, msg);
    return false;
  };
  bool all_numbers = true;
  for (const Param& p : r.params) all_numbers = all_numbers && p.is_number();
  const size_t n = r.params.size();
  SourceLoc first = n ? r.params[0].loc : r.end;
  if (r.id == MajorId::Msys) {
    source = ir::FrameSource::Msys;
    if (!all_numbers || n != 9)
      return fail(first, "MSYS needs 9 values (origin, X axis, Y axis), found " + std::to_string(n));
    auto v = [&](size_t i) { return r.params[i].number; };
    ir::Vec3 x{v(3), v(4), v(5)}, y{v(6), v(7), v(8)};
    f.origin = {v(0), v(1), v(2)};
    f.rotation.col(0) = x;
    f.rotation.col(1) = y;
    f.rotation.col(2) = x.cross(y);
  } else {
    source = r.id == MajorId::Camera ? ir::FrameSource::Camera : ir::FrameSource::Csys;
    if (!all_numbers || n != 12)
      return fail(first, std::string(r.major) + " needs 12 values (a 3x4 matrix by rows), found " + std::to_string(n));
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) f.rotation(row, col) = r.params[size_t(row * 4 + col)].number;
      f.origin[row] = r.params[size_t(row * 4 + 3)].number;
    }
  }
  std::string why;
  if (!orthonormalise(f.rotation, why)) return fail(r.loc, std::string(r.major) + ": not a valid frame: " + why);
  return true;
}

int read_set_register(const Record& r, Diagnostics* d) {
  const auto& ps = r.params;
  if (!ps.empty() && ps[0].is("MODE")) {
    if (ps.size() == 2 && ps[1].is("ABSOL")) return 0;
    if (d) {
      if (ps.size() == 2 && ps[1].is("INCR")) d->error(ps[1].loc, "SET/MODE,INCR (incremental CL data) is not supported");
      else d->error(r.loc, "SET/MODE: expected ABSOL or INCR");
    }
    return -1;
  }
  for (const Param& p : ps) {
    if (!p.is_number()) continue;
    double v = p.number;
    if (v != std::floor(v) || ir::register_index(int(v)) == 0) {
      if (d) d->error(p.loc, "SET: the work-offset register must be 54 to 59 (G54-G59) or 101 and up (extended register 1, ...), found " + num_text(v));
      return -1;
    }
    return int(v);
  }
  if (d) d->error(r.end, "SET: expected a work-offset register number");
  return -1;
}

}  // namespace clpc
