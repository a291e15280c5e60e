// Lathe threading (docs/lathe.md): the moves of a THREAD section as G32, and the cycles the
// thread-cycles pass proved (G92 per pass, G76 for all passes), with the spindle at a fixed
// speed (G97) while the thread is cut: a thread's passes must all run at one speed.
#include <cmath>
#include <cstdio>

#include "backends/lathe.h"
#include "machine/format.h"
#include "support/text.h"

namespace clpc {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

bool LatheBackend::is_thread_cut(const ir::Vec3& from, const ir::Vec3& to) const {
  const double dx = std::abs(to.x() - from.x()), dz = std::abs(to.z() - from.z());
  if (thread_->kind == ir::ThreadKind::Face) return dx > 1e-9 && dz < dx;
  return dz > 1e-9 && dx < dz;
}

double LatheBackend::thread_lead(SourceLoc loc) const {
  if (thread_ && thread_->lead > 0) return thread_->lead;
  if (feed_known_ && feed_mode_ == ir::FeedMode::PerRev && feed_ > 0) return feed_;
  d_.error(loc, "thread cut with no lead: give it in the THREAD record (THREAD/TURN,lead) or as a feed per revolution");
  return 0;
}

// F is the lead; its rounding accumulates turn by turn: refused where the thread's end would
// be off by more than the path tolerance clpc allows itself (arcs.tolerance, the chord error)
// and half an increment. Every pass starts at the spindle's index, so the error does not add
// up pass by pass: an inch thread on a metric control (13 TPI written F1.9538) ends 0.0006 mm
// off over 25 mm, as on any post; a longer one or a coarser format is refused.
bool LatheBackend::write_lead(double lead, double length, SourceLoc loc) {
  const AddressFormat& f = m_.feeds.lead;
  const double value = lead * k_;
  int64_t q;
  if (!quantize(value, f, q)) {
    d_.error(loc, "thread lead out of range: " + num_text(value));
    return false;
  }
  const double written = dequantize(q, f);
  const double drift = std::abs(written - value) * (length * k_) / value;
  const double increment = std::abs(dequantize(1, m_.format('Z')));
  if (q == 0 || drift >= std::max(0.5 * increment, m_.arcs.tolerance)) {
    std::string text;
    append_quantized(q, f, text);
    if (lead_refused_) return false;  // once per THREAD
    lead_refused_ = true;
    d_.error(thread_loc_, "the thread's lead of " + num_text(std::round(value * 1e9) / 1e9) + (m_.units == ir::Units::Inch ? " in" : " mm") +
                      " would be written F" + text + " (feeds.lead: " + std::to_string(f.decimals) +
                      (f.decimals == 1 ? " decimal" : " decimals") + "): the thread would end " +
                      num_text(std::round(drift * 1e6) / 1e6) + " off; give feeds.lead more decimals");
    return false;
  }
  e_.argument('F', value, f);
  feed_written_ = false;  // F now holds the lead: the next cutting move writes its feed again
  return true;
}

// Under constant surface speed the speed would change with the diameter between passes and
// the passes would not meet: the thread is cut at the speed the surface speed gives at its
// first cut's radius (within the clamp), and the surface speed comes back after THREAD/OFF.
void LatheBackend::fix_spindle_speed(double radius, SourceLoc loc) {
  if (!surface_ || rpm_fixed_ || spindle_ == ir::SpindleDir::Off) return;
  const double rpm = std::max(1.0, std::floor(surface_rpm(radius)));
  e_.begin(loc);
  e_.code(m_.codes.spindle_rpm_mode);
  e_.word('S', rpm);
  e_.code(spindle_ == ir::SpindleDir::Cw ? m_.codes.spindle_cw : m_.codes.spindle_ccw);
  e_.end();
  rpm_fixed_ = true;
  fixed_rpm_ = rpm;
}

// The rpm the control turns at under the surface speed in force, at `radius` (CL units), within
// its clamp.
double LatheBackend::surface_rpm(double radius) const {
  const double surface = m_.units == ir::Units::Inch ? surface_->speed / 0.3048 * 12 : surface_->speed * 1000;
  const double r = std::abs(radius * k_);
  double rpm = r > 1e-9 ? surface / (2 * kPi * r) : surface_clamp_;
  if (surface_clamp_ > 0 && rpm > surface_clamp_) rpm = surface_clamp_;
  return rpm;
}

// A dwell in revolutions under constant surface speed lasts as long as the spindle takes to
// make them at the speed the control holds where the tool stands (NX's groove-bottom dwell
// under SMM was refused; helper-54). Where the speed is fixed for a thread or a drill on
// centre, at that speed (it fell to the S of no SPINDL/RPM, 0, and was refused; helper-55).
double LatheBackend::dwell_rpm() const {
  if (surface_ && spindle_ != ir::SpindleDir::Off) return rpm_fixed_ ? fixed_rpm_ : surface_rpm(pos_.x());
  return ProgramWriter::dwell_rpm();
}

void LatheBackend::restore_surface_speed(SourceLoc loc) {
  if (!rpm_fixed_ || !surface_) return;
  rpm_fixed_ = false;
  const double speed = m_.units == ir::Units::Inch ? surface_->speed / 0.3048 : surface_->speed;
  e_.begin(loc);
  e_.code(m_.codes.spindle_css_mode);
  e_.word('S', speed);
  e_.code(spindle_ == ir::SpindleDir::Ccw ? m_.codes.spindle_ccw : m_.codes.spindle_cw);
  e_.end();
}

void LatheBackend::write_thread_mark(const ir::ThreadMark& t, SourceLoc loc) {
  end_drill_speed(loc);
  if (t.begin) {
    thread_ = t;
    thread_loc_ = loc;
    lead_refused_ = false;
    return;
  }
  thread_.reset();
  restore_surface_speed(loc);
}

void LatheBackend::write_thread_move(const ir::Move& mv, SourceLoc loc) {
  if (!tool_loaded_for_cut(loc)) return;
  if (m_.codes.thread.empty()) {
    d_.error(loc, "machine '" + m_.name + "' has no thread cutting code (codes.thread, e.g. G32)");
    return;
  }
  if (!position_known_) {
    d_.error(loc, "thread cut with no programmed start position before it");
    return;
  }
  const double lead = thread_lead(loc);
  if (!(lead > 0)) return;
  if (comp_pending_set_) {
    d_.error(loc, "tool nose radius compensation (CUTCOM) starts or ends on a thread cut: turn it on or off with a straight move");
    comp_pending_set_ = false;
    return;
  }
  fix_spindle_speed(pos_.x(), loc);
  const ir::Vec3 o = mv.point * k_;
  e_.begin(loc);
  absolute_code();
  e_.code(m_.codes.thread);
  e_.modal_word('X', o.x());
  e_.modal_word('Z', o.z());
  if (!write_lead(lead, (mv.point - pos_).norm(), loc)) return;
  e_.end();
  motion_ = Motion::None;  // G32 is a motion code of its own: the next G00/G01 is written
  note_cut_to(mv.point, loc);
  pos_ = mv.point;
}

void LatheBackend::write_thread_cycle(const ir::ThreadCycle& t, SourceLoc loc) {
  if (!tool_loaded_for_cut(loc)) return;
  end_drill_speed(loc);
  const CodeTemplate& code = t.multi ? m_.codes.thread_multi : m_.codes.thread_box;
  if (code.empty()) {
    d_.error(loc, "internal: machine '" + m_.name + "' has no " + (t.multi ? "G76" : "G92") + " code for a threading cycle");
    return;
  }
  if (!in_plane(t.start, loc) || !in_plane(t.end, loc)) return;
  const double crest = t.multi ? t.end.x() + (t.start.x() >= t.end.x() ? 1 : -1) * t.height : t.end.x();
  fix_spindle_speed(crest, loc);
  if (t.multi) {
    // G76 P(m)(r)(a) Q(Δdmin) R(d): m finishing passes, no chamfer, radial infeed (a = 0).
    char p[16];
    std::snprintf(p, sizeof p, "P%02d0000", t.finish_passes);
    e_.begin(loc);
    absolute_code();
    e_.code(code);
    e_.text(p);
    e_.word('Q', t.min_step * k_);
    e_.word('R', t.allowance * k_);
    e_.end();
  }
  e_.begin(loc);
  absolute_code();
  e_.code(code);
  e_.word('X', t.end.x() * k_);
  e_.word('Z', t.end.z() * k_);
  if (t.multi) {
    e_.word('P', t.height * k_);
    e_.word('Q', t.first_depth * k_);
  }
  if (!write_lead(t.lead, std::abs(t.end.z() - t.start.z()), loc)) return;
  e_.end();
  motion_ = Motion::None;
  // The cycle ends where it started.
  e_.set_last('X', t.start.x() * k_);
  e_.set_last('Z', t.start.z() * k_);
  note_cut(t.start, loc);
  note_cut(t.end, loc);
  reach_.went_in = false;  // the cycle returns to its start
  pos_ = t.start;
  position_known_ = true;
}

}  // namespace clpc
