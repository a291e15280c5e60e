// The comparison behind `clpc verify` and the certificate (readback/verify.h says what it
// checks): the CL walked one record at a time against the program read back, with a bounded
// window of program segments. One class, its state shared by every check; the checks of the
// mill, five-axis and drilling are defined in readback/verify.cpp, those of the lathe's cycles
// (stock removal, grooves, threads) in readback/verify_lathe.cpp. Internal to verify: only
// make_comparison() (verify.h) is the interface.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "ir/arc_geometry.h"
#include "ir/stock_model.h"
#include "machine/format.h"
#include "readback/verify.h"
#include "support/ring.h"
#include "support/text.h"
#include "support/worst_point.h"

namespace clpc::verify_detail {

using ir::Vec3;


constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr size_t kMaxLookahead = 1 << 16;  // segments searched for one CL point
constexpr size_t kMaxStored = 50;          // problems kept in the report

inline bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

inline double point_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
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

inline std::string xyz(const Vec3& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.4f, %.4f, %.4f)", v.x(), v.y(), v.z());
  return b;
}

class Comparison : public ProgramSink {
 public:
  Comparison(const Machine& m, const ir::ProgramInfo& info, ProgramReader& rd, Diagnostics& d, VerifyReport& rep)
      : m_(m), rd_(rd), d_(d), rep_(rep), tol_(rep.tolerance), axis_tol_(rep.axis_tolerance),
        axis_mid_tol_(std::max(rep.axis_tolerance, kin::kMidBlockAxisTolerance)) {
    k_ = ir::mm_per_unit(info.units) / ir::mm_per_unit(m.units);
    five_axis_ = m.kinematics.has_rotaries();
    increment_ = std::abs(dequantize(1, m.format('Z')));
    for (const RotaryAxis& r : m.kinematics.rotaries)
      if (r.name.size() == 1) rotary_increment_ = std::max(rotary_increment_, std::abs(dequantize(1, m.format(r.name[0]))));
    table_ = !info.offsets.empty();
    dwell_slack_ = dwell_slack(m);
  }

  void operation(const ir::Operation& op) override;

  // After the last CL record: what the program does beyond the CL path.
  void end() override;

 private:
  // --- the program's segments, through a window -----------------------------------------

  const TipSegment* peek(size_t i);

  void consume(size_t n);
  void finish_cycle_motion();
  void dwell_ok();
  static double dwell_slack(const Machine& m);
  void spindle_ok(const TipSegment& s);
  void register_ok(const TipSegment& s);
  // A cut across the tool axis with the cutter compensation the CL has in force (none, left,
  // right): verify takes D as no offset, so the path alone does not show a G41 where the CL has
  // no CUTCOM, or none where it has. Said once until they agree again.
  void comp_ok(const TipSegment& s);

  // A CL point within the tolerance of where the tool is already needs no block of its own
  // (a move shorter than the output resolution is rightly dropped).
  // Blocks that follow and end within the tolerance of the point too (the CL dithering about
  // it by less than the tolerance, each step written) are this point's: taken with it.
  bool already_there(const Vec3& p, const Vec3* axis = nullptr);

  void take_reader_problems();

  // --- reporting -------------------------------------------------------------------------

  void fail(SourceLoc loc, int gline, const std::string& msg, double deviation);

  void deviate(double d, SourceLoc loc, int gline);

  // --- the report's operations and deviation map -----------------------------------------

  void begin_operation(const ir::Operation& op);

  void end_operation();

  // The CL point just checked, with the largest deviation found for it.
  void sample(const Vec3& p);

  // --- CL geometry in the frame the program is read back in ------------------------------

  // NX MSYS points are in the operation's frame; where the offset table put them in
  // machine terms, the read-back gives model coordinates.
  // Lowering gives every point and tool axis in the program frame; a rotary index record
  // turns what follows it (kin::RotaryIndexing, as the kinematics pass does).
  Vec3 model(const Vec3& p) const { return (indexing_.on ? Vec3(indexing_.rotation * p) : p) * k_; }
  Vec3 model_dir(const Vec3& v) const { return indexing_.on ? Vec3(indexing_.rotation * v) : v; }

  bool axis_ok(const TipSegment& s, const Vec3& axis);
  void axis_between_ok(size_t j, const Vec3& axis);
  // A canned cycle's return: a move straight up the tool axis (away from the part).
  bool returns_up_the_axis(const TipSegment& s) const;

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
  double worst_while_turning(const TipSegment& s, const LineDistance& line);

  bool on_last_hole_axis(const TipSegment& s) const;

  // Finds the segment that reaches `p`; returns its index in the window, or nothing (then
  // `nearest`/`nearest_at` say how close the program came).
  template <class OnPath>
  // `turns`: a CL arc of more than a turn (extra_turns), whose end the program passes at each
  // turn: only an end reached after the program has turned round the arc's axis by its whole
  // sweep (less a degree) is the arc's.
  std::optional<size_t> reach(const Vec3& p, OnPath on_path, double& nearest, size_t& nearest_at, std::vector<double>& passed,
                              const Vec3* axis = nullptr, const ir::Arc* turns = nullptr) {
    nearest = kInf;
    nearest_at = 0;
    passed.clear();
    double turned = 0;  // degrees, the arc's way round
    for (size_t j = 0; j < kMaxLookahead; ++j) {
      const TipSegment* s = peek(j);
      if (!s) return std::nullopt;
      if (turns && finite(s->start) && finite(s->end)) turned += turned_deg(*turns, *s);
      if (finite(s->end) && (!turns || turned >= turns->sweep - 1)) {
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

  // How far a program segment turns round the arc's axis, in degrees, positive the arc's way.
  static double turned_deg(const ir::Arc& a, const TipSegment& s) {
    const bool arc = s.raw.kind == gcode::Segment::Kind::Arc;
    if (arc && s.raw.sweep >= 359.999) return 360;  // a full circle: back where it began
    const Vec3 u = arcgeo::radial(a, s.start), v = arcgeo::radial(a, s.end);
    if (u.norm() == 0 || v.norm() == 0) return 0;
    const double ccw = arcgeo::ccw_angle(u, v, a.axis) * 180 / arcgeo::kPi;  // [0, 360)
    const double way = a.dir == ir::ArcDir::Cw && ccw > 0 ? 360 - ccw : ccw;
    return !arc && way > 180 ? way - 360 : way;  // a straight move turns less than half round
  }

  // The programmed feed of a cutting block against the CL's: the same kind (per minute, per
  // revolution), the same value within the machine's feeds.max_rounding (or its max_feed, the
  // clamp); inverse-time blocks are the kinematics' and not compared.
  void feed_ok(const TipSegment& s, const ir::Feed* cl);

  // A tap's feed keeps its pitch: over the hole's depth the tap may drift from its thread by
  // less than half an output increment.
  void tap_ok(const TipSegment& s, const ir::CycleSpec& spec);
  bool coolant_known(ir::CoolantKind kind) const;
  // What the program does at and from a hole's bottom (win_[j]) as the control runs its code:
  // the spindle's part (a tap's reversal, a bore's stop), a feed out, the dwell, the pecks.
  void drills_as_asked(size_t j, const ir::CycleSpec& spec, const Vec3& top, const Vec3& axis);

  // Where blocks lie closer together than the tolerance (a five-axis finish in tiny steps),
  // the first block end within it may not be the CL point's own: of the blocks that follow on
  // the path with their ends within the tolerance (the walk stops at twice it), the one that
  // is nearest in tip and tool axis together — the larger of the two deviations, each over its
  // tolerance, so a block whose axis agrees wins over one whose axis does not — the earlier
  // on a tie.
  template <class OnPath>
  size_t nearest_end(size_t j, double d, OnPath on_path, std::vector<double>& passed, const Vec3& p, const Vec3* axis) {
    auto score = [&](const TipSegment& t, double dist) {
      // A block with another length offset than the CL's tool's stands there by chance (after
      // a tool change with no retract, the last tool's height is the new tool's first point
      // before its G43): the one with the tool's own register is the point's.
      double s = dist / tol_ + (wrong_length_register(t) ? 2 : 0);
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
  void missed(const Vec3& p, double nearest, size_t nearest_at, const char* what);

  // The tool the CL loaded cuts, with its own length offset (a wrong H puts the tip where
  // another tool's length says). Reported once per tool change.
  void tool_ok(const TipSegment& s);
  bool wrong_length_register(const TipSegment& s) const {
    return want_tool_ > 0 && s.raw.tool == want_tool_ && (s.raw.length_register > 0 || offsets_written()) &&
           s.raw.length_register != want_h_;
  }
  // Whether the machine's programs select a length offset register (a mill's G43 H{offset}, a
  // lathe's T word): then one must be in force where the CL's points are reached.
  // (A G43 with no H, or a D: the register comes from elsewhere, and none is read.)
  bool offsets_written() const { return m_.is_lathe() || m_.codes.length_offset.uses(Var::Offset); }

  // A rapid passed over on the way to a CL feed that runs along the CL path (both its ends on
  // it) is the cut made at rapid traverse. One that leaves the path (a retract, a positioning
  // move) is the post's own where the tool comes from no CL point of its own (the first move
  // after a tool change), or where the program goes up the tool axis and comes back to the
  // last point before it cuts on (a retract to unwind or to change branch, RotaryContinuity;
  // down into the stock and back passed, helper-58). Anywhere else the CL's cut
  // from the last point is not made: a G00 through the stock and a feed back up to the point
  // passed (helper-57), and so did a retract, re-tilt and plunge in place of an operation's
  // first cut.
  template <class OnPath>
  void no_rapid_cut(size_t j, OnPath on_path, const Vec3& to) {
    size_t back = 0;  // past the last segment that comes back to the last point
    for (size_t k = 0; k < j && k < win_.size(); ++k)
      if (have_prev_ && finite(win_[k].end) && (win_[k].end - prev_).norm() <= tol_) back = k + 1;
    for (size_t i = 0; i < j && i < win_.size(); ++i) {
      const TipSegment& s = win_[i];
      if (s.raw.kind != gcode::Segment::Kind::Rapid || s.raw.from_cycle) continue;
      // (A move in machine coordinates, G53 or G28, goes where no part position is known.)
      const bool placed = finite(s.start) && finite(s.end);
      const double off = placed ? std::max(on_path(s.start), on_path(s.end)) : kInf;
      if (placed && (s.end - s.start).norm() > tol_ && off <= tol_) {
        fail(loc_, s.raw.line, "this CL feed move is made at rapid traverse (G00)", 0);
        return;
      }
      // Out and back goes up, along the tool axis: a G00 down into the stock and back up to the
      // point passed (helper-58).
      const double down = finite(s.end) && s.axis.norm() > 0 ? -(s.end - prev_).dot(s.axis.normalized()) : 0;
      if (i < back && have_prev_ && !s.rotates && down > tol_) {
        fail(loc_, s.raw.line,
             "the program leaves the CL's cut at " + xyz(prev_) + " at rapid traverse (G00) " + fixed_text(down, 4) +
                 " down along the tool axis",
             down);
        return;
      }
      if (off > tol_ && have_prev_ && cut_from_point_ && i >= back) {
        fail(loc_, s.raw.line,
             "the program leaves the CL's cut from " + xyz(prev_) + " to " + xyz(to) + " at rapid traverse (G00), " +
                 (placed ? fixed_text(off, 4) + " off its path" : std::string("in machine coordinates")) +
                 ": that cut is not made",
             placed ? off : 0);
        return;
      }
    }
  }

  // The segment at j reached CL point p: the segments before it were passed over.
  void reached(size_t j, const Vec3& p, const Vec3& axis, bool rapid, const std::vector<double>& passed);

  // --- CL records --------------------------------------------------------------------------

  void point(const Vec3& p, const Vec3& axis, bool rapid);
  void rapid_stays_above(size_t j, const Vec3& p, const Vec3& axis);

  // Which way a CL arc turns, by the CL's own word (lowering's `hint`), and whether the move
  // entering it agrees: a tangent move (at least 20 output increments long in the arc's plane,
  // within 10 degrees of tangent) that runs against the arc's sense makes the CL ambiguous.
  ir::ArcDir arc_sense(const ir::Arc& a);

  void arc(const ir::Arc& a0);

  // A GOTO of a CYCLE: a hole at the point, down the tool axis by the cycle's depth.
  void hole(const Vec3& point, const Vec3& tool_axis);

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

  void rough_arc(const ir::Arc& a0);

  void end_rough();

  // After a cycle found wrong: the rest of its moves are not compared one by one.
  void skip_cycle_segments();

  // --- lathe grooves: the cycle's order is its own; every CL cut must be on its path --------

  // `record`: the CYCLE/FACE|RADIUS record of the section, null for a GRV section.
  void begin_groove(const ir::GrooveSpec* record = nullptr);

  // A groove's CL feed move: its end and its middle must each lie on a feed of the program
  // (the cycle pecks in its own order, so the order is not checked).
  void groove_point(const Vec3& p, bool rapid);

  // Is `q` (on the CL move to `p`) on a cutting move of the program (or, `cycle_shift_ok`, on a
  // groove cycle's own rapid shift), searched from the window's segment `from`? False,
  // reported, if not.
  bool groove_cut(const Vec3& q, const Vec3& p, bool cycle_shift_ok, size_t from = 0);

  void end_groove();

  // After a section whose rapids were not matched one by one (a groove, a thread): the rapids
  // that bring the tool to the section's last CL point are the section's, not the next
  // record's (a rapid whose ends both lie on a following arc is not that arc cut at rapid).
  void consume_rapids_to(const Vec3& p);

  // --- lathe threads: each CL thread cut is a synchronised cut of the program at the lead,
  // and each synchronised cut of the program is one of the CL's (a pass too deep scraps the
  // thread). Cycles (G92, G76) run their passes in their own order, as grooves do. -----------

  void begin_thread(const ir::ThreadMark& t);

  bool along_thread(const Vec3& from, const Vec3& to) const;

  void thread_point(const Vec3& p, bool rapid);

  // The CL cut from `from` to `p` must be one synchronised cut of the program: its end and its
  // middle on it (finishing passes at one depth each take a cut of their own), at the lead.
  void thread_cut(const Vec3& from, const Vec3& p, double lead);

  void end_thread();

  // --- limits --------------------------------------------------------------------------

  void check_limits(const TipSegment& s);

  void check_travel();

  const Machine& m_;
  ProgramReader& rd_;
  Diagnostics& d_;
  VerifyReport& rep_;
  const double tol_, axis_tol_;
  const double axis_mid_tol_;  // degrees, halfway through a block (kin::kMidBlockAxisTolerance)
  double k_ = 1;
  bool five_axis_ = false, table_ = false;
  Ring<TipSegment> win_;
  std::vector<ir::Vec3> samples_;        // points along the CL arc being checked (reused)
  std::vector<arcgeo::ArcProbe> probes_;  // the program arcs of the window a CL arc is checked against (reused)
  std::vector<double> passed_;
  SourceLoc loc_;
  Vec3 prev_ = Vec3::Zero();  // the last CL point
  bool have_prev_ = false;
  // prev_ is a CL point the tool has been followed to with the tool now in the spindle (not
  // the last tool's: after a tool change the post positions the new tool as it must).
  bool cut_from_point_ = false;
  Vec3 prev_axis_ = Vec3::UnitZ();  // the tool axis at prev_, where point() or arc() set it
  bool prev_axis_known_ = false;
  Vec3 at_ = Vec3::Zero();    // where the program has taken the tool (the last segment passed)
  Vec3 at_axis_ = Vec3::Zero();  // the tool axis there
  bool have_at_ = false;
  ir::Frame frame_;
  kin::RotaryIndexing indexing_;
  ir::Feed cl_feed_;          // the CL's feed in force
  SourceLoc cl_feed_loc_;
  bool cl_spindle_ = false;  // the CL's spindle turns (a SPINDL, no SPINDL/OFF since)
  double cl_rpm_ = 0;         // the CL's speed in rpm (0: none, or a surface speed)
  double cl_surface_ = 0;     // the CL's surface speed, output units per minute (0: none)
  double cl_clamp_ = 0;       // its MAXRPM (0: none given)
  bool speed_said_ = false;    // a cut at another speed reported (once until it is right again)
  bool cl_coolant_ = false;    // the CL's coolant is on, with a code the reader knows (M07, M08, M88, M83)
  bool coolant_said_ = false;  // a cut with the coolant off reported (once until it is on again)
  // Dwells (DELAY) since the last point compared, in seconds: the CL's and the program's G04s
  // (a cycle's own dwell at a hole's bottom is the cycle's, judged with the hole).
  double cl_dwell_ = 0, prog_dwell_ = 0;
  bool cl_dwell_known_ = true;  // false: a dwell in revolutions with no rpm to time it by
  SourceLoc cl_dwell_first_, cl_dwell_loc_;  // the first and last DELAY summed
  bool dwell_in_cut_ = false;   // a G04 summed stands before a feed move
  bool insert_dwell_ = false;   // the CL asks for a dwell through INSERT/G04: longer than its DELAYs is its own
  int dwell_line_ = 0;          // the G-code line to name: the last G04's move, else the first consumed
  double dwell_consumed_ = 0;   // every dwell consumed so far, G04 or a cycle's (the rest came after the last move)
  int cl_spindle_code_ = 0;  // the M code (3, 4) the machine writes for the CL's direction; 0: not known
  bool direction_said_ = false;  // a cut with the spindle turning the other way was reported
  bool spindle_said_ = false;  // a cut with the spindle stopped reported, and it has not turned since
  int cl_comp_ = 0;           // the CL's cutter compensation, as the program's: 0 none, 1 G41, 2 G42
  SourceLoc cl_comp_loc_;     // its CUTCOM
  bool cancelling_ = false;   // CUTCOM/OFF after compensation, and no straight cut across since
  bool comp_said_ = false;    // a cut with other compensation than the CL's reported, and they have not agreed since
  int cl_comp_reg_ = 0;       // the CUTCOM's register (0: the tool's own)
  bool register_said_ = false;  // a cut with another D register than the CL's reported
  bool have_cl_feed_ = false;
  double increment_ = 0;      // one output increment of Z
  double rotary_increment_ = 0;  // the coarsest rotary axis's output increment, degrees
  double dwell_slack_ = 0;       // a dwell's rounding in this machine's words (dwell_slack)
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
  bool groove_record_ = false;  // the section is a CYCLE/FACE|RADIUS record's
  bool groove_face_ = false;    // ... of a face groove (plunges along Z)
  size_t groove_reach_ = 0;
  bool thread_on_ = false;
  std::optional<ir::RoughMark> rough_;  // a CYCLE/ROUGH section being read: its profile is kept
  SourceLoc rough_loc_;
  std::vector<Want> rough_profile_;
  ir::ThreadMark thread_;
  std::vector<std::pair<Vec3, Vec3>> thread_cuts_;  // the CL's thread cuts of the section
  std::vector<bool> thread_used_;  // the program's segments (window index) a CL thread cut took
  size_t thread_next_ = 0;  // the window's segment after the last thread cut matched
  int limit_reported_[26] = {};
  double lo_[3] = {kInf, kInf, kInf}, hi_[3] = {-kInf, -kInf, -kInf};
  int lo_line_[3] = {}, hi_line_[3] = {};
  SourceLoc lo_loc_[3], hi_loc_[3];
};

}  // namespace clpc::verify_detail
