// The lathe cycles' checks of verify's comparison (readback/comparison.h): a CYCLE/ROUGH
// section against the stock-removal cycle the program makes (ir/stock_model), a groove's
// cutting points on the program's path, a thread's cuts made at its lead by synchronised
// blocks. docs/lathe.md and docs/verify-and-plot.md give the rules.
#include "readback/comparison.h"

#include "support/text.h"

namespace clpc::verify_detail {

void Comparison::rough_arc(const ir::Arc& a0) {
  ir::Arc a = a0;
  a.start = model(a0.start);
  a.end = model(a0.end);
  a.center = model(a0.center);
  a.axis = model_dir(a0.axis);
  const ir::ArcDir dir = arc_sense(a);
  if (dir == ir::ArcDir::Unknown || std::abs(a.axis.y()) < 1 - 1e-9) {
    fail(loc_, 0, "a CYCLE/ROUGH profile's arc that turns about no Y axis, or whose sense verify cannot tell", kInf);
    return;
  }
  rough_profile_.push_back({stock::Step::Kind::Arc, a.end, a.center, (dir == ir::ArcDir::Ccw) == (a.axis.y() > 0), loc_});
}

void Comparison::end_rough() {
  const ir::RoughMark m = *rough_;
  rough_.reset();
  // The CL's numbers as the program can give them (the machine's formats; a number it cannot
  // write stays as it is, and the comparison finds the block that differs).
  auto written = [&](char letter, double v) {
    const double w = as_written(v, m_.format(letter));
    return w == w ? w : v;
  };
  Vec3 start = model(m.start);
  std::vector<stock::Element> profile;
  Vec3 p = start;
  for (const Want& w : rough_profile_) {
    profile.push_back({p, w.to, w.kind == stock::Step::Kind::Arc, w.center, w.ccw, 0});
    p = w.to;
  }
  stock::Params sp =
      stock::params_of(m, k_, !rough_profile_.empty() && rough_profile_.front().kind == stock::Step::Kind::Rapid);
  stock::round_as_written(sp, start, profile, written);
  for (size_t i = 0; i < profile.size(); ++i) {
    rough_profile_[i].to = profile[i].end;
    rough_profile_[i].center = profile[i].center;
  }
  const char* name = m.facing ? "G72" : "G71";
  std::string why;
  const std::vector<stock::Step> steps = stock::expand(start, profile, sp, why);
  if (steps.empty()) {
    fail(rough_loc_, 0, std::string("CYCLE/ROUGH: the control's ") + name + " cannot cut this profile: " + why, 0);
    skip_cycle_segments();
    return;
  }
  std::vector<Want> wants;
  for (const stock::Step& s : steps) wants.push_back({s.kind, s.to, s.center, s.ccw, rough_loc_});
  if (m.finish) {
    // G70 runs the profile as written: a move to where the tool already is writes no block.
    Vec3 here = start;
    for (const Want& w : rough_profile_) {
      if (w.kind != stock::Step::Kind::Arc && (w.to - here).norm() <= 1e-9) continue;
      wants.push_back(w);
      here = w.to;
    }
    wants.push_back({stock::Step::Kind::Rapid, start, Vec3::Zero(), false, loc_});
  }
  size_t j = 0;
  for (const Want& w : wants) {
    const TipSegment* s = peek(j);
    // The profile's named end (N(Q)) is a block of no length.
    while (s && s->raw.kind != gcode::Segment::Kind::Arc && (s->end - s->start).norm() <= 1e-9) s = peek(++j);
    ++rep_.cl_points;
    if (!s) {
      fail(w.loc, 0, std::string("the program ends before the ") + name + " cycle's move to " + xyz(w.to), kInf);
      return;
    }
    const bool arc = s->raw.kind == gcode::Segment::Kind::Arc;
    const bool kind_ok = (w.kind == stock::Step::Kind::Rapid) == (s->raw.kind == gcode::Segment::Kind::Rapid) &&
                         (w.kind == stock::Step::Kind::Arc) == arc &&
                         (!arc || (s->raw.normal == Vec3::UnitY() && s->raw.ccw == w.ccw));
    double dev = (s->end - w.to).norm();
    if (arc && w.kind == stock::Step::Kind::Arc) dev = std::max(dev, (s->center - w.center).norm());
    if (!kind_ok || !(dev <= tol_)) {
      auto what = [](bool rapid, bool is_arc) { return rapid ? "rapid" : is_arc ? "arc" : "feed"; };
      fail(w.loc, s->raw.line,
           std::string("the ") + name + " cycle's " + what(w.kind == stock::Step::Kind::Rapid, w.kind == stock::Step::Kind::Arc) +
               " to " + xyz(w.to) + " is, in the program, a " +
               what(s->raw.kind == gcode::Segment::Kind::Rapid, arc) + " to " + xyz(s->end),
           kind_ok ? dev : kInf);
      consume(j);
      skip_cycle_segments();
      return;
    }
    deviate(dev, w.loc, s->raw.line);
    ++j;
  }
  consume(j);
  prev_ = start;
  have_prev_ = true;
  incoming_ = Vec3::Zero();
}

void Comparison::skip_cycle_segments() {
  while (const TipSegment* s = peek(0)) {
    if (!s->raw.from_cycle) break;
    consume(1);
  }
}

void Comparison::begin_groove(const ir::GrooveSpec* record) {
  groove_ = true;
  groove_reach_ = 0;
  groove_record_ = record != nullptr;
  groove_face_ = record && record->face;
}

void Comparison::groove_point(const Vec3& p, bool rapid) {
  const Vec3 from = prev_;
  const bool have_from = have_prev_;
  prev_ = p;
  have_prev_ = true;
  if (rapid) return;
  ++rep_.cl_groove_points;
  // A CYCLE/FACE|RADIUS record asks for the control's cycle, which shifts at rapid along its
  // start level between plunges: a CL feed along the shift axis only may be made by such a
  // shift of the cycle. Anywhere else (Creo's GRV sections, plain motion) a feed stays a feed.
  const double plunge_from = groove_face_ ? from.z() : from.x(), plunge_to = groove_face_ ? p.z() : p.x();
  const bool shift = groove_record_ && have_from && std::abs(plunge_to - plunge_from) <= tol_;
  if (groove_cut(p, p, shift) && have_from && (p - from).norm() > 2 * tol_) groove_cut((from + p) / 2, p, shift);
}

bool Comparison::groove_cut(const Vec3& q, const Vec3& p, bool cycle_shift_ok, size_t from) {
  double best = kInf;
  size_t best_at = 0;
  int rapid_line = 0;  // a rapid through the cut, while no feed made it
  for (size_t j = from; j < kMaxLookahead; ++j) {
    const TipSegment* s = peek(j);
    if (!s) break;
    if (!finite(s->start) || !finite(s->end)) continue;
    double d = point_segment(q, s->start, s->end);
    if (s->raw.kind == gcode::Segment::Kind::Rapid) {
      const bool cycle_shift = cycle_shift_ok && s->raw.from_cycle &&
                               std::abs(groove_face_ ? s->end.z() - s->start.z() : s->end.x() - s->start.x()) <= tol_;
      if (d <= tol_ && cycle_shift) {
        best = d;
        best_at = j;
        break;
      }
      if (d <= tol_ && !rapid_line) rapid_line = s->raw.line;
      continue;
    }
    if (d < best) {
      best = d;
      best_at = j;
    }
    if (d <= tol_) break;
    // Past the groove's own motion: stop at the first feed that is not a cycle's.
    if (!s->raw.from_cycle && j > groove_reach_ + 64) break;
  }
  if (best <= tol_) {
    deviate(best, loc_, win_[best_at].raw.line);
    groove_reach_ = std::max(groove_reach_, best_at + 1);
    return true;
  }
  if (rapid_line) {
    fail(loc_, rapid_line, "groove cut to " + xyz(p) + " is made at rapid traverse (G00)", 0);
  } else {
    fail(loc_, std::isfinite(best) ? win_[best_at].raw.line : 0,
         "groove cut to " + xyz(p) + " is not made: the program's path passes " + fixed_text(best, 5) + " from " +
             (q == p ? "it" : "its middle"),
         best);
  }
  return false;
}

void Comparison::end_groove() {
  groove_ = false;
  consume(groove_reach_);
  groove_reach_ = 0;
  consume_rapids_to(prev_);
}

void Comparison::consume_rapids_to(const Vec3& p) {
  if (!have_prev_) return;
  for (size_t j = 0; j < 64; ++j) {
    const TipSegment* s = peek(j);
    if (!s || s->raw.kind != gcode::Segment::Kind::Rapid || !finite(s->end)) return;
    if ((s->end - p).norm() <= tol_) {
      consume(j + 1);
      return;
    }
  }
}

void Comparison::begin_thread(const ir::ThreadMark& t) {
  if (thread_on_) end_thread();
  thread_ = t;
  thread_on_ = true;
  groove_reach_ = 0;
  thread_cuts_.clear();
  thread_used_.clear();
  thread_next_ = 0;
}

bool Comparison::along_thread(const Vec3& from, const Vec3& to) const {
  const double dx = std::abs(to.x() - from.x()), dz = std::abs(to.z() - from.z());
  if (thread_.kind == ir::ThreadKind::Face) return dx > 1e-9 && dz < dx;
  return dz > 1e-9 && dx < dz;
}

void Comparison::thread_point(const Vec3& p, bool rapid) {
  const Vec3 from = prev_;
  const bool have_from = have_prev_;
  prev_ = p;
  have_prev_ = true;
  if (rapid) return;
  if (!have_from) return;
  if (!along_thread(from, p)) {
    if ((p - from).norm() <= tol_) return;  // no move
    // An infeed or pull-out at feed: on the path, like a groove's, after the pass before it
    // (passes pull out along the same line: the first pass's pull-out is not the last's).
    ++rep_.cl_groove_points;
    groove_cut(p, p, false, thread_next_);
    return;
  }
  ++rep_.cl_thread_cuts;
  double lead = thread_.lead * k_;
  if (!(lead > 0) && have_cl_feed_ && cl_feed_.mode == ir::FeedMode::PerRev) lead = cl_feed_.value * k_;
  thread_cuts_.push_back({from, p});
  thread_cut(from, p, lead);
}

void Comparison::thread_cut(const Vec3& from, const Vec3& p, double lead) {
  const Vec3 mid = (from + p) / 2;
  double best = kInf;
  size_t best_at = 0;
  bool best_used = true;
  int plain_line = 0;  // a block through the cut that is not synchronised
  for (size_t j = 0; j < kMaxLookahead; ++j) {
    const TipSegment* s = peek(j);
    if (!s) break;
    if (!finite(s->start) || !finite(s->end)) continue;
    const double d = std::max(point_segment(p, s->start, s->end), point_segment(mid, s->start, s->end));
    if (!s->raw.thread) {
      if (d <= tol_ && !plain_line && (s->end - s->start).norm() > tol_) plain_line = s->raw.line;
      if (!s->raw.from_cycle && j > groove_reach_ + 64) break;
      continue;
    }
    const bool used = j < thread_used_.size() && thread_used_[j];
    // The nearest; among those within the tolerance, the first not taken by another CL cut.
    if ((d <= tol_ && best <= tol_) ? (best_used && !used) : d < best) {
      best = d;
      best_at = j;
      best_used = used;
    }
    if (best <= tol_ && !best_used) break;
  }
  if (best <= tol_) {
    const TipSegment& s = win_[best_at];
    deviate(best, loc_, s.raw.line);
    groove_reach_ = std::max(groove_reach_, best_at + 1);
    if (thread_used_.size() <= best_at) thread_used_.resize(best_at + 1, false);
    thread_used_[best_at] = true;
    thread_next_ = std::max(thread_next_, best_at + 1);
    const double length = (p - from).norm();
    const double drift = lead > 0 ? std::abs(s.raw.feed - lead) * length / lead : kInf;
    if (drift > tol_)
      fail(loc_, s.raw.line, "thread cut to " + xyz(p) + " at a lead of F" + fixed_text(s.raw.feed, 6) + " where the CL's is " +
                                 fixed_text(lead, 6) + ": the thread ends " + fixed_text(drift, 5) + " off", drift);
    return;
  }
  if (plain_line) {
    fail(loc_, plain_line, "thread cut to " + xyz(p) + " is made by a block not synchronised with the spindle (not G32/G92/G76)", 0);
  } else {
    fail(loc_, std::isfinite(best) ? win_[best_at].raw.line : 0,
         "thread cut to " + xyz(p) + " is not made: the program's nearest thread cut passes " + fixed_text(best, 5) + " from it",
         best);
  }
}

void Comparison::end_thread() {
  thread_on_ = false;
  // A cycle block's passes go together: finishing passes at one depth all match the CL's
  // first, and the rest of the block is the cycle's too.
  int last_line = 0;
  for (size_t j = 0; j < groove_reach_; ++j)
    if (const TipSegment* s = peek(j); s && s->raw.from_cycle) last_line = std::max(last_line, s->raw.line);
  while (const TipSegment* s = peek(groove_reach_)) {
    if (!s->raw.from_cycle || s->raw.line > last_line) break;
    ++groove_reach_;
  }
  auto on_cl = [&](const Vec3& q) {
    double best = kInf;
    for (const auto& [a, b] : thread_cuts_) best = std::min(best, point_segment(q, a, b));
    return best;
  };
  for (size_t j = 0; j < groove_reach_; ++j) {
    const TipSegment* s = peek(j);
    if (!s || !s->raw.thread || !finite(s->start) || !finite(s->end)) continue;
    const double d = std::max(on_cl(s->end), on_cl((s->start + s->end) / 2));
    if (d > tol_) {
      fail(loc_, s->raw.line, "the program cuts a thread pass to " + xyz(s->end) + " that the CL does not: " + fixed_text(d, 5) +
                                  " from the CL's thread cuts", d);
      break;
    }
  }
  consume(groove_reach_);
  groove_reach_ = 0;
  thread_cuts_.clear();
  thread_used_.clear();
  thread_next_ = 0;
  consume_rapids_to(prev_);
}

}  // namespace clpc::verify_detail
