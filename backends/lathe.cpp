#include "backends/lathe.h"

#include "machine/arc_center.h"
#include "ir/arc_geometry.h"

#include <cmath>

#include "backends/mill.h"
#include "support/text.h"

namespace clpc {

LatheBackend::LatheBackend(const Machine& m, OutputFile& out, Diagnostics& d) : ProgramWriter(m, out, d) {}

std::unique_ptr<Backend> make_backend(const Machine& m, OutputFile& out, Diagnostics& d) {
  if (m.is_lathe()) return std::make_unique<LatheBackend>(m, out, d);
  return std::make_unique<MillBackend>(m, out, d);
}

void LatheBackend::write_tool_change(const ir::ToolChange& t, SourceLoc loc) {
  const int offset = t.length_offset > 0 ? t.length_offset : t.tool;
  // The tool already at the cut with the same offset: nothing to write. With another offset
  // (OSETNO), the T word is written again: the turret stays, the offset changes.
  if (t.tool == tool_ && offset == length_offset_) return;
  end_drill_speed(loc);
  if (!tool_changer_for(t, loc)) return;
  const bool had_tool = tool_ >= 0;
  if (had_tool) {
    clear_to_retract(loc, "the tool change finds the tool");  // judged on the side the last tool worked
    blocks({m_.codes.safe_retract}, loc);
  }
  side_ = 0;  // the next tool's side is where it starts
  reach_ = {};
  before_tool_change(loc);
  const ir::ToolInfo* info = info_ ? info_->tool(t.tool) : nullptr;
  e_.begin(loc);
  e_.code(m_.codes.tool_change, TemplateVars().with(Var::Tool, t.tool).with(Var::Offset, offset));
  if (info) e_.trailing_comment(tool_comment(*info));
  e_.end(true);
  after_template(m_.codes.tool_change);
  tool_ = t.tool;
  length_offset_ = offset;  // the offset the T word selects: nose radius and tip for G41/G42
  motion_ = Motion::None;
  e_.forget_linear();
  feed_written_ = false;
  // The index leaves the spindle and coolant running, but each tool's blocks say them again: a
  // restart at this tool (the operator searches to its T word) found the spindle stopped, and
  // G98 fed the insert into a still bar (helper-70: certified). Said before the tool's first
  // move, unless the CL gives its own SPINDL and COOLNT first.
  if (had_tool) {
    control_stopped(true, false);
    spindle_restore_before_move_ = spindle_restore_;
  }
  after_tool_change(t.tool, loc);
}

void LatheBackend::retract_for_stop(SourceLoc loc) {
  clear_to_retract(loc, "the stop's retract finds the tool");
  blocks({m_.codes.safe_retract}, loc);
}

void LatheBackend::write_spindle(const ir::Spindle& s, SourceLoc loc) {
  if (s.dir == ir::SpindleDir::Off) {
    e_.begin(loc);
    e_.code(m_.codes.spindle_off);
    e_.end();
    spindle_ = ir::SpindleDir::Off;
    surface_.reset();
    rpm_fixed_ = false;
    drill_fixed_ = false;
    return;
  }
  const CodeTemplate& dir = s.dir == ir::SpindleDir::Cw ? m_.codes.spindle_cw : m_.codes.spindle_ccw;
  if (lacks(dir, loc, s.dir == ir::SpindleDir::Cw ? "spindle_cw" : "spindle_ccw",
            s.dir == ir::SpindleDir::Cw ? "start the spindle clockwise" : "start the spindle counter-clockwise",
            "the tool would cut with the spindle stopped")) {
    spindle_ = s.dir;
    return;
  }
  if (s.mode == ir::SpindleMode::SurfaceSpeed) {
    // The programmer's MAXRPM, never above the machine's limit. One given before holds until
    // another is (the part's or the chuck's limit): a later SPINDL/SMM without one raised
    // G50 S1500 to the machine's S3000 (helper-59).
    if (s.max_rpm > 0) cl_max_rpm_ = s.max_rpm;
    double clamp = cl_max_rpm_;
    if (m_.spindle_limit() > 0 && (clamp <= 0 || clamp > m_.spindle_limit())) clamp = m_.spindle_limit();
    if (cl_max_rpm_ > clamp)
      d_.warning(loc, "MAXRPM " + num_text(cl_max_rpm_) + " is above machine '" + m_.name + "''s spindle limit: clamped at " +
                          num_text(clamp) + " rpm",
                 "spindle-clamp");
    if (clamp <= 0) {
      d_.error(loc, "constant surface speed needs a spindle limit: give SPINDL/...,MAXRPM,n or set lathe.max_rpm");
      return;
    }
    // Near the axis G96 turns the spindle at its clamp: without one it runs to the machine's
    // top speed, past the chuck's or the part's limit. A clamp or a speed written as S0 is none.
    if (lacks(m_.codes.spindle_clamp, loc, "spindle_clamp", "clamp the spindle under constant surface speed",
              "near the axis the spindle would run past the CL's MAXRPM") ||
        lacks(m_.codes.spindle_css_mode, loc, "spindle_css_mode", "turn constant surface speed on")) {
      spindle_ = s.dir;
      return;
    }
    const double speed_written = m_.units == ir::Units::Inch ? s.speed / 0.3048 : s.speed;  // m/min, or ft/min in inches
    if (e_.round('S', clamp).q == 0 || e_.round('S', speed_written).q == 0) {
      d_.error(loc, "SPINDL: " + std::string(e_.round('S', clamp).q == 0 ? "the clamp of " + num_text(clamp) + " rpm"
                                                                         : "the surface speed of " + num_text(s.speed)) +
                        " would be written S0 (format.S): a spindle that does not turn");
      spindle_ = s.dir;
      return;
    }
    if (!(cl_max_rpm_ > 0))
      d_.warning(loc, "constant surface speed without MAXRPM: clamped at the machine's limit of " + num_text(clamp) +
                          " rpm (give SPINDL/...,MAXRPM,n for the part's or the chuck's limit)",
                 "spindle-clamp");
    e_.begin(loc);
    e_.code(m_.codes.spindle_clamp, TemplateVars().with(Var::Max, clamp));
    e_.end();
    after_template(m_.codes.spindle_clamp);
    e_.begin(loc);
    e_.code(m_.codes.spindle_css_mode);
    e_.word('S', speed_written);
    e_.code(dir);
    e_.end();
    surface_ = s;
    surface_clamp_ = clamp;
    rpm_fixed_ = false;
    drill_fixed_ = false;
    spindle_rpm_ = 0;  // the speed follows the diameter
  } else {
    surface_.reset();
    rpm_fixed_ = false;
    drill_fixed_ = false;
    if (!spindle_within_limit(s.speed, loc)) {
      spindle_ = s.dir;  // the error stands for the record: no "spindle stopped" on every move after it
      return;
    }
    e_.begin(loc);
    e_.code(m_.codes.spindle_rpm_mode);
    e_.word('S', s.speed);
    e_.code(dir);
    e_.end();
    spindle_rpm_ = s.speed;
  }
  spindle_ = s.dir;
}

void LatheBackend::motion_code(Motion mo) {
  if (m_.modal.motion && motion_ == mo) return;
  const Codes& c = m_.codes;
  e_.code(mo == Motion::Rapid ? c.rapid : mo == Motion::Linear ? c.linear : mo == Motion::Cw ? c.arc_cw : c.arc_ccw);
  motion_ = mo;
}

bool LatheBackend::in_plane(const ir::Vec3& p, SourceLoc loc) {
  if (std::abs(p.y()) <= 1e-6) return true;
  if (loc == off_plane_said_) return false;  // once per CL record (an arc cut into pieces gives many)
  off_plane_said_ = loc;
  d_.error(loc, "lathe motion must lie in the XZ plane (Y = 0), found Y = " + num_text(p.y()) +
                    ": the CL must give turning motion with X the radius and Z along the spindle (in NX, the "
                    "lathe work plane ZM-XM)");
  return false;
}

namespace {
// A tool that cuts along its own axis (the spindle's, on a lathe): it has a diameter, not a nose.
bool cuts_along_axis(const std::string& kind) {
  return kind == "DRILL" || kind == "TAP" || kind == "REAM" || kind == "CENTER" || kind == "SPOT" || kind == "CDRILL";
}
}  // namespace

// A lathe's tool cuts on one side of the spindle axis (the side of its first position more than
// 1 mm off it: a gang-tool lathe's tools may stand at minus X), and a facing cut ends its nose
// radius past it, no more. A feed that ends further on the other side is no turning: an NX file
// whose lathe work plane is XM-YM (the spindle along its X) gave a centre drill's plunge as a
// feed along X through the centre to X-50, certified (helper-45). A tool that cuts along the
// axis (a drill, centre drill, spot drill, tap, reamer) may go 1 mm past it and is never fed
// across it; other tools 13 mm, or their corner radius and 1 mm (round inserts reach R12; a
// TLDATA/TURN's nose radius is not read). An arc is judged by its end and by its furthest reach.
bool LatheBackend::stays_on_its_side(double x, bool feed, SourceLoc loc, const char* what) {
  const double mm = 1.0 / ir::mm_per_unit(m_.units), x0 = pos_.x() * k_, x1 = x * k_;
  const ir::ToolInfo* t = info_ ? info_->tool(tool_) : nullptr;
  const std::string kind = t ? t->kind : "";
  const bool axial = cuts_along_axis(kind);
  if (axial && feed && std::abs(x1 - x0) > 1 * mm) {
    d_.error(loc, "a " + kind + " tool fed along X, from radius " + num_text(std::round(x0 * 1e4) / 1e4) + " to " +
                      num_text(std::round(x1 * 1e4) / 1e4) + ": on a lathe it cuts along Z, on the spindle axis; the CL "
                      "must give X as the radius and Z along the spindle (in NX, the lathe work plane ZM-XM, not XM-YM)");
    return false;
  }
  const double allow = axial ? 1 * mm : std::max(13 * mm, (t ? t->corner_radius * k_ : 0) + 1 * mm);
  if (side_ == 0) {
    if (std::abs(x1) > 1 * mm) side_ = x1 > 0 ? 1 : -1;
    return true;
  }
  if (!feed || x1 * side_ >= -allow) return true;
  d_.error(loc, std::string(what) + " radius " + num_text(std::round(x1 * 1e4) / 1e4) + ", " +
                    num_text(std::round(std::abs(x1) * 1e4) / 1e4) + " past the spindle axis from the side this tool "
                    "works on: a lathe's tool cuts on one side of it (a facing cut ends its nose radius past it); the CL "
                    "must give X as the radius and Z along the spindle (in NX, the lathe work plane ZM-XM, not XM-YM)");
  return false;
}

bool LatheBackend::changed(char letter, double value) const {
  return !m_.modal.coordinates || e_.differs(letter, value);
}

void LatheBackend::write_move(const ir::Move& mv, SourceLoc loc) {
  if (mv.kind == ir::MoveKind::From) {
    pos_ = mv.point;
    return;
  }
  if (!in_plane(mv.point, loc)) return;
  if (mv.kind == ir::MoveKind::Feed && !tool_loaded_for_cut(loc)) return;
  // (No move is "away" on a lathe: out in X is into the wall of a bore; helper-69.)
  if (mv.kind == ir::MoveKind::Feed) warn_spindle_stopped(loc, "cutting move");
  if (thread_ && mv.kind == ir::MoveKind::Feed && is_thread_cut(pos_, mv.point)) {
    write_thread_move(mv, loc);
    return;
  }
  if (!thread_ && mv.kind == ir::MoveKind::Feed && !speed_on_centre(mv, loc)) return;
  if (!stays_on_its_side(mv.point.x(), mv.kind == ir::MoveKind::Feed, loc)) return;
  const ir::Vec3 o = mv.point * k_;
  const bool rapid = mv.kind == ir::MoveKind::Rapid;
  // A move to where the tool is moves nothing: a G41/G42 waiting for its first move waits on
  // (written alone it would start on the next block, maybe a cycle's profile).
  if (!changed('X', o.x()) && !changed('Z', o.z()) && !incremental_) {
    pos_ = mv.point;
    return;
  }
  e_.begin(loc);
  absolute_code();
  comp_code();  // tool nose radius compensation starts and ends on a straight move
  if (!rapid) feed_mode_code();
  motion_code(rapid ? Motion::Rapid : Motion::Linear);
  e_.modal_word('X', o.x());
  e_.modal_word('Z', o.z());
  if (!rapid) feed_word(loc);
  e_.end();
  if (rapid) reach_.went_in = false;
  else note_cut_to(mv.point, loc);
  pos_ = mv.point;
  position_known_ = true;
}

// Under constant surface speed a tool on the spindle's axis turns at the clamp (the speed at X0
// has no limit but it). The CL's surface speed is a drill's cutting speed at its diameter, as
// on a mill: a cut along the axis at X0 by a tool with a diameter (a drill, a reamer, a tap; not
// a turning tool) is made at the rpm that speed gives there (G97, within the clamp), and the
// surface speed comes back (G96) at the next cut off the axis. A drill without its diameter is
// refused: at the clamp it may turn many times too fast.
bool LatheBackend::speed_on_centre(const ir::Move& mv, SourceLoc loc) {
  constexpr double kOnAxis = 1e-6;
  const bool on_centre = std::abs(pos_.x()) < kOnAxis && std::abs(mv.point.x()) < kOnAxis;
  if (!on_centre) {
    end_drill_speed(loc);
    return true;
  }
  if (!surface_ || rpm_fixed_ || spindle_ == ir::SpindleDir::Off) return true;
  const ir::ToolInfo* t = info_ && tool_ >= 0 ? info_->tool(tool_) : nullptr;
  const std::string kind = t ? t->kind : "";
  const bool axial = cuts_along_axis(kind) || kind == "MILL";
  if (!axial && (kind != "" || !t || !(t->diameter > 0))) return true;  // a turning tool: the clamp is the CL's
  if (!(t->diameter > 0)) {
    d_.error(loc, "drilling on the spindle's axis under constant surface speed (G96): the spindle would turn at its "
                  "clamp; tool " + std::to_string(tool_) + " has no diameter to turn the surface speed into rpm "
                  "(TLDATA, CUTTER): give it one, or a SPINDL/RPM for the drilling");
    return false;
  }
  fix_spindle_speed(t->diameter / 2, loc);
  drill_fixed_ = rpm_fixed_;
  return true;
}

// The drill's speed belongs to its cuts on the axis: G96 comes back before the next cut off it,
// a tool change (the next tool's first cut may be a cycle: G71 would rough at the drill's rpm),
// a thread (its own G97 comes from the surface speed) or a groove or roughing cycle.
void LatheBackend::end_drill_speed(SourceLoc loc) {
  if (!drill_fixed_) return;
  drill_fixed_ = false;
  restore_surface_speed(loc);
}

void LatheBackend::write_arc(const ir::Operation& op, const ir::Arc& a, SourceLoc loc) {
  if (!tool_loaded_for_cut(loc)) return;
  warn_spindle_stopped(loc, "arc");
  end_drill_speed(loc);
  if (a.dir == ir::ArcDir::Unknown) {
    d_.error(loc, "internal: arc direction not decided (is 'arc-direction' in the machine's pipeline?)");
    return;
  }
  if (thread_) {
    d_.error(loc, "an arc inside THREAD: a thread is cut by straight synchronised moves (G32), not arcs");
    return;
  }
  if (comp_pending_set_) {
    d_.error(loc, "tool nose radius compensation (CUTCOM) starts or ends on an arc: the control needs a straight move "
                  "(G00/G01) for it; have the CAM system turn it on or off before a line");
    comp_pending_set_ = false;
    return;
  }
  if (std::abs(a.axis.y()) < 1 - 1e-9) {
    d_.error(loc, "lathe arcs must turn about the Y axis (lie in the XZ plane)");
    return;
  }
  if (!in_plane(a.end, loc) || !in_plane(a.center, loc)) return;
  if (!position_known_) {
    d_.error(loc, "arc with no programmed start position before it");
    return;
  }
  if (!stays_on_its_side(a.end.x(), true, loc)) return;
  // Judged by its end alone, an arc over the top of a circle centred past the axis went 38 mm
  // beyond it and was certified (helper-54): its furthest reach to the other side counts too.
  if (side_ != 0) {
    ir::Vec3 far = a.center;
    far.x() -= side_ * (a.end - a.center).norm();
    if (arcgeo::distance_to_arc(a, far) <= 1e-6 * std::max(1.0, std::abs(far.x())) &&
        !stays_on_its_side(far.x(), true, loc, "an arc reaching"))
      return;
  }
  // G02/G03 are seen from +Y unless the machine says otherwise.
  bool ccw = (a.dir == ir::ArcDir::Ccw) == (a.axis.y() > 0);
  if (m_.lathe.arcs_from_minus_y) ccw = !ccw;
  ir::Vec3 s_out = pos_ * k_;
  double last;
  if (e_.last('X', last)) s_out.x() = last;
  if (e_.last('Z', last)) s_out.z() = last;
  ir::Vec3 e_raw = a.end * k_, c_raw = a.center * k_;
  double ex = e_.as_written('X', e_raw.x()), ez = e_.as_written('Z', e_raw.z());
  // In the (Z, X) plane, right-handed about +Y: u = Z, v = X. I is a radius value whatever
  // X's scale, so the centre is chosen in radius units.
  ir::Vec3 mid = arcgeo::point_at(a, 0.5) * k_;
  bool ccw_math = (a.dir == ir::ArcDir::Ccw) == (a.axis.y() > 0);
  ArcCenterInput ci{s_out.z(), s_out.x(), ez, ex, c_raw.z(), c_raw.x(), mid.z(), mid.x(), ccw_math, a.sweep >= 360 - 1e-9};
  ArcCenterChoice ctr = choose_arc_center(ci, m_.format('K'), m_.format('I'), m_.arcs.center == ArcCenter::Incremental);
  double cz = ctr.cu, cx = ctr.cv;
  e_.begin(loc);
  absolute_code();
  feed_mode_code();
  motion_code(ccw ? Motion::Ccw : Motion::Cw);
  e_.modal_word('X', e_raw.x());
  e_.modal_word('Z', e_raw.z());
  if (m_.arcs.center == ArcCenter::Radius) {
    double r = std::hypot(cx - s_out.x(), cz - s_out.z());
    e_.word('R', a.sweep > 180 ? -r : r);
  } else {
    e_.word('I', cx - s_out.x());
    e_.word('K', cz - s_out.z());
  }
  feed_word(loc);
  e_.end();
  note_arc(a, loc);
  pos_ = a.end;
  (void)op;
}

// Fanuc's two-block G74/G75: "G75 R(e);" then "G75 X Z P Q [R] F;". P and Q go out in least
// input increments (their formats have no point); P is always the X amount and Q the Z
// amount, as radius values, whichever of them is the peck.
void LatheBackend::write_groove(const ir::Operation& op, const ir::Groove& g, SourceLoc loc) {
  if (!tool_loaded_for_cut(loc)) return;
  end_drill_speed(loc);
  const ir::GrooveSpec& s = op.grooves.at(g.spec);
  const CodeTemplate& code = s.face ? m_.codes.groove_face : m_.codes.groove_radial;
  if (code.empty()) {
    d_.error(loc, "machine '" + m_.name + "' has no " + (s.face ? "face" : "radial") + " groove cycle");
    return;
  }
  if (!in_plane(g.start, loc) || !in_plane(g.end, loc)) return;
  double feed = s.feed > 0 ? s.feed : feed_;
  ir::FeedMode mode = s.feed > 0 ? s.feed_mode : feed_mode_;
  if (!(feed > 0)) {
    d_.error(loc, "groove cycle with no feed rate");
    return;
  }
  e_.begin(loc);
  absolute_code();
  e_.code(code);
  e_.word('R', s.retract * k_);
  e_.end();
  e_.begin(loc);
  feed_mode_code(mode);
  e_.code(code);
  e_.word('X', g.end.x() * k_);
  e_.word('Z', g.end.z() * k_);
  e_.word('P', s.x_amount * k_);
  e_.word('Q', s.z_amount * k_);
  if (s.relief > 0) e_.word('R', s.relief * k_);
  if (!write_feed(feed * k_, mode, s.feed > 0 ? loc : feed_loc_)) return;
  e_.end();
  feed_written_ = false;
  motion_ = Motion::None;
  // The cycle ends where it started.
  e_.set_last('X', g.start.x() * k_);
  e_.set_last('Z', g.start.z() * k_);
  note_cut(g.start, loc);
  note_cut(g.end, loc);
  reach_.went_in = false;  // the cycle returns to its start
  pos_ = g.start;
  position_known_ = true;
}

}  // namespace clpc
