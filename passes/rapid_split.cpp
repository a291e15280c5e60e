// rapid-split: on a control whose rapids are not interpolated, a rapid that goes both along
// the tool axis and across it becomes two: up first, or across first and then down.
//
// The CL's rapid is a straight line, and the CAM system checked that line for collisions. A
// control with non-linear positioning (Fanuc's default: parameter 1401 bit 1 LRP = 0; machine
// key motion.rapids_linear = false) moves each axis at its own rapid rate, so the axis with
// the shortest way arrives first: going down, Z can reach the bottom before X and Y have
// left the start, and the tool crosses at the depth of the end, below the CL's line. Split,
// the tool never goes below that line: going up it rises first and crosses at the end's
// height; going down it crosses at the start's height and then goes down along the tool axis.
// Each piece moves along the tool axis or across it, so where the tool axis is the machine's
// Z (a three-axis mill, a table machine, a head at zero over a table turning about Z) each is
// Z alone or X and Y alone. A tilted head would move several axes on each piece, at their
// own rates again: there only rapids with the tool along the program's Z are split.
//
// A rapid is split only where the position before it is known (a move, an arc or a canned
// cycle's hole before it, the cycle leaving the tool at its return level, G98 or G99;
// a load of the tool already in the spindle, a frame or work offset, or a raw block that can
// move no axis is no motion: NX writes the first ones at every operation), and the tool axis
// does not change along it (a rapid that turns a rotary is left as the CL gives it). With
// cutter compensation on or switched by it, a block more would change the compensated path (or
// start or cancel it on a Z move): such a rapid is written as a straight feed at the machine's
// max_feed instead, along the CL's line, and the feed before it said again after. The first
// move after a tool change is the backend's (X Y, then Z with the length offset).
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and
// provides) is rapid_split_pass() at the end of this file.
#include <cmath>
#include <optional>

#include "machine/block_check.h"
#include "passes/passes.h"

namespace clpc {

namespace {

class RapidSplit : public Pass {
 public:
  void begin(PassContext& ctx) override {
    on_ = !ctx.machine.motion.rapids_linear;
    for (const RotaryAxis& r : ctx.machine.kinematics.rotaries) {
      if (!r.table) head_ = true;
      else if (std::abs(r.axis.normalized().z()) < 1 - 1e-9) tilting_table_ = true;
    }
    // Less than an increment along or across is no dog-leg the control could make.
    eps_ = ctx.resolution();
  }

  void run(ir::Operation& op, PassContext& ctx) override {
    if (!on_) return;
    std::vector<ir::Instr> out;  // built only once a rapid is split
    for (size_t i = 0; i < op.body.size(); ++i) {
      const ir::Instr& in = op.body[i];
      if (const auto* m = std::get_if<ir::Move>(&in.op)) {
        if (m->kind == ir::MoveKind::Rapid && known_) {
          if (auto mid = midpoint(*m)) {
            if (out.empty() && i > 0) out.assign(op.body.begin(), op.body.begin() + std::ptrdiff_t(i));
            split_ = true;
            if (!comp_ && !comp_switch_) {
              ir::Move piece = *m;
              piece.point = *mid;
              piece.axis_written = false;
              out.push_back({in.loc, piece});
            } else if (linear(*m, in.loc, out, ctx, feed_follows(op, i))) {
              continue;
            }
          }
        }
        at_ = m->point;
        axis_ = m->axis;
        known_ = true;
        comp_switch_ = false;
      } else if (const auto* a = std::get_if<ir::Arc>(&in.op)) {
        at_ = a->end;
        axis_ = a->tool_axis;
        known_ = true;  // (G40 and G41 are written on the next straight move, not on an arc)
      } else if (const auto* t = std::get_if<ir::ToolChange>(&in.op)) {
        if (t->tool != tool_) known_ = false;  // the same tool again: the backend writes nothing
        tool_ = t->tool;
      } else if (std::holds_alternative<ir::SetFrame>(in.op) || std::holds_alternative<ir::SelectOffset>(in.op)) {
        // Another frame or work offset moves no axis: the tool stands where it stood, and the
        // points before and after are in the one part frame. (The first rapid after one was
        // left whole: 100 mm across and 50 down in one non-linear G00, Z at the bottom first.)
        // Where the backend retracts first (a 3+2 frame), it then positions X Y before Z.
      } else if (const auto* c = std::get_if<ir::CutterComp>(&in.op)) {
        // The next move carries G41, G42 or G40; a CUTCOM/OFF with compensation off switches
        // nothing (its G40 cancels nothing on either piece): the rapid after it went down and
        // across at once.
        comp_switch_ = c->side != ir::CompSide::Off || comp_;
        comp_ = c->side != ir::CompSide::Off;
      } else if (const auto* ins = std::get_if<ir::Insert>(&in.op)) {
        // A raw block (INSERT, PREFUN, AUXFUN) that can move no axis (M08, G08 P1, a message)
        // leaves the tool where it stood: the rapid after it was written whole, down and across
        // at once. One that may move axes (G28, G53, an axis word, a macro) leaves it unknown.
        if (may_move_axes(op.str(ins->text))) known_ = false;
      } else if (const auto* h = std::get_if<ir::Hole>(&in.op)) {
        // A canned cycle leaves the tool over the hole at its return level (G98: where the
        // cycle started, G99: the R plane), as the backend writes it: the rapid after
        // CYCLE/OFF went up and across at once.
        const ir::CycleSpec& c = op.cycles[h->spec];
        const double ret = ctx.machine.cycles.return_initial ? std::max(h->initial, c.clearance) : c.clearance;
        at_ = h->point + h->axis * ret;
        axis_ = h->axis;
        known_ = true;
        comp_switch_ = false;
      } else if (const auto* f = std::get_if<ir::Feed>(&in.op)) {
        feed_ = *f;
      } else if (!keeps_position(in.op)) {
        known_ = false;
      }
      if (split_) out.push_back(in);
    }
    if (split_) op.body.swap(out);
    split_ = false;
  }

 private:
  // Records that neither move the tool nor change what a point means. Anything else (a tool
  // change, a hole, a frame, an INSERT for the control) leaves the position unknown.
  static bool keeps_position(const ir::Op& op) {
    return std::holds_alternative<ir::Feed>(op) || std::holds_alternative<ir::Spindle>(op) ||
           std::holds_alternative<ir::Coolant>(op) || std::holds_alternative<ir::Comment>(op) ||
           std::holds_alternative<ir::Passthrough>(op) || std::holds_alternative<ir::Dwell>(op) ||
           std::holds_alternative<ir::Stop>(op) || std::holds_alternative<ir::ToolPreselect>(op) ||
           std::holds_alternative<ir::CycleOff>(op);  // G80 moves nothing: the tool stays at the return level
  }

  // With cutter compensation on (or switched by it) a block more would add a corner to the
  // compensated path, and start or cancel the offset on a move along Z: the rapid is written as
  // a straight feed at the machine's fastest (max_feed, per minute), which the control
  // interpolates along the CL's line, and the feed in force before it is said again after it.
  // Left as a G00 it went down and across at once, 14 mm under the CL's line at the middle
  // (certified). False, with an error, where the machine has no max_feed, or no FEDRAT has
  // come before it nor comes before the next cut (the feed after it would be the fastest,
  // where a cut with no FEDRAT is refused).
  bool linear(const ir::Move& m, SourceLoc loc, std::vector<ir::Instr>& out, PassContext& ctx, bool feed_follows) {
    if (ctx.machine.max_feed <= 0 || (!feed_ && !feed_follows)) {
      ctx.diags.error(loc, "a rapid along and across the tool axis with cutter compensation on: the control's G00 is not "
                           "interpolated (motion.rapids_linear = false), so it would leave the CL's line, and split it "
                           "would change the compensated path; it is written as a feed at the machine's fastest, " +
                               (feed_ ? "which machine '" + ctx.machine.name + "' does not give (max_feed)"
                                      : std::string("and with no FEDRAT before it there is no feed to return to")));
      return false;
    }
    out.push_back({loc, ir::Feed{ctx.machine.max_feed * ctx.from_output(), ir::FeedMode::PerMinute}});
    ir::Move fed = m;
    fed.kind = ir::MoveKind::Feed;
    out.push_back({loc, fed});
    if (feed_) out.push_back({loc, *feed_});
    at_ = m.point;
    axis_ = m.axis;
    comp_switch_ = false;
    return true;
  }

  // A FEDRAT after instruction i, before any cut, in this chunk.
  static bool feed_follows(const ir::Operation& op, size_t i) {
    for (size_t j = i + 1; j < op.body.size(); ++j) {
      const ir::Op& o = op.body[j].op;
      if (std::holds_alternative<ir::Feed>(o)) return true;
      if (const auto* m = std::get_if<ir::Move>(&o); m && m->kind == ir::MoveKind::Feed) return false;
      if (std::holds_alternative<ir::Arc>(o) || std::holds_alternative<ir::Hole>(o)) return false;
    }
    return false;
  }

  // The corner of the split move, or nothing where the rapid goes only along the tool axis,
  // only across it, or turns the tool axis.
  std::optional<ir::Vec3> midpoint(const ir::Move& m) const {
    if ((m.axis - axis_).norm() > 1e-9) return std::nullopt;
    if (head_ && (tilting_table_ || (m.axis - ir::Vec3::UnitZ()).norm() > 1e-9)) return std::nullopt;
    const ir::Vec3 d = m.point - at_;
    const double along = d.dot(m.axis);
    const ir::Vec3 across = d - along * m.axis;
    if (std::abs(along) <= eps_ || across.norm() <= eps_) return std::nullopt;
    return along > 0 ? ir::Vec3(at_ + along * m.axis) : ir::Vec3(at_ + across);
  }

  bool on_ = false;
  double eps_ = 0;
  bool head_ = false, tilting_table_ = false;  // the machine's rotaries
  bool known_ = false, comp_ = false, comp_switch_ = false, split_ = false;
  std::optional<ir::Feed> feed_;  // the CL's feed in force
  int tool_ = -1;
  ir::Vec3 at_ = ir::Vec3::Zero(), axis_ = ir::Vec3::UnitZ();
};

}  // namespace

const PassInfo& rapid_split_pass() {
  static const PassInfo info{
      .name = "rapid-split",
      .summary = "split rapids that go along and across the tool axis, for controls whose rapids are not interpolated",
      .expects = "moves in the part frame with their tool axes (before kinematics); cycles formed",
      .guarantees = "where motion.rapids_linear is false: no CL rapid goes both along the tool axis and across it "
                    "(by more than an increment) from a known position with the tool axis unchanged (on a machine with a "
                    "head: only with the tool along Z and no tilting table); going up it rises first, going down it "
                    "crosses first, so the tool never passes below the CL's straight line; with cutter compensation on "
                    "or switched by it, it is a feed at max_feed along that line (an error where max_feed is 0). "
                    "Nothing changes where rapids are linear",
      .settings = "motion.rapids_linear, kinematics.axes (head or table, axis), format.X (one increment), max_feed",
      .needs = ir::CyclesFormed,
      .provides = ir::RapidsSplit,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<RapidSplit>()); },
  };
  return info;
}

}  // namespace clpc
