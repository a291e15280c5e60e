// Frame records: NX MSYS, Creo/APT CSYS and $$-> CSYS, CAMERA; SET work offsets; ROTATE.
#include <cmath>

#include "ir/lower.h"
#include "ir/params.h"

namespace clpc {

namespace {

// Checks and tidies a rotation read from a CL file (values are printed to ~1e-10): it must be
// orthonormal and right-handed within 1e-4, and is then re-orthonormalised exactly.
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

void Lowerer::lower_msys(const Record& r) {
  ParamReader ps(r, d_);
  if (!ps.all_numbers() || ps.size() != 9) {
    d_.error(ps.size() ? ps[0].loc : r.end, "MSYS needs 9 values (origin, X axis, Y axis), found " + std::to_string(ps.size()));
    return;
  }
  ir::Vec3 o{ps[0].number, ps[1].number, ps[2].number};
  ir::Vec3 x{ps[3].number, ps[4].number, ps[5].number};
  ir::Vec3 y{ps[6].number, ps[7].number, ps[8].number};
  ir::SetFrame f;
  f.source = ir::FrameSource::Msys;
  f.frame.origin = o;
  f.frame.rotation.col(0) = x;
  f.frame.rotation.col(1) = y;
  f.frame.rotation.col(2) = x.cross(y);
  std::string why;
  if (!orthonormalise(f.frame.rotation, why)) {
    d_.error(r.loc, "MSYS: not a valid frame: " + why);
    return;
  }
  ensure_operation(r.loc);
  push(r.loc, f);
}

void Lowerer::lower_matrix_frame(const Record& r, ir::FrameSource src) {
  ParamReader ps(r, d_);
  if (!ps.all_numbers() || ps.size() != 12) {
    d_.error(ps.size() ? ps[0].loc : r.end,
             std::string(r.major) + " needs 12 values (a 3x4 matrix by rows), found " + std::to_string(ps.size()));
    return;
  }
  ir::SetFrame f;
  f.source = src;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) f.frame.rotation(row, col) = ps[size_t(row * 4 + col)].number;
    f.frame.origin[row] = ps[size_t(row * 4 + 3)].number;
  }
  std::string why;
  if (!orthonormalise(f.frame.rotation, why)) {
    d_.error(r.loc, std::string(r.major) + ": not a valid frame: " + why);
    return;
  }
  ensure_operation(r.loc);
  push(r.loc, f);
}

void Lowerer::lower_set(const Record& r) {
  ParamReader ps(r, d_);
  // SET/MODE,ABSOL|INCR is a coordinate mode, not a work offset.
  if (ps.size() >= 1 && ps[0].is("MODE")) {
    if (ps.size() == 2 && ps[1].is("ABSOL")) return;
    if (ps.size() == 2 && ps[1].is("INCR")) {
      d_.error(ps[1].loc, "SET/MODE,INCR (incremental CL data) is not supported");
      return;
    }
    d_.error(r.loc, "SET/MODE: expected ABSOL or INCR");
    return;
  }
  // SET/word,n: work-offset register n for the motion that follows.
  int idx = -1;
  for (size_t i = 0; i < ps.size(); ++i)
    if (ps[i].is_number()) { idx = int(i); break; }
  if (idx < 0) {
    d_.error(r.end, "SET: expected a work-offset register number");
    return;
  }
  auto reg = ps.integer(size_t(idx), "the work-offset register", 1, 999);
  if (!reg) return;
  ensure_operation(r.loc);
  push(r.loc, ir::SelectOffset{*reg});
}

void Lowerer::lower_rotate(const Record& r) {
  ParamReader ps(r, d_);
  ir::RotaryIndex ri;
  bool axis = false, angle = false;
  for (size_t i = 0; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (p.is("AAXIS")) { ri.axis = 'A'; axis = true; }
    else if (p.is("BAXIS")) { ri.axis = 'B'; axis = true; }
    else if (p.is("CAXIS")) { ri.axis = 'C'; axis = true; }
    else if (p.is("INCR")) ri.incremental = true;
    else if (p.is("ATANGL") || p.is("ABSOL")) ri.incremental = false;
    else if (p.is("CLW")) ri.dir = ir::ArcDir::Cw;
    else if (p.is("CCLW")) ri.dir = ir::ArcDir::Ccw;
    else if (p.is_number()) { ri.angle = p.number; angle = true; }
    else {
      d_.error(p.loc, "ROTATE: unknown word '" + std::string(p.text) + "'");
      return;
    }
  }
  if (!axis || !angle) {
    d_.error(r.loc, "ROTATE needs an axis (AAXIS, BAXIS, CAXIS) and an angle");
    return;
  }
  ensure_operation(r.loc);
  push(r.loc, ri);
}

}  // namespace clpc
