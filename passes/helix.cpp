// helix: an arc whose end leaves its plane is a helix. Kept as one G02/G03 with the linear
// axis where the machine allows helical arcs and the sweep is within its helix limit; split
// into equal pieces of at most that sweep; linearised within tolerance on machines with no
// helical arcs. Multi-turn arcs (NX TIMES,n) are split so no block turns more than allowed,
// nor more than half a turn.
//
// Contract. Expects: decided arcs (arc-direction). Guarantees: no arc has extra turns; every
// helical arc has sweep <= arcs.helix_max_sweep on a machine with arcs.helical, and there are
// no helical arcs on a machine without; planar multi-turn arcs become pieces of at most
// arcs.max_sweep.
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
    const double tol = ctx.tolerance();
    arcedit::rewrite(op, [&](ir::Instr& in, std::vector<ir::Instr>& out) {
      auto* a = std::get_if<ir::Arc>(&in.op);
      if (!a || a->dir == ir::ArcDir::Unknown) return false;
      double rise = std::abs(arcgeo::axial(*a, a->end) - arcgeo::axial(*a, a->start));
      bool helical = rise > rise_tol;
      if (!helical && a->extra_turns == 0) return false;
      if (helical && !s.helical) {
        if (!arcedit::linearise(*a, tol, in.loc, out, ctx.diags)) out.push_back(in);
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

std::unique_ptr<Pass> make_helix() { return std::make_unique<Helix>(); }

}  // namespace clpc
