// drill-cycles: the GOTOs between a CYCLE record and CYCLE/OFF are hole positions. Each becomes
// a Hole (the machine's canned cycle), or, where the machine has no code for the cycle, the
// plain moves the cycle would make.
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and provides)
// is drill_cycles_pass() at the end of this file.
#include <cmath>

#include "passes/cycle_expand.h"
#include "support/text.h"
#include "passes/passes.h"

namespace clpc {

namespace {

std::string point_text(const ir::Vec3& v) {
  return num_text(v.x()) + ", " + num_text(v.y()) + ", " + num_text(v.z());
}

bool machine_has(const Codes& k, const ir::CycleSpec& c) {
  switch (c.kind) {
    case ir::CycleKind::Drill: return !k.cycle_drill.empty();
    case ir::CycleKind::SpotDwell: return !k.cycle_dwell.empty();
    case ir::CycleKind::Peck: return !k.cycle_peck.empty() && (c.peck_next <= 0 || c.peck_next == c.peck);
    case ir::CycleKind::ChipBreak: return !k.cycle_chip_break.empty() && (c.peck_next <= 0 || c.peck_next == c.peck);
    case ir::CycleKind::Tap: return !(c.left_hand ? k.cycle_tap_left : k.cycle_tap).empty();
    case ir::CycleKind::Bore: return !k.cycle_bore.empty();
    case ir::CycleKind::BoreDwell: return !k.cycle_bore_dwell.empty();
    case ir::CycleKind::BoreStop: return !k.cycle_bore_stop.empty();
    case ir::CycleKind::FineBore: return !k.cycle_fine_bore.empty();
    case ir::CycleKind::BackBore: return !k.cycle_back_bore.empty();
  }
  return false;
}

class DrillCycles : public Pass {
 public:
  void run(ir::Operation& op, PassContext& ctx) override {
    std::vector<ir::Instr>& out = scratch_;  // kept: no allocation per operation
    out.clear();
    out.reserve(op.body.size());
    int spec_in_op = -1;  // index of the active spec in this chunk's op.cycles
    if (active_) {        // a cycle carried over from the previous chunk
      op.cycles.push_back(*active_);
      spec_in_op = int(op.cycles.size() - 1);
    }
    for (ir::Instr& in : op.body) {
      if (auto* on = std::get_if<ir::CycleOn>(&in.op)) {
        if (active_) close(out, in.loc, false, ctx);
        active_ = op.cycles.at(on->spec);
        spec_in_op = int(on->spec);
        expand_ = !machine_has(ctx.machine.codes, *active_) || ctx.machine.is_lathe();
        have_start_ = have_pos_;
        start_ = pos_;
        first_hole_ = true;
        cycle_on_at_ = out.size();
        if (!expand_) out.push_back(std::move(in));
        continue;
      }
      // A lathe groove record (CYCLE/FACE|RADIUS) ends with CYCLE/OFF too: that one is
      // groove-cycles' to read.
      if (std::holds_alternative<ir::GrooveOn>(in.op)) groove_open_ = true;
      if (std::holds_alternative<ir::CycleOff>(in.op) && groove_open_ && !active_) {
        groove_open_ = false;
        out.push_back(std::move(in));
        continue;
      }
      if (std::holds_alternative<ir::CycleOff>(in.op)) {
        if (active_) close(out, in.loc, false, ctx);
        continue;
      }
      if (auto* f = std::get_if<ir::Feed>(&in.op)) {
        feed_ = *f;
        have_feed_ = true;
      }
      if (auto* s = std::get_if<ir::Spindle>(&in.op)) spindle_ = *s;
      auto* m = std::get_if<ir::Move>(&in.op);
      if (!m || !active_ || m->kind == ir::MoveKind::From) {
        if (m && m->kind == ir::MoveKind::From && returned_) {
          // A FROM after the holes (lowering lets one on the last hole's axis through) says
          // where the CL thinks the cycle left the tool. Where the cycle returns it, it is.
          if ((m->point - pos_).norm() > 0.001 / ir::mm_per_unit(ctx.info.units)) {
            from_off_return_ = in.loc;
            from_what_ = m->point;
          }
          out.push_back(std::move(in));
          continue;
        }
        if (from_off_return_ && (m || std::holds_alternative<ir::Arc>(in.op))) {
          // A feed on down the hole's axis through the FROM holds the CL's line (from higher up).
          const bool down_through = m && (from_what_ - pos_).cross(m->point - pos_).norm() <= 1e-6 * (1 + (m->point - pos_).norm()) &&
                                    (from_what_ - pos_).dot(m->point - pos_) > 0 &&
                                    (from_what_ - pos_).norm() <= (m->point - pos_).norm();
          if ((!m || m->kind == ir::MoveKind::Feed) && !down_through)
            ctx.diags.error(in.loc, "this cut starts at the FROM at line " + std::to_string(from_off_return_->line) +
                                        " (" + point_text(from_what_) + "), but the cycle before it returned the tool to (" +
                                        point_text(pos_) + "): cut from there it would run along a line the CL does not "
                                        "have; have the CAM system write the move to where the cut starts (a RAPID GOTO)");
          from_off_return_.reset();
        }
        if (m) {
          pos_ = m->point;
          have_pos_ = true;
          returned_ = false;
        } else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
          if (active_) ctx.diags.error(in.loc, "an arc inside a drilling cycle (no CYCLE/OFF before it?)");
          if (returned_ && !active_ && (a->start - pos_).norm() > 1e-9) {
            // The CL's arc starts at the last hole, but the cycle left the tool at its return
            // level: an arc from there would be another arc. Down to its start first, at feed.
            ctx.diags.warning(in.loc,
                              "this arc starts at the last hole of the cycle before it, where the tool no longer is "
                              "(the cycle returned it): a feed move to the arc's start is added",
                              "cycle");
            ir::Move down;
            down.kind = ir::MoveKind::Feed;
            down.point = a->start;
            down.axis = a->tool_axis;
            out.push_back({in.loc, down});
          }
          returned_ = false;
          pos_ = a->end;
          have_pos_ = true;
        }
        out.push_back(std::move(in));
        continue;
      }
      from_off_return_.reset();  // the cycle moves across to the next hole at its own level
      ir::Hole h;
      h.point = m->point;
      h.axis = m->axis;
      h.spec = uint32_t(spec_in_op);
      // The level the tool starts from, above this hole: where it was when the cycle began.
      double initial = have_start_ ? (start_ - h.point).dot(h.axis) : active_->clearance;
      if (first_hole_ && have_start_ && active_->retract >= 0 && std::abs(initial - active_->retract) > 1e-9) {
        // RTRCTO/RETURN sets the level the cycle returns to (G98 returns to where it started):
        // the tool goes there first, before the cycle starts: up on the spot, or down over the hole.
        ir::Move up;
        up.kind = ir::MoveKind::Rapid;
        up.axis = h.axis;
        std::vector<ir::Instr> first;
        if (active_->retract > initial) {
          up.point = start_ + h.axis * (active_->retract - initial);
        } else {
          up.point = h.point + h.axis * initial;
          first.push_back({in.loc, up});
          up.point = h.point + h.axis * active_->retract;
        }
        first.push_back({in.loc, up});
        out.insert(out.begin() + std::ptrdiff_t(std::min(cycle_on_at_, out.size())), first.begin(), first.end());
        initial = active_->retract;
        pos_ = up.point;  // where the cycle now moves across from
      }
      check_crossing_level(h, in.loc, out, ctx);
      // A lathe drills on its spindle's axis only: the part turns, and a drill off centre cuts a
      // ring, not a hole (a mill's hole program posted to a lathe; a mill-turn's live tooling
      // is not this machine).
      if (ctx.machine.is_lathe() && (std::abs(h.point.x()) > 1e-6 || std::abs(h.point.y()) > 1e-6 ||
                                     std::abs(std::abs(h.axis.z()) - 1) > 1e-9)) {
        ctx.diags.error(in.loc, "a hole off the spindle's axis on a lathe (at x " + num_text(h.point.x()) + ", y " +
                                    num_text(h.point.y()) + "): the part turns, so the drill would cut a ring; a lathe "
                                    "drills on centre (x 0, along Z) only");
        continue;
      }
      first_hole_ = false;
      h.initial = active_->retract >= 0 ? active_->retract : std::max(initial, active_->clearance);
      if (expand_) {
        ExpandContext x{ctx.machine.cycles.peck_clearance * ctx.from_output(), feed_.value, feed_.mode, have_feed_,
                        ctx.machine.cycles.return_initial, spindle_.speed, spindle_.dir, ctx.machine.is_lathe()};
        expand_hole(h, *active_, x, in.loc, out, ctx.diags);
      } else {
        out.push_back({in.loc, h});
      }
      // Where the tool ends: over the hole, at the return level.
      double ret = ctx.machine.cycles.return_initial ? std::max(h.initial, active_->clearance) : active_->clearance;
      pos_ = h.point + h.axis * ret;
      have_pos_ = true;
      returned_ = true;
      if (active_->retract < 0 && !ctx.machine.cycles.return_initial) {
        // G99: later holes start from the R plane of this one.
      }
    }
    if (active_ && op.last_chunk) {
      ctx.diags.warning(op.body.empty() ? op.loc : op.body.back().loc,
                        "CYCLE without CYCLE/OFF at the end of the operation: cancelled here", "cycle");
      close(out, op.body.empty() ? op.loc : op.body.back().loc, true, ctx);
    }
    op.body.swap(out);
  }

 private:
  bool groove_open_ = false;  // a GrooveOn whose CYCLE/OFF has not come yet
  bool returned_ = false;     // the tool is where the last hole's cycle returned it
  std::optional<SourceLoc> from_off_return_;  // a FROM after the holes, elsewhere than their return
  ir::Vec3 from_what_ = ir::Vec3::Zero();

  // A canned cycle moves across to each hole at the level the tool is at, then down to the R
  // plane: a tool below that plane, and not already over the hole, would cross below the
  // level the CAM system chose as clear of this hole (perhaps through the part; fuzzing found
  // a cycle starting 10 mm below its hole's top). The CL must retract first: refused here.
  // A tool already over the first hole, below its R plane (some CAM systems go to the hole's
  // top before the CYCLE), first rises to the R plane on the spot, as the control would: the
  // level G98 returns to is then the R plane, not one below it.
  void check_crossing_level(const ir::Hole& h, SourceLoc loc, std::vector<ir::Instr>& out, PassContext& ctx) {
    if (!have_pos_) return;
    ir::Vec3 d = pos_ - h.point;
    double level = d.dot(h.axis);
    double across = (d - h.axis * level).norm();
    double tiny = 1e-6 / ir::mm_per_unit(ctx.info.units);
    if (level >= active_->clearance - tiny) return;
    if (across <= tiny) {
      if (!first_hole_) return;
      ir::Move up;
      up.kind = ir::MoveKind::Rapid;
      up.axis = h.axis;
      up.point = pos_ + h.axis * (active_->clearance - level);
      out.insert(out.begin() + std::ptrdiff_t(std::min(cycle_on_at_, out.size())), ir::Instr{loc, up});
      pos_ = up.point;
      return;
    }
    const char* unit = ctx.info.units == ir::Units::Inch ? " in" : " mm";
    auto len = [&](double v) { return num_text(std::round(v * 1e4) / 1e4) + unit; };
    ctx.diags.error(loc, "the tool is " + len(active_->clearance - level) + " below this hole's R plane (CLEAR " +
                             len(active_->clearance) +
                             " above the hole) when the cycle moves across to it: the canned cycle would cross "
                             "at that level; retract above the R plane first (a GOTO, or RTRCTO)");
  }

  void close(std::vector<ir::Instr>& out, SourceLoc loc, bool implicit, PassContext& ctx) {
    if (!expand_) out.push_back({loc, ir::CycleOff{}});
    active_.reset();
    (void)implicit;
    (void)ctx;
  }

  std::optional<ir::CycleSpec> active_;
  std::vector<ir::Instr> scratch_;
  bool expand_ = false;
  ir::Vec3 pos_ = ir::Vec3::Zero(), start_ = ir::Vec3::Zero();
  bool have_pos_ = false, have_start_ = false;
  bool first_hole_ = false;  // the next hole is the cycle's first
  size_t cycle_on_at_ = 0;   // where in this chunk's output the cycle began
  ir::Feed feed_;
  bool have_feed_ = false;
  ir::Spindle spindle_;
};

}  // namespace

const PassInfo& drill_cycles_pass() {
  static const PassInfo info{
      .name = "drill-cycles",
      .summary = "turn the GOTOs of a CYCLE into canned-cycle holes, or moves where the machine lacks the cycle",
      .expects = "CYCLE records lowered to cycle-on / moves / cycle-off",
      .guarantees = "every move inside a cycle becomes a hole, with the level the tool started the cycle at (for "
                    "G98 returns; with RTRCTO the tool first goes to that level; a tool over the first hole below its R "
                    "plane first rises to it), or, where the machine has no "
                    "code for the cycle or the pecks vary (2NDPECK), the plain moves the cycle makes; every cycle "
                    "ends (a warning and an implicit cancel at the end of an operation without CYCLE/OFF); "
                    "tapping and oriented boring cannot be written as moves: an error naming the machine key that would "
                    "post them (codes.cycle_tap, ...), or on a lathe, which writes every drilling cycle as moves, saying "
                    "so; so is a tool below a hole's R plane "
                    "and beside the hole, where the cycle would cross at that level",
      .settings = "cycles.return, cycles.tap_feed, cycles.peck_clearance, codes.cycle_*, codes.rigid_tap",
      .needs = 0,
      .provides = ir::CyclesFormed,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<DrillCycles>()); },
  };
  return info;
}

}  // namespace clpc
