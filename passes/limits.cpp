// limits: every rotary and linear position against the machine's travel; an error names the
// CL record that went too far.
//
// Rotary positions are checked against each limited axis's min and max. Linear positions are
// checked in machine coordinates (the tool tip moved through the table axes, as the control
// will have it): against kinematics.travel absolutely when kinematics.work_zero says where the
// program zero is on the machine; otherwise the program's extent along each axis must fit the
// travel wherever the part is set up. A point in a work-offset register's frame (the offset
// table puts them there) is taken back to the part frame first, where the register's frame is
// only shifted and turned in the part's first setup; in another setup only the span counts.
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and provides)
// is limits_pass() at the end of this file.
#include <cmath>

#include "machine/kinematics.h"
#include "machine/tilted_plane.h"
#include "support/text.h"
#include "passes/passes.h"

namespace clpc {

namespace {

class Limits : public Pass {
 public:
  void begin(PassContext& ctx) override {
    k_ = ctx.kinematics();
  }

  void run(ir::Operation& op, PassContext& ctx) override {
    const double to_out = 1 / ctx.from_output();
    for (const ir::Instr& in : op.body) {
      if (auto* m = std::get_if<ir::MachineMode>(&in.op)) {
        if (m->kind == ir::ModeKind::TcpOn) tcp_ = true;
        if (m->kind == ir::ModeKind::TcpOff) tcp_ = false;
        if (m->kind == ir::ModeKind::DwoOn) dwo_ = true;
        if (m->kind == ir::ModeKind::DwoOff) dwo_ = false;
        if (m->kind == ir::ModeKind::PlaneOn) {
          plane_on_ = true;
          plane_ = plane::rotation(m->angles, ctx.machine.kinematics.plane_euler);
        }
        if (m->kind == ir::ModeKind::PlaneOff) plane_on_ = false;
      } else if (auto* o = std::get_if<ir::SelectOffset>(&in.op)) {
        select(*o, ctx);
      } else if (auto* t = std::get_if<ir::ToolChange>(&in.op)) {
        const ir::ToolInfo* tool = ctx.info.tool(t->tool);
        tool_length_ = tool ? tool->length : 0;
      } else if (auto* r = std::get_if<ir::RotaryPosition>(&in.op)) {
        rot_ = r->rotary;
        rotary(in.loc, ctx);
      } else if (auto* mv = std::get_if<ir::Move>(&in.op)) {
        if (mv->kind == ir::MoveKind::From) continue;
        if (mv->has_rotary) {
          rot_ = mv->rotary;
          rotary(in.loc, ctx);
        }
        linear(mv->point, in.loc, ctx, to_out);
      } else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
        linear(a->end, in.loc, ctx, to_out);
        // The arc's extreme points in its plane: the centre plus or minus the radius along
        // each machine axis the arc reaches.
        for (int i = 0; i < 3; ++i) {
          ir::Vec3 dir = ir::Vec3::Unit(i) - ir::Vec3::Unit(i).dot(a->axis) * a->axis;
          if (dir.norm() < 1e-9) continue;
          for (double s : {-1.0, 1.0}) {
            ir::Vec3 p = a->center + s * a->radius * dir.normalized();
            if (a->sweep >= 360 - 1e-9 || on_arc(*a, p)) linear(p, in.loc, ctx, to_out);
          }
        }
      } else if (auto* h = std::get_if<ir::Hole>(&in.op)) {
        const ir::CycleSpec& c = op.cycles.at(h->spec);
        linear(h->point - h->axis * c.depth, in.loc, ctx, to_out);
        linear(h->point + h->axis * std::max(h->initial, c.clearance), in.loc, ctx, to_out);
      } else if (auto* g = std::get_if<ir::Groove>(&in.op)) {
        linear(g->end, in.loc, ctx, to_out);
      }
    }
  }

 private:
  static bool on_arc(const ir::Arc& a, const ir::Vec3& p) {
    ir::Vec3 rs = a.start - a.center, rp = p - a.center;
    rs -= rs.dot(a.axis) * a.axis;
    rp -= rp.dot(a.axis) * a.axis;
    double ang = std::atan2(a.axis.dot(rs.cross(rp)), rs.dot(rp)) * 180 / 3.14159265358979323846;
    if (ang < 0) ang += 360;
    if (a.dir == ir::ArcDir::Cw) ang = ang == 0 ? 0 : 360 - ang;
    return ang <= a.sweep + 1e-9;
  }

  void rotary(SourceLoc loc, PassContext& ctx) {
    for (size_t i = 0; i < k_.rotaries.size(); ++i) {
      const RotaryAxis& r = k_.rotaries[i];
      if (r.cyclic == Cyclic::Modulo || (r.cyclic == Cyclic::Wind && !r.wind_range)) continue;
      double v = rot_[i];
      if (v < r.min - 1e-4 || v > r.max + 1e-4)  // as the solver allows (machine/kinematics.cpp)
        ctx.diags.error(loc, r.name + num_text(std::round(v * 1000) / 1000) + " is beyond machine '" + ctx.machine.name +
                                 "''s limit (" + r.name + " " + num_text(r.min) + " to " + num_text(r.max) + ")");
    }
  }

  // The tool tip's machine position for the point the control is given, in output units.
  // Under a dynamic work offset the given point is the part point already turned with the
  // table (T p); the chain's table_point is affine with that same rotation as its linear part,
  // so the machine position is the given point plus the chain's offset at this position.
  ir::Vec3 machine_position(const ir::Vec3& given, double to_out) {
    if (!k_.has_rotaries() || !(tcp_ || dwo_ || plane_on_)) return given * to_out;
    // In a tilted plane the given point is the part point written in the plane.
    if (plane_on_ && !tcp_) return kin::machine_point(k_, rot_, plane_ * given, k_.pivot + tool_length_) * to_out;
    if (dwo_) {
      // Memoised per position: indexed work keeps one for many moves.
      if (!dwo_known_ || dwo_for_ != rot_ || dwo_length_ != tool_length_) {
        dwo_offset_ = kin::machine_point(k_, rot_, ir::Vec3::Zero(), k_.pivot + tool_length_);
        dwo_for_ = rot_;
        dwo_length_ = tool_length_;
        dwo_known_ = true;
      }
      return (given + dwo_offset_) * to_out;
    }
    return kin::machine_point(k_, rot_, given, k_.pivot + tool_length_) * to_out;
  }

  // Another register: the offset table put the points in its frame (passes/offset_table.cpp).
  // Where the register's frame is only shifted and turned from the part frame in the part's
  // first setup, with the rotaries at zero, a point in it is the frame's point in the part
  // frame, which work_zero places on the machine. (Each SET frame was taken as the program
  // zero: 400 mm across, a fixture's cuts passed a 300 mm travel.) In another setup the part
  // is set up again, so only the span is checked there.
  void select(const ir::SelectOffset& o, PassContext& ctx) {
    frame_ = nullptr;
    other_setup_ = false;
    for (const ir::WorkOffset& w : ctx.info.offsets) {
      if (w.index != o.index) continue;
      const bool rotaries_at_zero = !w.has_rotary || (std::abs(w.rotary[0]) < 1e-9 && std::abs(w.rotary[1]) < 1e-9);
      if (w.setup > 1) other_setup_ = true;
      else if (rotaries_at_zero && !w.base) frame_ = &w.frame;
      return;
    }
  }

  void linear(const ir::Vec3& given_in_frame, SourceLoc loc, PassContext& ctx, double to_out) {
    const KinematicsSettings& k = ctx.machine.kinematics;
    if (!k.travel.set) return;
    const bool plain = !(tcp_ || dwo_ || plane_on_);
    const ir::Vec3 given =
        frame_ && plain ? ir::Vec3(frame_->rotation * given_in_frame + frame_->origin) : given_in_frame;
    ir::Vec3 p = machine_position(given, to_out);
    const char* names = "XYZ";
    const char* unit = ctx.machine.units == ir::Units::Inch ? " in" : " mm";
    for (int i = 0; i < 3; ++i) {
      if (k.work_zero_set && !other_setup_) {
        double v = k.work_zero[i] + p[i];
        if (v < k.travel.min[i] - 1e-9 || v > k.travel.max[i] + 1e-9)
          ctx.diags.error(loc, std::string(1, names[i]) + " reaches " + num_text(std::round(v * 1e4) / 1e4) +
                                   unit + " in machine coordinates, beyond the travel (" + num_text(std::round(k.travel.min[i] * 1e4) / 1e4) +
                                   " to " + num_text(std::round(k.travel.max[i] * 1e4) / 1e4) + ")");
        continue;
      }
      lo_[i] = std::min(lo_[i], p[i]);
      hi_[i] = std::max(hi_[i], p[i]);
      double span = hi_[i] - lo_[i], travel = k.travel.max[i] - k.travel.min[i];
      if (!reported_[i] && span > travel + 1e-9) {
        reported_[i] = true;
        ctx.diags.error(loc, std::string("the program's ") + names[i] + " positions now span " +
                                 num_text(std::round(span * 1e4) / 1e4) + unit + ", more than the machine's " + num_text(std::round(travel * 1e4) / 1e4) +
                                 unit + " of travel: it cannot fit wherever the part is set up" +
                                 (ctx.info.units_doubt.empty()
                                      ? std::string()
                                      : " (are the CL's units right? " + ctx.info.units_doubt + "; see --input-units)"));
      }
    }
  }

  KinematicsSettings k_;
  const ir::Frame* frame_ = nullptr;  // the selected register's frame, where its points are in it
  bool other_setup_ = false;          // the selected register is in another setup than the first
  kin::Angles rot_{0, 0};
  bool tcp_ = false, dwo_ = false, plane_on_ = false;
  ir::Mat3 plane_ = ir::Mat3::Identity();  // the tilted plane in force (plane -> part)
  ir::Vec3 dwo_offset_ = ir::Vec3::Zero();
  kin::Angles dwo_for_{0, 0};
  double dwo_length_ = 0;
  bool dwo_known_ = false;
  double tool_length_ = 0;
  double lo_[3] = {1e300, 1e300, 1e300}, hi_[3] = {-1e300, -1e300, -1e300};
  bool reported_[3] = {false, false, false};
};

}  // namespace

const PassInfo& limits_pass() {
  static const PassInfo info{
      .name = "limits",
      .summary = "check every rotary and linear position against the machine's travel",
      .expects = "rotary positions on moves and the control modes marked (kinematics)",
      .guarantees = "an error naming the CL record for a rotary beyond its limits, or a tool tip beyond "
                    "kinematics.travel in machine coordinates: absolutely when kinematics.work_zero is given, "
                    "otherwise when the program's extent along an axis exceeds the travel",
      .settings = "kinematics.axes (min, max), kinematics.travel, kinematics.work_zero; the offset table's "
                  "frames (offset-table, before it in the pipeline)",
      .needs = ir::Kinematic,
      .provides = ir::LimitsChecked,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<Limits>()); },
  };
  return info;
}

}  // namespace clpc
