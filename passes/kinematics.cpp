// kinematics (five-axis): tool axes become rotary positions, points become what the control
// is given.
//
// For each tool axis the model gives every rotary solution (machine/kinematics.cpp); the pass
// takes, of those within the limits, the one with the least rotary travel from where the
// machine is (the machine's preferred sign breaks ties; the first one prefers it). Continuous
// axes are wound or kept modulo 360 as the machine says; at the vertical singularity the free
// axis keeps its position. When the continuing solution is out of limits and only a jump to
// another would do, that is an error naming the CL record, or, where the machine enables it,
// a retract along the tool axis, a rotation and a re-engage.
//
// Operations with one tool axis are indexed (3+2): the rotaries are positioned once and
// clamped, and the points are cut 3-axis in the tilted frame: transformed through the chain
// (indexed = "transform"), turned about the part origin for Haas dynamic work offsets
// (indexed = "dwo", G254), written in the control's tilted working plane (indexed = "plane",
// G68.2 / G268), or left to TCPC. Other operations are simultaneous: with TCPC the
// points stay in the part frame with the rotaries beside them; without, each point goes
// through the chain, and moves are split where the rotation would take the tip off the CL
// segment by more than the tolerance. Inverse-time feeds (G93) where the machine asks.
// A long operation comes in chunks; once one is simultaneous, so is the rest of it.
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and provides)
// is kinematics_pass() at the end of this file.
#include <cctype>
#include <cmath>
#include <optional>

#include "ir/arc_geometry.h"
#include "machine/kinematics.h"
#include "machine/tilted_plane.h"
#include "passes/arc_edit.h"
#include "passes/cycle_expand.h"
#include "support/text.h"
#include "support/worst_point.h"
#include "passes/passes.h"

namespace clpc {

namespace {

using ir::Vec3;

inline ir::Mat3 Mat3Identity() { return ir::Mat3::Identity(); }

std::string vec_text(const Vec3& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.6g, %.6g, %.6g)", v.x(), v.y(), v.z());
  return b;
}

class Kinematics : public Pass {
 public:
  void begin(PassContext& ctx) override {
    k_ = ctx.kinematics();
    singular_ = find_singular_direction();
    // The address each angle of codes.plane_on is written with (I J K in "I{i} J{j} K{k}").
    for (const CodeTemplate::Word& w : ctx.machine.codes.plane_on.words) {
      const char letter = CodeTemplate::letter(w);
      if (w.size() < 2 || letter < 'A' || letter > 'Z') continue;
      for (const CodeTemplate::Piece& piece : w)
        if (piece.var >= int(Var::I) && piece.var <= int(Var::K))
          plane_angle_step_[size_t(piece.var - int(Var::I))] = std::pow(10.0, -ctx.machine.format(letter).decimals);
    }
  }

  void run(ir::Operation& op, PassContext& ctx) override {
    if (!k_.has_rotaries()) return;
    d_ = &ctx.diags;
    ctx_ = &ctx;
    apply_indexing(op);
    std::vector<ir::Instr>& out = scratch_;  // kept: no allocation per operation
    out.clear();
    out.reserve(op.body.size() + 8);
    // One tool axis for all the motion: an indexed (3+2) operation.
    std::optional<Vec3> axis;
    bool indexed = true;
    // The offset table positions 3+2 operations itself (the first chunk holds its
    // RotaryPosition); the later chunks of such an operation are positioned too.
    if (!op.continued) positioned_ = op_mode_known_ = moved_in_op_ = false;
    for (const ir::Instr& in : op.body) {
      if (std::holds_alternative<ir::RotaryPosition>(in.op)) positioned_ = true;
      const Vec3* a = nullptr;
      if (auto* m = std::get_if<ir::Move>(&in.op); m && m->kind != ir::MoveKind::From) a = &m->axis;
      else if (auto* arc = std::get_if<ir::Arc>(&in.op)) a = &arc->tool_axis;
      else if (auto* h = std::get_if<ir::Hole>(&in.op)) a = &h->axis;
      if (!a) continue;
      if (!axis) axis = *a;
      else if ((*axis - *a).norm() > 1e-9) indexed = false;
    }
    if (positioned_) {
      // The offset table positioned the rotaries and put the points in its frame already;
      // the control modes of the operation before are switched off first.
      if (!op.continued) modes_off(out, op.loc);
      for (ir::Instr& in : op.body) {
        if (auto* r = std::get_if<ir::RotaryPosition>(&in.op)) set_current(r->rotary);
        else if (auto* tc = std::get_if<ir::ToolChange>(&in.op)) {
          const ir::ToolInfo* t = ctx.info.tool(tc->tool);
          tool_length_ = t ? t->length : 0;
        } else if (auto* m = std::get_if<ir::Move>(&in.op)) stamp(*m);
        else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
          a->has_rotary = true;
          a->rotary = cur_;
        }
        out.push_back(std::move(in));
      }
      op.body.swap(out);
      return;
    }
    mode_indexed_ = indexed && axis.has_value();
    if (axis) {
      // A long operation comes in chunks, each seen alone. Once one chunk needed simultaneous
      // motion, or indexed work at another axis, the rest of the operation stays simultaneous:
      // the mode changes at most once per operation, and the rotaries never re-index mid-cut.
      if (op.continued && op_mode_known_ && (!op_indexed_ || (op_axis_ - *axis).norm() > 1e-9)) mode_indexed_ = false;
      op_mode_known_ = true;
      op_indexed_ = mode_indexed_;
      op_axis_ = *axis;
    }
    for (ir::Instr& in : op.body) {
      if (auto* tc = std::get_if<ir::ToolChange>(&in.op)) {
        // The tool goes up for a change, or for the tool in the spindle loaded with another
        // register; loaded again as it is (CATIA's LOADTL at every operation), it stays.
        const int offset = tc->length_offset > 0 ? tc->length_offset : tc->tool;
        if (tc->tool == tool_ && offset == tool_offset_) {
          // The tool in the spindle loaded again as it is (NX's LOAD/TOOL at every operation,
          // or between two points of a cut): the backend writes nothing, the tool stays at the
          // last CL point and the modes stay on. Switching them off and forgetting the point
          // wrote G49 and G234 in the cut and turned B and C together where C turns alone first.
          out.push_back(std::move(in));
          continue;
        }
        tool_up_ = true;
        tool_ = tc->tool;
        tool_offset_ = offset;
        const ir::ToolInfo* t = ctx.info.tool(tc->tool);
        tool_length_ = t ? t->length : 0;
        modes_off(out, in.loc);  // a tool change needs the modes off
        // The change took the tool away from the last CL point: no move starts there (a turn of
        // the free axis on the spot would bring the new tool back down to it at the old feed).
        have_prev_ = false;
        out.push_back(std::move(in));
        continue;
      }
      if (auto* f = std::get_if<ir::Feed>(&in.op)) {
        feed_ = *f;
        feed_known_ = true;
      }
      if (auto* s = std::get_if<ir::Spindle>(&in.op)) spindle_ = *s;
      if (auto* m = std::get_if<ir::Move>(&in.op)) {
        if (m->kind == ir::MoveKind::From) {
          prev_tip_ = m->point;
          prev_rapid_ = true;  // a FROM is where the tool stands in the air
          prev_axis_ = m->axis;
          have_prev_ = true;
          out.push_back(std::move(in));
          continue;
        }
        motion(*m, in.loc, out);
        continue;
      }
      if (auto* a = std::get_if<ir::Arc>(&in.op)) {
        arc(*a, in.loc, out);
        continue;
      }
      if (auto* h = std::get_if<ir::Hole>(&in.op)) {
        hole(op, *h, in.loc, out);
        continue;
      }
      if (std::holds_alternative<ir::CycleOn>(in.op) || std::holds_alternative<ir::CycleOff>(in.op)) {
        // Where the holes become moves (five-axis, or 3+2 under TCPC), the cycle goes with them.
        if (std::holds_alternative<ir::CycleOn>(in.op)) cycle_kept_ = cycles_kept();
        if (cycle_kept_) out.push_back(std::move(in));
        continue;
      }
      out.push_back(std::move(in));
    }
    if (op.last_chunk) modes_off(out, op.body.empty() ? op.loc : op.body.back().loc);
    op.body.swap(out);
  }

 private:
  // --- rotary indexing by record (kin::RotaryIndexing) -----------------------------------------

  void apply_indexing(ir::Operation& op) {
    for (auto it = op.body.begin(); it != op.body.end();) {
      if (auto* ri = std::get_if<ir::RotaryIndex>(&it->op)) {
        std::string why;
        if (!indexing_.apply(k_, *ri, why))
          d_->error(it->loc, "rotary indexing (ROTATE, ROTABL) on machine '" + ctx_->machine.name + "': " + why);
        it = op.body.erase(it);
        continue;
      }
      if (indexing_.on) turn(indexing_.rotation, *it, op);
      ++it;
    }
  }

  static void turn(const ir::Mat3& R, ir::Instr& in, ir::Operation& op) {
    if (auto* m = std::get_if<ir::Move>(&in.op)) {
      m->point = R * m->point;
      m->axis = R * m->axis;
    } else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
      a->start = R * a->start;
      a->end = R * a->end;
      a->center = R * a->center;
      a->axis = R * a->axis;
      a->tool_axis = R * a->tool_axis;
      for (uint32_t k = 0; k < a->via_count; ++k) op.points[a->via_begin + k] = R * op.points[a->via_begin + k];
    } else if (auto* h = std::get_if<ir::Hole>(&in.op)) {
      h->point = R * h->point;
      h->axis = R * h->axis;
    }
  }

  kin::RotaryIndexing indexing_;

  // --- choosing among solutions --------------------------------------------------------------

  using Choice = kin::Choice;

  // The tool direction at which one rotary axis is free (vertical: the C of a B/C trunnion, or
  // of a B head over a C table), if the machine has one; free_ is that axis.
  std::optional<Vec3> singular_direction() const { return singular_; }

  std::optional<Vec3> find_singular_direction() {
    const std::optional<size_t> free = kin::pole_free_axis(k_);
    if (!free) return std::nullopt;
    free_ = *free;
    return kin::tool_axis_in_part(k_, {0, 0});
  }

  // Turns the free axis to `to` with the tool at the last CL point (at the singularity the tool
  // keeps its direction). Without TCPC a table axis carries the tip round a circle while the
  // control moves X Y Z straight: in steps whose chord stays within the tolerance. Between two
  // rapids (a 3+2 reorientation in the air) the turn is a rapid: fed, it took a linear F as
  // degrees per minute, or stopped the post where no FEDRAT was given yet. Where a cut left the
  // tool it is fed, whatever comes next: the tip stays on the part only within the tolerance.
  void turn_free_axis(double to, ir::MoveKind kind, SourceLoc loc, std::vector<ir::Instr>& out) {
    ir::Move turn;
    turn.point = prev_tip_;
    turn.axis = prev_axis_;
    turn.kind = kind;
    const kin::Angles from = cur_;
    kin::Angles end = cur_;
    end[free_] = to;
    int steps = 1;
    if (!tcp(true)) {
      const double delta = std::abs(kin::travel(k_.rotaries[free_], from[free_], to)) * arcgeo::kPi / 180;
      const Vec3 m0 = kin::machine_point(k_, from, prev_tip_, pivot()), m1 = kin::machine_point(k_, end, prev_tip_, pivot());
      const double half = std::sin(std::min(delta, arcgeo::kPi) / 2);
      const double r = half > 1e-12 ? (m1 - m0).norm() / (2 * half) : 0;
      if (r > 0)
        steps = std::max(1, int(std::ceil(std::abs(kin::travel(k_.rotaries[free_], from[free_], to)) /
                                          arcgeo::sweep_for_chord_error(r, 0.5 * ctx_->tolerance()))));
    }
    for (int i = 1; i <= steps; ++i) {
      kin::Angles t = kin::between(k_, from, end, double(i) / steps);
      if (k_.rotaries[free_].cyclic == Cyclic::Modulo) t[free_] = std::fmod(t[free_] + 360.0, 360.0);
      if (i == steps) t = end;
      emit(turn, t, true, loc, out);
    }
  }

  // The table's rotation at `a`, memoised: indexed work asks for the same one every move.
  const ir::Mat3& table(const kin::Angles& a) const {
    if (!table_known_ || table_for_ != a) {
      table_ = kin::table_rotation(k_, a);
      table_for_ = a;
      table_known_ = true;
    }
    return table_;
  }

  // Whether the table is turned at all where the machine is now (memoised per position).
  bool turned() const {
    if (!turned_known_ || turned_for_ != cur_) {
      turned_ = (table(cur_) - Mat3Identity()).cwiseAbs().maxCoeff() >= 1e-12;
      turned_for_ = cur_;
      turned_known_ = true;
    }
    return turned_;
  }

  // Asked several times for each five-axis move: from the tool axis the position was chosen
  // for, when known (no forward kinematics), within 1e-6 degrees.
  bool at_singularity() const {
    if (!have_cur_ || !singular_) return false;
    if (!cur_axis_known_) {
      cur_axis_ = kin::tool_axis_in_part(k_, cur_);
      cur_axis_known_ = true;
    }
    const double n = cur_axis_.norm();
    return cur_axis_.dot(*singular_) > 0 && cur_axis_.cross(*singular_).norm() < 1.7453e-8 * n;
  }

  // At the singularity the free axis may turn without moving the tool, and for the first
  // position there is no path to continue: there the machine's preferred sign comes first.
  Choice choose(const Vec3& axis) const {
    return kin::choose(k_, axis, have_cur_ ? &cur_ : nullptr, at_singularity() || !have_cur_);
  }

  // Where the machine is now.
  // `axis`: the tool axis (part frame) the position gives, when the caller knows it.
  void set_current(const std::array<double, 2>& a, const Vec3* axis = nullptr) {
    cur_ = a;
    have_cur_ = true;
    cur_axis_known_ = axis != nullptr;
    if (axis) cur_axis_ = *axis;
  }

  void stamp(ir::Move& m) {
    m.has_rotary = true;
    m.rotary = cur_;
  }

  double pivot() const { return k_.pivot + tool_length_; }

  // The point the control is given for tip p at angles a, per mode.
  Vec3 output_point(const kin::Angles& a, const Vec3& p, bool simultaneous) const {
    if (simultaneous ? k_.simultaneous == Simultaneous::Tcp : k_.indexed == Indexed::Tcp) return p;
    if (!simultaneous && k_.indexed == Indexed::Dwo) return table(a) * p;  // identity at no rotation
    if (!simultaneous && k_.indexed == Indexed::Plane) return plane_on_ ? Vec3(plane_.transpose() * p) : p;
    return kin::machine_point(k_, a, p, pivot());
  }
  Vec3 output_axis(const kin::Angles& a, const Vec3& axis, bool simultaneous) const {
    if (simultaneous ? k_.simultaneous == Simultaneous::Tcp : k_.indexed == Indexed::Tcp) return axis;
    if (!simultaneous && k_.indexed == Indexed::Plane) return plane_on_ ? Vec3(plane_.transpose() * axis) : axis;
    return table(a) * axis;
  }
  bool tcp(bool simultaneous) const {
    return simultaneous ? k_.simultaneous == Simultaneous::Tcp : k_.indexed == Indexed::Tcp;
  }

  // --- control modes -------------------------------------------------------------------------

  void modes_off(std::vector<ir::Instr>& out, SourceLoc loc) {
    if (tcp_on_) out.push_back({loc, ir::MachineMode{ir::ModeKind::TcpOff}});
    if (dwo_on_) out.push_back({loc, ir::MachineMode{ir::ModeKind::DwoOff}});
    if (plane_on_) out.push_back({loc, ir::MachineMode{ir::ModeKind::PlaneOff}});
    tcp_on_ = dwo_on_ = plane_on_ = false;
    indexed_at_.reset();
  }

  // A tilted working plane for indexed work at tool axis n, as the control will rebuild it from
  // the angles written (rounded to their address's resolution: the points are written in that
  // plane, so the tip lands where the CL says; the tool axis is off by the angles' rounding).
  ir::MachineMode plane_for(const Vec3& n) {
    ir::MachineMode m{ir::ModeKind::PlaneOn};
    m.angles = plane::angles(plane::least_tilt(n), k_.plane_euler);
    for (int i = 0; i < 3; ++i) {
      double step = plane_angle_step_[size_t(i)];
      m.angles[i] = std::round(m.angles[i] / step) * step;
    }
    plane_ = plane::rotation(m.angles, k_.plane_euler);
    return m;
  }

  // Before a move in the given mode: the right control modes, and for indexed work the
  // rotaries positioned (once) for `axis`.
  bool prepare(bool simultaneous, const Vec3& axis, SourceLoc loc, std::vector<ir::Instr>& out) {
    bool want_tcp = tcp(simultaneous);
    bool want_dwo = !simultaneous && k_.indexed == Indexed::Dwo;
    if (!simultaneous) {
      bool same = indexed_at_ && (*indexed_at_ - axis).norm() <= 1e-9;
      if (!same) {
        Choice c = choose(axis);
        if (!c.found) return no_solution(axis, loc);
        // A jump to another solution is no hazard here: indexing turns the rotaries with the tool
        // retracted first (the backend's safe retract before a clamped RotaryPosition).
        // Rotaries move only with the modes that forbid it off.
        if (dwo_on_) out.push_back({loc, ir::MachineMode{ir::ModeKind::DwoOff}});
        if (plane_on_) out.push_back({loc, ir::MachineMode{ir::ModeKind::PlaneOff}});
        if (tcp_on_ && !want_tcp) out.push_back({loc, ir::MachineMode{ir::ModeKind::TcpOff}});
        dwo_on_ = plane_on_ = false;
        tcp_on_ = tcp_on_ && want_tcp;
        set_current(c.a, &axis);
        out.push_back({loc, ir::RotaryPosition{c.a, true}});
        indexed_at_ = axis;
        // The plane wherever the rotaries are turned (at +Z with a table turned about it too:
        // the plane is the part's, and the control follows the table).
        if (k_.indexed == Indexed::Plane && (c.a[0] != 0 || c.a[1] != 0)) {
          out.push_back({loc, plane_for(axis)});
          plane_on_ = true;
        }
      }
    } else {
      indexed_at_.reset();
      if (dwo_on_) {
        out.push_back({loc, ir::MachineMode{ir::ModeKind::DwoOff}});
        dwo_on_ = false;
      }
      if (plane_on_) {
        out.push_back({loc, ir::MachineMode{ir::ModeKind::PlaneOff}});
        plane_on_ = false;
      }
    }
    if (want_tcp && !tcp_on_) {
      out.push_back({loc, ir::MachineMode{ir::ModeKind::TcpOn}});
      tcp_on_ = true;
    }
    if (!want_tcp && tcp_on_) {
      out.push_back({loc, ir::MachineMode{ir::ModeKind::TcpOff}});
      tcp_on_ = false;
    }
    // A dynamic work offset at no rotation would change nothing.
    if (want_dwo && !turned()) want_dwo = false;
    if (want_dwo && !dwo_on_) {
      out.push_back({loc, ir::MachineMode{ir::ModeKind::DwoOn}});
      dwo_on_ = true;
    }
    return true;
  }

  bool no_solution(const Vec3& axis, SourceLoc loc) {
    d_->error(loc, "no position of the rotary axes of machine '" + ctx_->machine.name + "' within their limits turns the tool to " +
                       vec_text(axis));
    return false;
  }

  bool jump_error(const Choice& c, const Vec3& axis, SourceLoc loc) {
    std::string from, to;
    auto deg = [](double v) { return num_text(std::round(v * 1e4) / 1e4); };
    for (size_t i = 0; i < k_.rotaries.size(); ++i) {
      from += k_.rotaries[i].name + deg(cur_[i]) + " ";
      to += k_.rotaries[i].name + deg(c.a[i]) + " ";
    }
    d_->error(loc, "tool axis " + vec_text(axis) + ": continuing from " + from + "leaves the rotary limits; the only way on is a jump to " +
                       to + "(set kinematics.on_limit = \"retract\" to retract, rotate and re-engage)");
    return false;
  }

  // --- motion --------------------------------------------------------------------------------

  void motion(ir::Move m, SourceLoc loc, std::vector<ir::Instr>& out) {
    const bool simultaneous = !mode_indexed_;
    if (simultaneous && !moved_in_op_ && have_cur_) {
      // An operation starts from where the last one left the rotaries: when going on from there
      // means a jump, the rotaries are positioned first, with the tool retracted (as for 3+2).
      // A rapid into it that turns the rotaries, too: the table turning while the tool runs
      // across from the last operation's end may sweep it through the part (a side face's end
      // to a top face's start); the tool goes up first, as before a 3+2 operation. (After a tool
      // change it is up there already.)
      Choice c = choose(m.axis);
      const bool turns = c.found && (std::abs(c.a[0] - cur_[0]) > 1e-9 || std::abs(c.a[1] - cur_[1]) > 1e-9);
      if (c.found && (c.jump || (turns && m.kind == ir::MoveKind::Rapid && !tool_up_))) {
        modes_off(out, loc);
        out.push_back({loc, ir::RotaryPosition{c.a, true}});
        set_current(c.a, &m.axis);
        have_prev_ = false;
      }
    }
    moved_in_op_ = true;
    if (!prepare(simultaneous, m.axis, loc, out)) return;
    kin::Angles a = cur_;
    if (simultaneous) cross_singularity(m, loc, out);
    if (simultaneous) {
      Choice c = choose(m.axis);
      if (!c.found) {
        no_solution(m.axis, loc);
        return;
      }
      if (c.jump) {
        if (!k_.retract_on_limit) {
          jump_error(c, m.axis, loc);
          return;
        }
        retract_rotate(c.a, m, loc, out);
      } else if (at_singularity() && have_prev_ && std::abs(c.a[free_] - cur_[free_]) > 1e-9) {
        // Leaving the singularity on another branch: turn the free axis first, on the spot.
        turn_free_axis(c.a[free_], m.kind == ir::MoveKind::Rapid && prev_rapid_ ? ir::MoveKind::Rapid : ir::MoveKind::Feed,
                       loc, out);
      }
      // A feed that changes branch (the tilt's sign) goes through the pole: right where the
      // CL's sweep passes it, 10 degrees off where it does not (B20 C0 to B-20 C-60, the sweep
      // 10 degrees from the pole: the least travel, certified; helper-65). There the branch
      // stays, C swings, and the move is split along the sweep.
      if (m.kind == ir::MoveKind::Feed && have_prev_ && !c.jump && singular_ &&
          kin::off_sweep(*singular_, prev_axis_.normalized(), m.axis.normalized()) > kin::kMidBlockAxisTolerance / 2)
        on_branch_of(cur_, m.axis, c.a);
      a = c.a;
      const kin::Angles turns = unwind_turns(a);
      if ((turns[0] != 0 || turns[1] != 0) && !unwind(a, turns, loc, out)) return;
    }
    // Transform mode: split the move where the rotation takes the tip off the CL segment.
    // Under TCPC the tip goes straight, but the tool axis follows the rotaries: split where it
    // leaves the CL's sweep.
    if (simultaneous && have_prev_ && m.kind == ir::MoveKind::Feed) {
      if (!tcp(true)) subdivide(prev_tip_, prev_axis_, cur_, m.point, m.axis, a, loc, out, 0);
      else subdivide_axis(prev_tip_, prev_axis_, cur_, m.point, m.axis, a, loc, out, 0);
    }
    emit(m, a, simultaneous, loc, out);
  }

  // Where the CL tool axis passes exactly through the singular direction between the last
  // point and this one, a point goes there (the tool tip on the CL segment, the axis singular):
  // the free axis can then turn to the preferred branch without tilting the tool at all.
  void cross_singularity(const ir::Move& m, SourceLoc loc, std::vector<ir::Instr>& out) {
    auto s = singular_direction();
    if (!s || !have_prev_ || !have_cur_ || m.kind != ir::MoveKind::Feed) return;
    const Vec3 a0 = prev_axis_, a1 = m.axis;
    // The great circle from a0 to a1 passes through s when s lies in their plane, between
    // them (tested first: it is cheap, and almost never so).
    const Vec3 c = a0.cross(a1);
    const double cn = c.norm();
    if (cn < 1e-12 || std::abs(c.dot(*s)) > 1e-9 * cn) return;
    double total = kin::angle_between(a0, a1);
    if (total < 1e-9) return;
    double t = kin::angle_between(a0, *s) / total;
    if (!(t > 1e-9 && t < 1 - 1e-9) || std::abs(kin::angle_between(a0, *s) + kin::angle_between(*s, a1) - total) > 1e-9)
      return;
    Choice here = choose(*s);
    if (!here.found) return;
    ir::Move mid;
    mid.point = prev_tip_ + t * (m.point - prev_tip_);
    mid.axis = *s;
    mid.kind = ir::MoveKind::Feed;
    // Without TCPC the way there is split within tolerance, as any move (the rotation would take
    // the tip off the CL line).
    if (!tcp(true)) subdivide(prev_tip_, prev_axis_, cur_, mid.point, mid.axis, here.a, loc, out, 0);
    emit(mid, here.a, true, loc, out);
    // Turn the free axis to the branch the rest of the move takes, on the spot.
    Choice next = choose(m.axis);
    if (next.found && std::abs(next.a[free_] - cur_[free_]) > 1e-9) turn_free_axis(next.a[free_], ir::MoveKind::Feed, loc, out);
  }

  void emit(ir::Move m, const kin::Angles& a, bool simultaneous, SourceLoc loc, std::vector<ir::Instr>& out) {
    const Vec3 tip = m.point, axis = m.axis;
    bool rotates = have_cur_ && (std::abs(a[0] - cur_[0]) > 1e-9 || std::abs(a[1] - cur_[1]) > 1e-9);
    m.point = output_point(a, tip, simultaneous);
    m.axis = output_axis(a, axis, simultaneous);
    m.has_rotary = true;
    m.rotary = a;
    if (k_.inverse_time && simultaneous && rotates && m.kind == ir::MoveKind::Feed && feed_known_ &&
        feed_.mode == ir::FeedMode::PerMinute && have_prev_) {
      m.inverse_time = inverse_time(prev_tip_, tip, a);
      // The tip standing still while the rotaries turn, and no rate to time them by: F1e9
      // was written, the rotaries whipped round at their fastest against the part (helper-57).
      if (m.inverse_time >= kNoTime && !rotary_time_reported_) {
        rotary_time_reported_ = true;
        d_->error(loc, "the rotaries turn at feed about the tool tip, which stands still: the CL's feed gives the move "
                       "no time, and machine '" + ctx_->machine.name + "' gives its rotary axes no rate (degrees per "
                       "minute) to time it by; set kinematics.axes[].rate, or kinematics.max_inverse_time");
      }
    }
    // A feed per revolution on a move that turns the rotaries without TCPC: the control reads F
    // over all its axes, G93 and degrees per minute take a feed per minute; G95 F0.1 was written
    // and the tip ran at five times the CL's feed (helper-57).
    if ((k_.inverse_time || k_.degrees_per_minute) && simultaneous && !tcp(true) && rotates &&
        m.kind == ir::MoveKind::Feed && feed_known_ && feed_.mode == ir::FeedMode::PerRev && !per_rev_reported_) {
      per_rev_reported_ = true;
      d_->error(loc, "a feed per revolution on a move that turns the rotaries without tool centre point control: the "
                     "control reads F over all its axes at once, and the feed that keeps the tip at the CL's (" +
                     std::string(ctx_->machine.kinematics.inverse_time ? "G93" : "degrees per minute") +
                     ") is one per minute; give five-axis moves a feed per minute (FEDRAT/MMPM, IPM)");
    }
    if (k_.degrees_per_minute && simultaneous && !tcp(true) && rotates && m.kind == ir::MoveKind::Feed && feed_known_ &&
        feed_.mode == ir::FeedMode::PerMinute && have_prev_)
      m.combined_feed = combined_feed(prev_tip_, tip, a);
    // Neither: the control reads the CL's F over all its axes at once (mm and degrees), and the
    // tip runs at another feed: five times the CL's on a part 300 mm from the axis.
    if (!k_.inverse_time && !k_.degrees_per_minute && simultaneous && !tcp(true) && rotates &&
        m.kind == ir::MoveKind::Feed && !feed_mode_reported_) {
      feed_mode_reported_ = true;  // the machine's, not the record's: said once
      d_->error(loc, "machine '" + ctx_->machine.name +
                         "' turns its rotaries while feeding without tool centre point control, and says neither "
                         "kinematics.inverse_time (G93) nor kinematics.degrees_per_minute: its control reads F over "
                         "all the axes at once, so the tool would not cut at the CL's feed; set the one the control "
                         "uses (docs/kinematics.md)");
    }
    set_current(a, &axis);
    prev_tip_ = tip;
    prev_axis_ = axis;
    prev_rapid_ = m.kind == ir::MoveKind::Rapid;
    tool_up_ = false;
    have_prev_ = true;
    out.push_back({loc, m});
  }

  // F in G93: the move takes as long as the CL feed along the CL path says, and no less than
  // the machine's axes allow; capped at the machine's maximum.
  static constexpr double kNoTime = 1e9;  // F of a move the CL and the machine give no time
  double inverse_time(const Vec3& from, const Vec3& to, const kin::Angles& a) const {
    double minutes = (to - from).norm() / feed_.value;
    const double out_per_prog = 1 / ctx_->from_output();
    if (ctx_->machine.max_feed > 0) {
      Vec3 m0 = output_point(cur_, from, true), m1 = output_point(a, to, true);
      minutes = std::max(minutes, (m1 - m0).norm() * out_per_prog / ctx_->machine.max_feed);
    }
    for (size_t i = 0; i < k_.rotaries.size(); ++i)
      if (k_.rotaries[i].rate > 0) minutes = std::max(minutes, std::abs(kin::travel(k_.rotaries[i], cur_[i], a[i])) / k_.rotaries[i].rate);
    double f = minutes > 0 ? 1 / minutes : kNoTime;
    if (k_.max_inverse_time > 0) f = std::min(f, k_.max_inverse_time);
    return f;
  }

  // F in degrees-per-minute mode: the control takes F along the move's length over all its
  // axes at once, sqrt(dX^2 + dY^2 + dZ^2 + dA^2 + dB^2 + dC^2) (output units and degrees), so
  // that the move takes as long as the CL feed along the tip's path says: F = that length /
  // (tip length / CL feed).
  double combined_feed(const Vec3& from, const Vec3& to, const kin::Angles& a) const {
    const double out_per_prog = 1 / ctx_->from_output();
    const double minutes = (to - from).norm() / feed_.value;
    const Vec3 m0 = output_point(cur_, from, true) * out_per_prog, m1 = output_point(a, to, true) * out_per_prog;
    double sq = (m1 - m0).squaredNorm();
    for (size_t i = 0; i < k_.rotaries.size(); ++i) sq += std::pow(kin::travel(k_.rotaries[i], cur_[i], a[i]), 2);
    return minutes > 0 ? std::sqrt(sq) / minutes : 0;
  }

  // Between CL points (p0, a0) and (p1, a1), without TCPC, the control interpolates machine
  // coordinates and rotary angles linearly; where the tip it then cuts leaves the CL segment by
  // more than the tolerance, a point (on the segment, with the tool axis halfway) goes between.
  void subdivide(const Vec3& p0, const Vec3& ax0, const kin::Angles& t0, const Vec3& p1, const Vec3& ax1,
                 const kin::Angles& t1, SourceLoc loc, std::vector<ir::Instr>& out, int depth) {
    Vec3 m0 = kin::machine_point(k_, t0, p0, pivot()), m1 = kin::machine_point(k_, t1, p1, pivot());
    const Vec3 seg = p1 - p0;
    const double len2 = seg.squaredNorm();
    double worst = worst_point([&](double t) {
      const kin::Angles ta = kin::between(k_, t0, t1, t);
      Vec3 tip = kin::part_tip(k_, ta, m0 + t * (m1 - m0), pivot());
      double s = len2 > 0 ? std::clamp((tip - p0).dot(seg) / len2, 0.0, 1.0) : 0;
      return (p0 + s * seg - tip).norm();
    });
    if (worst <= 0.5 * ctx_->tolerance()) return;
    if (depth >= 12) {
      // Halving 4096 times did not do it: the angles halfway do not lie between the ends'.
      // Never a move off the path left unsaid.
      if (!(bow_reported_ == loc)) {
        d_->error(loc, "without tool centre point control the machine's straight interpolation of its axes takes the tip " +
                           num_text(std::round(worst * 1e4) / 1e4) +
                           " off the CL line here, and splitting the move does not bring it within arcs.tolerance");
        bow_reported_ = loc;
      }
      return;
    }
    Vec3 pm = (p0 + p1) / 2;
    Vec3 am = (ax0 + ax1).normalized();
    if (!std::isfinite(am.x())) am = ax0;
    Choice c = choose_from(t0, am);
    if (!c.found) return;
    subdivide(p0, ax0, t0, pm, am, c.a, loc, out, depth + 1);
    emit_feed_point(pm, am, c.a, loc, out);
    subdivide(pm, am, c.a, p1, ax1, t1, loc, out, depth + 1);
  }

  // The angles for `axis` continuing from t0 (not from where the machine is now).
  Choice choose_from(const kin::Angles& t0, const Vec3& axis) {
    const kin::Angles save = cur_;
    const bool save_have = have_cur_;
    cur_ = t0;
    have_cur_ = true;
    Choice c = choose(axis);
    cur_ = save;
    have_cur_ = save_have;
    return c;
  }

  // A point a split puts between two CL points: fed, at angles a.
  void emit_feed_point(const Vec3& p, const Vec3& axis, const kin::Angles& a, SourceLoc loc, std::vector<ir::Instr>& out) {
    ir::Move mid;
    mid.point = p;
    mid.axis = axis;
    mid.kind = ir::MoveKind::Feed;
    emit(mid, a, true, loc, out);
  }

  // Under TCPC the control moves the tip straight and turns the rotaries at proportional
  // rates: near the pole C swings far while B barely moves, and halfway through the block the
  // tool axis is off the CL's sweep from ax0 to ax1 (10 degrees on a pass 3 degrees from
  // vertical, certified; helper-63). Where it leaves the sweep by more than half the mid-block
  // tolerance (kin::kMidBlockAxisTolerance, as verify holds it), a point goes between.
  void subdivide_axis(const Vec3& p0, const Vec3& ax0, const kin::Angles& t0, const Vec3& p1, const Vec3& ax1,
                      const kin::Angles& t1, SourceLoc loc, std::vector<ir::Instr>& out, int depth) {
    // A move from one branch to the other goes through the pole: off the sweep by as far as
    // the sweep passes from it, whatever the splitting (docs/kinematics.md).
    if (singular_ && t0[1 - free_] * t1[1 - free_] < 0) return;
    // Turned d degrees in all, the axis halfway is within d/2 of an end of the sweep.
    const double allowed = kin::kMidBlockAxisTolerance;
    double turned = 0;
    for (size_t i = 0; i < k_.rotaries.size(); ++i) turned += std::abs(kin::travel(k_.rotaries[i], t0[i], t1[i]));
    if (turned <= allowed) return;
    const Vec3 u0 = ax0.normalized(), u1 = ax1.normalized();
    const double worst = worst_point([&](double t) {
      return kin::off_sweep(kin::tool_axis_in_part(k_, kin::between(k_, t0, t1, t)).normalized(), u0, u1);
    });
    if (worst <= 0.5 * allowed) return;
    if (depth >= 12) {
      if (!(bow_reported_ == loc)) {
        d_->error(loc, "the machine's interpolation of its rotaries takes the tool axis " + num_text(std::round(worst * 1e3) / 1e3) +
                           " degrees off the CL's sweep here, and splitting the move does not bring it within " +
                           num_text(std::round(allowed * 1e3) / 1e3) + " degrees");
        bow_reported_ = loc;
      }
      return;
    }
    const Vec3 pm = (p0 + p1) / 2;
    Vec3 am = (u0 + u1).normalized();
    if (!std::isfinite(am.x())) am = u0;
    Choice c = choose_from(t0, am);
    if (!c.found) return;
    if (t0[1 - free_] * t1[1 - free_] > 0) on_branch_of(t0, am, c.a);
    subdivide_axis(p0, ax0, t0, pm, am, c.a, loc, out, depth + 1);
    emit_feed_point(pm, am, c.a, loc, out);
    subdivide_axis(pm, am, c.a, p1, ax1, t1, loc, out, depth + 1);
  }

  // The position for `axis` on the branch (the tilt's sign) of `ref`, where `a` is on the other
  // one and that branch is within the limits: halfway between two points on one branch (near
  // the pole the nearest angles are often the other branch, the free axis half a turn round:
  // the pieces of the move would go through the pole; NX APT_Variable_Axis.cls:224), and a
  // feed whose sweep stays clear of the pole.
  void on_branch_of(const kin::Angles& ref, const Vec3& axis, kin::Angles& a) const {
    if (!singular_ || k_.rotaries.size() != 2) return;
    const size_t tilt = 1 - free_;
    if (!(a[tilt] * ref[tilt] < 0)) return;
    kin::Angles alt = a;
    alt[tilt] = -a[tilt];
    alt[free_] = ref[free_] + std::remainder(a[free_] + 180 - ref[free_], 360.0);
    if (k_.rotaries[free_].cyclic == Cyclic::Modulo) alt[free_] = std::fmod(alt[free_] + 360.0, 360.0);
    for (size_t i = 0; i < 2; ++i) {
      const RotaryAxis& r = k_.rotaries[i];
      if (r.cyclic == Cyclic::No && (alt[i] < r.min - 1e-9 || alt[i] > r.max + 1e-9)) return;
    }
    if ((kin::tool_axis_in_part(k_, alt) - axis.normalized()).norm() <= 1e-9) a = alt;
  }

  // Whole turns (degrees) that bring each winding axis of `a` with a range (kinematics axes'
  // min / max) back to the middle of it, for those `a` would take past it; zeros otherwise.
  kin::Angles unwind_turns(const kin::Angles& a) const {
    kin::Angles turns{0, 0};
    for (size_t i = 0; i < k_.rotaries.size() && i < turns.size(); ++i) {
      const RotaryAxis& r = k_.rotaries[i];
      if (!r.wind_range || (a[i] >= r.min - 1e-9 && a[i] <= r.max + 1e-9)) continue;
      turns[i] = -360 * std::round((a[i] - (r.min + r.max) / 2) / 360);
    }
    return turns;
  }

  // A winding axis about to pass its range: where the tool is (the last CL point), retract
  // along the tool axis, turn the axis back by whole turns (the tool's orientation is the same,
  // so nothing moves but the axis), come back down to the point at feed, and go on from there
  // with `a` unwound too. Never a turn with the tool on the part.
  bool unwind(kin::Angles& a, const kin::Angles& turns, SourceLoc loc, std::vector<ir::Instr>& out) {
    std::string what;
    auto deg = [](double v) { return num_text(std::round(v * 1000) / 1000); };
    for (size_t i = 0; i < k_.rotaries.size() && i < turns.size(); ++i)
      if (turns[i] != 0) {
        const RotaryAxis& r = k_.rotaries[i];
        what += (what.empty() ? "" : "; ") + r.name + " would wind to " + r.name + deg(a[i]) + ", past its range (" +
                deg(r.min) + " to " + deg(r.max) + ")";
      }
    const bool one_axis = (turns[0] != 0) != (turns[1] != 0);
    if (!ctx_->machine.codes.unwind.empty() && one_axis) {
      // The control renames the axis's position: nothing moves, the tool may stay on the part.
      d_->warning(loc, what + ": renamed by whole turns (codes.unwind)", "unwind");
      kin::Angles back{cur_[0] + turns[0], cur_[1] + turns[1]};
      ir::RotaryPosition rename{back, false};
      rename.rename = true;
      out.push_back({loc, rename});
      set_current(back, have_prev_ ? &prev_axis_ : nullptr);
      a = {a[0] + turns[0], a[1] + turns[1]};
      return true;
    }
    if (!have_prev_ || !(k_.retract_distance > 0)) {
      d_->error(loc, what + ": set kinematics.retract_distance so that clpc can retract, unwind and re-engage");
      return false;
    }
    d_->warning(loc, what + ": retracting along the tool axis, unwinding and re-engaging", "unwind");
    retract_turn_reengage({cur_[0] + turns[0], cur_[1] + turns[1]}, loc, out);
    a = {a[0] + turns[0], a[1] + turns[1]};
    return true;
  }

  // Retract from the last CL point along its tool axis and turn the rotaries to `turn` up
  // there, TCPC off while they turn: the tool is where the rotaries' turn cannot touch the part.
  void retract_and_turn(const kin::Angles& turn, const Vec3* axis, SourceLoc loc, std::vector<ir::Instr>& out) {
    ir::Move up;
    up.point = prev_tip_ + prev_axis_ * k_.retract_distance;
    up.axis = prev_axis_;
    up.kind = ir::MoveKind::Rapid;
    emit(up, cur_, true, loc, out);
    if (tcp_on_) {
      out.push_back({loc, ir::MachineMode{ir::ModeKind::TcpOff}});
      tcp_on_ = false;
    }
    set_current(turn, axis);
    out.push_back({loc, ir::RotaryPosition{turn, false}});
    if (tcp(true)) {
      out.push_back({loc, ir::MachineMode{ir::ModeKind::TcpOn}});
      tcp_on_ = true;
    }
  }

  // At the last CL point: retract along the tool axis, turn the rotaries to `turn` (the same
  // tool axis), come back to the point (rapid to the retract point, then down at feed). The cut
  // goes on from that point, so no piece of the CL path is left out.
  void retract_turn_reengage(const kin::Angles& turn, SourceLoc loc, std::vector<ir::Instr>& out) {
    const Vec3 at = prev_tip_, axis = prev_axis_;
    retract_and_turn(turn, &axis, loc, out);
    ir::Move up;
    up.point = at + axis * k_.retract_distance;
    up.axis = axis;
    up.kind = ir::MoveKind::Rapid;
    emit(up, turn, true, loc, out);  // the retract point again, in the turned rotaries
    ir::Move down;
    down.point = at;
    down.axis = axis;
    down.kind = ir::MoveKind::Feed;
    emit(down, turn, true, loc, out);
  }

  // Only a jump to another solution goes on to `to` (the continuing one leaves the limits):
  // retract at the last CL point, turn to the other branch there, re-engage, and cut on.
  // Where the last point has no solution on that branch within the limits, the tool re-engages
  // at `to` instead, along its axis.
  void retract_rotate(const kin::Angles& a, const ir::Move& to, SourceLoc loc, std::vector<ir::Instr>& out) {
    if (!have_prev_) return;
    d_->warning(loc, "the rotary axes must jump here: retracting, rotating and re-engaging", "retract-rotate");
    Choice here = kin::choose(k_, prev_axis_, &a, false);
    if (here.found && !here.jump) {
      retract_turn_reengage(here.a, loc, out);
      return;
    }
    retract_and_turn(a, nullptr, loc, out);
    ir::Move over;
    over.point = to.point + to.axis * k_.retract_distance;
    over.axis = to.axis;
    over.kind = ir::MoveKind::Rapid;
    have_prev_ = false;  // no subdivision across the jump
    emit(over, a, true, loc, out);
  }

  void arc(ir::Arc a, SourceLoc loc, std::vector<ir::Instr>& out) {
    const bool simultaneous = !mode_indexed_;
    if (tcp(simultaneous)) {
      // Under TCPC the control is given part-frame points: lines within tolerance are safe
      // whatever the tool's tilt.
      std::vector<ir::Instr> lines;
      if (!arcedit::linearise(a, ctx_->tolerance(), loc, lines, *d_)) return;
      for (ir::Instr& in : lines) motion(std::get<ir::Move>(in.op), in.loc, out);
      return;
    }
    if (!prepare(simultaneous, a.tool_axis, loc, out)) return;
    if (simultaneous) {
      Choice c = choose(a.tool_axis);
      if (!c.found) {
        no_solution(a.tool_axis, loc);
        return;
      }
      if (std::abs(c.a[0] - cur_[0]) > 1e-9 || std::abs(c.a[1] - cur_[1]) > 1e-9) {
        // The rotaries must turn before the arc: a move to its start with the arc's axis.
        ir::Move m;
        m.point = a.start;
        m.axis = a.tool_axis;
        m.kind = ir::MoveKind::Feed;
        emit(m, c.a, true, loc, out);
      }
    }
    // A rigid motion keeps an arc an arc: move its points and turn its axes.
    const Vec3 end_in_part = a.end, axis_in_part = a.tool_axis;
    const kin::Angles t = cur_;
    a.start = output_point(t, a.start, simultaneous);
    a.end = output_point(t, a.end, simultaneous);
    a.center = output_point(t, a.center, simultaneous);
    a.axis = output_axis(t, a.axis, simultaneous);
    a.tool_axis = output_axis(t, a.tool_axis, simultaneous);
    a.has_rotary = true;
    a.rotary = t;
    prev_tip_ = end_in_part;
    prev_axis_ = axis_in_part;
    prev_rapid_ = false;
    tool_up_ = false;
    have_prev_ = true;
    out.push_back({loc, a});
  }

  // A canned cycle drills along the machine's Z: only indexed work whose tool the rotaries turn
  // onto it (table axes, or a tilted plane, whose Z the tool is), not under TCPC. Otherwise the
  // holes become moves, and their cycle records go.
  bool cycles_kept() const {
    if (!mode_indexed_ || tcp(false)) return false;
    if (k_.indexed == Indexed::Plane) return true;
    Choice c = choose(op_axis_);
    return c.found && kin::angle_between(table(c.a) * op_axis_, Vec3::UnitZ()) < 1e-7;
  }

  void hole(const ir::Operation& op, ir::Hole h, SourceLoc loc, std::vector<ir::Instr>& out) {
    const ir::CycleSpec& c = op.cycles.at(h.spec);
    if (cycle_kept_) {
      if (!prepare(false, h.axis, loc, out)) return;
      Vec3 axis = output_axis(cur_, h.axis, false);
      // A tilted plane's angles are rounded to their addresses (0.001 degree): its Z is that
      // near the tool axis, and the control drills along it.
      if (kin::angle_between(axis, Vec3::UnitZ()) > 0.002) {
        d_->error(loc, "internal: an indexed hole's axis is not the machine's Z after the kinematics (" + vec_text(axis) + ")");
        return;
      }
      h.point = output_point(cur_, h.point, false);
      h.axis = Vec3::UnitZ();
      out.push_back({loc, h});
      have_prev_ = false;
      tool_up_ = false;  // at the hole's return level, not up
      return;
    }
    std::vector<ir::Instr> moves;
    ExpandContext x{ctx_->machine.cycles.peck_clearance * ctx_->from_output(), feed_.value, feed_.mode, feed_known_,
                    ctx_->machine.cycles.return_initial, spindle_.speed, spindle_.dir};
    // (The machine may have the cycle: the tilt is why it cannot be used. helper-52 was told
    // codes.cycle_tap is empty on a head-head machine that has G84.)
    const Codes& k = ctx_->machine.codes;
    const CodeTemplate& code = c.kind == ir::CycleKind::FineBore   ? k.cycle_fine_bore
                               : c.kind == ir::CycleKind::BackBore ? k.cycle_back_bore
                               : c.left_hand                       ? k.cycle_tap_left
                                                                   : k.cycle_tap;
    // (In a simultaneous operation the axes follow the tool under TCPC or the transform,
    // whatever the hole's axis: the vertical tap of a five-axis operation was said to be tilted;
    // helper-55.)
    if (!code.empty())
      x.why_moves = !mode_indexed_
                        ? "this hole is in a simultaneous five-axis operation (its tool axis changes), where the axes "
                          "follow the tool and no canned cycle runs: give the hole an operation of its own"
                        : "this hole cannot take one: its axis is not the machine's Z here (a tilting head, or tool "
                          "centre point control), along which a canned cycle drills";
    if (!expand_hole(h, c, x, loc, moves, *d_)) return;
    for (ir::Instr& in : moves) {
      if (auto* m = std::get_if<ir::Move>(&in.op)) motion(*m, in.loc, out);
      else {
        if (auto* f = std::get_if<ir::Feed>(&in.op)) {
          feed_ = *f;
          feed_known_ = true;
        }
        out.push_back(std::move(in));
      }
    }
  }

  KinematicsSettings k_;
  std::vector<ir::Instr> scratch_;
  Diagnostics* d_ = nullptr;
  PassContext* ctx_ = nullptr;
  kin::Angles cur_{0, 0};
  bool have_cur_ = false;
  bool mode_indexed_ = false;
  // The mode this operation's chunks so far were cut in, and the tool axis of the last one.
  bool op_mode_known_ = false, op_indexed_ = false;
  Vec3 op_axis_ = Vec3::UnitZ();
  std::optional<Vec3> indexed_at_;
  bool tcp_on_ = false, dwo_on_ = false, plane_on_ = false;
  bool cycle_kept_ = false;  // the cycle in force stays a canned cycle (cycles_kept() at its CycleOn)
  ir::Mat3 plane_ = ir::Mat3::Identity();  // the tilted plane in force (plane -> part)
  std::array<double, 3> plane_angle_step_{1e-3, 1e-3, 1e-3};  // the resolution of its angles' addresses
  bool positioned_ = false;  // this operation was positioned by the offset table
  std::optional<Vec3> singular_;  // the tool direction where an axis is free
  size_t free_ = 1;               // that axis
  SourceLoc bow_reported_;        // the record a bow beyond the tolerance was reported at
  bool feed_mode_reported_ = false;  // a rotary feed with no feed mode (once: it is the machine's)
  bool rotary_time_reported_ = false;  // a turn about a still tip with no rate to time it
  bool per_rev_reported_ = false;      // a feed per revolution on a rotary move without TCPC
  mutable ir::Mat3 table_ = ir::Mat3::Identity();
  mutable kin::Angles table_for_{0, 0};
  mutable bool table_known_ = false;
  mutable Vec3 cur_axis_ = Vec3::UnitZ();  // the tool axis at cur_, part frame
  bool moved_in_op_ = false;  // this operation has had motion
  mutable bool cur_axis_known_ = false;
  mutable kin::Angles turned_for_{0, 0};
  mutable bool turned_known_ = false, turned_ = false;
  double tool_length_ = 0;
  ir::Feed feed_;
  bool feed_known_ = false;
  ir::Spindle spindle_;
  Vec3 prev_tip_ = Vec3::Zero(), prev_axis_ = Vec3::UnitZ();
  bool have_prev_ = false;
  bool prev_rapid_ = false;
  // The tool is up from a tool change, no motion since (a rapid that turns the rotaries into
  // the next operation needs no retract first). Not after a reload of the same tool.
  bool tool_up_ = true;
  int tool_ = -1, tool_offset_ = -1;  // the tool came to prev_tip_ at rapid (in the air, not at a cut)
};

}  // namespace

const PassInfo& kinematics_pass() {
  static const PassInfo info{
      .name = "kinematics",
      .summary = "turn tool axes into rotary positions and points into what the control is given (five-axis, 3+2)",
      .expects = "decided arcs, holes, offsets assigned, tool axes in the part frame",
      .guarantees = "on machines with rotary axes, every move and arc carries its rotary positions, within "
                    "limits, chosen for the least travel and continuity (the preferred sign first at the start "
                    "and at the singularity); operations with one tool axis are indexed: positioned once, "
                    "clamped, cut 3-axis in the tilted frame (with indexed = \"plane\" in the control's tilted working "
                    "plane, its angles rounded as the control will read them); holes stay canned cycles only along the machine's "
                    "Z; the TCPC / dynamic work offset / tilted plane modes are switched around the moves that need them and off "
                    "at tool changes and the end of each operation; no solution within limits, or a jump the "
                    "limits force, is an error naming the CL record (or, with on_limit = \"retract\", a retract, "
                    "rotate and re-engage at the last CL point); a winding axis with a range is unwound before it "
                    "passes it (renamed by codes.unwind, or retract, unwind, re-engage; an error without either); arcs may leave the machine's planes, so arc-legalise must follow. On "
                    "three-axis machines it changes nothing",
      .settings = "kinematics.* (axes, pivot, simultaneous, indexed, plane_euler, inverse_time, on_limit), "
                  "codes.plane_on, codes.unwind, arcs.tolerance",
      .needs = ir::ArcsDecided | ir::CyclesFormed | ir::OffsetsAssigned,
      .provides = ir::Kinematic,
      .breaks = ir::ArcsLegal,
      .costly = true,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<Kinematics>()); },
  };
  return info;
}

}  // namespace clpc
