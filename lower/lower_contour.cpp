// Arc forms other than CIRCLE/...+GOTO, and the tool-axis record:
//
//   MOVARC/xc,yc,zc,i,j,k,r,ANGLE,a     Fusion ("APT ISO 4343" post): a turn of a degrees about
//                                       the axis (right-hand rule; a < 0 turns the other way)
//                                       from where the tool is; the end point is not written
//   INDIRV/i,j,k                        the direction the next contour motion starts in
//   TLON,GOFWD/(CIRCLE/xc,yc,zc,r),ON,[n,INTOF,](LINE/x1,y1,z1,x2,y2,z2)
//                                       CATIA: the tool centre along a circle, setting off
//                                       along INDIRV, up to the n-th time (default 1) it meets
//                                       the line; CIRCLE may also be xc,yc,zc,i,j,k,r
//   TLAXIS/i,j,k                        CATIA: the tool axis of the GOTOs that follow
//
// Contouring other than this (TLLFT/TLRGT, TO/PAST/TANTO, other drive or check surfaces)
// needs the tool's shape to find where it stops; it is refused with a located error that
// says what to ask of the CAM system (docs/cl-input.md).
#include <cmath>

#include "ir/arc_geometry.h"
#include "lower/lower.h"
#include "lower/params.h"

namespace clpc {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Rotates v about unit axis n by angle (radians), right-handed.
ir::Vec3 rotate(const ir::Vec3& v, const ir::Vec3& n, double angle) {
  return v * std::cos(angle) + n.cross(v) * std::sin(angle) + n * n.dot(v) * (1 - std::cos(angle));
}

// The numbers of a group (CIRCLE/..., LINE/...), or false when it holds anything else.
bool group_numbers(const Param* g, std::vector<double>& out) {
  out.clear();
  for (uint32_t i = 1; i <= g->group_size; ++i) {
    if (!g[i].is_number()) return false;
    out.push_back(g[i].number);
  }
  return true;
}

}  // namespace

bool is_contour_motion(MajorId id) {
  switch (id) {
    case MajorId::Gofwd: case MajorId::Golft: case MajorId::Gorgt: case MajorId::Goback: case MajorId::Goup:
    case MajorId::Godown:
      return true;
    default: return false;
  }
}

void Lowerer::lower_tlaxis(const Record& r) {
  ParamReader ps(r, d_);
  if (ps.size() != 3 || !ps.all_numbers()) {
    motion_not_read(r, "only TLAXIS/i,j,k (a fixed tool axis) is read; an axis tied to surfaces needs the part model: "
                       "have the CAM system write the tool axis on every GOTO (MULTAX)");
    return;
  }
  ir::Vec3 a{ps[0].number, ps[1].number, ps[2].number};
  double n = a.norm();
  if (!(n > 1e-9)) {
    d_.error(ps[0].loc, "TLAXIS: the tool axis (i,j,k) must not be zero");
    return;
  }
  axis_ = a / n;
}

void Lowerer::lower_indirv(const Record& r) {
  ParamReader ps(r, d_);
  if (ps.size() != 3 || !ps.all_numbers()) {
    d_.error(ps.size() ? ps[0].loc : r.end, "INDIRV needs a direction i,j,k");
    return;
  }
  ir::Vec3 v{ps[0].number, ps[1].number, ps[2].number};
  if (!(v.norm() > 1e-9)) {
    d_.error(ps[0].loc, "INDIRV: the direction must not be zero");
    return;
  }
  indirv_ = xf_dir(v.normalized());
  has_indirv_ = true;
  indirv_loc_ = r.loc;
}

// An arc as lowering hands it on: decided by its record, checked by the arc-direction pass.
void Lowerer::push_arc(ir::Arc& a, SourceLoc loc, const char* what) {
  if (rapid_next_) {
    d_.warning(loc, std::string(what) + " after RAPID is cut at the feed rate, as every arc", "rapid-arc");
    rapid_next_ = false;
  }
  a.tool_axis = xf_dir(axis_);
  ensure_operation(loc);
  push(loc, a);
  pos_ = a.end;
  has_pos_ = true;
  // Forward, for a contour that follows without INDIRV: along the arc at its end.
  direction_ = arcgeo::tangent_at(a, 1.0);
  has_direction_ = direction_.norm() > 0;
}

void Lowerer::lower_movarc(const Record& r) {
  ParamReader ps(r, d_);
  const int angle_at = ps.find("ANGLE");
  if (ps.size() != 9 || angle_at != 7) {
    d_.error(ps.size() ? ps[0].loc : r.end, "MOVARC needs xc,yc,zc,i,j,k,r,ANGLE,a (the centre, the axis, the radius and the "
                                           "angle turned)");
    return;
  }
  for (size_t i : {0, 1, 2, 3, 4, 5, 6, 8})
    if (!ps[i].is_number()) {
      d_.error(ps[i].loc, "MOVARC: expected a number, found '" + std::string(ps[i].name()) + "'");
      return;
    }
  if (!tool_ready(r.loc, ir::MoveKind::Feed)) return;
  if (!has_pos_) {
    d_.error(r.loc, "MOVARC needs a start point: no motion comes before it");
    return;
  }
  ir::Arc a;
  a.layout = ir::ArcLayout::Movarc;
  a.start = pos_;
  a.center = xf_point({ps[0].number, ps[1].number, ps[2].number});
  ir::Vec3 axis = xf_dir({ps[3].number, ps[4].number, ps[5].number});
  if (!(axis.norm() > 1e-9)) {
    d_.error(ps[3].loc, "MOVARC: the axis (i,j,k) must not be zero");
    return;
  }
  a.axis = axis.normalized();
  a.radius = ps[6].number;
  const double angle = ps[8].number;
  if (!(a.radius > 0)) {
    d_.error(ps[6].loc, "MOVARC: the radius must be greater than zero, found " + num_text(a.radius));
    return;
  }
  if (!(std::abs(angle) > 1e-9) || std::abs(angle) > 360.0 * 10000) {
    d_.error(ps[8].loc, "MOVARC: the angle must be other than zero (and at most 10000 turns), found " + num_text(angle));
    return;
  }
  const ir::Vec3 rs = arcgeo::radial(a, a.start);
  a.end = a.center + a.axis * arcgeo::axial(a, a.start) + rotate(rs, a.axis, angle * kPi / 180);
  if (!on_circle(a, r.loc, r.loc)) return;
  a.hint = angle > 0 ? ir::ArcDir::Ccw : ir::ArcDir::Cw;
  const double turns = std::abs(angle) / 360;
  a.extra_turns = uint16_t(std::max(0.0, std::ceil(turns - 1e-9) - 1));
  push_arc(a, r.loc, "MOVARC");
}

void Lowerer::lower_contour(const Record& r) {
  const std::string major = upper(r.major);
  auto refuse = [&](SourceLoc at, const std::string& what) {
    d_.error(at, "TLON,GOFWD contouring: " + what +
                     "; have the CAM system write the motion as GOTO and CIRCLE records (in CATIA: circular "
                     "interpolation output as CIRCLE, or the PP table's GOTO form)");
  };
  if (r.head.empty()) {
    // APT keeps the tool position (TLON, TLLFT, TLRGT) of the last motion statement that gave
    // one; a CL record without it says nothing of where the tool stands against the curve.
    refuse(r.loc, major + " without TLON, TLLFT or TLRGT before it: where the tool stands against the curve (on it, "
                          "or beside it by its radius) is not said");
    return;
  }
  if (r.head.size() != 1 || !r.head[0].is("TLON")) {
    refuse(r.loc, "only TLON (the tool centre on the drive surface) is read; TLLFT and TLRGT set the tool beside it by "
                  "its radius");
    return;
  }
  if (r.id != MajorId::Gofwd) {
    refuse(r.loc, major + " turns off the direction of travel; only GOFWD is read");
    return;
  }
  ParamReader ps(r, d_);
  // (CIRCLE/...), ON, [n, INTOF,] (LINE/...)
  if (ps.size() == 0 || !ps[0].is_group() || !iequals(ps[0].text, "CIRCLE")) {
    refuse(ps.size() ? ps[0].loc : r.end, "the drive surface must be (CIRCLE/...)");
    return;
  }
  std::vector<double> c;
  if (!group_numbers(&ps[0], c) || (c.size() != 4 && c.size() != 7)) {
    d_.error(ps[0].loc, "TLON,GOFWD: (CIRCLE/xc,yc,zc,r) or (CIRCLE/xc,yc,zc,i,j,k,r) expected");
    return;
  }
  size_t i = 1 + ps[0].group_size;
  if (i >= ps.size() || !ps[i].is_word()) {
    d_.error(ps.loc(i), "TLON,GOFWD: the check modifier (ON) must follow the circle");
    return;
  }
  if (!ps[i].is("ON")) {
    refuse(ps[i].loc, "only ON (the tool centre on the check surface) is read; " + upper(ps[i].text) +
                          " stops the tool by its radius");
    return;
  }
  ++i;
  int nth = 1;
  if (i + 1 < ps.size() && ps[i].is_number() && ps[i + 1].is("INTOF")) {
    auto n = ps.integer(i, "the intersection count", 1, 16);
    if (!n) return;
    nth = *n;
    i += 2;
  }
  if (i >= ps.size() || !ps[i].is_group() || !iequals(ps[i].text, "LINE") || i + 1 + ps[i].group_size != ps.size()) {
    refuse(ps.loc(i), "the check surface must be (LINE/...), last in the record");
    return;
  }
  std::vector<double> l;
  if (!group_numbers(&ps[i], l) || (l.size() != 6 && l.size() != 4)) {
    d_.error(ps[i].loc, "TLON,GOFWD: (LINE/x1,y1,z1,x2,y2,z2) or (LINE/x1,y1,x2,y2) expected");
    return;
  }
  if (!tool_ready(r.loc, ir::MoveKind::Feed)) return;
  if (!has_pos_) {
    d_.error(r.loc, "TLON,GOFWD needs a start point: no motion comes before it");
    return;
  }
  const bool from_indirv = has_indirv_;
  ir::Vec3 dir = has_indirv_ ? indirv_ : direction_;
  if (!has_indirv_ && !has_direction_) {
    d_.error(r.loc, "TLON,GOFWD: no direction to set off in (INDIRV, or a motion before it)");
    return;
  }
  has_indirv_ = false;

  ir::Arc a;
  a.layout = ir::ArcLayout::Contour;
  a.start = pos_;
  a.center = xf_point({c[0], c[1], c[2]});
  a.radius = c.back();
  if (!(a.radius > 0)) {
    d_.error(ps[0].loc, "TLON,GOFWD: the circle's radius must be greater than zero");
    return;
  }
  const ir::Vec3 rs = a.start - a.center;
  const double tol = std::max(0.01 / ir::mm_per_unit(info_.units), 1e-6 * a.radius);
  if (std::abs(rs.norm() - a.radius) > tol) {
    refuse(r.loc, "the tool (at " + num_text(rs.norm()) + " from the centre) is not on the circle of radius " +
                      num_text(a.radius));
    return;
  }
  // The plane the tool turns in holds the start, the centre and the direction it sets off in;
  // it turns counter-clockwise about n = (start - centre) x direction.
  ir::Vec3 n = rs.cross(dir);
  if (n.norm() < 0.02 * a.radius) {
    d_.error(r.loc, "TLON,GOFWD: the direction to set off in (INDIRV) points along the radius: which way round is not "
                    "told");
    return;
  }
  n.normalize();
  if (c.size() == 4 && !from_indirv) {
    // No INDIRV: the plane holds the direction of the motion before. After a ramp it tilted
    // with the ramp, after a plunge it stood upright, and the arc left the plane the circle's
    // centre lies in (CATIA writes INDIRV before every contour: 405 of 405 in the corpus, in
    // XY and, on its lathes, ZX). Only a motion in the XY plane says the plane: any other is
    // refused, not guessed.
    const ir::Vec3 local = has_xf_ ? ir::Vec3(xf_.rotation.transpose() * n) : n;  // in the CL's own axes
    if (std::abs(local.z()) < 1 - 1e-9) {
      d_.error(r.loc, "TLON,GOFWD with no INDIRV: the plane the tool turns in is taken from the motion before it, "
                      "which is not in the XY plane (a ramp, a plunge?); give INDIRV before the contour");
      return;
    }
  }
  if (c.size() == 7) {
    ir::Vec3 given = xf_dir({c[3], c[4], c[5]});
    if (!(given.norm() > 1e-9) || std::abs(std::abs(given.normalized().dot(n)) - 1) > 1e-6) {
      refuse(ps[0].loc, "the direction to set off in does not lie in the circle's plane");
      return;
    }
  }
  a.axis = n;
  a.hint = ir::ArcDir::Ccw;
  // Where the line meets the circle, in the circle's plane, in the order the tool comes to them.
  // (LINE/x1,y1,x2,y2) lies at the height of the circle's centre as written.
  ir::Vec3 p1 = xf_point(l.size() == 6 ? ir::Vec3(l[0], l[1], l[2]) : ir::Vec3(l[0], l[1], c[2]));
  ir::Vec3 p2 = xf_point(l.size() == 6 ? ir::Vec3(l[3], l[4], l[5]) : ir::Vec3(l[2], l[3], c[2]));
  auto flat = [&](const ir::Vec3& p) { return ir::Vec3(p - n * n.dot(p - a.center) - a.center); };
  ir::Vec3 q1 = flat(p1), q2 = flat(p2), d = q2 - q1;
  if (!(d.norm() > 1e-9)) {
    d_.error(ps[i].loc, "TLON,GOFWD: the check line is a point (or stands square to the circle's plane)");
    return;
  }
  d.normalize();
  double tc = -q1.dot(d);
  ir::Vec3 foot = q1 + d * tc;
  double h2 = a.radius * a.radius - foot.squaredNorm();
  std::vector<double> angles;
  if (h2 >= -tol * a.radius) {
    double h = std::sqrt(std::max(0.0, h2));
    for (double s : {-h, h}) {
      ir::Vec3 p = foot + d * s;
      double ang = arcgeo::ccw_angle(rs, p, n);
      if (ang < 1e-9 || 2 * kPi - ang < 1e-9) ang = 2 * kPi;  // at the start: met after a full turn
      angles.push_back(ang);
      if (h == 0) break;
    }
  }
  std::sort(angles.begin(), angles.end());
  // The k-th meeting: on later turns the same points come again.
  if (angles.empty()) {
    refuse(ps[i].loc, "the check line does not meet the circle");
    return;
  }
  const size_t per_turn = angles.size();
  const double sweep = angles[size_t(nth - 1) % per_turn] + 2 * kPi * double(size_t(nth - 1) / per_turn);
  if (sweep > 2 * kPi + 1e-9) {
    refuse(ps[i].loc, "the circle meets the check line " + std::to_string(per_turn) + " time(s) a turn; meeting it " +
                          std::to_string(nth) + " times goes round more than once");
    return;
  }
  a.end = a.center + rotate(rs, n, sweep);
  push_arc(a, r.loc, "TLON,GOFWD");
}

}  // namespace clpc
