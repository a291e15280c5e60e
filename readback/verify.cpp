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

#include <unistd.h>

#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "machine/block_check.h"
#include "readback/comparison.h"

namespace clpc {

namespace verify_detail {

void Comparison::operation(const ir::Operation& op) {
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
            finish_cycle_motion();
            // (The tool in the spindle loaded again writes no change: it stays in the cut. CATIA
            // loads it at every operation; taken for a change, a retract in place of a cut passed;
            // helper-58.)
            if (x.tool != want_tool_ || (x.length_offset > 0 ? x.length_offset : x.tool) != want_h_) cut_from_point_ = false;
            if (!rep_.operations.empty()) rep_.operations.back().tool = x.tool;
            want_tool_ = x.tool;
            want_h_ = x.length_offset > 0 ? x.length_offset : x.tool;
            want_tool_loc_ = loc_;
            tool_reported_ = false;
          } else if constexpr (std::is_same_v<T, ir::Insert>) {
            // A block of the user's that may move the axes (G53 Z0.): the CL's next cut starts
            // where it leaves the tool, which the post positions as after a tool change.
            // (Not any M code may_move_axes fears: after INSERT/M88 the post writes the CL's move
            // whole, and a retract in its place passed; helper-58.)
            if (moves_axes_by_itself(op.str(x.text))) cut_from_point_ = false;
            // INSERT/G04 P1000: the CL asks for a dwell in the control's own words (shops put one
            // at a hole's bottom through INSERT in Mastercam, PowerMill, hyperMILL). Its time is
            // the control's reading of the block: the program may dwell longer than the CL's
            // DELAYs there, never shorter (helper-66: refused as a dwell the CL has no DELAY for;
            // helper-69: a DELAY beside it cut short passed).
            for (double g : code_numbers(control_words(op.str(x.text)), 'G'))
              if (g == 4) insert_dwell_ = true;
          } else if constexpr (std::is_same_v<T, ir::SetFrame>) {
            frame_ = x.frame;
          } else if constexpr (std::is_same_v<T, ir::CutterComp>) {
            const int was = cl_comp_;
            cl_comp_ = x.side == ir::CompSide::Off ? 0 : x.side == ir::CompSide::Left ? 1 : 2;
            cl_comp_reg_ = x.reg;
            cancelling_ = cl_comp_ == 0 && was != 0;
            cl_comp_loc_ = loc_;
          } else if constexpr (std::is_same_v<T, ir::Dwell>) {
            if (x.revolutions && !(cl_rpm_ > 0)) cl_dwell_known_ = false;
            if (cl_dwell_ == 0) cl_dwell_first_ = loc_;
            cl_dwell_ += x.revolutions ? (cl_rpm_ > 0 ? x.value * 60 / cl_rpm_ : 0) : x.value;
            cl_dwell_loc_ = loc_;
          } else if constexpr (std::is_same_v<T, ir::Coolant>) {
            cl_coolant_ = x.kind != ir::CoolantKind::Off && coolant_known(x.kind);
          } else if constexpr (std::is_same_v<T, ir::Spindle>) {
            finish_cycle_motion();
            cl_spindle_ = x.dir != ir::SpindleDir::Off;
            cl_rpm_ = cl_spindle_ && x.mode == ir::SpindleMode::Rpm ? x.speed : 0;
            // A surface speed per minute in output units (m/min in the IR), as high as the
            // machine's S may write it (S37 for 120 ft/min, 36.6 m/min), and its clamp.
            if (cl_spindle_ && x.mode == ir::SpindleMode::SurfaceSpeed) {
              const bool inch_out = m_.units == ir::Units::Inch;
              double s_word = x.speed;                                // m/min
              if (inch_out) s_word /= 0.3048;                         // ft/min
              s_word += 0.5 * std::abs(dequantize(1, m_.format('S')));
              cl_surface_ = s_word * (inch_out ? 12 : 1000);
            } else {
              cl_surface_ = 0;
            }
            cl_clamp_ = cl_surface_ > 0 ? x.max_rpm : 0;
            // The M code the machine starts this direction with (M03 clockwise on the built-ins).
            const std::vector<double> m =
                code_numbers(x.dir == ir::SpindleDir::Ccw ? m_.codes.spindle_ccw.text : m_.codes.spindle_cw.text, 'M');
            cl_spindle_code_ = m.empty() ? 0 : int(std::lround(m.front()));
          } else if constexpr (std::is_same_v<T, ir::Move>) {
            Vec3 p = model(x.point), a = model_dir(x.axis);
            if (x.kind == ir::MoveKind::From) {
              prev_ = p;
              prev_axis_known_ = false;
              have_prev_ = true;
            } else if (rough_) {
              rough_profile_.push_back({x.kind == ir::MoveKind::Rapid ? stock::Step::Kind::Rapid : stock::Step::Kind::Feed, p,
                                        Vec3::Zero(), false, loc_});
            } else if (thread_on_) {
              thread_point(p, x.kind == ir::MoveKind::Rapid);
            } else if (cycle_on_ && !groove_) {
              prev_axis_known_ = false;
              hole(x.point, x.axis);
            } else if (groove_) {
              groove_point(p, x.kind == ir::MoveKind::Rapid);
            } else {
              point(p, a, x.kind == ir::MoveKind::Rapid);
            }
            if (x.kind != ir::MoveKind::From) sample(p);
            if (x.kind != ir::MoveKind::From) cancelling_ = false;  // only an arc right after CUTCOM/OFF keeps the offset
          } else if constexpr (std::is_same_v<T, ir::Arc>) {
            if (rough_) {
              rough_arc(x);
            } else {
              arc(x);
              sample(model(x.end));
            }
            cancelling_ = false;
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
            begin_groove(&op.grooves.at(x.spec));
          } else if constexpr (std::is_same_v<T, ir::GrooveMark>) {
            if (x.begin) begin_groove();
            else end_groove();
          } else if constexpr (std::is_same_v<T, ir::CycleOff>) {
            if (groove_) {
              end_groove();
            } else {
              cycle_on_ = false;
              // The cycle left the tool at its return, not at the last hole's CL point (a cycle
              // written as moves returns with a plain G00; helper-58).
              cut_from_point_ = false;
            }
          }
        },
        in.op);
  }
}

void Comparison::end() {
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
  // A G04 after the last move belongs to no segment: what the program dwelt in all, less what
  // came before its moves and at its holes' bottoms (the cycles' P counted as the missing
  // G04's: a DELAY after the last move deleted passed; helper-55).
  prog_dwell_ += std::max(0.0, rd_.totals().dwell_minutes * 60 - dwell_consumed_);
  dwell_ok();
  check_travel();
}

const TipSegment* Comparison::peek(size_t i) {
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

// The last cycle's own motion out of its last hole (a tap's feed out, the return), judged
// with the cycle's spindle before the CL changes it: left for the next CL point, a tap at
// S200 was judged against the next tool's S6000 (helper-56).
void Comparison::finish_cycle_motion() {
  if (cycle_on_ || groove_) return;
  size_t n = 0;
  while (const TipSegment* s = peek(n)) {
    if (!s->raw.from_cycle) break;
    ++n;
  }
  consume(n);
}

void Comparison::consume(size_t n) {
  for (size_t i = 0; i < n && !win_.empty(); ++i) {
    const gcode::Segment& raw = win_.front().raw;
    prog_dwell_ += raw.dwell_before;
    dwell_consumed_ += raw.dwell_before + raw.dwell;
    if (raw.dwell_before > 0 || dwell_line_ == 0) dwell_line_ = raw.line;
    if (raw.dwell_before > 0 && raw.kind != gcode::Segment::Kind::Rapid) dwell_in_cut_ = true;
    check_limits(win_.front());
    spindle_ok(win_.front());
    comp_ok(win_.front());
    if (finite(win_.front().end)) {
      at_ = win_.front().end;
      at_axis_ = win_.front().axis;
      have_at_ = true;
    }
    win_.pop_front();
  }
}

// The G04s the program makes dwell what the CL's DELAYs ask: G04 X1250. for 1.25 s (1250 s
// with the point), a dwell written twice as long, one deleted or one inserted mid-contour
// passed (helper-52). Compared where the program has been followed to a CL point (a G04 is
// written before the move after its DELAY, so it is counted with that move), and at the end.
// Within a cycle, a groove or a thread the dwells are summed, and compared at the first point
// after it. The program may dwell longer than the CL before a rapid: a machine's own codes
// dwell there (a G04 in its tool change or start for the spindle or the coolant); never
// shorter, and never longer before a cut.
void Comparison::dwell_ok() {
  if (cycle_on_ || groove_ || thread_on_ || rough_) return;
  if (prog_dwell_ == 0 && cl_dwell_ == 0 && cl_dwell_known_) {  // (almost every point)
    dwell_line_ = 0;
    insert_dwell_ = false;
    return;
  }
  const double slack = dwell_slack_;
  const bool shorter = prog_dwell_ < cl_dwell_ - slack, longer = !insert_dwell_ && prog_dwell_ > cl_dwell_ + slack;
  if (cl_dwell_known_ && (shorter || (longer && dwell_in_cut_))) {
    std::string cl = "the CL has no DELAY here";
    if (cl_dwell_ > 0)
      cl = cl_dwell_first_.line == cl_dwell_loc_.line
               ? "the CL's DELAY (line " + std::to_string(cl_dwell_loc_.line) + ") is " + fixed_text(cl_dwell_, 3) + " s"
               : "the CL's DELAYs (lines " + std::to_string(cl_dwell_first_.line) + " to " +
                     std::to_string(cl_dwell_loc_.line) + ") make " + fixed_text(cl_dwell_, 3) + " s";
    fail(loc_, dwell_line_, "the program dwells " + fixed_text(prog_dwell_, 3) + " s before this move, " + cl, 0);
  }
  cl_dwell_ = prog_dwell_ = 0;
  cl_dwell_known_ = true;
  dwell_in_cut_ = false;
  insert_dwell_ = false;
  dwell_line_ = 0;
}

// A dwell's rounding: half an increment of the word codes.dwell writes it in (P, X, U; whole
// milliseconds where P takes no point), 1.5 ms at least. (The compile writes the time rounded
// to that word, so no more is lost. Taken from every dwell letter, a mill's unused format.U of
// one decimal let any dwell be 50 ms off; helper-55.)
double Comparison::dwell_slack(const Machine& m) {
  double slack = 0.0015;
  for (const CodeTemplate::Word& w : m.codes.dwell.words) {
    const char letter = CodeTemplate::letter(w);
    bool time = false;
    for (const CodeTemplate::Piece& p : w) time = time || p.var == int(Var::Seconds) || p.var == int(Var::Milliseconds);
    if (!time || letter == 0) continue;
    const AddressFormat& f = m.format(letter);
    if (f.point != AddressFormat::Point::Never || f.decimals > 0)
      slack = std::max(slack, 0.5 * std::pow(10.0, -f.decimals) + 1e-9);
  }
  return slack;
}

// Compared on a mill's cuts across the tool axis: the post starts and ends G41/G42 on the move
// across after a plunge or a retract (CutterComp.StartsAndEndsOnAMoveInThePlane), and a
// rapid after a tool change positions before it. (A lathe's tool nose compensation is not
// compared.)
void Comparison::comp_ok(const TipSegment& s) {
  if (m_.is_lathe() || s.raw.kind == gcode::Segment::Kind::Rapid || !finite(s.start) || !finite(s.end)) return;
  const Vec3 d = s.end - s.start;
  const Vec3 ax = s.axis.norm() > 0 ? Vec3(s.axis.normalized()) : Vec3(Vec3::UnitZ());
  if ((d - d.dot(ax) * ax).norm() <= tol_) return;
  // The control cancels on a straight move: an arc right after CUTCOM/OFF keeps the offset
  // (RapidSplit.NotTheMoveThatCarriesG40AfterAnArc) until the first straight move across.
  if (cancelling_ && s.raw.kind == gcode::Segment::Kind::Arc) return;
  cancelling_ = false;
  if (s.raw.comp == cl_comp_) {
    comp_said_ = false;
    register_ok(s);
    return;
  }
  if (comp_said_) return;
  comp_said_ = true;
  static const char* const kCode[] = {"no cutter compensation (G40)", "G41 (left)", "G42 (right)"};
  fail(loc_, s.raw.line,
       std::string("the program cuts here with ") + kCode[s.raw.comp] + ", where the CL has " +
           (cl_comp_ == 0 ? std::string("no cutter compensation") + (cl_comp_loc_.line > 0 ? " (CUTCOM/OFF at line " + std::to_string(cl_comp_loc_.line) + ")" : std::string())
                          : std::string(cl_comp_ == 1 ? "CUTCOM/LEFT" : "CUTCOM/RIGHT") + " (line " + std::to_string(cl_comp_loc_.line) + "), " + kCode[cl_comp_]) +
           ": the cut is offset by the cutter's radius from where the CL puts it",
       0);
}

// The register G41/G42 takes the cutter's radius from: the CUTCOM's, or the tool's own number
// (D3 made D13 passed: a radius off by what D13 holds; helper-49). Judged where the machine's
// code writes a register ({register}); said once until they agree.
void Comparison::register_ok(const TipSegment& s) {
  const CodeTemplate& code = cl_comp_ == 1 ? m_.codes.comp_left : m_.codes.comp_right;
  const int want = cl_comp_reg_ > 0 ? cl_comp_reg_ : want_tool_;
  if (cl_comp_ == 0 || !code.uses(Var::Register) || want <= 0 || s.raw.comp_register == want) {
    register_said_ = false;
    return;
  }
  if (register_said_) return;
  register_said_ = true;
  fail(loc_, s.raw.line,
       "the program compensates here with " +
           (s.raw.comp_register > 0 ? "register D" + std::to_string(s.raw.comp_register) : std::string("no D register")) +
           ", where the CL's CUTCOM (line " + std::to_string(cl_comp_loc_.line) + ") takes the radius from register " +
           std::to_string(want) + (cl_comp_reg_ > 0 ? "" : " (the tool's own)"),
       0);
}

// A cut made with the spindle stopped where the CL has it turning (after SPINDL, before
// SPINDL/OFF): the tool is fed into the part without turning. Said once until it turns again.
void Comparison::spindle_ok(const TipSegment& s) {
  const bool cut = s.raw.kind != gcode::Segment::Kind::Rapid && finite(s.start) && (s.end - s.start).norm() > tol_;
  // Turning the other way (M04 where the CL says CLW): the cutter rubs, or a tap strips its
  // thread. Said once until the direction is right again.
  if (cut && cl_spindle_ && s.raw.spindle && cl_spindle_code_ != 0 && s.raw.spindle_code != 0 &&
      s.raw.spindle_code != cl_spindle_code_) {
    if (!direction_said_)
      fail(loc_, s.raw.line, "the program cuts here with the spindle turning M0" + std::to_string(s.raw.spindle_code) +
                                 ", where the CL turns it the way the machine's M0" + std::to_string(cl_spindle_code_) + " does",
           0);
    direction_said_ = true;
    return;
  }
  if (s.raw.spindle && s.raw.spindle_code == cl_spindle_code_) direction_said_ = false;
  // A lathe never turns faster than the CL asks where it cuts: its rpm, or its surface speed at
  // the cut's radius within its clamp. A G50 clamp deleted, G96 S raised, G97 S1000 made S3000
  // passed (helper-59, helper-60). (Slower is left: a thread or a drill on centre runs at the
  // speed fixed where it starts; threads and cycles are their own.)
  if (cut && cl_spindle_ && s.raw.spindle && m_.is_lathe() && !s.raw.thread && !s.raw.from_cycle &&
      (cl_rpm_ > 0 || cl_surface_ > 0)) {
    double want = cl_rpm_;
    if (cl_surface_ > 0) {
      const double r = std::abs((s.start.x() + s.end.x()) / 2);
      want = r > 1e-9 ? cl_surface_ / (2 * arcgeo::kPi * r) : kInf;
      if (cl_clamp_ > 0) want = std::min(want, cl_clamp_);
    }
    const double slack = 0.01 * want + std::abs(dequantize(1, m_.format('S')));
    if (std::isfinite(want) && s.raw.rpm > want + slack) {
      if (!speed_said_)
        fail(loc_, s.raw.line, "the program turns the spindle at " + fixed_text(s.raw.rpm, 0) + " rpm here, faster than the CL's " +
                                   (cl_surface_ > 0 ? "surface speed" + std::string(cl_clamp_ > 0 ? " within its clamp" : "") +
                                                          " makes it at this radius (" + fixed_text(want, 0) + " rpm)"
                                                    : "speed (" + fixed_text(want, 0) + " rpm)"),
             0);
      speed_said_ = true;
    }
  }
  // The speed: a mill's S is the CL's rpm, rounded to S's increment. S5000 made S500 or S50000,
  // and a drill's S0, passed (helper-49).
  // (A cycle's way out of a hole, a tap's feed out, is the hole's, at its speed: a SPINDL between
  // two holes was read as the speed for the last one's way out, and a right program refused;
  // helper-67, helper-70.)
  const bool out_of_hole = s.raw.from_cycle && s.raw.end.z() > s.raw.start.z();
  if (cut && cl_spindle_ && s.raw.spindle && cl_rpm_ > 0 && !m_.is_lathe() && !out_of_hole) {
    const double slack = 0.5 * std::abs(dequantize(1, m_.format('S'))) + 1e-9 * cl_rpm_;
    if (std::abs(s.raw.rpm - cl_rpm_) > slack) {
      if (!speed_said_)
        fail(loc_, s.raw.line, "the program cuts here at S" + num_text(s.raw.rpm) + ", the CL's spindle speed is " +
                                   num_text(cl_rpm_) + " rpm",
             0);
      speed_said_ = true;
    } else {
      speed_said_ = false;
    }
  }
  // The coolant: a cut with none on where the CL has it on (M08 made M09 passed; helper-49).
  if (cut && cl_coolant_ && !s.raw.coolant) {
    if (!coolant_said_)
      fail(loc_, s.raw.line, "the program cuts here with the coolant off, where the CL has it on", 0);
    coolant_said_ = true;
  } else if (s.raw.coolant) {
    coolant_said_ = false;
  }
  if (!cut || !cl_spindle_ || s.raw.spindle) {
    if (s.raw.spindle) spindle_said_ = false;
    return;
  }
  if (spindle_said_) return;
  spindle_said_ = true;
  fail(loc_, s.raw.line, "the program cuts here with the spindle stopped (no M03/M04 since an M05, M19, M00, M01 or tool "
                         "change), where the CL has it turning",
       0);
}

// Whether the machine turns this coolant on with a code the reader knows (M07, M08, M88, M83),
// or floods for it: a machine with other codes, or none, is not judged.
bool Comparison::coolant_known(ir::CoolantKind kind) const {
  const Codes& c = m_.codes;
  const CodeTemplate& t = kind == ir::CoolantKind::Mist ? c.coolant_mist
                          : kind == ir::CoolantKind::Thru ? c.coolant_thru
                          : kind == ir::CoolantKind::Air  ? c.coolant_air
                          : kind == ir::CoolantKind::Tap  ? c.coolant_tap
                                                          : c.coolant_flood;
  const std::vector<double> m = code_numbers(t.empty() ? c.coolant_flood.text : t.text, 'M');
  return !m.empty() && std::all_of(m.begin(), m.end(), [](double v) { return v == 7 || v == 8 || v == 88 || v == 83; });
}

bool Comparison::already_there(const Vec3& p, const Vec3* axis) {
  if (!have_at_ || (at_ - p).norm() > tol_) return false;
  // The tip is there, but not the tool axis (a turn of the rotaries on the spot still to come):
  // the point is reached by the block that turns them. Taken as reached, a tilt moved into the
  // next cut passed, the axis 15 degrees off at the CL point.
  if (axis && five_axis_ && at_axis_.norm() > 0 &&
      kin::angle_between(at_axis_.normalized(), axis->normalized()) > axis_tol_)
    return false;
  deviate((at_ - p).norm(), loc_, 0);
  // The blocks after that come nearer the point go with it; one that goes away again is the
  // way on to the next point (where the path turns back on itself, a cusp, the blocks past the
  // turn lie within the tolerance too: taken here, the turn's own point was never reached).
  double nearest = (at_ - p).norm();
  while (const TipSegment* s = peek(0)) {
    const double d = finite(s->end) ? (s->end - p).norm() : kInf;
    if (d > tol_ || d > nearest || s->rotates) break;
    nearest = d;
    deviate(d, loc_, s->raw.line);
    consume(1);
  }
  return true;
}

void Comparison::take_reader_problems() {
  for (const gcode::Problem& p : rd_.take_problems()) fail(loc_, p.line, "the program: " + p.message, 0);
}

void Comparison::fail(SourceLoc loc, int gline, const std::string& msg, double deviation) {
  if (!rep_.operations.empty()) ++rep_.operations.back().problems;
  std::string text = msg;
  if (gline > 0) text += " [G-code line " + std::to_string(gline) + "]";
  d_.error(loc, text);
  ++rep_.problem_count;
  if (rep_.problems.size() < kMaxStored) rep_.problems.push_back({loc, gline, msg, deviation});
  if (deviation > 0) deviate(deviation, loc, gline);
}

void Comparison::deviate(double d, SourceLoc loc, int gline) {
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

void Comparison::begin_operation(const ir::Operation& op) {
  end_operation();
  OperationCheck o;
  o.number = op.number;
  o.name = op.name;
  o.loc = op.loc;
  o.tool = want_tool_;
  rep_.operations.push_back(std::move(o));
  counts_at_start_ = {rep_.cl_points, rep_.cl_arcs, rep_.cl_holes, rep_.cl_groove_points};
}

void Comparison::end_operation() {
  if (rep_.operations.empty()) return;
  OperationCheck& o = rep_.operations.back();
  o.points = rep_.cl_points - counts_at_start_[0];
  o.arcs = rep_.cl_arcs - counts_at_start_[1];
  o.holes = rep_.cl_holes - counts_at_start_[2];
  o.groove_points = rep_.cl_groove_points - counts_at_start_[3];
}

void Comparison::sample(const Vec3& p) {
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

bool Comparison::axis_ok(const TipSegment& s, const Vec3& axis) {
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

// Between CL points the control turns the rotaries at proportional rates: near the pole C
// swings far while B barely moves, and the tool axis halfway through the block is not on the
// CL's sweep from the last point's axis to this one's (10 degrees off under TCPC, certified;
// helper-63). Each turning feed block on the way is held to the sweep within the mid-block
// axis tolerance (the tip is held by the line check).
void Comparison::axis_between_ok(size_t j, const Vec3& axis) {
  if (!five_axis_ || !prev_axis_known_ || !(axis_mid_tol_ > 0)) return;
  const Vec3 a0 = prev_axis_.normalized(), a1 = axis.normalized();
  for (size_t i = 0; i <= j && i < win_.size(); ++i) {
    const TipSegment& b = win_[i];
    if (!b.rotates || b.raw.kind == gcode::Segment::Kind::Rapid || b.raw.from_cycle) continue;
    // A block that ends between the CL points (the compile's split of the move) ends on the
    // sweep, as its tip ends on the CL line: within the axis tolerance.
    if (i < j && b.axis.norm() > 0) {
      const double end = kin::off_sweep(b.axis.normalized(), a0, a1);
      if (end > axis_tol_) {
        fail(loc_, b.raw.line, "the tool axis where this block ends, between CL points, is " + fixed_text(end, 4) +
                                   " degrees off the CL's sweep from one point's axis to the next", 0);
        return;
      }
    }
    // Turning the rotaries by d degrees in all turns the axis no further than d from where it
    // starts, so halfway it is within d/2 of an end of the sweep: most blocks end here.
    double turned = 0;
    for (size_t k = 0; k < 3; ++k) turned += std::abs(b.raw.rotary[k] - b.raw.rotary_start[k]);
    if (!(turned > 2 * axis_mid_tol_)) continue;
    // Through the pole (the tilt's sign changes) the axis leaves the sweep by as far as the
    // sweep passes from the pole, whatever the points: not judged (docs/verify-and-plot.md;
    // the pass keeps the branch where the sweep stays clear of the pole).
    if (rd_.through_pole(b)) continue;
    // Without TCPC the tip's bow is the measure (worst_while_turning); the pass splits for it.
    if (!b.raw.tcp) continue;
    auto off = [&](double t) { return kin::off_sweep(rd_.axis_at(b, t).normalized(), a0, a1); };
    double dev = off(0.5);
    if (dev > axis_mid_tol_ / 4) dev = std::max(dev, worst_point(off));
    if (dev > axis_mid_tol_) {
      fail(loc_, b.raw.line,
           "halfway between CL points the tool axis is " + fixed_text(dev, 3) + " degrees off the CL's sweep from one "
           "point's axis to the next (the control turns the rotaries at proportional rates; the move wants more points)",
           0);
      return;
    }
  }
}

double Comparison::worst_while_turning(const TipSegment& s, const LineDistance& line) {
  // A tip that moves straight (TCPC, a tilted plane) does not bow: the distance to the CL
  // line, convex along a straight move, is largest at one of its ends. Exact, where the
  // search only comes near it, and it spares the search on every block of a TCPC finish.
  if (ProgramReader::tip_moves_straight(s)) return std::max(line(s.start), line(s.end));
  if (s.index != bow_.index || line.from != bow_.from || line.to != bow_.to || line.active != bow_.active)
    bow_ = {s.index, line.from, line.to, line.active, worst_point([&](double t) { return line(rd_.tip_at(s, t)); })};
  return bow_.dev;
}

bool Comparison::on_last_hole_axis(const TipSegment& s) const {
  if (!have_hole_) return false;
  auto off_axis = [&](const Vec3& p) {
    Vec3 d = p - hole_point_;
    return (d - d.dot(hole_axis_) * hole_axis_).norm();
  };
  return off_axis(s.end) <= tol_ && (!finite(s.start) || off_axis(s.start) <= tol_);
}

void Comparison::feed_ok(const TipSegment& s, const ir::Feed* cl) {
  if (s.raw.kind == gcode::Segment::Kind::Rapid || s.raw.inverse_time || !cl || cl->mode == ir::FeedMode::InverseTime) return;
  const bool per_rev = cl->mode == ir::FeedMode::PerRev;
  double want = cl->value * k_;
  if (m_.kinematics.degrees_per_minute && gcode::feeds_combined(s.raw)) {
    // Degrees per minute: F over all the axes, for the tip's own length at the CL feed.
    // Both lengths come from rounded words, and the tip's ends are checked only within the
    // tolerance: on a short block they are known only within that (one 0.001 mm step on a
    // 0.003 mm move is a third of its F). F is wrong only outside what those limits allow.
    const double tip = (s.end - s.start).norm();
    if (!(tip > 0)) return;
    const double combined = gcode::combined_length(s.raw, m_.kinematics);
    const double tip_slack = 2 * tol_, combined_slack = 2 * (increment_ + rotary_increment_);
    want *= combined / tip;
    if (tip <= tip_slack) return;  // too short to tell: its time is below what the tolerance sees
    double lo = cl->value * k_ * std::max(0.0, combined - combined_slack) / (tip + tip_slack);
    double hi = cl->value * k_ * (combined + combined_slack) / (tip - tip_slack);
    if (m_.max_feed > 0) {  // written as max_feed where more (the control would clamp it)
      lo = std::min(lo, m_.max_feed);
      hi = std::min(hi, m_.max_feed);
    }
    const double r = m_.feeds.max_rounding;
    if (s.raw.feed < lo * (1 - r) - 1e-12 || s.raw.feed > hi * (1 + r) + 1e-12)
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

void Comparison::tap_ok(const TipSegment& s, const ir::CycleSpec& spec) {
  const double pitch = spec.pitch * k_;
  const double lead = s.raw.per_rev ? s.raw.feed : (s.raw.rpm > 0 ? s.raw.feed / s.raw.rpm : 0);
  const double drift = std::abs(lead - pitch) * (spec.depth * k_) / pitch;
  if (drift >= 0.5 * increment_)
    fail(loc_, s.raw.line, "the tap advances " + fixed_text(lead, 6) + " a turn, its thread's pitch is " + fixed_text(pitch, 6) + ": " +
                               fixed_text(drift, 5) + " off at the bottom",
         drift);
}

void Comparison::missed(const Vec3& p, double nearest, size_t nearest_at, const char* what) {
  const TipSegment* s = std::isfinite(nearest) ? peek(nearest_at) : nullptr;
  std::string msg = std::string(what) + " " + xyz(p) + " is never reached";
  if (s) msg += ": the program comes within " + fixed_text(nearest, 5) + " of it";
  fail(loc_, s ? s->raw.line : 0, msg, std::isfinite(nearest) ? nearest : kInf);
  if (s && nearest <= std::max(20 * tol_, 0.1 / ir::mm_per_unit(m_.units))) consume(nearest_at + 1);
}

void Comparison::tool_ok(const TipSegment& s) {
  if (want_tool_ <= 0 || tool_reported_) return;
  auto cl = [&] { return " (the CL loads tool " + std::to_string(want_tool_) + " at line " + std::to_string(want_tool_loc_.line) + ")"; };
  // No T word at all: the station and offset the last program left (a lathe's T0202 deleted
  // passed; helper-59). (A machine with no tool change cuts with the tool the operator loads.)
  if (s.raw.tool <= 0) {
    if (s.raw.kind == gcode::Segment::Kind::Rapid || m_.codes.tool_change.empty()) return;
    fail(loc_, s.raw.line, "this is cut with no tool selected (no T word)" + cl(), 0);
    tool_reported_ = true;
    return;
  }
  if (s.raw.tool != want_tool_) {
    fail(loc_, s.raw.line, "this is cut with tool " + std::to_string(s.raw.tool) + cl(), 0);
    tool_reported_ = true;
  } else if (wrong_length_register(s)) {
    // Register 0 (G43 H00, a lathe's T0100) is no offset at all: the tip off by the tool's
    // length. It was taken for "none said" and passed.
    fail(loc_, s.raw.line,
         (s.raw.length_register == 0 ? std::string("no tool length offset is in force (register 0)")
                                     : "the tool length offset in force is register " + std::to_string(s.raw.length_register)) +
             ", tool " + std::to_string(want_tool_) + "'s is " + std::to_string(want_h_) + cl(),
         0);
    tool_reported_ = true;
  }
}

bool Comparison::returns_up_the_axis(const TipSegment& s) const {
  if (!finite(s.start) || !finite(s.end)) return false;
  const Vec3 d = s.end - s.start;
  const double along = d.dot(s.axis.normalized());
  return along >= -tol_ && (d - along * s.axis.normalized()).norm() <= tol_;
}

void Comparison::reached(size_t j, const Vec3& p, const Vec3& axis, bool rapid, const std::vector<double>& passed) {
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
  // hole to where the cycle returned it is made by the cycle, at rapid, away from the part,
  // straight up the tool axis. Any other rapid of a cycle is no stand-in for a CL feed.)
  if (!rapid && s.raw.kind == gcode::Segment::Kind::Rapid && !(s.raw.from_cycle && returns_up_the_axis(s)))
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
  if (!rapid) axis_between_ok(j, axis);
  if (s.rotates && have_prev_ && finite(s.start) && !rapid) {
    // Five-axis without TCPC: the tip between the block's ends must stay on the CL line.
    double dev = worst_while_turning(s, LineDistance{prev_, p, true});
    deviate(dev, loc_, s.raw.line);
    if (dev > tol_)
      fail(loc_, s.raw.line, "while the rotaries turn the tool tip leaves the CL line by " + fixed_text(dev, 5) + " at its worst point", dev);
  }
  consume(j + 1);
  dwell_ok();
  cut_from_point_ = true;
}

void Comparison::point(const Vec3& p, const Vec3& axis, bool rapid) {
  ++rep_.cl_points;
  const Vec3 from = prev_;
  const bool have_from = have_prev_;
  const LineDistance on_path{from, p, have_from};
  double nearest;
  size_t at;
  if (already_there(p, &axis)) {
    cut_from_point_ = true;
  } else if (auto j = reach(p, on_path, nearest, at, passed_, &axis)) {
    if (!rapid) no_rapid_cut(*j, on_path, p);
    else rapid_stays_above(*j, p, axis);
    reached(*j, p, axis, rapid, passed_);
  } else {
    missed(p, nearest, at, "CL point");
  }
  incoming_ = rapid || !have_from ? Vec3::Zero() : Vec3(p - from);
  prev_ = p;
  have_prev_ = true;
  have_hole_ = false;
  prev_axis_ = axis;
  prev_axis_known_ = true;
}

// A mill's rapids on the way to a CL rapid point, along the tool axis both CL points share, go
// no lower than the lower of the two (no lower than the point itself after a tool change,
// whose start is the post's): a rapid split goes up first or down last, a retract goes up. A
// G00 down into the stock and across, a dive in the new tool's approach, passed (helper-60).
void Comparison::rapid_stays_above(size_t j, const Vec3& p, const Vec3& axis) {
  if (m_.is_lathe() || !have_prev_ || !prev_axis_known_ || axis.norm() == 0 ||
      kin::angle_between(prev_axis_.normalized(), axis.normalized()) > axis_tol_)
    return;
  const Vec3 ax = axis.normalized();
  const double floor = cut_from_point_ ? std::min(prev_.dot(ax), p.dot(ax)) : p.dot(ax);
  for (size_t i = 0; i < j && i < win_.size(); ++i) {
    const TipSegment& s = win_[i];
    if (s.raw.kind != gcode::Segment::Kind::Rapid || s.raw.from_cycle || !finite(s.end)) continue;
    const double below = floor - s.end.dot(ax);
    if (below > tol_) {
      fail(loc_, s.raw.line,
           "the program's rapid goes " + fixed_text(below, 4) + " lower along the tool axis than the CL's rapid " +
               (cut_from_point_ ? "from " + xyz(prev_) + " " : std::string()) + "to " + xyz(p) + ", to " + xyz(s.end),
           below);
      return;
    }
  }
}

ir::ArcDir Comparison::arc_sense(const ir::Arc& a) {
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

void Comparison::arc(const ir::Arc& a0) {
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
    prev_axis_known_ = false;
    have_prev_ = true;
    return;
  }
  if (!(a.sweep > 0)) a.sweep = arcgeo::sweep_deg(a, a.dir, 1e-7);
  const bool turns = a.extra_turns > 0;  // MOVARC's angle, CIRCLE/TIMES: whole turns (in the sweep)
  const arcgeo::ArcProbe cl(a);
  auto on_arc = [&](const Vec3& q) { return cl.distance(q); };
  double nearest;
  size_t at;
  const double length = a.radius * a.sweep * arcgeo::kPi / 180;
  std::optional<size_t> j;
  if (length <= tol_ && already_there(a.end)) {
    // An arc shorter than the tolerance: the tool is there.
  } else if (!(j = reach(a.end, on_arc, nearest, at, passed_, nullptr, turns ? &a : nullptr))) {
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
    cl.interior_points(n, samples_);
    for (int i = 1; i < n; ++i) {
      const Vec3& q = samples_[size_t(i - 1)];
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
      prev_axis_known_ = false;
    prev_axis_known_ = false;
      have_prev_ = true;
      have_hole_ = false;
      return;
    }
    no_rapid_cut(*j, on_arc, a.end);
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
  prev_axis_known_ = false;
  have_prev_ = true;
  have_hole_ = false;
}

void Comparison::hole(const Vec3& point, const Vec3& tool_axis) {
  ++rep_.cl_holes;
  const ir::CycleSpec& spec = cycle_;
  incoming_ = Vec3::Zero();
  const Vec3 top = model(point), axis = model_dir(tool_axis).normalized();
  const Vec3 bottom = top - axis * (spec.depth * k_);
  // The same hole again (a GOTO repeated in the cycle): drilled already, nothing to reach.
  if (have_hole_ && (hole_point_ - top).norm() <= tol_ && (hole_bottom_ - bottom).norm() <= tol_) return;
  // Until this hole is reached the last hole is the one before: its feed out (a bore's, written
  // as moves) is passed over on the way here. Taken as this one, every bore after the first
  // was refused on machines without G85.
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
    // A rapid down the hole's axis stops at the CL's R plane (CLEAR, RAPTO), or where the cycle
    // has fed to already (a peck cycle's rapid back into the hole): an R below the CL's rapids
    // into what the CL feeds through (R-9. on a hole whose top is Z0 passed).
    const double r_plane = spec.clearance * k_;
    double floor = r_plane;  // the lowest height along the axis a rapid may reach
    for (size_t i = 0; i < *j; ++i) {
      const TipSegment& d = win_[i];
      if (!finite(d.start) || !finite(d.end) || on_axis(d.start) > tol_ || on_axis(d.end) > tol_) continue;
      const double end_height = (d.end - top).dot(axis);
      if (d.raw.kind != gcode::Segment::Kind::Rapid) {
        floor = std::min(floor, end_height);
      } else if ((d.start - d.end).dot(axis) > tol_ && end_height < floor - tol_) {
        fail(loc_, d.raw.line, "the cycle rapids down to " + fixed_text(end_height, 4) + " above the hole's top, below the "
                               "CL's R plane (" + fixed_text(r_plane, 4) + " above it): a rapid into what the CL feeds through",
             0);
        break;
      }
    }
    if (!axis_ok(s, axis)) fail(loc_, s.raw.line, "the hole is drilled with the tool off its axis", 0);
    if (spec.kind == ir::CycleKind::Tap) {
      tap_ok(s, spec);
    } else {
      ir::Feed f = have_cl_feed_ ? cl_feed_ : ir::Feed{0, ir::FeedMode::PerMinute};
      if (spec.feed > 0) f = ir::Feed{spec.feed, spec.feed_mode};
      feed_ok(s, f.value > 0 ? &f : nullptr);
    }
    drills_as_asked(*j, spec, top, axis);
    consume(*j + 1);
  }
  hole_bottom_ = bottom;
  hole_point_ = top;
  hole_axis_ = axis;
  have_hole_ = true;
  prev_ = top;
  have_prev_ = true;
}

// A canned cycle's code says what the spindle does at the bottom and how the tool comes out,
// which the path alone does not show: G81 for a tap fed it in and rapided it out turning forward,
// G83 made G81 drilled 20 mm deep in one feed, G82 made G81 lost the dwell, all passed
// (helper-49). Judged from the CL's cycle by the controls' meaning of the codes:
//   - a tap is G84 (G74 left hand); a fine bore G76; a back bore G87; a bore that stops the
//     spindle at the bottom G86, or moves that stop it; no other cycle reverses, orients or
//     stops the spindle at the bottom;
//   - a bore (or ream) and a bore with a dwell come out at feed;
//   - a spot-dwell and a bore-dwell dwell at the bottom for the CL's time (within half P's
//     increment, 1.5 ms at least); a peck's dwell is no part of the hole's size (clpc warns it is not written);
//   - a peck cycle feeds no deeper at a time than its largest peck; a DEEP cycle leaves the hole
//     between pecks (G73's chip break does not).
void Comparison::drills_as_asked(size_t j, const ir::CycleSpec& spec, const Vec3& top, const Vec3& axis) {
  using K = ir::CycleKind;
  const TipSegment* out = peek(j + 1);  // the move out of the hole (before `s`: peeking may grow the window)
  const TipSegment& s = win_[j];
  const int code = s.raw.cycle;
  const std::string asked = "the CL's cycle is " + std::string(ir::cycle_kind_name(spec.kind));
  auto wrong = [&](const std::string& what) { fail(loc_, s.raw.line, what + ", " + asked, 0); };
  auto g = [](int c) { return "G" + std::to_string(c); };
  const int spindle_code = spec.kind == K::Tap        ? (spec.left_hand ? 74 : 84)
                           : spec.kind == K::FineBore ? 76
                           : spec.kind == K::BackBore ? 87
                           : spec.kind == K::BoreStop ? 86
                                                      : 0;
  const bool acts = code == 84 || code == 74 || code == 76 || code == 87 || code == 86;
  if (spindle_code != 0 && code != spindle_code) {
    const bool stopped_by_moves = spec.kind == K::BoreStop && code == 0 && out && !out->raw.spindle;
    if (!stopped_by_moves)
      wrong("the hole is made " + (code ? "with " + g(code) : std::string("with plain moves")) + ", not " + g(spindle_code));
    return;
  }
  if (spindle_code == 0 && acts) {
    wrong(g(code) + (code == 84 || code == 74 ? " reverses" : code == 86 ? " stops" : " orients") +
          " the spindle at the bottom");
    return;
  }
  if ((spec.kind == K::Bore || spec.kind == K::BoreDwell) && out && out->raw.kind == gcode::Segment::Kind::Rapid)
    wrong("the tool comes out of the hole at rapid traverse" + (code ? " (" + g(code) + ")" : std::string()));
  if (spec.kind == K::SpotDwell || spec.kind == K::BoreDwell) {
    const double dwell = s.raw.dwell + (out ? out->raw.dwell_before : 0.0);
    // (A bore-dwell written as moves dwells with a G04 before the move out: the hole's, not a DELAY.)
    if (out) prog_dwell_ -= out->raw.dwell_before;
    if (std::abs(dwell - spec.dwell) > dwell_slack_)
      wrong("the tool dwells " + fixed_text(dwell, 3) + " s at the bottom, not " + fixed_text(spec.dwell, 3) + " s");
  }
  if ((spec.kind == K::Peck || spec.kind == K::ChipBreak) && spec.peck > 0) {
    if (spec.kind == K::Peck && code == 73) {
      wrong("G73 breaks the chip without leaving the hole between pecks");
      return;
    }
    // Each feed down the axis cuts from the deepest point reached before it (a peck cycle feeds
    // back in from just above it).
    const double most = std::max(spec.peck, spec.peck_next) * k_;
    auto off_axis = [&](const Vec3& q) { return ((q - top) - (q - top).dot(axis) * axis).norm(); };
    double deepest = std::max(0.0, -spec.clearance * k_);  // an R plane inside the hole: pecks count from it
    for (size_t i = 0; i <= j; ++i) {
      const TipSegment& d = win_[i];
      if (d.raw.kind == gcode::Segment::Kind::Rapid || !finite(d.start) || !finite(d.end) || off_axis(d.start) > tol_ ||
          off_axis(d.end) > tol_)
        continue;
      const double to = (top - d.end).dot(axis);  // depth below the top
      if (to - deepest > most + tol_) {
        wrong("the drill feeds " + fixed_text(to - deepest, 4) + " deeper at once" + (code ? " (" + g(code) + ")" : std::string()) +
              ", its pecks are " + fixed_text(most, 4));
        break;
      }
      deepest = std::max(deepest, to);
    }
  }
}

void Comparison::check_limits(const TipSegment& s) {
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

void Comparison::check_travel() {
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

}  // namespace verify_detail

using verify_detail::Comparison;

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
