#include "ir/verify.h"

#include <cmath>
#include <string>

namespace clpc {

bool verify_operation(const ir::Operation& op, std::string_view after_pass, ir::Facts established, Diagnostics& d) {
  bool ok = true;
  auto bad = [&](SourceLoc loc, const std::string& what) {
    d.error(loc, "internal: IR invariant broken after pass '" + std::string(after_pass) + "': " + what);
    ok = false;
  };
  auto finite = [](const ir::Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); };
  auto has = [&](ir::Fact f) { return (established & f) != 0; };
  bool in_cycle = false;  // between a cycle-on and its cycle-off, in this chunk
  for (const ir::Instr& in : op.body) {
    if (std::holds_alternative<ir::CycleOn>(in.op)) in_cycle = true;
    else if (std::holds_alternative<ir::CycleOff>(in.op)) in_cycle = false;
    if (has(ir::GroovesFormed) && (std::holds_alternative<ir::GrooveOn>(in.op) || std::holds_alternative<ir::GrooveMark>(in.op)))
      bad(in.loc, "groove record left after the grooves were formed");
    if (auto* m = std::get_if<ir::Move>(&in.op)) {
      if (!finite(m->point)) bad(in.loc, "move to a non-finite point");
      if (std::abs(m->axis.norm() - 1) > 1e-9) bad(in.loc, "tool axis is not a unit vector");
      const bool motion = m->kind != ir::MoveKind::From;
      if (has(ir::CyclesFormed) && in_cycle && motion) bad(in.loc, "plain move inside a formed cycle");
      if (has(ir::Kinematic) && motion && !m->has_rotary) bad(in.loc, "move without its rotary positions");
    } else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
      if (has(ir::ArcsDecided) && a->dir == ir::ArcDir::Unknown) bad(in.loc, "undecided arc after the arcs were decided");
      if ((has(ir::ArcsOneTurn) || has(ir::ArcsLegal)) && (a->extra_turns > 0 || a->sweep > 360 + 1e-9))
        bad(in.loc, "arc of more than one turn after the turns were split");
      if (!finite(a->start) || !finite(a->end) || !finite(a->center)) bad(in.loc, "arc with a non-finite point");
      if (std::abs(a->axis.norm() - 1) > 1e-9) bad(in.loc, "arc axis is not a unit vector");
      if (!(a->radius > 0)) bad(in.loc, "arc radius is not positive");
      if (uint64_t(a->via_begin) + a->via_count > op.points.size() && a->via_count) bad(in.loc, "arc via points out of range");
      if (a->dir != ir::ArcDir::Unknown && !(a->sweep > 0)) bad(in.loc, "decided arc without a sweep");
    } else if (auto* t = std::get_if<ir::Comment>(&in.op)) {
      if (uint64_t(t->text.offset) + t->text.size > op.text.size()) bad(in.loc, "comment text out of range");
    }
  }
  if (has(ir::CyclesFormed) && in_cycle && op.last_chunk)
    bad(op.body.empty() ? op.loc : op.body.back().loc, "cycle still on at the end of the operation");
  return ok;
}

}  // namespace clpc
