#include "ir/verify.h"

#include <cmath>
#include <string>

namespace clpc {

bool verify_operation(const ir::Operation& op, std::string_view after_pass, Diagnostics& d) {
  bool ok = true;
  auto bad = [&](SourceLoc loc, const std::string& what) {
    d.error(loc, "internal: IR invariant broken after pass '" + std::string(after_pass) + "': " + what);
    ok = false;
  };
  auto finite = [](const ir::Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); };
  for (const ir::Instr& in : op.body) {
    if (auto* m = std::get_if<ir::Move>(&in.op)) {
      if (!finite(m->point)) bad(in.loc, "move to a non-finite point");
      if (std::abs(m->axis.norm() - 1) > 1e-9) bad(in.loc, "tool axis is not a unit vector");
    } else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
      if (!finite(a->start) || !finite(a->end) || !finite(a->center)) bad(in.loc, "arc with a non-finite point");
      if (std::abs(a->axis.norm() - 1) > 1e-9) bad(in.loc, "arc axis is not a unit vector");
      if (!(a->radius > 0)) bad(in.loc, "arc radius is not positive");
      if (uint64_t(a->via_begin) + a->via_count > op.points.size() && a->via_count) bad(in.loc, "arc via points out of range");
      if (a->dir != ir::ArcDir::Unknown && !(a->sweep > 0)) bad(in.loc, "decided arc without a sweep");
    } else if (auto* t = std::get_if<ir::Comment>(&in.op)) {
      if (uint64_t(t->text.offset) + t->text.size > op.text.size()) bad(in.loc, "comment text out of range");
    }
  }
  return ok;
}

}  // namespace clpc
