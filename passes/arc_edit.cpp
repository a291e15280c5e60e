#include "passes/arc_edit.h"

#include <cmath>

#include "ir/arc_geometry.h"
#include "support/text.h"

namespace clpc::arcedit {

void split(const ir::Arc& a, int n, SourceLoc loc, std::vector<ir::Instr>& out) {
  ir::Vec3 prev = a.start;
  for (int i = 1; i <= n; ++i) {
    ir::Arc piece = a;
    piece.start = prev;
    piece.end = i == n ? a.end : arcgeo::point_at(a, double(i) / n);
    piece.sweep = a.sweep / n;
    piece.extra_turns = 0;
    piece.via_count = 0;
    piece.via_begin = 0;
    out.push_back(ir::Instr{loc, piece});
    prev = piece.end;
  }
}

bool linearise(const ir::Arc& a, double tol, SourceLoc loc, std::vector<ir::Instr>& out, Diagnostics& d) {
  double r = std::max(arcgeo::radial(a, a.start).norm(), arcgeo::radial(a, a.end).norm());
  double step = arcgeo::sweep_for_chord_error(r, tol);
  const double pieces = std::ceil(a.sweep / step);
  if (!(pieces <= kMaxPieces)) {
    d.error(loc, "this arc (radius " + num_text(r) + ", " + num_text(a.sweep) + " degrees) would need " +
                     (std::isfinite(pieces) ? num_text(pieces) : std::string("countless")) + " lines within the tolerance of " +
                     num_text(tol) + "; at most " + std::to_string(long(kMaxPieces)) + " are written");
    return false;
  }
  int n = std::max(1, int(pieces));
  for (int i = 1; i <= n; ++i) {
    ir::Move m;
    m.point = i == n ? a.end : arcgeo::point_at(a, double(i) / n);
    m.axis = a.tool_axis;
    m.kind = ir::MoveKind::Feed;
    m.has_rotary = a.has_rotary;
    m.rotary = a.rotary;
    out.push_back(ir::Instr{loc, m});
  }
  return true;
}

}  // namespace clpc::arcedit
