// The mill backend: tool changes with length offsets, work offsets, rapid/feed moves and
// arcs in G17/G18/G19 for a machine whose spindle is along Z.
#include "backends/mill.h"
#include "machine/block_check.h"

#include "machine/arc_center.h"
#include "ir/arc_geometry.h"

#include <cmath>

#include "support/text.h"

namespace clpc {

namespace {
constexpr double kAxisTol = 1e-6;
}

MillBackend::MillBackend(const Machine& m, OutputFile& out, Diagnostics& d) : ProgramWriter(m, out, d) {}

void MillBackend::write_tool_change(const ir::ToolChange& t, SourceLoc loc) {
  const int offset = t.length_offset > 0 ? t.length_offset : t.tool;
  if (t.tool == tool_) {
    // Already in the spindle: no M06. A reload that names another length register (one tool,
    // two offsets) retracts and brings Z back down with the new H, as after a tool change.
    if (offset == length_offset_) return;
    // With no G43 the register has no block to go in: the change was dropped, certified
    // (helper-65). (A tool change's {offset} is written only when the tool changes.)
    if (m_.codes.length_offset.empty())
      d_.error(loc, "machine '" + m_.name + "' has no length offset (codes.length_offset): the change of tool " +
                        std::to_string(t.tool) + "'s offset from " + std::to_string(length_offset_) + " to " +
                        std::to_string(offset) + " cannot be written");
    retract(loc);
    length_offset_ = offset;
    need_length_offset_ = !m_.codes.length_offset.empty() && !tcp_on_;
    return;
  }
  if (!tool_changer_for(t, loc)) return;
  // No G43 and no offset in the tool change: every tool would cut at the first one's length
  // (a machine with codes.length_offset = "" certified T2 plunging at T1's Z; helper-62). A
  // control that applies the length with the tool (Siemens' D) says so with {offset}.
  if (tool_ >= 0 && m_.codes.length_offset.empty() && !m_.codes.tool_change.uses(Var::Offset))
    d_.error(loc, "machine '" + m_.name + "' has no length offset (codes.length_offset) and its tool change (" +
                      m_.codes.tool_change.text + ") selects none: tool " + std::to_string(t.tool) +
                      " would cut at tool " + std::to_string(tool_) + "'s length; give codes.length_offset (G43 "
                      "H{offset}), or {offset} in codes.tool_change where the control applies the length with it");
  const bool had_tool = tool_ >= 0;
  if (had_tool) retract(loc);
  before_tool_change(loc);
  const ir::ToolInfo* info = info_ ? info_->tool(t.tool) : nullptr;
  e_.begin(loc);
  length_offset_ = offset;
  // (A tool change that moves, "G53 G00 X-500. Y0. Z0. T{tool} M06", after the retract's G91:
  // in G90, where G53 is read; helper-74.)
  if (!axis_words(m_.codes.tool_change.text).empty() && !sets_distance_mode(m_.codes.tool_change)) absolute_code();
  e_.code(m_.codes.tool_change, TemplateVars().with(Var::Tool, t.tool).with(Var::Offset, length_offset_));
  if (info) e_.trailing_comment(tool_comment(*info));
  e_.end(true);
  after_template(m_.codes.tool_change);
  tool_ = t.tool;
  need_length_offset_ = !m_.codes.length_offset.empty();
  need_work_offset_ = true;
  motion_ = Motion::None;
  e_.forget_linear();
  feed_written_ = false;
  // M06 stops the spindle. After another tool's, the coolant is said again too (before the
  // tool's first move), so that each tool's blocks hold it: a restart at this tool's T word ran
  // the tool dry (helper-70).
  control_stopped(had_tool, true);
  rotaries_unsaid_ = had_tool && m_.kinematics.has_rotaries();
  after_tool_change(t.tool, loc);
}

void MillBackend::retract(SourceLoc loc) {
  blocks({m_.codes.safe_retract}, loc);
  at_safe_height_ = true;
  left_in_cut_ = false;
}

void MillBackend::moved() {
  position_known_ = true;
  at_safe_height_ = false;
  after_raw_move_ = false;
  moved_since_off_ = true;
}

std::pair<const CodeTemplate*, TemplateVars> MillBackend::offset_select(int index) const {
  int standard = m_.offsets.standard_last - m_.offsets.standard_first + 1;
  if (index <= standard) return {&m_.codes.work_offset, TemplateVars().with(Var::Number, m_.offsets.standard_first + index - 1)};
  return {&m_.codes.work_offset_extended, TemplateVars().with(Var::Number, index - standard)};
}

void MillBackend::work_offset_code() {
  if (!need_work_offset_) return;
  auto [code, vars] = offset_select(work_offset_ > 0 ? work_offset_ : m_.offsets.default_index);
  e_.code(*code, vars);
  need_work_offset_ = false;
}

void MillBackend::motion_code(Motion mo) {
  if (m_.modal.motion && motion_ == mo) return;
  const Codes& c = m_.codes;
  e_.code(mo == Motion::Rapid ? c.rapid : mo == Motion::Linear ? c.linear : mo == Motion::Cw ? c.arc_cw : c.arc_ccw);
  motion_ = mo;
}

bool MillBackend::check_axis(const ir::Vec3& axis, SourceLoc loc) {
  if (m_.kinematics.has_rotaries()) {
    // G41/G42 offset in the XY plane of the coordinates the program is in: square to the tool
    // only where the tool is along their Z. Under TCPC they are the part's, with the tool
    // tilted in them; a head that tilts the tool leaves it tilted in the machine's. (A table
    // turned under the tool, or a tilted plane, leaves it along Z.) The block that cancels
    // compensation (G40) ends it, and may tilt.
    const bool cancels = comp_pending_set_ && comp_pending_.side == ir::CompSide::Off;
    const bool comp = !cancels && (comp_on_ || comp_pending_set_);
    if (comp && std::abs(axis.z()) < 1 - 1e-9) {
      if (comp_tilt_said_) return false;  // said once: the rest of it is the same error
      comp_tilt_said_ = true;
      d_.error(loc, std::string("cutter compensation (CUTCOM) with the tool tilted ") +
                        (tcp_on_ ? "under TCPC: G41/G42 offset in the part's XY plane"
                                 : "by the head: G41/G42 offset in the machine's XY plane") +
                        ", which is not square to the tool, so the cutter would be offset wrong; have the CAM system "
                        "write the compensated path (no CUTCOM), or cut the face in a tilted frame (3+2 on a table, "
                        "kinematics.indexed \"dwo\" or \"plane\")");
      return false;
    }
    return true;  // the kinematics pass gave the rotary positions
  }
  if ((axis - ir::Vec3::UnitZ()).norm() <= kAxisTol) return true;
  d_.error(loc, "tool axis (" + num_text(axis.x()) + ", " + num_text(axis.y()) + ", " + num_text(axis.z()) +
                    ") is not the spindle axis, and machine '" + m_.name + "' has no rotary axes to tilt it");
  return false;
}

bool MillBackend::changed(char letter, double value) const {
  return !m_.modal.coordinates || e_.differs(letter, value);
}

// A rapid block in X Y (and the rotaries) with the work offset: the positioning before Z.
template <class RotaryWords>
void MillBackend::position_across(const Emitter::Rounded& x, const Emitter::Rounded& y, bool rotaries,
                                  const RotaryWords& rotary_words, SourceLoc loc) {
  e_.begin(loc);
  absolute_code();
  work_offset_code();
  motion_code(Motion::Rapid);
  e_.modal_word('X', x);
  e_.modal_word('Y', y);
  if (rotaries) rotary_words();
  e_.end();
}

void MillBackend::write_move(const ir::Move& mv, SourceLoc loc) {
  if (mv.kind == ir::MoveKind::From) {
    pos_ = mv.point;
    return;
  }
  say_rotaries(loc);
  if (!check_axis(mv.axis, loc)) return;
  if (mv.kind == ir::MoveKind::Feed && !tool_loaded_for_cut(loc)) return;
  if (m_.kinematics.has_rotaries() && !mv.has_rotary) {
    d_.error(loc, "internal: a move without rotary positions on a five-axis machine (is 'kinematics' in the pipeline?)");
    return;
  }
  if (reposition_rotaries_ && mv.has_rotary) {
    // Where the raw block left the tool: no retract of the post's own (the next move, from the
    // retract height, would be a long diagonal feed into the part).
    reposition_rotaries_ = false;
    turn_rotaries(mv.rotary, false, loc);
    clamp(loc);
  }
  const ir::Vec3 o = mv.point * k_;
  const bool rapid = mv.kind == ir::MoveKind::Rapid;
  // Every coordinate rounded once: for "has anything changed" and for the words.
  const Emitter::Rounded x = e_.round('X', o.x()), y = e_.round('Y', o.y()), z = e_.round('Z', o.z());
  Emitter::Rounded rot[2];
  bool rotates = false;
  const auto& rotaries = m_.kinematics.rotaries;
  if (mv.has_rotary)
    for (size_t i = 0; i < rotaries.size() && i < 2; ++i) {
      rot[i] = e_.round(rotaries[i].name[0], mv.rotary[i]);
      if (e_.differs(rotaries[i].name[0], rot[i])) rotates = true;
    }
  auto rotary_words = [&] {
    for (size_t i = 0; i < rotaries.size() && i < 2; ++i) e_.modal_word(rotaries[i].name[0], rot[i]);
  };
  if (rotates) unclamp(loc);
  if (!rapid && tool_ >= 0)
    warn_spindle_stopped(loc, "cutting move", !mv.has_rotary && mv.point.x() == pos_.x() && mv.point.y() == pos_.y() &&
                                                  mv.point.z() > pos_.z());

  if (rapid && after_raw_move_ && raw_z_only_ && tool_ >= 0 && !need_length_offset_ && mv.point.z() > pos_.z()) {
    // Up from the last CL point: along Z first, then across at that height (the rule of
    // rapid-split, from the last point the CL knows; the raw block may have left the tool low).
    e_.begin(loc);
    absolute_code();
    work_offset_code();
    motion_code(Motion::Rapid);
    e_.word('Z', o.z());
    e_.end();
    after_raw_move_ = false;
  }
  if (rapid && (need_length_offset_ || ((at_safe_height_ || after_raw_move_) && tool_ >= 0))) {
    // From the safe height (or where a raw block left the tool): position in X Y (and the
    // rotaries) with the work offset, then bring Z down (with the length offset after a tool
    // change).
    position_across(x, y, mv.has_rotary, rotary_words, loc);
    e_.begin(loc);
    if (need_length_offset_)
      e_.code(m_.codes.length_offset, TemplateVars().with(Var::Offset, length_offset_).with(Var::Tool, tool_));
    e_.word('Z', o.z());
    e_.end();
    need_length_offset_ = false;
    pos_ = mv.point;
    moved();
    left_in_cut_ = false;
    return;
  }

  if (!rapid && (need_length_offset_ || at_safe_height_ || (after_raw_move_ && raw_z_only_)) && tool_ >= 0 &&
      (e_.differs('X', x) || e_.differs('Y', y))) {
    // A cut from the safe height (a tool's first move, -Wapproach; after a retract of the
    // post's own, or a raw block that moves Z alone, G53 Z0.): over the point at rapid first,
    // then fed down along Z. Fed straight from up there it went diagonally down through
    // whatever stands between. (After a pallet change or a macro, where the tool stands is
    // not known even in Z: fed from there as the CL says.)
    position_across(x, y, mv.has_rotary, rotary_words, loc);
  }
  const bool modal = m_.modal.coordinates;
  const bool in_plane = e_.differs('X', x) || e_.differs('Y', y);
  bool any = !modal || in_plane || e_.differs('Z', z) || rotates;
  // A pending G41/G42 waits for a block that moves in the plane: on a move along Z alone the
  // control starts the offset during it, so the tool went sideways by the radius while it
  // plunged beside the wall; the plunge is made on the CL's point, the offset comes on with the
  // lead-in across (before an arc, the arc refuses it). A pending G40 waits likewise past a
  // retract (cancelled on it the tool was pulled onto the contour as it came up), but goes on a
  // plunge: the CL has the tool down there without the offset, and an arc after it, which
  // cannot carry G40, was cut still offset.
  if (!any && !need_work_offset_ && !need_length_offset_ && !incremental_) {
    pos_ = mv.point;
    return;  // the control is there already
  }
  e_.begin(loc);
  absolute_code();
  work_offset_code();
  // (A G40 that cancels nothing goes on the next move, as before.)
  // (Nor may compensation stay on through a move that tilts the tool: the G40 goes on it.)
  const bool cancel_here = comp_pending_set_ && comp_pending_.side == ir::CompSide::Off &&
                           (!comp_on_ || mv.point.z() < pos_.z() || rotates);
  if (in_plane || cancel_here) comp_code();
  if (need_length_offset_) {
    e_.code(m_.codes.length_offset, TemplateVars().with(Var::Offset, length_offset_).with(Var::Tool, tool_));
    need_length_offset_ = false;
  }
  if (!rapid && mv.inverse_time > 0) {
    inverse_time_words(mv, loc);
    motion_code(Motion::Linear);
  } else {
    if (!rapid) feed_mode_code();
    motion_code(rapid ? Motion::Rapid : Motion::Linear);
  }
  e_.modal_word('X', x);
  e_.modal_word('Y', y);
  e_.modal_word('Z', z);
  if (mv.has_rotary) rotary_words();
  if (!rapid) {
    if (mv.inverse_time > 0) {
      write_feed(mv.inverse_time, ir::FeedMode::InverseTime, loc);
    } else if (mv.combined_feed > 0) {
      // This block's own F (degrees per minute); the next ordinary block writes its feed again.
      // Above max_feed (a rotary turning fast near the pole) the control holds it there: F
      // says so rather than a number of seven digits, and the slower cut is said, as any.
      if (m_.max_feed > 0 && mv.combined_feed > m_.max_feed * (1 + 1e-9) && !(loc == feed_clamp_said_)) {
        d_.warning(loc, "the rotaries turn too fast for the CL's feed here: F over all the axes would be " +
                            num_text(std::round(mv.combined_feed)) + ", above machine '" + m_.name + "''s max_feed " +
                            num_text(std::round(m_.max_feed * 1e4) / 1e4) + ": written as max_feed, slower than the CL asks",
                   "feed-clamped");
        feed_clamp_said_ = loc;
      }
      write_feed(m_.max_feed > 0 ? std::min(mv.combined_feed, m_.max_feed) : mv.combined_feed, ir::FeedMode::PerMinute, loc);
      feed_written_ = false;
    } else {
      feed_word(loc);
    }
  }
  e_.end();
  // Clear of the wall after a rapid (the CAM system's rapids are in the air) or a feed straight
  // up the tool axis (the retract).
  // (Within an increment of the axes: a CL's 4-decimal point after an intersection is a few
  // 1e-5 off its arc's end; helper-72.)
  const ir::Vec3 step = mv.point - pos_;
  const double up = step.dot(mv.axis);
  const double increment = std::abs(dequantize(1, m_.format('X'))) / k_;
  left_in_cut_ = !rapid && !(up > 0 && (step - up * mv.axis).norm() <= increment);
  pos_ = mv.point;
  moved();
}

// G93 for this block (F follows the coordinates); the next ordinary feed switches back.
void MillBackend::inverse_time_words(const ir::Move& m, SourceLoc loc) {
  if (m_.codes.inverse_time.empty()) {
    d_.error(loc, "machine '" + m_.name + "' has no inverse-time feed code (codes.inverse_time)");
    return;
  }
  if (!feed_mode_known_ || written_feed_mode_ != ir::FeedMode::InverseTime) {
    e_.code(m_.codes.inverse_time);
    written_feed_mode_ = ir::FeedMode::InverseTime;
    feed_mode_known_ = true;
    feed_written_ = false;
  }
}

void MillBackend::rotary_words(const std::array<double, 2>& a, bool modal) {
  const auto& r = m_.kinematics.rotaries;
  for (size_t i = 0; i < r.size(); ++i) {
    char l = r[i].name[0];
    if (modal) e_.modal_word(l, a[i]);
    else e_.word(l, a[i]);
  }
}

void MillBackend::unclamp(SourceLoc loc) {
  if (!clamped_) return;
  e_.begin(loc);
  for (const RotaryAxis& r : m_.kinematics.rotaries)
    if (!r.unclamp.empty()) e_.text(r.unclamp);
  e_.end();
  clamped_ = false;
}

void MillBackend::clamp(SourceLoc loc) {
  if (clamped_) return;
  e_.begin(loc);
  for (const RotaryAxis& r : m_.kinematics.rotaries)
    if (!r.clamp.empty()) e_.text(r.clamp);
  if (!e_.block_empty()) {
    e_.end();
    clamped_ = true;
  }
}

// 3+2: the rotaries go to their angles in a rapid of their own, then clamp.
void MillBackend::write_rotary_position(const ir::RotaryPosition& r, SourceLoc loc) {
  if (r.rename) {
    // codes.unwind: the axis's position renamed by whole turns, without motion.
    for (size_t i = 0; i < m_.kinematics.rotaries.size(); ++i) {
      char l = m_.kinematics.rotaries[i].name[0];
      if (!e_.differs(l, r.rotary[i])) continue;
      e_.begin(loc);
      e_.code(m_.codes.unwind, TemplateVars().with(Var::Angle, r.rotary[i]));
      e_.end();
      after_template(m_.codes.unwind);
      e_.forget(l);
    }
    return;
  }
  bool moves = false;
  for (size_t i = 0; i < m_.kinematics.rotaries.size(); ++i) {
    char l = m_.kinematics.rotaries[i].name[0];
    if (e_.differs(l, r.rotary[i])) moves = true;
  }
  if (moves || rotaries_unsaid_) {
    // Turning the table for the next orientation with the tool down at the part is how
    // fixtures get hit: retract first (a rotation within a path, clamp = false, has its own).
    if (moves && r.clamp && !at_safe_height_ && tool_ >= 0) retract(loc);
    turn_rotaries(r.rotary, !rotaries_unsaid_, loc);
    rotaries_unsaid_ = false;
  }
  if (r.clamp) clamp(loc);
}

// After another tool's change every rotary is said again with the first block that turns one
// (the next 3+2 position), or where it stands, unclamped and clamped again as it was, before
// the tool's first mode or move: an operator who restarts at this tool's T word (the table
// homed after a broken tool) had the next 3+2 face cut at B0, or a five-axis entry made
// untilted; no axis moves in a run from the start (helper-70).
void MillBackend::say_rotaries(SourceLoc loc) {
  if (!rotaries_unsaid_) return;
  rotaries_unsaid_ = false;
  const auto& r = m_.kinematics.rotaries;
  std::array<double, 2> angles{0, 0};
  for (size_t i = 0; i < r.size() && i < angles.size(); ++i)
    if (!e_.last(r[i].name[0], angles[i])) return;  // never written: nothing to say
  const bool was_clamped = clamped_;
  turn_rotaries(angles, false, loc);
  if (was_clamped) clamp(loc);
}

// The rotaries unclamped and turned in a rapid of their own (`modal`: only the words that change).
void MillBackend::turn_rotaries(const std::array<double, 2>& angles, bool modal, SourceLoc loc) {
  unclamp(loc);
  e_.begin(loc);
  absolute_code();
  motion_code(Motion::Rapid);
  rotary_words(angles, modal);
  e_.end();
}

void MillBackend::write_mode(const ir::MachineMode& m, SourceLoc loc) {
  if (m.kind == ir::ModeKind::TcpOn && rotaries_unsaid_) {
    // Simultaneous motion next: its first move says every rotary (they are forgotten), not a
    // turn to where they stand that it would undo (helper-73).
    rotaries_unsaid_ = false;
    for (const RotaryAxis& r : m_.kinematics.rotaries) e_.forget(r.name[0]);
  }
  say_rotaries(loc);
  const Codes& k = m_.codes;
  switch (m.kind) {
    case ir::ModeKind::TcpOn:
      if (k.tcp_on.empty()) {
        d_.error(loc, "machine '" + m_.name + "' has no tool centre point control code (codes.tcp_on)");
        return;
      }
      e_.begin(loc);
      absolute_code();
      work_offset_code();
      e_.code(k.tcp_on, TemplateVars().with(Var::Offset, length_offset_).with(Var::Tool, tool_));
      e_.end();
      after_template(k.tcp_on);
      need_length_offset_ = false;  // TCPC takes the length offset with it
      tcp_on_ = true;
      break;
    case ir::ModeKind::TcpOff:
      e_.begin(loc);
      e_.code(k.tcp_off);
      e_.end();
      after_template(k.tcp_off);
      tcp_on_ = false;
      need_length_offset_ = tool_ >= 0 && !k.length_offset.empty();
      break;
    case ir::ModeKind::DwoOn:
    case ir::ModeKind::DwoOff: {
      const CodeTemplate& t = m.kind == ir::ModeKind::DwoOn ? k.dwo_on : k.dwo_off;
      if (t.empty()) {
        d_.error(loc, "machine '" + m_.name + "' has no dynamic work offset codes (codes.dwo_on, dwo_off)");
        return;
      }
      e_.begin(loc);
      if (m.kind == ir::ModeKind::DwoOn) work_offset_code();  // the offset G254 turns with the table
      e_.code(t);
      e_.end();
      after_template(t);
      break;
    }
    case ir::ModeKind::PlaneOn: {
      // The plane about the part zero, then (where the control turns the rotaries to it) the
      // orientation block.
      // The plane is set in the work offset in force: that first, in a block of its own (a
      // control may take G68.2 only alone).
      e_.begin(loc);
      work_offset_code();
      e_.end();
      e_.begin(loc);
      e_.code(k.plane_on, TemplateVars()
                              .with(Var::X, 0)
                              .with(Var::Y, 0)
                              .with(Var::Z, 0)
                              .with(Var::I, m.angles.x())
                              .with(Var::J, m.angles.y())
                              .with(Var::K, m.angles.z()));
      e_.end();
      after_template(k.plane_on);
      if (!k.plane_orient.empty()) {
        e_.begin(loc);
        e_.code(k.plane_orient);
        e_.end();
        after_template(k.plane_orient);
      }
      break;
    }
    case ir::ModeKind::PlaneOff:
      e_.begin(loc);
      e_.code(k.plane_off);
      e_.end();
      after_template(k.plane_off);
      break;
  }
}

void MillBackend::write_arc(const ir::Operation& op, const ir::Arc& a, SourceLoc loc) {
  say_rotaries(loc);
  if (!check_axis(a.tool_axis, loc)) return;
  if (!tool_loaded_for_cut(loc)) return;
  warn_spindle_stopped(loc, "arc");
  if (a.dir == ir::ArcDir::Unknown) {
    d_.error(loc, "internal: arc direction not decided (is 'arc-direction' in the machine's pipeline?)");
    return;
  }
  if (a.extra_turns > 0) {
    d_.error(loc, "internal: multi-turn arc reached the backend (is 'helix' in the machine's pipeline?)");
    return;
  }
  if (!position_known_) {
    d_.error(loc, "arc with no programmed start position before it");
    return;
  }
  if (comp_pending_set_ && comp_pending_.side != ir::CompSide::Off) {
    // Written on the line after, the compensation came on a move later than the CL asks: the
    // arc was cut on the tool's centre where the CL offsets it. (G40 after an arc is written on
    // the next line: the arc keeps the offset it had, RapidSplit.NotTheMoveThatCarriesG40AfterAnArc.)
    d_.error(loc, "cutter compensation (CUTCOM) starts on an arc: the control starts G41/G42 only on a straight move "
                  "(G00/G01), and clpc only on one across the tool axis (not on a plunge); have the CAM system turn "
                  "it on before a line across (a lead-in)");
    comp_pending_set_ = false;
    return;
  }
  if (comp_pending_set_ && comp_on_ && moved_since_off_) {
    // The G40 waited past a retract (on it, the control would have pulled the tool sideways by
    // the radius) for a straight move across; an arc cannot carry it, and cut still offset it
    // is not the CL's arc (certified).
    d_.error(loc, "cutter compensation is to end (CUTCOM/OFF) before this arc, with only a move along the tool axis "
                  "between: the control ends G41/G42 only on a straight move, and clpc only on one across the tool "
                  "axis or down it (on a retract it would pull the tool sideways by the radius); have the CAM system "
                  "end it on a line across (a lead-out)");
    return;
  }
  // Plane from the arc axis: G17 (axis Z), G18 (axis Y), G19 (axis X).
  struct P {
    Plane plane;
    int u, v, w;  // in-plane axes (u, v) and the linear axis w, as indices 0..2
    char cu, cv;  // centre letters
  };
  static const char kAxisLetter[] = {'X', 'Y', 'Z'};
  P p;
  ir::Vec3 normal;
  if (std::abs(a.axis.z()) > 1 - 1e-9) p = {Plane::XY, 0, 1, 2, 'I', 'J'}, normal = ir::Vec3::UnitZ();
  else if (std::abs(a.axis.y()) > 1 - 1e-9) p = {Plane::ZX, 2, 0, 1, 'K', 'I'}, normal = ir::Vec3::UnitY();
  else if (std::abs(a.axis.x()) > 1 - 1e-9) p = {Plane::YZ, 1, 2, 0, 'J', 'K'}, normal = ir::Vec3::UnitX();
  else {
    d_.error(loc, "internal: arc outside the XY, ZX and YZ planes reached the backend (is 'arc-legalise' in the pipeline?)");
    return;
  }
  bool ok_plane = p.plane == Plane::XY ? m_.arcs.xy : p.plane == Plane::ZX ? m_.arcs.zx : m_.arcs.yz;
  if (!ok_plane) {
    d_.error(loc, "internal: machine '" + m_.name + "' has no arcs in this plane (is 'arc-legalise' in the pipeline?)");
    return;
  }
  const bool ccw = (a.dir == ir::ArcDir::Ccw) == (a.axis.dot(normal) > 0);

  // The control's start point is what it was given: the rounded last position.
  ir::Vec3 s_out = pos_ * k_;
  for (int i = 0; i < 3; ++i) {
    double last;
    if (e_.last(kAxisLetter[i], last)) s_out[i] = last;
  }
  ir::Vec3 e_raw = a.end * k_, c_raw = a.center * k_;
  ir::Vec3 e_out = e_raw;
  for (int i = 0; i < 3; ++i) e_out[i] = e_.as_written(kAxisLetter[i], e_raw[i]);
  double su = s_out[p.u], sv = s_out[p.v], eu = e_out[p.u], ev = e_out[p.v];
  double len = std::hypot(eu - su, ev - sv);
  ir::Vec3 mid = arcgeo::point_at(a, 0.5) * k_;
  // (u, v) is right-handed about the plane normal in all three planes (X-Y, Z-X, Y-Z).
  ArcCenterInput ci{su, sv, eu, ev, c_raw[p.u], c_raw[p.v], mid[p.u], mid[p.v], ccw, a.sweep >= 360 - 1e-9};
  ArcCenterChoice ctr = choose_arc_center(ci, m_.format(p.cu), m_.format(p.cv), m_.arcs.center == ArcCenter::Incremental);
  double cu = ctr.cu, cv = ctr.cv;

  e_.begin(loc);
  absolute_code();
  work_offset_code();
  if (plane_ != p.plane) {
    e_.code(p.plane == Plane::XY ? m_.codes.plane_xy : p.plane == Plane::ZX ? m_.codes.plane_zx : m_.codes.plane_yz);
    plane_ = p.plane;
    off_xy_plane_ = p.plane != Plane::XY;
  }
  feed_mode_code();
  motion_code(ccw ? Motion::Ccw : Motion::Cw);
  e_.modal_word('X', e_raw.x());
  e_.modal_word('Y', e_raw.y());
  e_.modal_word('Z', e_raw.z());
  if (m_.arcs.center == ArcCenter::Radius) {
    double r = std::hypot(cu - su, cv - sv);
    if (len < 1e-12) {
      d_.error(loc, "internal: full circle in R format (is 'arc-legalise' in the pipeline?)");
      return;
    }
    e_.word('R', a.sweep > 180 ? -r : r);
  } else if (m_.arcs.center == ArcCenter::Absolute) {
    e_.word(p.cu, cu);
    e_.word(p.cv, cv);
  } else {
    e_.word(p.cu, cu - su);
    e_.word(p.cv, cv - sv);
  }
  feed_word(loc);
  e_.end();
  pos_ = a.end;
  left_in_cut_ = true;
  (void)op;
}

void MillBackend::cancel_cycle(SourceLoc loc) {
  if (!cycle_active_) return;
  e_.begin(loc);
  e_.code(m_.codes.cycle_cancel);
  e_.end();
  cycle_active_ = false;
  motion_ = Motion::None;  // write G00/G01 again after the cycle
}

void MillBackend::write_hole(const ir::Operation& op, const ir::Hole& h, SourceLoc loc) {
  say_rotaries(loc);
  const ir::CycleSpec& c = op.cycles.at(h.spec);
  if (!check_axis(h.axis, loc)) return;
  if (!tool_loaded_for_cut(loc)) return;
  // A drill fed into the part without turning breaks: no reading of the CL makes this safe.
  if (spindle_ == ir::SpindleDir::Off) {
    d_.error(loc, "a hole drilled with the spindle stopped (no SPINDL since the tool change, or SPINDL/OFF): the tool "
                  "would be fed into the part without turning");
    return;
  }
  const Codes& k = m_.codes;
  const CodeTemplate* code = nullptr;
  switch (c.kind) {
    case ir::CycleKind::Drill: code = &k.cycle_drill; break;
    case ir::CycleKind::SpotDwell: code = &k.cycle_dwell; break;
    case ir::CycleKind::Peck: code = &k.cycle_peck; break;
    case ir::CycleKind::ChipBreak: code = &k.cycle_chip_break; break;
    case ir::CycleKind::Tap: code = c.left_hand ? &k.cycle_tap_left : &k.cycle_tap; break;
    case ir::CycleKind::Bore: code = &k.cycle_bore; break;
    case ir::CycleKind::BoreDwell: code = &k.cycle_bore_dwell; break;
    case ir::CycleKind::BoreStop: code = &k.cycle_bore_stop; break;
    case ir::CycleKind::FineBore: code = &k.cycle_fine_bore; break;
    case ir::CycleKind::BackBore: code = &k.cycle_back_bore; break;
  }
  const ir::Vec3 o = h.point * k_;
  ActiveCycle want;
  want.code = code;
  want.top = o.z();
  want.bottom = o.z() - c.depth * k_;
  want.r = o.z() + c.clearance * k_;
  want.peck = c.kind == ir::CycleKind::Peck || c.kind == ir::CycleKind::ChipBreak ? c.peck * k_ : 0;
  want.dwell = c.kind == ir::CycleKind::SpotDwell || c.kind == ir::CycleKind::BoreDwell ? c.dwell : 0;
  want.left_hand = c.left_hand;
  bool tap = c.kind == ir::CycleKind::Tap;
  ir::FeedMode mode = c.feed > 0 ? c.feed_mode : feed_mode_;
  if (tap) {
    mode = m_.cycles.tap_per_rev ? ir::FeedMode::PerRev : ir::FeedMode::PerMinute;
    if (!m_.cycles.tap_per_rev && !(spindle_rpm_ > 0)) {
      d_.error(loc, "tapping needs the spindle speed (SPINDL/RPM) to set the feed: F = pitch x S");
      return;
    }
    // F from the S as written: a tap at S333.4 was fed for it at S333 (Creo writes speeds with
    // fractions), 0.1 % off its pitch, and refused by verify (helper-71).
    want.feed = m_.cycles.tap_per_rev ? c.pitch * k_ : c.pitch * k_ * e_.as_written('S', spindle_rpm_);
  } else if (c.feed > 0) {
    want.feed = c.feed * k_;
  } else if (feed_known_) {
    want.feed = feed_ * k_;
  } else {
    d_.error(loc, "drilling with no feed rate: no FEDRAT and none in the CYCLE record");
    return;
  }
  // A drilling feed above the machine's limit is written at the limit, as a move's is (and as
  // verify reads it); a tap's cannot be (write_tap_feed refuses it).
  if (!tap && mode == ir::FeedMode::PerMinute && m_.max_feed > 0 && want.feed > m_.max_feed) {
    if (!(cycle_active_ && cycle_.feed == m_.max_feed))  // once for the holes of a cycle
      d_.warning(loc, "feed " + num_text(std::round(want.feed * 1e4) / 1e4) + " is above machine '" + m_.name + "''s max_feed " + num_text(std::round(m_.max_feed * 1e4) / 1e4) +
                        ": written as " + num_text(std::round(m_.max_feed * 1e4) / 1e4) + ", slower than the CL asks",
               "feed-clamped");
    want.feed = m_.max_feed;
  }
  if (!tap && mode == ir::FeedMode::PerRev && m_.max_feed > 0 && spindle_rpm_ > 0 &&
      want.feed * spindle_rpm_ > m_.max_feed * (1 + 1e-9) && !(cycle_active_ && cycle_.feed == want.feed)) {
    const std::string unit = m_.units == ir::Units::Inch ? " in" : " mm";
    d_.warning(loc, "feed " + num_text(want.feed) + unit + "/rev at " + num_text(spindle_rpm_) + " rpm is " +
                        num_text(std::round(want.feed * spindle_rpm_ * 1e4) / 1e4) + unit + "/min, above machine '" + m_.name +
                        "''s max_feed " + num_text(std::round(m_.max_feed * 1e4) / 1e4) +
                        ": the control drills it slower than the CL asks",
               "feed-clamped");
  }
  double ret = m_.cycles.return_initial ? std::max(h.initial, c.clearance) : c.clearance;
  bool same = cycle_active_ && !need_work_offset_ && cycle_.code == want.code && e_.as_written('Z', cycle_.bottom) == e_.as_written('Z', want.bottom) &&
              e_.as_written('R', cycle_.r) == e_.as_written('R', want.r) && cycle_.peck == want.peck &&
              cycle_.dwell == want.dwell && cycle_.feed == want.feed;
  if (at_safe_height_ && tool_ >= 0) {
    // From the post's retract (another fixture's offset, a stop): over the hole, then down to
    // where the CL starts the cycle, its G98 level. From up there the cycle went down at the
    // home height's XY, and returned up there.
    if (cycle_active_) cancel_cycle(loc);
    same = false;
    position_across(e_.round('X', o.x()), e_.round('Y', o.y()), false, [] {}, loc);
    e_.begin(loc);
    if (need_length_offset_) {
      e_.code(m_.codes.length_offset, TemplateVars().with(Var::Offset, length_offset_).with(Var::Tool, tool_));
      need_length_offset_ = false;
    }
    e_.word('Z', o.z() + h.initial * k_);
    e_.end();
    at_safe_height_ = false;
  }
  if (!same) {
    if (cycle_active_) cancel_cycle(loc);
    if (tap && !k.rigid_tap.empty()) {
      e_.begin(loc);
      e_.code(k.rigid_tap, TemplateVars().with(Var::Speed, spindle_rpm_));
      e_.end();
    }
    e_.begin(loc);
    absolute_code();
    work_offset_code();
    if (need_length_offset_) {
      e_.code(m_.codes.length_offset, TemplateVars().with(Var::Offset, length_offset_).with(Var::Tool, tool_));
      need_length_offset_ = false;
    }
    xy_plane_code();  // the drilling axis is the one square to the plane
    feed_mode_code(mode);
    e_.code(m_.cycles.return_initial ? k.cycle_return_initial : k.cycle_return_r);
    e_.code(*code);
    e_.word('X', o.x());
    e_.word('Y', o.y());
    e_.word('Z', want.bottom);
    e_.word('R', want.r);
    if (want.peck > 0) {
      // Q0 would be an alarm (or an endless cycle): a peck must survive the rounding.
      if (e_.round('Q', want.peck).q == 0)
        d_.error(loc, "the peck depth " + num_text(want.peck) + " rounds to Q0 at machine '" + m_.name + "''s resolution");
      e_.word('Q', want.peck);
    }
    // The fine bore's shift off the wall before it rapids out (Q, modal on Fanuc: left out, the
    // last one's or none, and the bar scores the finished bore).
    if (c.kind == ir::CycleKind::FineBore) e_.word('Q', c.shift * k_);
    if (want.dwell > 0)
      e_.code(k.cycle_dwell_word, TemplateVars().with(Var::Seconds, want.dwell).with(Var::Milliseconds, want.dwell * 1000));
    if (tap ? !write_tap_feed(want.feed, c.pitch * k_, e_.as_written('S', spindle_rpm_), c.depth * k_, loc)
            : !write_feed(want.feed, mode, c.feed > 0 || !feed_loc_.valid() ? loc : feed_loc_))
      return;
    e_.end();
    cycle_ = want;
    cycle_active_ = true;
    feed_written_ = false;  // F in a cycle block holds the cycle's feed
  } else {
    bool xy = changed('X', o.x()) || changed('Y', o.y());
    if (!xy) return;  // the same hole again
    e_.begin(loc);
    e_.modal_word('X', o.x());
    e_.modal_word('Y', o.y());
    e_.end();
  }
  e_.set_last('X', o.x());
  e_.set_last('Y', o.y());
  e_.set_last('Z', o.z() + ret * k_);
  pos_ = h.point + h.axis * ret;
  moved();
  left_in_cut_ = false;
}

}  // namespace clpc
