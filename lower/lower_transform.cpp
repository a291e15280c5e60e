// Records that transform or repeat motion, and NURBS:
//
//   TRACUT/a11,a12,a13,a14,a21,...,a34   the motion that follows is moved by this 3x4 matrix
//   TRACUT/NOMORE                        (rows: rotation and translation, as CSYS) ... until here
//   INDEX/n                              marks the start of block n of records
//   INDEX/n,NOMORE                       ... and its end (else the block runs to its COPY)
//   COPY/n,SAME,k                        block n again, k times
//   COPY/n,TRANSL,dx,dy,dz,k             k times, each copy moved by (dx,dy,dz) from the last
//   COPY/n,XYROT,a,k                     k times, each turned a degrees about Z from the last
//   COPY/n,MODIFY,a11,...,a34,k          k times, each moved by the matrix from the last
//
// The copies are lowered again record by record (as CALSUB replays a DEFSUB), with the
// transform applied to every point and direction the records give (Lowerer::xf_point).
#include <cmath>

#include "lower/frame_records.h"
#include "lower/lower.h"
#include "lower/params.h"

namespace clpc {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr size_t kMaxCopies = 10000;

// Twelve numbers from `from` as a 3x4 matrix by rows; the rotation must be a rotation.
bool read_matrix(const ParamReader& ps, size_t from, ir::Frame& f, std::string& why) {
  if (ps.size() < from + 12) {
    why = "12 values (a 3x4 matrix by rows) expected";
    return false;
  }
  for (size_t i = from; i < from + 12; ++i)
    if (!ps[i].is_number()) {
      why = "expected a number, found '" + std::string(ps[i].name()) + "'";
      return false;
    }
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) f.rotation(row, col) = ps[from + size_t(row * 4 + col)].number;
    f.origin[row] = ps[from + size_t(row * 4 + 3)].number;
  }
  ir::Mat3 g = f.rotation.transpose() * f.rotation - ir::Mat3::Identity();
  if (g.cwiseAbs().maxCoeff() > 1e-4 || f.rotation.determinant() < 0) {
    why = "the matrix must turn and move the motion, not scale or mirror it";
    return false;
  }
  return true;
}

}  // namespace

ir::Vec3 Lowerer::xf_point(const ir::Vec3& p) const { return has_xf_ ? ir::Vec3(xf_.rotation * p + xf_.origin) : p; }
ir::Vec3 Lowerer::xf_dir(const ir::Vec3& v) const { return has_xf_ ? ir::Vec3(xf_.rotation * v) : v; }

// Program coordinates of what the CL writes: the MSYS frame (NX writes its points in it) after
// a COPY's transform after TRACUT's.
void Lowerer::update_xf() {
  ir::Frame f = ir::compose(msys_, copy_xf_);
  if (has_tracut_) f = ir::compose(f, tracut_);
  xf_ = f;
  has_xf_ = !f.is_identity(1e-12);
}

void Lowerer::lower_transform(const Record& r) {
  ParamReader ps(r, d_);
  if (r.id == MajorId::Tracut) {
    if (ps.size() == 1 && ps[0].is("NOMORE")) {
      has_tracut_ = false;
      update_xf();
      return;
    }
    ir::Frame f;
    std::string why;
    if (ps.size() != 12 || !read_matrix(ps, 0, f, why)) {
      d_.error(ps.size() ? ps[0].loc : r.end,
               "TRACUT: " + (why.empty() ? std::string("12 values (a 3x4 matrix by rows) or NOMORE expected") : why));
      return;
    }
    tracut_ = f;
    has_tracut_ = true;
    update_xf();
    return;
  }
  if (r.id == MajorId::Index) {
    auto n = ps.integer(0, "the block number", 0, 99999);
    if (!n) return;
    if (ps.size() == 2 && ps[1].is("NOMORE")) {
      if (recording_index_ != *n) {
        d_.error(r.loc, "INDEX/" + std::to_string(*n) + ",NOMORE: block " + std::to_string(*n) + " is not open");
        return;
      }
      recording_index_ = -1;
      return;
    }
    if (ps.size() != 1) {
      d_.error(ps.loc(1), "INDEX: expected INDEX/n or INDEX/n,NOMORE");
      return;
    }
    if (recording_index_ >= 0)
      d_.warning(r.loc, "INDEX/" + std::to_string(*n) + " ends block " + std::to_string(recording_index_) +
                            " (no INDEX/" + std::to_string(recording_index_) + ",NOMORE)",
                 "subroutine");
    blocks_[*n].clear();
    recording_index_ = *n;
    return;
  }
  // COPY/n,how,...,k
  auto n = ps.integer(0, "the block number", 0, 99999);
  if (!n) return;
  auto it = blocks_.find(*n);
  if (it == blocks_.end()) {
    d_.error(ps[0].loc, "COPY/" + std::to_string(*n) + ": no INDEX/" + std::to_string(*n) + " block before it");
    return;
  }
  if (ps.size() < 3 || !ps[1].is_word()) {
    d_.error(ps.loc(1), "COPY: expected COPY/n,SAME|TRANSL|XYROT|MODIFY,...,times");
    return;
  }
  ir::Frame step;
  size_t count_at = 0;
  std::string how = upper(ps[1].text);
  if (how == "SAME") {
    count_at = 2;
  } else if (how == "TRANSL") {
    if (ps.size() != 6 || !ps[2].is_number() || !ps[3].is_number() || !ps[4].is_number()) {
      d_.error(ps.loc(2), "COPY/n,TRANSL needs dx,dy,dz and the number of copies");
      return;
    }
    step.origin = {ps[2].number, ps[3].number, ps[4].number};
    count_at = 5;
  } else if (how == "XYROT") {
    if (ps.size() != 4 || !ps[2].is_number()) {
      d_.error(ps.loc(2), "COPY/n,XYROT needs the angle and the number of copies");
      return;
    }
    double a = ps[2].number * kPi / 180;
    step.rotation << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
    count_at = 3;
  } else if (how == "MODIFY") {
    std::string why;
    if (ps.size() != 15 || !read_matrix(ps, 2, step, why)) {
      d_.error(ps.loc(2), "COPY/n,MODIFY: " + (why.empty() ? std::string("a 3x4 matrix and the number of copies expected") : why));
      return;
    }
    count_at = 14;
  } else {
    d_.error(ps[1].loc, "COPY: unknown way to copy '" + std::string(ps[1].name()) + "' (SAME, TRANSL, XYROT or MODIFY)");
    return;
  }
  if (count_at + 1 != ps.size()) {
    d_.error(ps.loc(count_at + 1), "COPY: the number of copies must come last");
    return;
  }
  auto times = ps.integer(count_at, "the number of copies", 1, int(kMaxCopies));
  if (!times) return;
  if (recording_index_ == *n) recording_index_ = -1;  // the block ends at its COPY
  if (call_depth_ >= 16) {
    d_.error(r.loc, "COPY/" + std::to_string(*n) + ": copies nest deeper than 16");
    return;
  }
  ++call_depth_;
  const std::vector<OwnedRecord> body = it->second;  // the block may be redefined as it plays
  const ir::Frame saved = copy_xf_;
  ir::Frame acc = saved;
  std::vector<Param> scratch;
  bool more = true;
  for (int k = 0; k < *times && more; ++k) {
    acc = ir::compose(acc, step);
    copy_xf_ = acc;
    update_xf();
    d_.push_context(r.loc, "copied by the COPY at");
    for (const OwnedRecord& o : body) {
      if (!(more = replay_one_more(r.loc))) break;
      record(o.view(scratch));
    }
    d_.pop_context();
  }
  copy_xf_ = saved;
  update_xf();
  --call_depth_;
}

// NX writes NURBS/, KNOT/ and CNTRL/ records when an operation's output is set to NURBS. Their
// layout is not published and no real file shows it, so clpc cannot evaluate the curve.
void Lowerer::lower_nurbs(const Record& r) {
  if (r.id != MajorId::Nurbs) return;  // one error per curve, at its NURBS record
  motion_not_read(r, "NURBS curves are not read; in NX set the operation's Machine Control > Motion Output to "
                     "'Linear Only' or 'Arcs' (or the post's NURBS output off) and write the CLSF again");
}

}  // namespace clpc
