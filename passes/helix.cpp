// helix: an arc whose end leaves its plane is a helix. Kept as one G02/G03 with the linear
// axis where the machine allows helical arcs and the sweep is within its helix limit; split
// into equal pieces of at most that sweep; linearised within tolerance on machines with no
// helical arcs. Multi-turn arcs (NX TIMES,n) are split so no block turns more than allowed,
// nor more than half a turn.
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and provides)
// is helix_pass() at the end of this file.
#include <cmath>

#include "passes/arc_edit.h"
#include "ir/arc_geometry.h"
#include "passes/passes.h"

namespace clpc {

namespace {

class Helix : public Pass {
 public:
  void run(ir::Operation& op, PassContext& ctx) override {
    const ArcSettings& s = ctx.machine.arcs;
    const double rise_tol = ctx.resolution() / 2;
    arcedit::rewrite(op, [&](ir::Instr& in, std::vector<ir::Instr>& out) {
      auto* a = std::get_if<ir::Arc>(&in.op);
      if (!a || a->dir == ir::ArcDir::Unknown) return false;
      double rise = std::abs(arcgeo::axial(*a, a->end) - arcgeo::axial(*a, a->start));
      bool helical = rise > rise_tol;
      if (!helical && a->extra_turns == 0) return false;
      if (helical && !s.helical) {
        if (!arcedit::linearise(*a, ctx.chord_tolerance(), in.loc, out, ctx.diags)) out.push_back(in);
        return true;
      }
      double limit = helical ? s.helix_max_sweep : s.max_sweep;
      // A multi-turn arc goes in half turns at most: a piece of nearly a whole turn has a chord
      // too short to place its centre within an increment once its ends are rounded.
      if (a->extra_turns > 0) limit = std::min(limit, 180.0);
      int n = int(std::ceil(a->sweep / limit - 1e-9));
      if (n <= 1 && a->extra_turns == 0) return false;
      arcedit::split(*a, std::max(n, 1), in.loc, out);
      return true;
    });
  }
};

}  // namespace

const PassInfo& helix_pass() {
  static const PassInfo info{
      .name = "helix",
      .summary = "keep, split or linearise helical and multi-turn arcs as the machine allows",
      .expects = "decided arcs",
      .guarantees = "no arc has extra turns; a helical arc (end more than half an increment off the start's "
                    "plane) has a sweep of at most arcs.helix_max_sweep where arcs.helical, and there is none "
                    "(linearised within arcs.tolerance) where not; planar multi-turn arcs are split into pieces "
                    "of at most arcs.max_sweep, multi-turn arcs into pieces of at most half a turn",
      .settings = "arcs.helical, arcs.helix_max_sweep, arcs.max_sweep, arcs.tolerance",
      .needs = ir::ArcsDecided,
      .provides = ir::ArcsOneTurn,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<Helix>()); },
  };
  return info;
}

}  // namespace clpc
