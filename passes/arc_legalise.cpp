// arc-legalise: arcs the machine cannot do become arcs or lines it can. Arcs outside the
// machine's planes (or in an arbitrary plane) and radii outside min/max are linearised within
// tolerance; sweeps over the maximum are split; R-format machines never get a full circle;
// an arc too short to survive rounding (its rounded ends would meet, which a control reads as
// a full circle) becomes a straight move; an arc over half a turn whose centre, once its ends
// are rounded, would put the arc off the CL arc by more than the tolerance is split in two; an
// R-format arc whose rounded R and ends put its path off (near half or a full turn) is split
// into the fewest equal pieces that are not.
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and provides)
// is arc_legalise_pass() at the end of this file.
#include <cmath>

#include "ir/arc_geometry.h"
#include "machine/arc_center.h"
#include "machine/format.h"
#include "passes/arc_edit.h"
#include "passes/passes.h"

namespace clpc {

namespace {

bool plane_ok(const ArcSettings& s, const ir::Vec3& axis) {
  const double k = 1 - 1e-9;
  if (std::abs(axis.z()) > k) return s.xy;
  if (std::abs(axis.y()) > k) return s.zx;
  if (std::abs(axis.x()) > k) return s.yz;
  return false;
}

double rounded(double value, const AddressFormat& f) {
  int64_t q;
  return quantize(value, f, q) ? dequantize(q, f) : value;
}

// How far the arc the control cuts passes from this one at its midpoint, with the centre the
// backend will choose for the rounded ends (output units). Over half a turn the centre lies
// beyond the chord: a short chord turns each increment of rounding at its ends into R/chord
// increments at the centre, and twice that on the far side of the arc (a near-full helix of
// 0.74 in radius with a 0.135 in chord came out 0.00042 in off on the UMC-750).
double rounded_centre_deviation(const ir::Arc& a, const Machine& m, double to_out) {
  struct Plane {
    int u, v;
    char lu, lv, cu, cv;
  } p;
  if (std::abs(a.axis.z()) > 1 - 1e-9) p = {0, 1, 'X', 'Y', 'I', 'J'};
  else if (std::abs(a.axis.y()) > 1 - 1e-9) p = {2, 0, 'Z', 'X', 'K', 'I'};
  else p = {1, 2, 'Y', 'Z', 'J', 'K'};
  const ir::Vec3 s = a.start * to_out, e = a.end * to_out, c = a.center * to_out;
  const ir::Vec3 mid = arcgeo::point_at(a, 0.5) * to_out;
  const ir::Vec3 normal = ir::Vec3::Unit(p.u == 0 ? 2 : p.u == 2 ? 1 : 0);
  const bool ccw = (a.dir == ir::ArcDir::Ccw) == (a.axis.dot(normal) > 0);
  ArcCenterInput in{rounded(s[p.u], m.format(p.lu)), rounded(s[p.v], m.format(p.lv)),
                    rounded(e[p.u], m.format(p.lu)), rounded(e[p.v], m.format(p.lv)),
                    c[p.u], c[p.v], mid[p.u], mid[p.v], ccw, false};
  return choose_arc_center(in, m.format(p.cu), m.format(p.cv), m.arcs.center == ArcCenter::Incremental).deviation;
}

// The same for an R-format arc: how far the CL arc lies from the circle the control cuts. The
// backend writes R from the rounded start to the centre it chooses (choose_arc_center), rounded
// to format.R; the control puts the centre on the bisector of the rounded chord at the distance
// that R gives. Near half a turn that distance is small and each increment of R moves it by
// R/distance increments (179.5 degrees of R10 came out 0.044 off); near a full turn the short
// chord turns with its rounded ends. Measured on the path (at a quarter, half and three
// quarters), not at the centre: on a short arc the centre moves far and the path hardly at all.
// Infinite when the written R cannot span the rounded chord (a control alarm).
double r_format_deviation(const ir::Arc& a, const Machine& m, double to_out) {
  int u = 0, v = 1, n = 2;
  char cu_letter = 'I', cv_letter = 'J';
  if (std::abs(a.axis.y()) > 1 - 1e-9) u = 2, v = 0, n = 1, cu_letter = 'K', cv_letter = 'I';
  else if (std::abs(a.axis.x()) > 1 - 1e-9) u = 1, v = 2, n = 0, cu_letter = 'J', cv_letter = 'K';
  const char letters[] = {'X', 'Y', 'Z'};
  const ir::Vec3 s = a.start * to_out, e = a.end * to_out, c = a.center * to_out;
  const ir::Vec3 mid = arcgeo::point_at(a, 0.5) * to_out;
  const bool ccw = (a.dir == ir::ArcDir::Ccw) == (a.axis.dot(ir::Vec3::Unit(n)) > 0);
  const double su = rounded(s[u], m.format(letters[u])), sv = rounded(s[v], m.format(letters[v]));
  const double eu = rounded(e[u], m.format(letters[u])), ev = rounded(e[v], m.format(letters[v]));
  const ArcCenterInput in{su, sv, eu, ev, c[u], c[v], mid[u], mid[v], ccw, false};
  const ArcCenterChoice chosen = choose_arc_center(in, m.format(cu_letter), m.format(cv_letter), false);
  const double written_r = rounded(std::hypot(chosen.cu - su, chosen.cv - sv), m.format('R'));
  const double du = eu - su, dv = ev - sv, chord = std::hypot(du, dv);
  if (chord < 1e-12 || written_r < chord / 2) return INFINITY;
  const double h = std::sqrt(written_r * written_r - chord * chord / 4);
  const double side = ccw == (a.sweep <= 180) ? 1 : -1;  // the centre left of the chord (CCW, up to half a turn)
  const double ccu = (su + eu) / 2 - side * h * dv / chord, ccv = (sv + ev) / 2 + side * h * du / chord;
  // A helix climbs with the angle about the control's centre: a point's height is where that
  // angle puts it between the rounded ends' heights, so a centre off turns into a height off too.
  const double pi = 3.14159265358979323846;
  auto turn = [&](double from, double to) {  // the angle from `from` to `to`, in the arc's sense, 0..2 pi
    double d = ccw ? to - from : from - to;
    while (d < 0) d += 2 * pi;
    while (d >= 2 * pi) d -= 2 * pi;
    return d;
  };
  const double a0 = std::atan2(sv - ccv, su - ccu), a1 = std::atan2(ev - ccv, eu - ccu);
  double whole = turn(a0, a1);
  if (whole < 1e-12) whole = 2 * pi;
  const double sn = rounded(s[n], m.format(letters[n])), en = rounded(e[n], m.format(letters[n]));
  double worst = 0;
  for (double t : {0.25, 0.5, 0.75}) {
    const ir::Vec3 q = arcgeo::point_at(a, t) * to_out;
    const double radial = std::hypot(q[u] - ccu, q[v] - ccv) - written_r;
    const double height = q[n] - (sn + (en - sn) * turn(a0, std::atan2(q[v] - ccv, q[u] - ccu)) / whole);
    worst = std::max(worst, std::hypot(radial, height));
  }
  return worst;
}

// The fewest equal pieces (from `n`) of an R-format arc whose paths the control keeps within
// `tol`, none with a chord under ten output increments; 0 where none does.
int r_format_pieces(const ir::Arc& a, int n, const Machine& m, double to_out, double tol, double increment) {
  const double r = arcgeo::radial(a, a.start).norm() * to_out;
  for (int k = n; k < 64; ++k) {
    const double piece_chord = 2 * r * std::sin(std::min(a.sweep / k, 180.0) * 3.14159265358979323846 / 360);
    if (k > n && piece_chord < 10 * increment) break;
    double worst = 0;
    for (int i = 0; i < k && worst <= tol; ++i) {
      ir::Arc piece = a;
      piece.start = arcgeo::point_at(a, double(i) / k);
      piece.end = arcgeo::point_at(a, double(i + 1) / k);
      piece.sweep = a.sweep / k;
      worst = std::max(worst, r_format_deviation(piece, m, to_out));
    }
    if (worst <= tol) return k;
  }
  return 0;
}

// A feed move to the arc's end, in its place: where the arc is within the tolerance of it.
ir::Instr straight_to_end(const ir::Arc& a, SourceLoc loc) {
  ir::Move m;
  m.point = a.end;
  m.axis = a.tool_axis;
  m.kind = ir::MoveKind::Feed;
  m.has_rotary = a.has_rotary;
  m.rotary = a.rotary;
  return ir::Instr{loc, m};
}

class ArcLegalise : public Pass {
 public:
  void run(ir::Operation& op, PassContext& ctx) override {
    const ArcSettings& s = ctx.machine.arcs;
    const double to_prog = ctx.from_output();
    const double res = ctx.resolution();
    const bool r_format = s.center == ArcCenter::Radius;
    arcedit::rewrite(op, [&](ir::Instr& in, std::vector<ir::Instr>& out) {
      auto* a = std::get_if<ir::Arc>(&in.op);
      if (!a || a->dir == ir::ArcDir::Unknown) return false;
      double r = arcgeo::radial(*a, a->start).norm();
      bool closed = a->sweep >= 360 - 1e-9;
      double chord = (arcgeo::radial(*a, a->end) - arcgeo::radial(*a, a->start)).norm();
      // Too short to write as an arc: a straight move (or nothing) is within tolerance.
      if (!closed && chord < 2 * res && a->sweep < 180) {
        out.push_back(straight_to_end(*a, in.loc));
        return true;
      }
      if (closed && r < res) {  // a circle smaller than the resolution: nothing to cut
        if ((a->end - a->start).norm() > 0) {
          out.push_back(straight_to_end(*a, in.loc));
        }
        return true;
      }
      bool radius_ok = (s.min_radius <= 0 || r >= s.min_radius * to_prog) && (s.max_radius <= 0 || r <= s.max_radius * to_prog);
      if (!plane_ok(s, a->axis) || !radius_ok) {
        if (!arcedit::linearise(*a, ctx.chord_tolerance(), in.loc, out, ctx.diags)) out.push_back(in);
        return true;
      }
      double limit = s.max_sweep;
      if (r_format && closed) limit = std::min(limit, 180.0);
      int n = int(std::ceil(a->sweep / limit - 1e-9));
      if (n <= 1 && !closed && a->sweep > 180 &&
          rounded_centre_deviation(*a, ctx.machine, 1 / to_prog) > s.tolerance)
        n = 2;  // each half's chord is nearly a diameter: its centre is well placed
      if (r_format) {
        const int first = std::max(n, closed ? 2 : 1);
        n = r_format_pieces(*a, first, ctx.machine, 1 / to_prog, s.tolerance, res / to_prog);
        if (n == 0 && 2 * r <= s.tolerance * to_prog && (a->end - a->start).norm() > 0) {
          // No piece holds, and the whole arc lies within the tolerance of its end (a circle of
          // a few increments, whose rounded ends meet): a straight move.
          out.push_back(straight_to_end(*a, in.loc));
          return true;
        }
        if (n == 0) n = first;  // left as it is: verify judges it
      }
      if (n <= 1) return false;
      arcedit::split(*a, n, in.loc, out);
      return true;
    });
  }
};

}  // namespace

const PassInfo& arc_legalise_pass() {
  static const PassInfo info{
      .name = "arc-legalise",
      .summary = "make every arc one the machine can do, or lines within tolerance",
      .expects = "decided arcs without extra turns",
      .guarantees = "every arc lies in a plane the machine has (arcs.planes; arbitrary planes are linearised "
                    "within arcs.tolerance), with a radius inside arcs.min_radius / max_radius and a sweep of at "
                    "most arcs.max_sweep (split into equal pieces); no full circle on an R-format machine; no arc "
                    "whose rounded ends would meet (chord under two increments and sweep under 180 degrees: a "
                    "straight move; a circle smaller than one increment: nothing); an arc over 180 degrees whose "
                    "centre, chosen for its rounded ends, would leave its midpoint more than arcs.tolerance off "
                    "is split in two; an R-format arc or circle whose path, with the centre the control finds "
                    "from its rounded ends and written R, would be more than arcs.tolerance off (near a half or "
                    "a full turn) is split into the fewest equal pieces that hold, none under ten increments of "
                    "chord (else left whole for verify to judge)",
      .settings = "arcs.planes, arcs.min_radius, arcs.max_radius, arcs.max_sweep, arcs.center, arcs.tolerance, "
                  "format.X, format.Y, format.Z, format.I, format.J, format.K",
      .needs = ir::ArcsDecided | ir::ArcsOneTurn,
      .provides = ir::ArcsLegal,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<ArcLegalise>()); },
  };
  return info;
}

}  // namespace clpc
