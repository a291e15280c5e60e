// clpc verify. The reference is the CL data itself, lowered again and given its meaning by
// verify's own rules, none of the compile's passes: an arc turns the way the CL says (its CAM
// system's CIRCLE convention, a sense word, MOVARC's angle, INDIRV: the `hint` lowering
// records), the GOTOs between a CYCLE and CYCLE/OFF are holes of the cycle's depth. Where an
// arc's tangent move contradicts its convention the CL is ambiguous: the report counts it.
// The program is read back by the independent
// reader (readback/gcode_interp.cpp) into tool-tip segments in the part frame
// (readback/program_reader.cpp). The two are walked together, one CL record at a time, with a bounded
// window of program segments:
//   - a CL point must be the end of a segment within the tolerance (and its tool axis within
//     the axis tolerance), reached in order: the segments passed over on the way must lie on
//     the CL path between the previous point and this one (rapids and canned-cycle motion
//     excepted: positioning is the post's business);
//   - a CL feed must not be reached by a rapid;
//   - a CL arc must be followed: points sampled along it lie within the tolerance of the
//     program's path, and the program's arcs stay on it;
//   - a hole must be drilled to its bottom (along its axis);
//   - a groove's cutting points (lathe) must lie on the program's path in its section;
//   - rotaries stay within their limits, the program within the machine's travel;
//   - nothing the reader flags (arc radii, missing feeds, unknown codes) goes unreported.
#include "readback/verify.h"
#include "support/worst_point.h"

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "ir/arc_geometry.h"
#include "ir/stock_model.h"
#include "support/ring.h"
#include "support/text.h"
#include "machine/format.h"

namespace clpc {

using ir::Vec3;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr size_t kMaxLookahead = 1 << 16;  // segments searched for one CL point
constexpr size_t kMaxStored = 50;          // problems kept in the report

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

double point_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  Vec3 ab = b - a;
  double l2 = ab.squaredNorm();
  double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// How far a point lies from the CL line from→to (0 while there is no line yet: the first
// point of a program).
struct LineDistance {
  Vec3 from, to;
  bool active;
  double operator()(const Vec3& q) const { return active ? point_segment(q, from, to) : 0.0; }
};

std::string xyz(const Vec3& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.4f, %.4f, %.4f)", v.x(), v.y(), v.z());
  return b;
}

class Comparison : public ProgramSink {
 public:
  Comparison(const Machine& m, const ir::ProgramInfo& info, ProgramReader& rd, Diagnostics& d, VerifyReport& rep)
      : m_(m), info_(info), rd_(rd), d_(d), rep_(rep), tol_(rep.tolerance), axis_tol_(rep.axis_tolerance) {
    k_ = ir::mm_per_unit(info.units) / ir::mm_per_unit(m.units);
    five_axis_ = m.kinematics.has_rotaries();
    increment_ = std::abs(dequantize(1, m.format('Z')));
    table_ = !info.offsets.empty();
  }

  void operation(const ir::Operation& op) override {
    if (!op.continued || rep_.operations.empty()) begin_operation(op);
    for (const ir::Instr& in : op.body) {
      loc_ = in.loc;
      point_dev_ = -1;
      std::visit(
          [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, ir::Feed>) {
              cl_feed_ = x;
              cl_feed_loc_ = loc_;
              have_cl_feed_ = true;
            } else if constexpr (std::is_same_v<T, ir::RotaryIndex>) {
              std::string why;  // the compile reports a machine without the axis
              indexing_.apply(m_.kinematics, x, why);
            } else if constexpr (std::is_same_v<T, ir::ToolChange>) {
              if (!rep_.operations.empty()) rep_.operations.back().tool = x.tool;
              want_tool_ = x.tool;
              want_h_ = x.length_offset > 0 ? x.length_offset : x.tool;
              want_tool_loc_ = loc_;
              tool_reported_ = false;
            } else if constexpr (std::is_same_v<T, ir::SetFrame>) {
              frame_ = x.frame;
            } else if constexpr (std::is_same_v<T, ir::Move>) {
              Vec3 p = model(x.point), a = model_dir(x.axis);
              if (x.kind == ir::MoveKind::From) {
                prev_ = p;
                have_prev_ = true;
              } else if (rough_) {
                rough_profile_.push_back({x.kind == ir::MoveKind::Rapid ? stock::Step::Kind::Rapid : stock::Step::Kind::Feed, p,
                                          Vec3::Zero(), false, loc_});
              } else if (thread_on_) {
                thread_point(p, x.kind == ir::MoveKind::Rapid);
              } else if (cycle_on_ && !groove_) {
                hole(x.point, x.axis);
              } else if (groove_) {
                groove_point(p, x.kind == ir::MoveKind::Rapid);
              } else {
                point(p, a, x.kind == ir::MoveKind::Rapid);
              }
              if (x.kind != ir::MoveKind::From) sample(p);
            } else if constexpr (std::is_same_v<T, ir::Arc>) {
              if (rough_) {
                rough_arc(x);
              } else {
                arc(x);
                sample(model(x.end));
              }
            } else if constexpr (std::is_same_v<T, ir::RoughMark>) {
              if (x.begin) {
                rough_ = x;
                rough_loc_ = loc_;
                rough_profile_.clear();
              } else if (rough_) {
                end_rough();
              }
            } else if constexpr (std::is_same_v<T, ir::CycleOn>) {
              cycle_ = op.cycles.at(x.spec);  // by value: the cycle's GOTOs may come in later chunks
              cycle_on_ = true;
            } else if constexpr (std::is_same_v<T, ir::ThreadMark>) {
              if (x.begin) begin_thread(x);
              else if (thread_on_) end_thread();
            } else if constexpr (std::is_same_v<T, ir::GrooveOn>) {
              begin_groove();
            } else if constexpr (std::is_same_v<T, ir::GrooveMark>) {
              if (x.begin) begin_groove();
              else end_groove();
            } else if constexpr (std::is_same_v<T, ir::CycleOff>) {
              if (groove_) end_groove();
              else cycle_on_ = false;
            }
          },
          in.op);
    }
  }

  // After the last CL record: what the program does beyond the CL path.
  void end() override {
    end_operation();
    if (groove_) end_groove();
    if (thread_on_) end_thread();
    bool reported = false;
    while (const TipSegment* s = peek(0)) {
      if (!reported && s->raw.kind != gcode::Segment::Kind::Rapid && !s->raw.from_cycle && finite(s->start)) {
        fail(loc_, s->raw.line, "the program cuts on past the last CL point (to " + xyz(s->end) + ")", kInf);
        reported = true;
      }
      consume(1);
    }
    check_travel();
  }

 private:
  // --- the program's segments, through a window -----------------------------------------

  const TipSegment* peek(size_t i) {
    while (win_.size() <= i) {
      if (!rd_.next(win_.push_back_slot())) {
        win_.pop_back();
        take_reader_problems();
        return nullptr;
      }
      take_reader_problems();
    }
    return &win_[i];
  }

  void consume(size_t n) {
    for (size_t i = 0; i < n && !win_.empty(); ++i) {
      check_limits(win_.front());
      if (finite(win_.front().end)) {
        at_ = win_.front().end;
        have_at_ = true;
      }
      win_.pop_front();
    }
  }

  // A CL point within the tolerance of where the tool is already needs no block of its own
  // (a move shorter than the output resolution is rightly dropped).
  // Blocks that follow and end within the tolerance of the point too (the CL dithering about
  // it by less than the tolerance, each step written) are this point's: taken with it.
  bool already_there(const Vec3& p) {
    if (!have_at_ || (at_ - p).norm() > tol_) return false;
    deviate((at_ - p).norm(), loc_, 0);
    while (const TipSegment* s = peek(0)) {
      if (!finite(s->end) || (s->end - p).norm() > tol_ || s->rotates) break;
      deviate((s->end - p).norm(), loc_, s->raw.line);
      consume(1);
    }
    return true;
  }

  void take_reader_problems() {
    for (const gcode::Problem& p : rd_.take_problems()) fail(loc_, p.line, "the program: " + p.message, 0);
  }

  // --- reporting -------------------------------------------------------------------------

  void fail(SourceLoc loc, int gline, const std::string& msg, double deviation) {
    if (!rep_.operations.empty()) ++rep_.operations.back().problems;
    std::string text = msg;
    if (gline > 0) text += " [G-code line " + std::to_string(gline) + "]";
    d_.error(loc, text);
    ++rep_.problem_count;
    if (rep_.problems.size() < kMaxStored) rep_.problems.push_back({loc, gline, msg, deviation});
    if (deviation > 0) deviate(deviation, loc, gline);
  }

  void deviate(double d, SourceLoc loc, int gline) {
    point_dev_ = std::max(point_dev_, d);
    if (!rep_.operations.empty()) {
      OperationCheck& o = rep_.operations.back();
      if (d > o.max_deviation || (std::isinf(d) && !std::isinf(o.max_deviation))) {
        o.max_deviation = d;
        o.max_loc = loc;
        o.max_gcode_line = gline;
      }
    }
    if (d > rep_.max_deviation || (std::isinf(d) && !std::isinf(rep_.max_deviation))) {
      rep_.max_deviation = d;
      rep_.max_loc = loc;
      rep_.max_gcode_line = gline;
    }
  }

  // --- the report's operations and deviation map -----------------------------------------

  void begin_operation(const ir::Operation& op) {
    end_operation();
    OperationCheck o;
    o.number = op.number;
    o.name = op.name;
    o.loc = op.loc;
    o.tool = want_tool_;
    rep_.operations.push_back(std::move(o));
    counts_at_start_ = {rep_.cl_points, rep_.cl_arcs, rep_.cl_holes, rep_.cl_groove_points};
  }

  void end_operation() {
    if (rep_.operations.empty()) return;
    OperationCheck& o = rep_.operations.back();
    o.points = rep_.cl_points - counts_at_start_[0];
    o.arcs = rep_.cl_arcs - counts_at_start_[1];
    o.holes = rep_.cl_holes - counts_at_start_[2];
    o.groove_points = rep_.cl_groove_points - counts_at_start_[3];
  }

  // The CL point just checked, with the largest deviation found for it.
  void sample(const Vec3& p) {
    if (!rep_.collect_samples || point_dev_ < 0) return;
    if (++sample_count_ % rep_.sample_stride != 0) return;
    rep_.samples.push_back({p, point_dev_});
    if (rep_.samples.size() >= VerifyReport::kMaxSamples) {  // thin out: every other one
      size_t k = 0;
      for (size_t i = 0; i < rep_.samples.size(); i += 2) rep_.samples[k++] = rep_.samples[i];
      rep_.samples.resize(k);
      rep_.sample_stride *= 2;
    }
  }

  // --- CL geometry in the frame the program is read back in ------------------------------

  // NX MSYS points are in the operation's frame; where the offset table put them in
  // machine terms, the read-back gives model coordinates.
  // Lowering gives every point and tool axis in the program frame; a rotary index record
  // turns what follows it (kin::RotaryIndexing, as the kinematics pass does).
  Vec3 model(const Vec3& p) const { return (indexing_.on ? Vec3(indexing_.rotation * p) : p) * k_; }
  Vec3 model_dir(const Vec3& v) const { return indexing_.on ? Vec3(indexing_.rotation * v) : v; }

  bool axis_ok(const TipSegment& s, const Vec3& axis) {
    if (!five_axis_) return true;
    // The angle (an atan2) only where it may be a new largest or beyond the tolerance.
    const double c = s.axis.dot(axis) / (s.axis.norm() * axis.norm());
    const double cut = std::min(rep_.max_axis_deviation, axis_tol_);
    if (cut != cut_deg_) cut_deg_ = cut, cut_cos_ = std::cos(cut * arcgeo::kPi / 180);
    if (c >= cut_cos_) return true;
    double a = kin::angle_between(s.axis, axis.normalized());
    if (a > rep_.max_axis_deviation) {
      rep_.max_axis_deviation = a;
      rep_.max_axis_loc = loc_;
      rep_.max_axis_gcode_line = s.raw.line;
    }
    return a <= axis_tol_;
  }

  // May the walk pass over segment s on its way to the next CL point? Rapids and cycle
  // motion always; feeds only on `on_path`.
  template <class OnPath>
  bool passable(const TipSegment& s, OnPath on_path, double& dev) {
    dev = 0;
    if (s.raw.kind == gcode::Segment::Kind::Rapid || s.raw.from_cycle) return true;
    if (!finite(s.end)) return true;
    if (on_last_hole_axis(s)) return true;
    dev = on_path(s.end);
    if (dev > tol_) return false;  // (then its bow does not matter: the walk stops here)
    if (s.rotates && finite(s.start)) dev = std::max(dev, worst_while_turning(s, on_path));
    return dev <= tol_;
  }

  // Without TCPC the control interpolates the axes, not the tip: while a block turns the
  // rotaries its tip bows away from the line. The distance at its worst point.
  template <class Distance>
  double worst_while_turning(const TipSegment& s, Distance distance) {
    return worst_point([&](double t) { return distance(rd_.tip_at(s, t)); });
  }

  // The same against the CL line from→to, remembered for the last segment asked: the walk
  // asks it twice of the block that reaches a CL point (looking past it for a nearer end,
  // then taking it), and the search costs some twenty-five tip positions.
  double worst_while_turning(const TipSegment& s, const LineDistance& line) {
    if (s.index != bow_.index || line.from != bow_.from || line.to != bow_.to || line.active != bow_.active)
      bow_ = {s.index, line.from, line.to, line.active, worst_point([&](double t) { return line(rd_.tip_at(s, t)); })};
    return bow_.dev;
  }

  bool on_last_hole_axis(const TipSegment& s) const {
    if (!have_hole_) return false;
    auto off_axis = [&](const Vec3& p) {
      Vec3 d = p - hole_point_;
      return (d - d.dot(hole_axis_) * hole_axis_).norm();
    };
    return off_axis(s.end) <= tol_ && (!finite(s.start) || off_axis(s.start) <= tol_);
  }

  // Finds the segment that reaches `p`; returns its index in the window, or nothing (then
  // `nearest`/`nearest_at` say how close the program came).
  template <class OnPath>
  std::optional<size_t> reach(const Vec3& p, OnPath on_path, double& nearest, size_t& nearest_at, std::vector<double>& passed,
                              const Vec3* axis = nullptr) {
    nearest = kInf;
    nearest_at = 0;
    passed.clear();
    for (size_t j = 0; j < kMaxLookahead; ++j) {
      const TipSegment* s = peek(j);
      if (!s) return std::nullopt;
      if (finite(s->end)) {
        double d = (s->end - p).norm();
        if (d <= tol_) return nearest_end(j, d, on_path, passed, p, axis);
        if (d < nearest) {
          nearest = d;
          nearest_at = j;
        }
      }
      double dev;
      if (!passable(*s, on_path, dev)) return std::nullopt;
      passed.push_back(dev);
    }
    return std::nullopt;
  }

  // The programmed feed of a cutting block against the CL's: the same kind (per minute, per
  // revolution), the same value within the machine's feeds.max_rounding (or its max_feed, the
  // clamp); inverse-time blocks are the kinematics' and not compared.
  void feed_ok(const TipSegment& s, const ir::Feed* cl) {
    if (s.raw.kind == gcode::Segment::Kind::Rapid || s.raw.inverse_time || !cl || cl->mode == ir::FeedMode::InverseTime) return;
    const bool per_rev = cl->mode == ir::FeedMode::PerRev;
    double want = cl->value * k_;
    if (m_.kinematics.degrees_per_minute && gcode::feeds_combined(s.raw)) {
      // Degrees per minute: F over all the axes, for the tip's own length at the CL feed.
      const double tip = (s.end - s.start).norm();
      if (!(tip > 0)) return;
      want *= gcode::combined_length(s.raw, m_.kinematics) / tip;
      if (std::abs(s.raw.feed - want) > m_.feeds.max_rounding * want + 1e-12)
        fail(loc_, s.raw.line,
             "the block's F is " + fixed_text(s.raw.feed, 4) + " (degrees per minute: over X Y Z and the rotaries); the CL's feed " +
                 "along the tip's path makes it " + fixed_text(want, 4),
             0);
      return;
    }
    if (!per_rev && m_.max_feed > 0 && want > m_.max_feed) want = m_.max_feed;
    const std::string unit = std::string(m_.units == ir::Units::Inch ? "in" : "mm") + (per_rev ? "/rev" : "/min");
    if (s.raw.per_rev != per_rev) {
      fail(loc_, s.raw.line, std::string("the block feeds per ") + (s.raw.per_rev ? "revolution" : "minute") +
                                 ", the CL's FEDRAT (line " + std::to_string(cl_feed_loc_.line) + ") per " +
                                 (per_rev ? "revolution" : "minute"),
           0);
      return;
    }
    if (std::abs(s.raw.feed - want) > m_.feeds.max_rounding * want + 1e-12)
      fail(loc_, s.raw.line, "the block's feed is " + fixed_text(s.raw.feed, 4) + " " + unit + ", the CL's " + fixed_text(want, 4) + " " + unit,
           0);
  }

  // A tap's feed keeps its pitch: over the hole's depth the tap may drift from its thread by
  // less than half an output increment.
  void tap_ok(const TipSegment& s, const ir::CycleSpec& spec) {
    const double pitch = spec.pitch * k_;
    const double lead = s.raw.per_rev ? s.raw.feed : (s.raw.rpm > 0 ? s.raw.feed / s.raw.rpm : 0);
    const double drift = std::abs(lead - pitch) * (spec.depth * k_) / pitch;
    if (drift >= 0.5 * increment_)
      fail(loc_, s.raw.line, "the tap advances " + fixed_text(lead, 6) + " a turn, its thread's pitch is " + fixed_text(pitch, 6) + ": " +
                                 fixed_text(drift, 5) + " off at the bottom",
           drift);
  }

  // Where blocks lie closer together than the tolerance (a five-axis finish in tiny steps),
  // the first block end within it may not be the CL point's own: of the blocks that follow on
  // the path with their ends within the tolerance (the walk stops at twice it), the one that
  // is nearest in tip and tool axis together — the larger of the two deviations, each over its
  // tolerance, so a block whose axis agrees wins over one whose axis does not — the earlier
  // on a tie.
  template <class OnPath>
  size_t nearest_end(size_t j, double d, OnPath on_path, std::vector<double>& passed, const Vec3& p, const Vec3* axis) {
    auto score = [&](const TipSegment& t, double dist) {
      double s = dist / tol_;
      if (five_axis_ && axis && axis_tol_ > 0) {
        const double n = t.axis.norm() * axis->norm();
        const double c = n > 0 ? std::clamp(t.axis.dot(*axis) / n, -1.0, 1.0) : 1.0;
        s = std::max(s, std::acos(c) * 180 / arcgeo::kPi / axis_tol_);
      }
      return s;
    };
    size_t best = j;
    double best_score = score(*peek(j), d);
    std::vector<double> devs;  // of the segments after j passed over, in order
    for (size_t k = j + 1; k < kMaxLookahead; ++k) {
      double dev;
      if (!passable(*peek(k - 1), on_path, dev)) break;
      devs.push_back(dev);
      const TipSegment* t = peek(k);
      // The path must run on unbroken, with the same tool: a block after a move the reader
      // cannot place (G53, G28) or after a tool change may come back to the same point, and
      // is then the next CL record's, not this one's.
      if (!t || !finite(t->end) || !finite(t->start) || t->raw.tool != peek(j)->raw.tool) break;
      // Near a singularity the tip creeps while the rotaries turn (a block of C moves it a
      // thousandth of a millimetre), and the rounding of the angles, times the tool's length,
      // shakes it by as much: one block end may sit just outside the tolerance between two
      // inside it. The walk goes on until the tip has clearly left the point.
      const double dk = (t->end - p).norm();
      if (dk > 2 * tol_) break;
      if (dk > tol_) continue;
      const double sk = score(*t, dk);
      if (sk < best_score) {
        passed.insert(passed.end(), devs.begin(), devs.end());
        devs.clear();
        best = k;
        best_score = sk;
      }
    }
    return best;
  }

  // A CL point not reached: report how close the program came, and resynchronise past the
  // nearest segment when it was a near miss (a shifted point), not when the program went
  // elsewhere (a dropped block): then the next CL point finds its own segment.
  void missed(const Vec3& p, double nearest, size_t nearest_at, const char* what) {
    const TipSegment* s = std::isfinite(nearest) ? peek(nearest_at) : nullptr;
    std::string msg = std::string(what) + " " + xyz(p) + " is never reached";
    if (s) msg += ": the program comes within " + fixed_text(nearest, 5) + " of it";
    fail(loc_, s ? s->raw.line : 0, msg, std::isfinite(nearest) ? nearest : kInf);
    if (s && nearest <= std::max(20 * tol_, 0.1 / ir::mm_per_unit(m_.units))) consume(nearest_at + 1);
  }

  // The tool the CL loaded cuts, with its own length offset (a wrong H puts the tip where
  // another tool's length says). Reported once per tool change.
  void tool_ok(const TipSegment& s) {
    if (want_tool_ <= 0 || tool_reported_ || s.raw.tool <= 0) return;
    auto cl = [&] { return " (the CL loads tool " + std::to_string(want_tool_) + " at line " + std::to_string(want_tool_loc_.line) + ")"; };
    if (s.raw.tool != want_tool_) {
      fail(loc_, s.raw.line, "this is cut with tool " + std::to_string(s.raw.tool) + cl(), 0);
      tool_reported_ = true;
    } else if (s.raw.length_register > 0 && s.raw.length_register != want_h_) {
      fail(loc_, s.raw.line,
           "the tool length offset in force is register " + std::to_string(s.raw.length_register) + ", tool " +
               std::to_string(want_tool_) + "'s is " + std::to_string(want_h_) + cl(),
           0);
      tool_reported_ = true;
    }
  }

  // A rapid passed over on the way to a CL feed that runs along the CL path (both its ends on
  // it) is the cut made at rapid traverse; a rapid the post adds (a retract, a positioning
  // move) leaves the path.
  template <class OnPath>
  void no_rapid_cut(size_t j, OnPath on_path) {
    for (size_t i = 0; i < j && i < win_.size(); ++i) {
      const TipSegment& s = win_[i];
      if (s.raw.kind != gcode::Segment::Kind::Rapid || s.raw.from_cycle || !finite(s.start) || !finite(s.end)) continue;
      if ((s.end - s.start).norm() > tol_ && on_path(s.start) <= tol_ && on_path(s.end) <= tol_) {
        fail(loc_, s.raw.line, "this CL feed move is made at rapid traverse (G00)", 0);
        return;
      }
    }
  }

  // The segment at j reached CL point p: the segments before it were passed over.
  void reached(size_t j, const Vec3& p, const Vec3& axis, bool rapid, const std::vector<double>& passed) {
    for (size_t i = 0; i < j && i < passed.size(); ++i) deviate(passed[i], loc_, win_[i].raw.line);
    const TipSegment& s = win_[j];
    tool_ok(s);
    double d = (s.end - p).norm();
    deviate(d, loc_, s.raw.line);
    if (!axis_ok(s, axis))
      fail(loc_, s.raw.line,
           "the tool axis at this CL point is off by " + fixed_text(kin::angle_between(s.axis, axis.normalized()), 4) + " degrees",
           0);
    // (A canned cycle's own return may bring the tool there: the CL's feed up from the last
    // hole to where the cycle returned it is made by the cycle, at rapid, away from the part.)
    if (!rapid && s.raw.kind == gcode::Segment::Kind::Rapid && !s.raw.from_cycle)
      fail(loc_, s.raw.line, "this CL feed move is made at rapid traverse (G00)", 0);
    for (size_t i = 0; i <= j && i < win_.size(); ++i)
      if (win_[i].raw.thread) {
        fail(loc_, win_[i].raw.line, "the program cuts a thread here (synchronised, F the lead) where the CL has no THREAD", 0);
        break;
      }
    if (!rapid)  // every feed block on the way here: a split move's pieces each carry their own F
      for (size_t i = 0; i <= j && i < win_.size(); ++i) {
        const TipSegment& b = win_[i];
        if (b.raw.kind == gcode::Segment::Kind::Rapid || b.raw.from_cycle) continue;
        // A turn of the rotaries with the tip on the spot (at a singularity) cuts nothing: the
        // CL gives no feed for it.
        if (b.rotates && finite(b.start) && (b.end - b.start).norm() <= tol_) continue;
        feed_ok(b, have_cl_feed_ ? &cl_feed_ : nullptr);
      }
    if (s.rotates && have_prev_ && finite(s.start) && !rapid) {
      // Five-axis without TCPC: the tip between the block's ends must stay on the CL line.
      double dev = worst_while_turning(s, LineDistance{prev_, p, true});
      deviate(dev, loc_, s.raw.line);
      if (dev > tol_)
        fail(loc_, s.raw.line, "while the rotaries turn the tool tip leaves the CL line by " + fixed_text(dev, 5) + " at its worst point", dev);
    }
    consume(j + 1);
  }

  // --- CL records --------------------------------------------------------------------------

  void point(const Vec3& p, const Vec3& axis, bool rapid) {
    ++rep_.cl_points;
    const Vec3 from = prev_;
    const bool have_from = have_prev_;
    const LineDistance on_path{from, p, have_from};
    double nearest;
    size_t at;
    if (already_there(p)) {
    } else if (auto j = reach(p, on_path, nearest, at, passed_, &axis)) {
      if (!rapid) no_rapid_cut(*j, on_path);
      reached(*j, p, axis, rapid, passed_);
    } else {
      missed(p, nearest, at, "CL point");
    }
    incoming_ = rapid || !have_from ? Vec3::Zero() : Vec3(p - from);
    prev_ = p;
    have_prev_ = true;
    have_hole_ = false;
  }

  // Which way a CL arc turns, by the CL's own word (lowering's `hint`), and whether the move
  // entering it agrees: a tangent move (at least 20 output increments long in the arc's plane,
  // within 10 degrees of tangent) that runs against the arc's sense makes the CL ambiguous.
  ir::ArcDir arc_sense(const ir::Arc& a) {
    const ir::ArcDir dir = a.dir != ir::ArcDir::Unknown ? a.dir : a.hint;
    if (dir == ir::ArcDir::Unknown) return dir;
    const Vec3 n = a.axis.normalized();
    const Vec3 in = incoming_ - incoming_.dot(n) * n;
    const Vec3 t = arcgeo::sense(dir) * n.cross(arcgeo::radial(a, a.start));
    if (in.norm() >= 20 * increment_ && t.norm() > 0 && in.dot(t) <= -0.985 * in.norm() * t.norm()) {
      if (rep_.ambiguous_arcs++ == 0) rep_.ambiguous_loc = loc_;
    }
    return dir;
  }

  void arc(const ir::Arc& a0) {
    ++rep_.cl_arcs;
    ir::Arc a = a0;
    a.start = model(a0.start);
    a.end = model(a0.end);
    a.center = model(a0.center);
    a.axis = model_dir(a0.axis);
    a.radius = a0.radius * k_;
    a.dir = arc_sense(a);
    incoming_ = Vec3::Zero();
    if (a.dir == ir::ArcDir::Unknown) {
      // Lowering gives every CL arc a sense; only an arc a pass made has none.
      fail(loc_, 0, "verify cannot tell which way this CL arc turns", kInf);
      prev_ = a.end;
      have_prev_ = true;
      return;
    }
    if (!(a.sweep > 0)) a.sweep = arcgeo::sweep_deg(a, a.dir, 1e-7);
    const arcgeo::ArcProbe cl(a);
    auto on_arc = [&](const Vec3& q) { return cl.distance(q); };
    double nearest;
    size_t at;
    const double length = a.radius * a.sweep * arcgeo::kPi / 180;
    std::optional<size_t> j;
    if (length <= tol_ && already_there(a.end)) {
      // An arc shorter than the tolerance: the tool is there.
    } else if (!(j = reach(a.end, on_arc, nearest, at, passed_))) {
      missed(a.end, nearest, at, "the end of the CL arc");
    } else {
      // The program's path from the arc's start to its end, against the arc, both ways.
      double worst = 0;
      int worst_line = win_[*j].raw.line;
      const int n = std::max(8, int(std::ceil(std::abs(a.sweep) / 5)));
      // Samples along the CL arc meet the program's pieces in order; going back through them
      // (a linearised circle run the wrong way) turns the other way as surely as G02 for G03.
      int backwards = 0;
      size_t last_piece = 0;
      probes_.clear();  // the program's arcs, in the window's order
      for (size_t s = 0; s <= *j; ++s)
        if (win_[s].raw.kind == gcode::Segment::Kind::Arc) probes_.emplace_back(arc_of(win_[s]));
      for (int i = 1; i < n; ++i) {
        Vec3 q = cl.point(double(i) / n);
        double best = kInf;
        int line = 0;
        size_t piece = 0;
        size_t k = 0;
        for (size_t s = 0; s <= *j; ++s) {
          const TipSegment& g = win_[s];
          const bool is_arc = g.raw.kind == gcode::Segment::Kind::Arc;
          const arcgeo::ArcProbe* probe = is_arc ? &probes_[k++] : nullptr;
          if (!finite(g.start) || !finite(g.end)) continue;
          double d = is_arc ? probe->distance(q) : point_segment(q, g.start, g.end);
          if (d < best) {
            best = d;
            line = g.raw.line;
            piece = s;
          }
        }
        if (best > worst) {
          worst = best;
          worst_line = line;
        }
        if (i > 1 && piece < last_piece) ++backwards;
        last_piece = piece;
      }
      // And each program arc turns the CL arc's way (a full circle's points cannot tell).
      const double cl_sense = a.dir == ir::ArcDir::Ccw ? 1 : -1;
      int reversed_line = 0;
      for (size_t s = 0; s <= *j; ++s) {
        const TipSegment& g = win_[s];
        if (g.raw.kind != gcode::Segment::Kind::Arc) continue;
        double along = g.normal.dot(a.axis.normalized());
        if (std::abs(along) < 0.5) continue;  // another plane: the samples judge it
        if ((g.raw.ccw ? 1 : -1) * (along > 0 ? 1 : -1) != cl_sense) reversed_line = g.raw.line;
      }
      if (reversed_line || backwards > n / 2) {
        // Said as a machinist sees it: from the positive end of the nearest principal axis.
        const Vec3 ax = a.axis.normalized();
        int k = 0;
        for (int c = 1; c < 3; ++c)
          if (std::abs(ax[c]) > std::abs(ax[k])) k = c;
        const bool ccw_seen = (cl_sense > 0) == (ax[k] > 0);
        fail(loc_, reversed_line ? reversed_line : worst_line,
             std::string("the program turns this CL arc the other way (the CL arc turns ") +
                 (ccw_seen ? "counter-clockwise" : "clockwise") + " seen from +" + "XYZ"[k] + ")",
             0);
        deviate(worst, loc_, worst_line);
        consume(*j + 1);
        prev_ = a.end;
        have_prev_ = true;
        have_hole_ = false;
        return;
      }
      no_rapid_cut(*j, on_arc);
      size_t k = 0;
      for (size_t s = 0; s <= *j; ++s) {
        const TipSegment& g = win_[s];
        if (g.raw.kind != gcode::Segment::Kind::Arc) continue;
        const arcgeo::ArcProbe& probe = probes_[k++];
        if (!finite(g.start)) continue;
        double d = cl.distance(probe.point(0.5));
        if (d > worst) {
          worst = d;
          worst_line = g.raw.line;
        }
      }
      if (worst > tol_) {
        fail(loc_, worst_line,
             "the CL arc is not followed: the program's path is " + fixed_text(worst, 5) + " from it (does it turn the other way?)",
             worst);
        consume(*j + 1);
      } else {
        deviate(worst, loc_, worst_line);
        reached(*j, a.end, a.tool_axis, false, passed_);
      }
    }
    incoming_ = arcgeo::tangent_at(a, 1.0) * (1e6 * increment_);  // leaves along its tangent
    prev_ = a.end;
    have_prev_ = true;
    have_hole_ = false;
  }

  // A GOTO of a CYCLE: a hole at the point, down the tool axis by the cycle's depth.
  void hole(const Vec3& point, const Vec3& tool_axis) {
    ++rep_.cl_holes;
    const ir::CycleSpec& spec = cycle_;
    incoming_ = Vec3::Zero();
    const Vec3 top = model(point), axis = model_dir(tool_axis).normalized();
    const Vec3 bottom = top - axis * (spec.depth * k_);
    // The same hole again (a GOTO repeated in the cycle): drilled already, nothing to reach.
    if (have_hole_ && (hole_point_ - top).norm() <= tol_ && (hole_bottom_ - bottom).norm() <= tol_) return;
    hole_bottom_ = bottom;
    hole_point_ = top;
    hole_axis_ = axis;
    have_hole_ = true;
    // On the way: rapids, cycle motion, and feeds along this hole's axis.
    auto on_axis = [&](const Vec3& q) {
      Vec3 d = q - top;
      return (d - d.dot(axis) * axis).norm();
    };
    double nearest;
    size_t at;
    auto j = reach(bottom, on_axis, nearest, at, passed_);
    if (!j) {
      missed(bottom, nearest, at, "the bottom of the hole at");
    } else {
      const TipSegment& s = win_[*j];
      tool_ok(s);
      deviate((s.end - bottom).norm(), loc_, s.raw.line);
      if (s.raw.kind == gcode::Segment::Kind::Rapid)
        fail(loc_, s.raw.line, "the hole's bottom is reached at rapid traverse", 0);
      if (!axis_ok(s, axis)) fail(loc_, s.raw.line, "the hole is drilled with the tool off its axis", 0);
      if (spec.kind == ir::CycleKind::Tap) {
        tap_ok(s, spec);
      } else {
        ir::Feed f = have_cl_feed_ ? cl_feed_ : ir::Feed{0, ir::FeedMode::PerMinute};
        if (spec.feed > 0) f = ir::Feed{spec.feed, spec.feed_mode};
        feed_ok(s, f.value > 0 ? &f : nullptr);
      }
      consume(*j + 1);
    }
    prev_ = top;
    have_prev_ = true;
  }

  // --- lathe stock removal: the control's cycle over the CL's profile, block for block ---------
  // The reference is the CL's profile and cycle words expanded by the control's rules
  // (ir/stock_model.h), from verify's own reading of the CL (its arcs' sense by the CAM
  // convention); the program's G71/G72 and G70 as the reader runs them must make the same moves.
  struct Want {
    stock::Step::Kind kind;
    Vec3 to, center;
    bool ccw;
    SourceLoc loc;
  };

  void rough_arc(const ir::Arc& a0) {
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

  void end_rough() {
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

  // After a cycle found wrong: the rest of its moves are not compared one by one.
  void skip_cycle_segments() {
    while (const TipSegment* s = peek(0)) {
      if (!s->raw.from_cycle) break;
      consume(1);
    }
  }

  // --- lathe grooves: the cycle's order is its own; every CL cut must be on its path --------

  void begin_groove() {
    groove_ = true;
    groove_reach_ = 0;
  }

  // A groove's CL feed move: its end and its middle must each lie on a feed of the program
  // (the cycle pecks in its own order, so the order is not checked).
  void groove_point(const Vec3& p, bool rapid) {
    const Vec3 from = prev_;
    const bool have_from = have_prev_;
    prev_ = p;
    have_prev_ = true;
    if (rapid) return;
    ++rep_.cl_groove_points;
    if (groove_cut(p, p) && have_from && (p - from).norm() > 2 * tol_) groove_cut((from + p) / 2, p);
  }

  // Is `q` (on the CL move to `p`) on a cutting move of the program? False, reported, if not.
  bool groove_cut(const Vec3& q, const Vec3& p) {
    double best = kInf;
    size_t best_at = 0;
    int rapid_line = 0;  // a rapid through the cut, while no feed made it
    for (size_t j = 0; j < kMaxLookahead; ++j) {
      const TipSegment* s = peek(j);
      if (!s) break;
      if (!finite(s->start) || !finite(s->end)) continue;
      double d = point_segment(q, s->start, s->end);
      if (s->raw.kind == gcode::Segment::Kind::Rapid) {
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

  void end_groove() {
    groove_ = false;
    consume(groove_reach_);
    groove_reach_ = 0;
    consume_rapids_to(prev_);
  }

  // After a section whose rapids were not matched one by one (a groove, a thread): the rapids
  // that bring the tool to the section's last CL point are the section's, not the next
  // record's (a rapid whose ends both lie on a following arc is not that arc cut at rapid).
  void consume_rapids_to(const Vec3& p) {
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

  // --- lathe threads: each CL thread cut is a synchronised cut of the program at the lead,
  // and each synchronised cut of the program is one of the CL's (a pass too deep scraps the
  // thread). Cycles (G92, G76) run their passes in their own order, as grooves do. -----------

  void begin_thread(const ir::ThreadMark& t) {
    if (thread_on_) end_thread();
    thread_ = t;
    thread_on_ = true;
    groove_reach_ = 0;
    thread_cuts_.clear();
    thread_used_.clear();
  }

  bool along_thread(const Vec3& from, const Vec3& to) const {
    const double dx = std::abs(to.x() - from.x()), dz = std::abs(to.z() - from.z());
    if (thread_.kind == ir::ThreadKind::Face) return dx > 1e-9 && dz < dx;
    return dz > 1e-9 && dx < dz;
  }

  void thread_point(const Vec3& p, bool rapid) {
    const Vec3 from = prev_;
    const bool have_from = have_prev_;
    prev_ = p;
    have_prev_ = true;
    if (rapid) return;
    if (!have_from) return;
    if (!along_thread(from, p)) {
      if ((p - from).norm() <= tol_) return;  // no move
      ++rep_.cl_groove_points;  // an infeed or pull-out at feed: on the path, like a groove's
      groove_cut(p, p);
      return;
    }
    ++rep_.cl_thread_cuts;
    double lead = thread_.lead * k_;
    if (!(lead > 0) && have_cl_feed_ && cl_feed_.mode == ir::FeedMode::PerRev) lead = cl_feed_.value * k_;
    thread_cuts_.push_back({from, p});
    thread_cut(from, p, lead);
  }

  // The CL cut from `from` to `p` must be one synchronised cut of the program: its end and its
  // middle on it (finishing passes at one depth each take a cut of their own), at the lead.
  void thread_cut(const Vec3& from, const Vec3& p, double lead) {
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

  void end_thread() {
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
    consume_rapids_to(prev_);
  }

  // --- limits --------------------------------------------------------------------------

  void check_limits(const TipSegment& s) {
    const KinematicsSettings& k = m_.kinematics;
    for (const RotaryAxis& r : k.rotaries) {
      if (r.cyclic != Cyclic::No) continue;
      double v = s.raw.rotary[size_t(r.name[0] - 'A')];
      double slack = std::abs(dequantize(1, m_.format(r.name[0])));
      if (v < r.min - slack || v > r.max + slack) {
        if (!limit_reported_[size_t(r.name[0] - 'A')]++)
          fail(loc_, s.raw.line, r.name + fixed_text(v, 3) + " is beyond the " + r.name + " axis's limits (" + num_text(r.min) + " to " +
                                     num_text(r.max) + ")",
               0);
      }
    }
    // The machine position of the tool's reference point, for travel.
    if (!finite(s.raw.end)) return;
    Vec3 pos = s.raw.end;
    if (s.raw.tcp) {
      kin::Angles a{0, 0};
      for (size_t i = 0; i < k.rotaries.size() && i < 2; ++i) a[i] = s.raw.rotary[size_t(k.rotaries[i].name[0] - 'A')];
      pos = kin::machine_point(k, a, s.raw.end, k.pivot);
    }
    for (int i = 0; i < 3; ++i) {
      if (pos[i] < lo_[i]) lo_[i] = pos[i], lo_line_[i] = s.raw.line, lo_loc_[i] = loc_;
      if (pos[i] > hi_[i]) hi_[i] = pos[i], hi_line_[i] = s.raw.line, hi_loc_[i] = loc_;
    }
  }

  void check_travel() {
    const LinearLimits& t = m_.kinematics.travel;
    for (int i = 0; i < 3; ++i) {
      if (!t.set || !(lo_[i] <= hi_[i])) continue;
      const double tmin = t.min[i], tmax = t.max[i];
      const char axis = "XYZ"[i];
      const double slack = tol_;
      if (m_.kinematics.work_zero_set) {
        double zero = m_.kinematics.work_zero[i];
        if (zero + lo_[i] < tmin - slack)
          fail(lo_loc_[i], lo_line_[i], std::string(1, axis) + " goes to " + fixed_text(zero + lo_[i], 4) + " in machine coordinates, beyond its travel (" +
                                            num_text(tmin) + " to " + num_text(tmax) + ")", 0);
        if (zero + hi_[i] > tmax + slack)
          fail(hi_loc_[i], hi_line_[i], std::string(1, axis) + " goes to " + fixed_text(zero + hi_[i], 4) + " in machine coordinates, beyond its travel (" +
                                            num_text(tmin) + " to " + num_text(tmax) + ")", 0);
      } else if (hi_[i] - lo_[i] > tmax - tmin + slack) {
        fail(hi_loc_[i], hi_line_[i], "the program spans " + fixed_text(hi_[i] - lo_[i], 4) + " in " + axis + ", more than the machine's travel of " +
                                          num_text(tmax - tmin), 0);
      }
    }
  }

  const Machine& m_;
  const ir::ProgramInfo& info_;
  ProgramReader& rd_;
  Diagnostics& d_;
  VerifyReport& rep_;
  const double tol_, axis_tol_;
  double k_ = 1;
  bool five_axis_ = false, table_ = false;
  Ring<TipSegment> win_;
  std::vector<arcgeo::ArcProbe> probes_;  // the program arcs of the window a CL arc is checked against (reused)
  std::vector<double> passed_;
  SourceLoc loc_;
  Vec3 prev_ = Vec3::Zero();  // the last CL point
  bool have_prev_ = false;
  Vec3 at_ = Vec3::Zero();    // where the program has taken the tool (the last segment passed)
  bool have_at_ = false;
  ir::Frame frame_;
  kin::RotaryIndexing indexing_;
  ir::Feed cl_feed_;          // the CL's feed in force
  SourceLoc cl_feed_loc_;
  bool have_cl_feed_ = false;
  double increment_ = 0;      // one output increment of Z
  Vec3 hole_point_ = Vec3::Zero(), hole_axis_ = Vec3::UnitZ(), hole_bottom_ = Vec3::Zero();
  bool have_hole_ = false;
  struct Bow {
    int index = -1;
    Vec3 from, to;
    bool active = false;
    double dev = 0;
  } bow_;  // worst_while_turning's last answer against a CL line
  double cut_deg_ = -1, cut_cos_ = 1;  // axis_ok's angle below which nothing changes, and its cosine
  double point_dev_ = -1;      // the largest deviation found for the CL record being checked
  long sample_count_ = 0;
  std::array<long, 4> counts_at_start_{};  // points, arcs, holes, groove cuts when the operation began
  int want_tool_ = 0, want_h_ = 0;  // the CL's tool and its length offset register
  SourceLoc want_tool_loc_;
  bool tool_reported_ = false;
  ir::CycleSpec cycle_;       // the drilling cycle in force
  bool cycle_on_ = false;
  Vec3 incoming_ = Vec3::Zero();  // the last CL feed move (zero after a rapid or a hole)
  bool groove_ = false;
  size_t groove_reach_ = 0;
  bool thread_on_ = false;
  std::optional<ir::RoughMark> rough_;  // a CYCLE/ROUGH section being read: its profile is kept
  SourceLoc rough_loc_;
  std::vector<Want> rough_profile_;
  ir::ThreadMark thread_;
  std::vector<std::pair<Vec3, Vec3>> thread_cuts_;  // the CL's thread cuts of the section
  std::vector<bool> thread_used_;  // the program's segments (window index) a CL thread cut took
  int limit_reported_[26] = {};
  double lo_[3] = {kInf, kInf, kInf}, hi_[3] = {-kInf, -kInf, -kInf};
  int lo_line_[3] = {}, hi_line_[3] = {};
  SourceLoc lo_loc_[3], hi_loc_[3];
};

}  // namespace

double default_tolerance(const Machine& m) {
  double inc = 0;
  for (char c : {'X', 'Y', 'Z'}) {
    const AddressFormat& f = m.format(c);
    inc = std::max(inc, std::abs(dequantize(1, f)) / (f.scale > 0 ? f.scale : 1));
  }
  return m.arcs.tolerance + inc;
}

std::unique_ptr<ProgramSink> make_comparison(const Machine& m, const ir::ProgramInfo& info, ProgramReader& rd, Diagnostics& d,
                                             VerifyReport& rep) {
  return std::make_unique<Comparison>(m, info, rd, d, rep);
}

}  // namespace clpc
