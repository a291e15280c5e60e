// What every backend shares: the program frame, header, spindle, coolant, dwell, stops,
// comments and feeds.
#include "backends/backend.h"
#include "machine/block_check.h"

#include <algorithm>
#include <cctype>
#include <numbers>

#include "machine/format.h"
#include "support/text.h"

namespace clpc {

ProgramWriter::ProgramWriter(const Machine& m, OutputFile& out, Diagnostics& d) : m_(m), e_(m, out, d), d_(d) {}

std::string ProgramWriter::length_text(double program_units) const {
  AddressFormat f;
  f.decimals = m_.units == ir::Units::Inch ? 4 : 3;
  std::string s;
  int64_t q;
  if (quantize(program_units * k_, f, q)) append_quantized(q, f, s);
  return s;
}

std::string ProgramWriter::tool_comment(const ir::ToolInfo& t) const {
  std::string c = "T" + std::to_string(t.number);
  if (t.diameter > 0 || t.corner_radius > 0) c += " D=" + length_text(t.diameter) + " CR=" + length_text(t.corner_radius);
  if (!t.name.empty()) c += " - " + t.name;
  else if (!t.kind.empty()) c += " - " + t.kind;
  return c;
}

void ProgramWriter::begin(const ir::ProgramInfo& info) {
  info_ = &info;
  k_ = ir::mm_per_unit(info.units) / ir::mm_per_unit(m_.units);
  for (const std::string& l : m_.program_start) e_.line(l);
  if (const long number = program_number(info); number > 0) {
    std::string o = "O";
    int64_t q = number;  // the number as it is if the format cannot scale it
    quantize(double(number), m_.format('O'), q);
    append_quantized(q, m_.format('O'), o);
    if (m_.comments.enabled && !info.part_name.empty()) {
      std::string c = e_.clean_comment(info.part_name);
      if (!c.empty()) o += " " + m_.comments.open + c + m_.comments.close;
    }
    e_.line(o);
  } else if (!info.part_name.empty()) {
    e_.comment(info.part_name);
  }
  write_header(info);
  e_.begin({});
  e_.code(m_.units == ir::Units::Inch ? m_.codes.units_inch : m_.codes.units_mm);
  e_.end();
  blocks(m_.safe_start, {});
  write_smoothing(true);
  start_program();
}

void ProgramWriter::end() {
  cancel_cycle({});
  before_finish();
  // Compensation still on (a CUTCOM/OFF with no move after it, or none at all) is cancelled
  // before the finish's moves: the retract and park are no compensated path.
  if (comp_on_) {
    check_comp_end_in_cut();
    e_.begin({});
    e_.code(m_.codes.comp_off);
    e_.end();
    comp_on_ = false;
  }
  comp_pending_set_ = false;
  write_smoothing(false);
  // The finish sequence, less a spindle or coolant stop the program has already made; the
  // park blocks before its last block (the program end, M30). A coolant with its own off code
  // is stopped by it first (the finish's M09 may leave it on).
  if ((coolant_ == ir::CoolantKind::Thru && !m_.codes.coolant_thru_off.empty()) ||
      (coolant_ == ir::CoolantKind::Air && !m_.codes.coolant_air_off.empty()))
    write_coolant(ir::Coolant{ir::CoolantKind::Off}, {});
  absolute_before(m_.finish, {});
  for (size_t i = 0; i < m_.finish.size(); ++i) {
    const CodeTemplate& t = m_.finish[i];
    if (m_.park && i + 1 == m_.finish.size()) blocks(m_.park_blocks, {});
    if (spindle_ == ir::SpindleDir::Off && t.text == m_.codes.spindle_off.text) continue;
    if (coolant_ == ir::CoolantKind::Off && t.text == m_.codes.coolant_off.text) continue;
    write_block(t, {});
  }
  if (m_.park && m_.finish.empty()) blocks(m_.park_blocks, {});
  after_finish();
  for (const std::string& l : m_.program_end) e_.line(l);
}

void ProgramWriter::blocks(const std::vector<CodeTemplate>& list, SourceLoc loc) {
  absolute_before(list, loc);
  for (const CodeTemplate& t : list) write_block(t, loc);
}

void ProgramWriter::write_block(const CodeTemplate& t, SourceLoc loc) {
  e_.begin(loc);
  e_.code(t);
  e_.end();
  after_template(t);
}

// A list of fixed blocks was checked when the machine loaded as the control reads it from
// G90; one of the post's own left G91 (G91 G28 Z0. before a tool change) and a finish's
// "G53 G00 Z0." ran in G91, where a Fanuc ignores it (helper-72). G90 first, unless the list
// says its mode before its first axis word. Once per list, never between its blocks: a
// finish's "G91" then "G28 Z0." is a home from where the tool is (helper-74).
void ProgramWriter::absolute_before(const std::vector<CodeTemplate>& list, SourceLoc loc) {
  if (!incremental_ || m_.codes.absolute.empty()) return;
  for (const CodeTemplate& t : list) {
    if (sets_distance_mode(t)) return;
    if (axis_words(t.text).empty()) continue;
    e_.begin(loc);
    absolute_code();
    e_.end();
    return;
  }
}

bool ProgramWriter::sets_distance_mode(const CodeTemplate& t) const {
  for (const CodeTemplate::Word& w : t.words)
    if (w.size() == 1 && w[0].var < 0 && (w[0].literal == m_.codes.incremental.text || w[0].literal == m_.codes.absolute.text))
      return true;
  return false;
}

// A template may change modal state clpc does not model word by word (a G-code, a move in
// machine coordinates): after one, every modal word is written again.
void ProgramWriter::after_template(const CodeTemplate& t) {
  if (t.empty()) return;
  // The last of G90 / G91 in the template sets the distance mode.
  for (const CodeTemplate::Word& w : t.words) {
    if (w.size() != 1 || w[0].var >= 0) continue;
    if (w[0].literal == m_.codes.incremental.text) incremental_ = true;
    else if (w[0].literal == m_.codes.absolute.text) incremental_ = false;
  }
  note_plane_codes(t.text);
  if (t.has_g_code()) {
    motion_ = Motion::None;
    plane_ = Plane::None;
    feed_mode_known_ = false;
    feed_written_ = false;
    // The linear axes may mean something else now (a machine-coordinate move, a new frame);
    // rotary axes move only if the template names them.
    e_.forget_linear();
    for (const CodeTemplate::Word& w : t.words)
      if (const char l = CodeTemplate::letter(w); l == 'A' || l == 'B' || l == 'C') e_.forget(l);
  }
}

void ProgramWriter::absolute_code() {
  if (!incremental_) return;
  e_.code(m_.codes.absolute);
  incremental_ = false;
}

void ProgramWriter::operation(const ir::Operation& op) {
  // program.optional_stop = "operation": M01 before each operation after one that moved, at
  // its first record that does something (a tool change writes it after its own retract).
  if (!op.continued && m_.optional_stop == Machine::OptionalStop::Operation && cut_since_stop_) stop_pending_ = true;
  if (!op.continued && !op.name.empty()) e_.comment(op.name);
  resume_at_ = 0;
  for (size_t i = 0; i < op.body.size(); i = std::max(i + 1, resume_at_)) visit(op, op.body[i]);
}

void ProgramWriter::visit(const ir::Operation& op, const ir::Instr& in) {
  const SourceLoc loc = in.loc;
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (!std::is_same_v<T, ir::Comment> && !std::is_same_v<T, ir::Feed> && !std::is_same_v<T, ir::SetFrame> &&
                      !std::is_same_v<T, ir::SelectOffset> && !std::is_same_v<T, ir::Passthrough> &&
                      !std::is_same_v<T, ir::ToolChange> && !std::is_same_v<T, ir::ToolPreselect> &&
                      !std::is_same_v<T, ir::CutterComp> && !std::is_same_v<T, ir::GrooveMark> &&
                      !std::is_same_v<T, ir::ThreadMark> &&
                      !std::is_same_v<T, ir::CycleOn> && !std::is_same_v<T, ir::CycleOff>)
          if (stop_pending_) optional_stop_between_operations(loc);
        // Something that moves the tool: the coolant a tool change turned off comes back first.
        if constexpr (std::is_same_v<T, ir::Hole> || std::is_same_v<T, ir::Arc> || std::is_same_v<T, ir::Groove> ||
                      std::is_same_v<T, ir::ThreadCycle>) {
          restore_after_stop(loc, true);
          cut_since_stop_ = true;
        } else if constexpr (std::is_same_v<T, ir::Move>) {
          if (x.kind != ir::MoveKind::From) {
            restore_after_stop(loc, x.kind != ir::MoveKind::Rapid);
            cut_since_stop_ = true;
          }
        } else if constexpr (std::is_same_v<T, ir::Coolant>) {
          // The CL says what it wants. A stop may have left the coolant on (an M01 with the
          // operator's switch off): the next one is written as from the one the CL left on, so
          // through-spindle coolant gets its own off code (M89) before flood, not nothing.
          if (coolant_restore_ && coolant_ == ir::CoolantKind::Off) coolant_ = coolant_after_;
          coolant_restore_ = false;
        } else if constexpr (std::is_same_v<T, ir::Spindle>) {
          spindle_restore_ = spindle_restore_before_move_ = false;  // the CL says what it wants
          if (x.dir == ir::SpindleDir::Off && tool_turned_) cl_stopped_spindle_at_ = loc;
          if (x.dir != ir::SpindleDir::Off) cl_stopped_spindle_at_ = {}, spindle_stop_refused_ = false, tool_turned_ = true;
          if (x.dir == ir::SpindleDir::Off) spindle_on_.reset();
          else spindle_on_ = x;
        } else if constexpr (std::is_same_v<T, ir::ToolChange>) {
          if (x.tool != tool_) {  // another tool's own (a forming tool does not turn); not a reload
            tool_turned_ = false;
            cl_stopped_spindle_at_ = {};
            spindle_stop_refused_ = false;
          }
        }
        // (A load of the tool in the spindle with its own offset, NX's at every operation,
        // changes nothing: the CL's moves after it carry the G40; helper-72.)
        if constexpr (std::is_same_v<T, ir::ToolChange>) {
          if (x.tool != tool_ || (x.length_offset > 0 ? x.length_offset : x.tool) != length_offset_) end_pending_comp();
        }
        if constexpr (std::is_same_v<T, ir::Hole> || std::is_same_v<T, ir::RotaryPosition> ||
                      std::is_same_v<T, ir::RotaryIndex> || std::is_same_v<T, ir::MachineMode> ||
                      std::is_same_v<T, ir::Groove> || std::is_same_v<T, ir::ThreadCycle>)
          end_pending_comp();
        if constexpr (std::is_same_v<T, ir::Hole>) {
          write_hole(op, x, loc);
          return;
        }
        if constexpr (std::is_same_v<T, ir::GrooveMark>) return;
        if constexpr (std::is_same_v<T, ir::RotaryPosition>) {
          cancel_cycle(loc);
          write_rotary_position(x, loc);
          return;
        }
        if constexpr (std::is_same_v<T, ir::MachineMode>) {
          cancel_cycle(loc);
          write_mode(x, loc);
          return;
        }
        if constexpr (std::is_same_v<T, ir::GrooveOn>) {
          d_.error(loc, "internal: a groove cycle record reached the backend (is 'groove-cycles' in the pipeline of a lathe?)");
          return;
        }
        if constexpr (std::is_same_v<T, ir::Groove>) {
          cancel_cycle(loc);
          write_groove(op, x, loc);
          return;
        }
        if constexpr (std::is_same_v<T, ir::ThreadMark>) {
          write_thread_mark(x, loc);
          return;
        }
        if constexpr (std::is_same_v<T, ir::ThreadCycle>) {
          write_thread_cycle(x, loc);
          return;
        }
        if constexpr (std::is_same_v<T, ir::RoughMark>) {
          cancel_cycle(loc);
          if (x.begin) write_rough(op, size_t(&in - op.body.data()), loc);
          return;
        }
        if constexpr (std::is_same_v<T, ir::CycleOn> || std::is_same_v<T, ir::CycleOff>) {
          cancel_cycle(loc);  // a new cycle starts with all its words; OFF ends the run
          in_cycle_ = std::is_same_v<T, ir::CycleOn>;
          return;
        }
        // drill-cycles turns every GOTO of a cycle into a hole or the moves it takes: a plain
        // move inside a cycle would be cut as a move to the hole's top, the hole not drilled.
        if constexpr (std::is_same_v<T, ir::Move>) {
          if (in_cycle_ && x.kind != ir::MoveKind::From) {
            d_.error(loc, "a canned cycle's hole reached the program as a plain move: machine '" + m_.name +
                              "' needs 'drill-cycles' in its pipeline");
            in_cycle_ = false;
            return;
          }
        }
        // Anything else that moves or changes the machine ends a cycle run first.
        if constexpr (!std::is_same_v<T, ir::Feed> && !std::is_same_v<T, ir::Comment> &&
                      !std::is_same_v<T, ir::SetFrame> && !std::is_same_v<T, ir::SelectOffset>)
          cancel_cycle(loc);
        if constexpr (std::is_same_v<T, ir::Move>) {
          write_move(x, loc);
        } else if constexpr (std::is_same_v<T, ir::Arc>) {
          write_arc(op, x, loc);
        } else if constexpr (std::is_same_v<T, ir::ToolChange>) {
          write_tool_change(x, loc);
        } else if constexpr (std::is_same_v<T, ir::ToolPreselect>) {
          e_.begin(loc);
          e_.code(m_.codes.tool_preselect, TemplateVars().with(Var::Tool, x.tool));
          e_.end();
        } else if constexpr (std::is_same_v<T, ir::Spindle>) {
          write_spindle(x, loc);
        } else if constexpr (std::is_same_v<T, ir::Feed>) {
          if (x.mode == ir::FeedMode::PerRev &&
              lacks(m_.codes.feed_per_rev, loc, "feed_per_rev", "feed per revolution",
                    "its F would be read per minute; have the CAM system write the feed per minute"))
            return;
          if (x.mode != feed_mode_ || !feed_known_ || x.value != feed_) feed_written_ = false;
          feed_mode_ = x.mode;
          feed_ = x.value;
          feed_known_ = true;
          feed_loc_ = loc;
        } else if constexpr (std::is_same_v<T, ir::Coolant>) {
          write_coolant(x, loc);
        } else if constexpr (std::is_same_v<T, ir::CutterComp>) {
          write_cutter_comp(x, loc);
        } else if constexpr (std::is_same_v<T, ir::Dwell>) {
          write_dwell(x, loc);
        } else if constexpr (std::is_same_v<T, ir::Stop>) {
          write_stop(x, loc);
        } else if constexpr (std::is_same_v<T, ir::Comment>) {
          e_.comment(op.str(x.text));
        } else if constexpr (std::is_same_v<T, ir::Insert>) {
          std::string why;
          std::string_view text = op.str(x.text);
          if (m_.inserts != Machine::Inserts::Raw && !is_control_block(text, why)) {
            const std::string msg = "INSERT '" + std::string(text) + "' is no block the control reads (" + why + ")";
            if (m_.inserts == Machine::Inserts::Error) {
              d_.error(loc, msg + "; program.inserts = \"error\"");
              return;
            }
            d_.warning(loc, msg + ": written as a comment (program.inserts = \"raw\" writes it as it is)", "insert");
            e_.comment(text);
            return;
          }
          if (const std::string why_not = unkept_code(text); !why_not.empty()) {
            d_.error(loc, "the block '" + std::string(text) + "' (INSERT, PREFUN or AUXFUN) " + why_not);
            return;
          }
          if (const std::string axes = axis_words(text); !axes.empty())
            d_.warning(loc, "INSERT '" + std::string(text) + "' holds axis words (" + axes +
                                "): it is written as given, and what it moves is not checked against the CL "
                                "(the certificate follows the CL's own moves)", "insert");
          if (may_move_axes(text)) end_pending_comp();
          e_.line(text);
          note_plane_codes(text);
          // A program stop written raw stops the spindle and the coolant as STOP's does: both are
          // started again as the CL left them (the next hole was drilled with the spindle stopped).
          for (double mc : code_numbers(text, 'M'))
            if (std::lround(mc) == 0 || std::lround(mc) == 1) control_stopped(true, false);
          // The inserted line may do anything: write every modal word again after it, and
          // the plane (with the next arc), distance mode, work offset and feed mode it sets.
          for (double g : code_numbers(text, 'G')) {
            if (g > 16.5 && g < 19.5) plane_ = Plane::None;
            if (std::abs(g - 91) < 1e-6) incremental_ = true;  // G90 with the next motion block
            if ((g > 53.5 && g < 59.5) || std::abs(g - 154) < 1e-6) need_work_offset_ = true;
            if (g > 92.5 && g < 99.5) feed_mode_known_ = false;  // G93-G95, a lathe's G98/G99
            // G49 with a tool loaded (a safety line before a tool change): the length offset
            // again with the next move.
            if (!m_.is_lathe() && std::abs(g - 49) < 1e-6 && tool_ >= 0 && !m_.codes.length_offset.empty())
              need_length_offset_ = true;
          }
          motion_ = Motion::None;
          // The rotaries stay where they were where the block can move no axis: restating them
          // unclamped the rotary brakes in the middle of a cut (Haas: M11 M13, then the feed).
          // A block that may move axes may have moved them: then they are written again.
          const bool moves_axes = may_move_axes(text);
          std::string rotaries_kept;
          if (!moves_axes)
            for (const RotaryAxis& r : m_.kinematics.rotaries) rotaries_kept += r.name[0];
          e_.forget_all_but(rotaries_kept);
          if (moves_axes) after_raw_motion(returns_z_home(text));
          feed_written_ = false;
        } else if constexpr (std::is_same_v<T, ir::Passthrough>) {
          e_.comment("CL: " + std::string(op.str(x.text)));
        } else if constexpr (std::is_same_v<T, ir::SelectOffset>) {
          int standard = m_.offsets.standard_last - m_.offsets.standard_first + 1;
          if (x.index > standard + m_.offsets.extended_count) {
            d_.error(loc, "work-offset register " + std::to_string(x.reg) + " is beyond machine '" + m_.name + "''s " +
                              std::to_string(standard + m_.offsets.extended_count) + " registers");
            return;
          }
          if (x.index != work_offset_) {
            if ((work_offset_ > 0 ? work_offset_ : m_.offsets.default_index) != x.index) before_offset_change(loc);
            need_work_offset_ = true;
            e_.forget_linear();  // the same X Y Z is another place in another offset
          }
          work_offset_ = x.index;
        } else if constexpr (std::is_same_v<T, ir::SetFrame>) {
          // Frames are for the passes (offset table, kinematics); nothing to write here. A
          // lathe has neither: an NX frame (MSYS) turned from the first one, or moved off the
          // spindle's axis, is no single-spindle program (a Z reversed is the part turned round
          // for a second setup; its points were put through the first frame, cut from the chuck's side).
          if (m_.is_lathe()) check_lathe_frame(x, loc);
        } else if constexpr (std::is_same_v<T, ir::RotaryIndex>) {
          write_rotary_index(x, loc);
        }
      },
      in.op);
}

// An NX MSYS is given relative to the first (the program's frame); a Creo or APT CSYS is the
// frame itself, its points in the program's frame already: the first one's turn is the setup's.
// Within what the CL's digits hold: 7 decimals for an axis, 4 for an origin.
void ProgramWriter::check_lathe_frame(const ir::SetFrame& x, SourceLoc loc) {
  constexpr double kTurn = 1e-6, kShift = 2e-4;
  const bool msys = x.source == ir::FrameSource::Msys;
  if (!msys && !first_csys_) first_csys_ = x.frame.rotation;
  const ir::Mat3 turn = msys ? x.frame.rotation : ir::Mat3(first_csys_->transpose() * x.frame.rotation);
  const bool turned = !turn.isIdentity(kTurn);
  const bool moved = msys && (std::abs(x.frame.origin.x()) > kShift || std::abs(x.frame.origin.y()) > kShift);
  if (!turned && !moved) return;
  d_.error(loc, "this " + std::string(msys ? "MSYS" : "frame") + " is " + (turned ? "turned from" : "moved off") +
                    " the first one (the program's frame, along the spindle's axis): on a lathe only a shift along Z is "
                    "one setup; a part turned round is a setup of its own: post it as a program of its own");
}

void ProgramWriter::write_thread_mark(const ir::ThreadMark& t, SourceLoc loc) {
  if (t.begin) d_.error(loc, "machine '" + m_.name + "' is a mill: THREAD (a thread cut synchronised with the spindle) needs a lathe");
}

void ProgramWriter::write_thread_cycle(const ir::ThreadCycle&, SourceLoc loc) {
  d_.error(loc, "internal: a threading cycle reached the mill backend");
}

void ProgramWriter::write_rough(const ir::Operation&, size_t, SourceLoc loc) {
  d_.error(loc, "CYCLE/ROUGH is a lathe's stock-removal cycle: machine '" + m_.name + "' is a mill");
}

void ProgramWriter::write_hole(const ir::Operation&, const ir::Hole&, SourceLoc loc) {
  d_.error(loc, "internal: machine '" + m_.name + "' writes no canned cycles (is 'drill-cycles' in its pipeline?)");
}

void ProgramWriter::write_rotary_position(const ir::RotaryPosition&, SourceLoc loc) {
  d_.error(loc, "internal: machine '" + m_.name + "' has no rotary axes");
}

void ProgramWriter::write_mode(const ir::MachineMode&, SourceLoc loc) {
  d_.error(loc, "internal: machine '" + m_.name + "' has no five-axis modes");
}

void ProgramWriter::write_groove(const ir::Operation&, const ir::Groove&, SourceLoc loc) {
  d_.error(loc, "machine '" + m_.name + "' is not a lathe: it has no groove cycles");
}

void ProgramWriter::write_stop(const ir::Stop& s, SourceLoc loc) {
  if (!s.setup) {
    // A program stop is where the operator acts (a clamp moved, a chip cleared): never lost. An
    // optional stop the machine cannot make is said.
    if (s.kind == ir::StopKind::Optional && m_.codes.optional_stop.empty()) {
      d_.warning(loc, "machine '" + m_.name + "' has no optional stop (codes.optional_stop is empty): OPSTOP is not written",
                 "machine-code");
      return;
    }
    if (s.kind != ir::StopKind::Optional && lacks(m_.codes.stop, loc, "stop", "stop the program")) return;
    e_.begin(loc);
    e_.code(s.kind == ir::StopKind::Optional ? m_.codes.optional_stop : m_.codes.stop);
    e_.end();
    control_stopped(true, false);  // M00 (M01 with the switch on) stops the spindle and the coolant
    return;
  }
  // The operator turns the part over: tool clear, spindle and coolant off, then on again.
  // Without a retract the part was turned under the tool, and the next setup's first move
  // crossed at the last one's height (helper-67: certified).
  if (lacks(m_.codes.stop, loc, "stop", "stop the program for the operator")) return;
  if (lacks(m_.codes.safe_retract, loc, "safe_retract", "retract the tool before the operator sets the part up again",
            "the part would be turned under the tool, and the next setup's first move made at the last one's height"))
    return;
  const ir::SpindleDir dir = spindle_;
  const double rpm = spindle_rpm_;
  const ir::CoolantKind coolant = coolant_;
  end_comp_before_retract(loc, "a setup stop");
  retract_for_stop(loc);
  if (dir != ir::SpindleDir::Off) write_spindle(ir::Spindle{0, ir::SpindleMode::Rpm, ir::SpindleDir::Off, 0}, loc);
  if (coolant != ir::CoolantKind::Off) write_coolant(ir::Coolant{ir::CoolantKind::Off}, loc);
  e_.begin(loc);
  e_.code(m_.codes.stop);
  e_.end();
  if (dir != ir::SpindleDir::Off) write_spindle(ir::Spindle{rpm, ir::SpindleMode::Rpm, dir, 0}, loc);
  if (coolant != ir::CoolantKind::Off) write_coolant(ir::Coolant{coolant}, loc);
  // The length offset again with the next setup's first Z: an operator who turned the part may
  // have pressed RESET (a Fanuc set so cancels G43), or restarts at this setup's blocks; the
  // tool came down a whole tool length lower than the CL's point (helper-67, helper-70).
  if (tool_ >= 0 && !m_.is_lathe() && !m_.codes.length_offset.empty()) need_length_offset_ = true;
}

void ProgramWriter::write_rotary_index(const ir::RotaryIndex& r, SourceLoc loc) {
  // A table sent to 0 on a machine with no table: the part stays as it was set up.
  if (!r.incremental && r.angle == 0) {
    d_.warning(loc, "the rotary table is sent to 0 but machine '" + m_.name + "' has none: nothing to do", "rotary-index");
    return;
  }
  d_.error(loc, std::string("rotary indexing (ROTATE, ROTABL): machine '") + m_.name + "' has no " +
                    (r.axis == '?' ? std::string("rotary table") : std::string(1, r.axis) + " axis") + " to index");
}

void ProgramWriter::write_spindle(const ir::Spindle& s, SourceLoc loc) {
  e_.begin(loc);
  if (s.dir == ir::SpindleDir::Off) {
    e_.code(m_.codes.spindle_off);
    spindle_ = ir::SpindleDir::Off;
    e_.end();
    return;
  }
  const bool cw = s.dir == ir::SpindleDir::Cw;
  if (lacks(cw ? m_.codes.spindle_cw : m_.codes.spindle_ccw, loc, cw ? "spindle_cw" : "spindle_ccw",
            cw ? "start the spindle clockwise" : "start the spindle counter-clockwise",
            "the tool would cut with the spindle stopped")) {
    e_.end();
    spindle_ = s.dir;  // the error stands for the record: no "spindle stopped" on every move after it
    return;
  }
  double rpm = s.speed;
  if (s.mode == ir::SpindleMode::SurfaceSpeed) {
    // A mill's cutting speed (CATIA and others write SPINDL/v,SMM|SFM when the speed is given
    // as a cutting speed) is the speed at the cutter's diameter: n = 1000 v / (pi D), fixed for
    // the tool (a milling spindle has no constant surface speed to hold).
    const ir::ToolInfo* t = info_ && tool_ >= 0 ? info_->tool(tool_) : nullptr;
    if (t && t->other_diameter_at.valid()) {
      d_.error(loc, "a cutting speed (SPINDL/SFM, SMM) on a mill turns into rpm at the cutter's diameter, and tool " +
                        std::to_string(tool_) + " is given two (" + num_text(t->diameter) + ", and " +
                        num_text(t->other_diameter) + " at line " + std::to_string(t->other_diameter_at.line) +
                        "): give the speed in RPM, or each cutter a number of its own");
      spindle_ = s.dir;  // the error stands for the record: no "spindle stopped" on every move after it
      return;
    }
    if (!t || !(t->diameter > 0)) {
      d_.error(loc, "a cutting speed (SPINDL/SFM, SMM) on a mill turns into rpm at the cutter's diameter, and " +
                        std::string(tool_ < 0 ? "no tool is loaded" : "tool " + std::to_string(tool_) + " has no diameter (CUTTER, TLDATA)") +
                        ": give the speed in RPM, or the tool's diameter");
      spindle_ = s.dir;
      return;
    }
    rpm = s.speed * 1000 / (std::numbers::pi * t->diameter * ir::mm_per_unit(info_->units));
    if (s.max_rpm > 0) rpm = std::min(rpm, s.max_rpm);  // the programmer's MAXRPM holds
  }
  if (!spindle_within_limit(rpm, loc)) {
    spindle_ = s.dir;  // the error stands for the record: no "spindle stopped" on every move after it
    return;
  }
  e_.word('S', rpm);
  e_.code(s.dir == ir::SpindleDir::Cw ? m_.codes.spindle_cw : m_.codes.spindle_ccw);
  spindle_ = s.dir;
  spindle_rpm_ = rpm;
  e_.end();
}

// No tool change before the first cut: a mill's start block cancels length compensation (G49),
// so no tool length offset is in force and the gauge line, not the tip, would go to the CL's
// points; a lathe's program would have no T word, and cut with the station and offset the last
// program left (it was certified so; helper-59). Said once.
bool ProgramWriter::tool_loaded_for_cut(SourceLoc loc) {
  if (tool_ >= 0) return true;
  if (!no_tool_reported_)
    d_.error(loc, std::string("cutting with no tool loaded: the CL loads none before this move (LOADTL, LOAD/TOOL, "
                              "TURRET), so ") +
                      (m_.is_lathe() ? "the program would select no turret station and no offset (no T word) and cut "
                                       "with whatever the last program left; add TURRET/n or LOADTL/n before it"
                                     : "no tool length offset is in force; add LOADTL/n before it") +
                      ", or have the CAM system write its tool change");
  no_tool_reported_ = true;
  return false;
}

// An empty code in the machine's TOML means the machine lacks the function. Where the CL asks
// for one nothing else can stand in for, the record is refused: written as nothing, a tool
// change, a spindle start, a stop, a dwell or cutter compensation would leave the wrong tool
// cutting, the spindle stopped, no operator stop, no wait, or the cut on the tool's centre.
bool ProgramWriter::lacks(const CodeTemplate& code, SourceLoc loc, const char* key, const std::string& what,
                          const std::string& why) {
  if (!code.empty()) return false;
  d_.error(loc, "machine '" + m_.name + "' has no code to " + what + " (codes." + key + " is empty)" + (why.empty() ? "" : ": " + why));
  return true;
}

// A machine without a tool changer (an empty tool_change) takes the first tool as the operator
// loads it before the start; another tool cannot be brought in by the program. False (and an
// error) for such a change; the tool is taken as loaded, so no error follows at every cut.
bool ProgramWriter::tool_changer_for(const ir::ToolChange& t, SourceLoc loc) {
  if (tool_ < 0 || !lacks(m_.codes.tool_change, loc, "tool_change", "change the tool",
                          "tool " + std::to_string(tool_) + " would cut on for tool " + std::to_string(t.tool) +
                              "; post each tool's operations as a program of its own"))
    return true;
  tool_ = t.tool;
  return false;
}

bool ProgramWriter::spindle_within_limit(double rpm, SourceLoc loc) {
  // S0 M03 turns nothing: every cut after it would be made with the spindle stopped.
  if (e_.round('S', rpm).q == 0) {
    d_.error(loc, "SPINDL: " + num_text(rpm) + " rpm would be written S0 (format.S), a spindle that does not turn; give "
                  "the speed in rpm (a speed under 1 rpm is no cutting speed)");
    return false;
  }
  const double limit = m_.spindle_limit();
  if (limit <= 0 || rpm <= limit) return true;
  d_.error(loc, "SPINDL: " + num_text(rpm) + " rpm is above machine '" + m_.name + "''s spindle limit of " + num_text(limit) +
                    " rpm (max_rpm)");
  return false;
}

void ProgramWriter::write_feed_mode(ir::FeedMode mode) {
  const CodeTemplate& t = mode == ir::FeedMode::PerMinute ? m_.codes.feed_per_minute
                          : mode == ir::FeedMode::PerRev  ? m_.codes.feed_per_rev
                                                          : m_.codes.inverse_time;
  e_.code(t);
}

void ProgramWriter::feed_mode_code() { feed_mode_code(feed_mode_); }

void ProgramWriter::feed_mode_code(ir::FeedMode mode) {
  if (feed_mode_known_ && written_feed_mode_ == mode) return;
  write_feed_mode(mode);
  written_feed_mode_ = mode;
  feed_mode_known_ = true;
  feed_written_ = false;
}

bool ProgramWriter::feed_word(SourceLoc loc) {
  if (!feed_known_) {
    // Once: the program is refused already, and a feed of 0 made up here drew a second error
    // at every later move, with advice (more decimals) that had nothing to do with it.
    if (!no_feed_said_) d_.error(loc, "cutting move with no feed rate: no FEDRAT before it");
    no_feed_said_ = true;
    return false;
  }
  if (feed_mode_ == ir::FeedMode::InverseTime) {
    // G93's F is one over the block's minutes: the CL gave it for one move. Where the post
    // writes that move as several blocks (an arc made lines, a turn of the table inserted),
    // each would take the whole move's time.
    if (inverse_for_.valid() && loc == inverse_for_) {
      if (!(loc == inverse_refused_))
        d_.error(loc, "an inverse-time feed (FEDRAT/INVERS) for a move the program writes as more than one block: "
                      "each block would take the whole move's time; have the CAM system write a feed per minute "
                      "here (or the move as the blocks it writes)");
      inverse_refused_ = loc;
      return false;
    }
    inverse_for_ = loc;
  }
  double f = feed_mode_ == ir::FeedMode::InverseTime ? feed_ : feed_ * k_;
  if (m_.max_feed > 0 && feed_mode_ == ir::FeedMode::PerMinute && f > m_.max_feed) {
    // The control clamps a feed above its limit as well; the CL's feed is not what is cut.
    if (!(feed_loc_ == feed_clamp_said_))
      d_.warning(feed_loc_.valid() ? feed_loc_ : loc,
                 "feed " + num_text(std::round(f * 1e4) / 1e4) + " is above machine '" + m_.name + "''s max_feed " + num_text(std::round(m_.max_feed * 1e4) / 1e4) +
                     ": written as " + num_text(std::round(m_.max_feed * 1e4) / 1e4) + ", slower than the CL asks",
                 "feed-clamped");
    feed_clamp_said_ = feed_loc_;
    f = m_.max_feed;
  }
  // Per revolution at a fixed speed the feed per minute is known: above max_feed the control
  // holds it there, as it would a feed per minute (the F stays: it is per revolution).
  if (m_.max_feed > 0 && feed_mode_ == ir::FeedMode::PerRev && spindle_ != ir::SpindleDir::Off && spindle_rpm_ > 0 &&
      f * spindle_rpm_ > m_.max_feed * (1 + 1e-9) && !(feed_loc_ == feed_clamp_said_)) {
    const std::string unit = m_.units == ir::Units::Inch ? " in" : " mm";
    d_.warning(feed_loc_.valid() ? feed_loc_ : loc,
               "feed " + num_text(f) + unit + "/rev at " + num_text(spindle_rpm_) + " rpm is " + num_text(f * spindle_rpm_) + unit +
                   "/min, above machine '" + m_.name + "''s max_feed " + num_text(std::round(m_.max_feed * 1e4) / 1e4) +
                   ": the control cuts it slower than the CL asks",
               "feed-clamped");
    feed_clamp_said_ = feed_loc_;
  }
  if (!m_.modal.feed || !feed_written_ || feed_mode_ == ir::FeedMode::InverseTime) {
    if (!write_feed(f, feed_mode_, feed_loc_.valid() ? feed_loc_ : loc)) return false;
    feed_written_ = true;
  }
  return true;
}

namespace {

std::string feed_unit(ir::FeedMode mode, ir::Units u) {
  if (mode == ir::FeedMode::InverseTime) return "1/min";
  return std::string(u == ir::Units::Inch ? "in" : "mm") + (mode == ir::FeedMode::PerRev ? "/rev" : "/min");
}

const char* feed_key(ir::FeedMode mode) {
  return mode == ir::FeedMode::PerRev ? "feeds.per_rev" : mode == ir::FeedMode::InverseTime ? "feeds.inverse_time" : "feeds.per_minute";
}

}  // namespace

bool ProgramWriter::write_feed(double value, ir::FeedMode mode, SourceLoc cl) {
  const AddressFormat& f = m_.feed_format(mode);
  int64_t q;
  if (!quantize(value, f, q)) {
    d_.error(cl, "feed out of range: " + num_text(value) + " " + feed_unit(mode, m_.units));
    return false;
  }
  const double written = dequantize(q, f);
  if (q == 0 || std::abs(written - value) > m_.feeds.max_rounding * std::abs(value)) {
    std::string text;
    append_quantized(q, f, text);
    d_.error(cl, "the feed of " + num_text(value) + " " + feed_unit(mode, m_.units) + " would be written F" + text + " (" +
                     feed_key(mode) + ": " + std::to_string(f.decimals) + (f.decimals == 1 ? " decimal" : " decimals") + "): " +
                     (q == 0 ? std::string("it rounds to zero")
                             : "rounding changes it by more than " + num_text(m_.feeds.max_rounding * 100) + "%") +
                     "; give " + feed_key(mode) + " more decimals");
    return false;
  }
  e_.argument('F', value, f);
  return true;
}

bool ProgramWriter::write_tap_feed(double value, double pitch, double rpm, double depth, SourceLoc cl) {
  // A tap advances one pitch a turn whatever else happens: a control holding it to its feed
  // limit strips the thread or breaks the tap. It cannot be slowed as another feed is.
  if (m_.max_feed > 0 && rpm > 0 && pitch * rpm > m_.max_feed * (1 + 1e-9)) {
    d_.error(cl, "the tap feeds " + num_text(pitch * rpm) + (m_.units == ir::Units::Inch ? " in" : " mm") + "/min (pitch " +
                     num_text(pitch) + " at " + num_text(rpm) + " rpm), above machine '" + m_.name + "''s max_feed " +
                     num_text(std::round(m_.max_feed * 1e4) / 1e4) + ": give the tap a lower speed");
    return false;
  }
  const AddressFormat& f = m_.feeds.tap;
  int64_t q;
  if (!quantize(value, f, q)) {
    d_.error(cl, "tap feed out of range: " + num_text(value));
    return false;
  }
  const double written = dequantize(q, f);
  const double lead = m_.cycles.tap_per_rev ? written : written / rpm;  // the pitch the control cuts
  const double turns = depth / pitch;
  const double drift = std::abs(lead - pitch) * turns;  // where the tap is off its thread at the bottom
  const double increment = std::abs(dequantize(1, m_.format('Z')));
  if (q == 0 || drift >= 0.5 * increment) {
    std::string text;
    append_quantized(q, f, text);
    d_.error(cl, "the tap's pitch of " + num_text(pitch) + (m_.units == ir::Units::Inch ? " in" : " mm") + " would be written F" +
                     text + " (feeds.tap: " + std::to_string(f.decimals) + (f.decimals == 1 ? " decimal" : " decimals") +
                     "): the tap would advance " + num_text(std::round(lead * 1e6) / 1e6) + " a turn and be " +
                     num_text(std::round(drift * 1e6) / 1e6) + " off its thread at the bottom; give feeds.tap more decimals");
    return false;
  }
  e_.argument('F', value, f);
  return true;
}

void ProgramWriter::write_coolant(const ir::Coolant& c, SourceLoc loc) {
  const Codes& k = m_.codes;
  // One coolant replaces another: the one on is stopped first (COOLNT/AIR after FLOOD blew air
  // into the flood). Through-spindle coolant and air with their own off code (Haas M89, M84)
  // are stopped by it, before another coolant or none: coolant_off alone may leave them on.
  const CodeTemplate* own_off = coolant_ == ir::CoolantKind::Thru ? &k.coolant_thru_off
                                : coolant_ == ir::CoolantKind::Air ? &k.coolant_air_off
                                                                   : nullptr;
  auto flood = [](ir::CoolantKind x) { return x == ir::CoolantKind::On ? ir::CoolantKind::Flood : x; };
  const bool changes = flood(c.kind) != flood(coolant_);
  const bool replaced = coolant_ != ir::CoolantKind::Off && c.kind != ir::CoolantKind::Off && changes;
  if (own_off && own_off->empty()) own_off = nullptr;
  if (replaced && !own_off && !k.coolant_off.empty()) own_off = &k.coolant_off;
  if (own_off && changes) {
    e_.begin(loc);
    e_.code(*own_off);
    e_.end();
    coolant_ = ir::CoolantKind::Off;
    if (c.kind == ir::CoolantKind::Off) return;
  }
  const CodeTemplate* t = nullptr;
  switch (c.kind) {
    case ir::CoolantKind::Off: t = &k.coolant_off; break;
    case ir::CoolantKind::On: case ir::CoolantKind::Flood: t = &k.coolant_flood; break;
    case ir::CoolantKind::Mist: t = &k.coolant_mist; break;
    case ir::CoolantKind::Thru: t = &k.coolant_thru; break;
    case ir::CoolantKind::Air: t = &k.coolant_air; break;
    case ir::CoolantKind::Tap: t = &k.coolant_tap; break;
  }
  if (t->empty() && (c.kind == ir::CoolantKind::Off || k.coolant_flood.empty())) {
    // Never flood for OFF; a machine without flood has no coolant to fall back to.
    d_.warning(loc, "machine '" + m_.name + "' has no code to turn " +
                        (c.kind == ir::CoolantKind::Off ? std::string("the coolant off (codes.coolant_off)") : std::string("this coolant on")) +
                        ": nothing is written",
               "coolant");
    coolant_ = c.kind;
    return;
  }
  if (t->empty()) {
    d_.warning(loc, "machine '" + m_.name + "' has no code for this coolant; flood coolant used", "coolant");
    t = &k.coolant_flood;
  }
  e_.begin(loc);
  e_.code(*t);
  e_.end();
  coolant_ = c.kind;
}

void ProgramWriter::write_dwell(const ir::Dwell& d, SourceLoc loc) {
  if (lacks(m_.codes.dwell, loc, "dwell", "dwell")) return;
  double seconds = d.value;
  if (d.revolutions) {
    // A dwell of so many turns lasts as long as the spindle takes to make them at the speed in
    // force (under constant surface speed, the one it holds where the tool stands); controls
    // dwell in seconds (or ms), so it is written as that time.
    const double rpm = dwell_rpm();
    if (!(rpm > 0)) {
      d_.error(loc, std::string("DELAY/REV: a dwell of ") + num_text(d.value) + " revolutions needs the spindle turning at a " +
                        (spindle_ == ir::SpindleDir::Off ? "set speed, and it is stopped here" : "known rpm") +
                        "; give the dwell in seconds");
      return;
    }
    seconds = d.value * 60 / rpm;
  }
  e_.begin(loc);
  e_.code(m_.codes.dwell, TemplateVars().with(Var::Seconds, seconds).with(Var::Milliseconds, seconds * 1000));
  e_.end();
}

// What a block written as given (INSERT, PREFUN, AUXFUN) may not do: set a state the post
// neither keeps nor writes again after it, so that every move after it would be off (or the
// program would go elsewhere). "" when none. The post writes again after an inserted block
// the plane, distance mode, feed mode and work offset; it cannot undo these.
std::string ProgramWriter::unkept_code(std::string_view text) const {
  const bool lathe = m_.is_lathe();
  auto is = [](double g, double want) { return std::abs(g - want) < 1e-6; };
  // #5221=100. moved G54's X by 100 mm, certified, where G10 L2 P1 X100. was refused (helper-57).
  if (const std::string var = system_variable_set(text); !var.empty())
    return "sets the control's system variable " + var + " (work and tool offsets and modal state live there), so " +
           "the program's positions or offsets after it could mean other places: the frames (SET, CAMERA, MSYS) " +
           "and the tool records give them; the program's own variables (#1 to #999), alarms, counters and timers (#3000 to #3999) are written";
  for (double g : code_numbers(text, 'G')) {
    const std::string code = "G" + num_text(g);
    if (is(g, 41) || is(g, 42))
      return "turns cutter compensation on (" + code + "), which moves every point after it off the CL's: CUTCOM gives it";
    if (is(g, 40) && comp_on_)
      return "cancels the cutter compensation (G40) that a CUTCOM turned on: CUTCOM/OFF gives it";
    if (is(g, 20) || is(g, 21)) return "changes the program's units (" + code + "), which the post writes for the machine";
    // A return with no axis named homes every axis on a Haas (a Fanuc alarms): the CL's next
    // move, a cut, would be fed from there, with the rotaries turning.
    if ((is(g, 28) || is(g, 30)) && axis_words(text).empty())
      return "returns to a reference point (" + code + ") with no axis named, which homes every axis on some "
             "controls: the CL's next move would start there; name the axes it returns (G91 " + code + " Z0.)";
    // A work offset the post does not select: it writes its own (SET/n) again at the next move,
    // so the cuts after INSERT/G55 ran in G54, certified (helper-45). The register in force is
    // harmless to say again.
    // (Its index: 1 = G54 ... 6 = G59, 7.. the extended registers, G54.1 P1 or G154 P1 = 7;
    // Haas's G110-G129 = G154 P1-P20. A machine that writes no work offset leaves the block's
    // in force, which verify judges.)
    if (!m_.codes.work_offset.empty()) {
      int index = 0;
      const std::vector<double> p = code_numbers(text, 'P');
      if (is(g, 54) && !p.empty()) index = 6 + int(std::lround(p.front()));  // Fanuc's G54 Pn = G54.1 Pn
      else if (g > 53.5 && g < 59.5 && is(g, std::round(g))) index = int(std::lround(g)) - 53;
      else if (is(g, 54.1) || is(g, 154)) index = p.empty() ? -1 : 6 + int(std::lround(p.front()));
      else if (g > 109.5 && g < 129.5 && is(g, std::round(g))) index = 6 + int(std::lround(g)) - 109;
      const int in_force = work_offset_ > 0 ? work_offset_ : m_.offsets.default_index;
      if (index != 0 && index != in_force)
        return "selects a work offset (" + code + ") other than the one the post has in force: it writes its own "
               "with the next move, so the cuts after it would not run in the block's; SET/n (55 for G55, 101 for the "
               "first extended register) selects it, with its frame (CAMERA, MSYS) if it has one";
    }
    if (is(g, 10) || is(g, 52) || (!lathe && (is(g, 92) || is(g, 16) || is(g, 51) || is(g, 51.1) || is(g, 68) ||
                                              is(g, 68.2) || is(g, 68.3) || is(g, 68.4))))
      return "changes the coordinate system or its offsets (" + code + "), so the program's positions would mean "
             "other places: the frames (SET, CAMERA, MSYS) give them";
    // A lathe's G50 with axis words sets the coordinate system where the tool stands (its G50 S
    // is the spindle clamp, which moves nothing).
    if (lathe && is(g, 50) &&
        (!code_numbers(text, 'X').empty() || !code_numbers(text, 'Z').empty() || !code_numbers(text, 'U').empty() ||
         !code_numbers(text, 'W').empty()))
      return "sets the coordinate system where the tool stands (G50 with axis words), so the program's positions "
             "would mean other places: the frames (SET, ORIGIN) give them";
    if (!lathe && (is(g, 43) || is(g, 44) || is(g, 43.4) || is(g, 43.5) || is(g, 234)))
      return "applies a tool length offset (" + code + "), which the post applies from LOADTL (and MULTAX)";
    if (!lathe && is(g, 49) && tcp_in_force())
      return "cancels tool centre point control (G49), which MULTAX motion is written for";
    if (!lathe && (is(g, 73) || is(g, 74) || is(g, 76) || (g > 80.5 && g < 89.5)))
      return "starts a drilling cycle (" + code + "): CYCLE records give it";
    if (lathe && (is(g, 32) || is(g, 34) || (g > 69.5 && g < 76.5) || is(g, 90) || is(g, 92) || is(g, 94)))
      return "starts a cycle or a thread cut (" + code + "): CYCLE and THREAD records give it";
    // Every S after a G96 is a surface speed, with no clamp: a face cut at 800 rpm ran at 800
    // m/min, 12700 rpm at 20 mm across (certified).
    if (lathe && (is(g, 96) || is(g, 97)))
      return "turns constant surface speed " + std::string(is(g, 96) ? "on" : "off") + " (" + code +
             "), so every S after it would be read as the other kind of speed: SPINDL/SMM|SFM (with MAXRPM) or "
             "SPINDL/RPM gives it";
  }
  // An H alone changes the length offset in force on a mill (G43 stays modal with the new
  // register): every Z after it would be off by the two registers' difference.
  // (In a macro call, G65, H and D are arguments: a probing macro's tolerance, a diameter.)
  bool macro_call = false;
  for (double g : code_numbers(text, 'G')) macro_call |= is(g, 65);
  if (!lathe && !macro_call && !code_numbers(text, 'H').empty())
    return "changes the tool length register (H), which the post selects from LOADTL: every Z after it would be off";
  if (!macro_call && !code_numbers(text, 'D').empty() && comp_on_)
    return "changes the cutter compensation register (D) while a CUTCOM is on: every point after it would be off";
  // An O word (or ':') at the start of a block begins another program when the file is loaded:
  // the program would end there.
  std::string_view head = text;
  while (!head.empty() && (head.front() == ' ' || head.front() == '\t')) head.remove_prefix(1);
  if (!head.empty() && (head.front() == 'O' || head.front() == ':') && head.size() > 1 &&
      std::isdigit(static_cast<unsigned char>(head[1])))
    return "starts another program (" + std::string(head.substr(0, head.find(' '))) +
           "): loaded into the control, the program would end before it; the post writes the program number";
  for (double mc : code_numbers(text, 'M')) {
    const int n = int(std::lround(mc));
    if (n == 2 || n == 30)
      return "ends the program (M" + std::to_string(n) + "): the blocks after it would never run; the post ends it";
    if (n == 97)
      return "calls a local subprogram (M97, Haas): the control jumps to the N number it names, and the post writes "
             "no subprograms";
    if (n == 98 || n == 99)
      return "calls or returns from a subprogram (M" + std::to_string(n) + "): in a main program M99 starts it again "
             "from the top, endlessly; the post writes no subprograms";
    if (n == 6) return "changes the tool (M06): LOADTL gives it";
    // The post clamps the rotaries after each positioning and unclamps them before the next:
    // one clamped behind its back is turned against its brake.
    for (const RotaryAxis& r : m_.kinematics.rotaries)
      for (const std::string* brake : {&r.clamp, &r.unclamp})
        for (double b : code_numbers(*brake, 'M'))
          if (std::lround(b) == n)
            return "clamps or unclamps the rotary axis " + r.name + " (M" + std::to_string(n) +
                   "), which the post does around each rotary move: the next would turn it against its brake, "
                   "or cut with it free";
    if (n == 3 || n == 4 || n == 5 || n == 19)
      return "turns, stops or orients the spindle (M" + std::to_string(n) + ") where the post's spindle state does not "
             "follow: SPINDL gives it";
  }
  return {};
}

// A tool fed with the spindle stopped is a warning: CL files feed tools that do not turn
// (CATIA's peening and incremental forming, NX course files without SPINDL). But a cutter whose
// spindle the CL turned and then stopped with SPINDL/OFF, fed on without a SPINDL to start it
// again, is fed into the part without turning: an error, said once (helper-67). Not a feed
// straight away from the part (`away`: up a mill's Z), the retract after it. A SPINDL/OFF
// between a tool change and the new tool's first move says that tool does not turn (a forming
// or peening tool after a cutter): its feeds warn.
void ProgramWriter::warn_spindle_stopped(SourceLoc loc, const char* what, bool away) {
  if (spindle_ != ir::SpindleDir::Off) return;
  if (cl_stopped_spindle_at_.valid() && !away) {
    d_.error(loc, std::string(what) + " with the spindle stopped: SPINDL/OFF at line " +
                      std::to_string(cl_stopped_spindle_at_.line) +
                      " stopped it and no SPINDL starts it again, so the cutter would be fed in without turning");
    cl_stopped_spindle_at_ = {};
    spindle_stop_refused_ = true;
    return;
  }
  if (!spindle_stop_refused_) d_.warning(loc, std::string(what) + " with the spindle stopped", "spindle-stopped");
}

void ProgramWriter::note_plane_codes(std::string_view text) {
  // By the G numbers, as the control reads them: outside comments, G018 as G18.
  const std::vector<double> gs = code_numbers(text, 'G');
  auto has = [&](const CodeTemplate& code) {
    for (double want : code_numbers(code.text, 'G'))
      for (double g : gs)
        if (std::abs(g - want) < 1e-6) return true;
    return false;
  };
  if (has(m_.codes.plane_zx) || has(m_.codes.plane_yz)) off_xy_plane_ = true;
  else if (has(m_.codes.plane_xy)) off_xy_plane_ = false;
}

void ProgramWriter::xy_plane_code() {
  if (m_.is_lathe() || !off_xy_plane_) return;
  e_.code(m_.codes.plane_xy);
  plane_ = Plane::XY;
  off_xy_plane_ = false;
}

void ProgramWriter::comp_code() {
  if (!comp_pending_set_) return;
  const ir::CutterComp& c = comp_pending_;
  if (c.side == ir::CompSide::Off) {
    e_.code(m_.codes.comp_off);
  } else {
    xy_plane_code();
    int reg = c.reg > 0 ? c.reg : tool_;
    // Left and right of the path are seen from the side the control views its plane from, as
    // G02/G03 are: a lathe viewing from -Y swaps them too.
    bool left = c.side == ir::CompSide::Left;
    if (m_.is_lathe() && m_.lathe.arcs_from_minus_y) left = !left;
    e_.code(left ? m_.codes.comp_left : m_.codes.comp_right,
            TemplateVars().with(Var::Register, reg).with(Var::Tip, m_.lathe.tip));
  }
  comp_pending_set_ = false;
  comp_on_ = c.side != ir::CompSide::Off;
  comp_now_ = c;
}

void ProgramWriter::end_pending_comp() {
  // (One that cancels nothing stays for the next move, as the CL's CUTCOM/OFF asks.)
  if (!comp_pending_set_ || comp_pending_.side != ir::CompSide::Off || !comp_on_) return;
  check_comp_end_in_cut();
  e_.begin({});
  e_.code(m_.codes.comp_off);
  e_.end();
  comp_pending_set_ = false;
  comp_on_ = false;
}

void ProgramWriter::write_cutter_comp(const ir::CutterComp& c, SourceLoc loc) {
  // A mill's G41/G42 offsets in the plane square to the tool (G17, or the tilted frame's):
  // the CL's compensation in a plane the tool is not square to would be taken in another one.
  // (A lathe's CL names its turning plane as its CAM system draws it: the lathe's either way.)
  if (!m_.is_lathe() && c.side != ir::CompSide::Off && c.plane != 0) {
    d_.error(loc, std::string("CUTCOM in the ") + (c.plane == 'Z' ? "XY" : c.plane == 'Y' ? "ZX" : "YZ") +
                      " plane, which is not square to the tool axis: a mill's cutter compensation is taken in the "
                      "plane square to the tool, so the offset would be taken in another plane than the CL asks");
    return;
  }
  // The side and register already in force: nothing starts (a CUTCOM/LEFT repeated before an arc).
  if (comp_on_ && !comp_pending_set_ && c.side == comp_now_.side && c.reg == comp_now_.reg) return;
  // A register the machine's G41/G42 has no place for (a Fanuc lathe takes the nose radius and
  // tip from the offset its T word selects) is not written: say so once, unless it is the
  // register the T word selects anyway.
  const CodeTemplate& code = c.side == ir::CompSide::Left ? m_.codes.comp_left : m_.codes.comp_right;
  if (c.side != ir::CompSide::Off &&
      lacks(code, loc, c.side == ir::CompSide::Left ? "comp_left" : "comp_right",
            "offset the cutter to the " + std::string(c.side == ir::CompSide::Left ? "left" : "right") + " of the path",
            "the cut would run on the tool's centre"))
    return;
  if (c.side == ir::CompSide::Off && (comp_on_ || comp_pending_set_) && lacks(m_.codes.comp_off, loc, "comp_off", "end cutter compensation"))
    return;
  const int selected = length_offset_ > 0 ? length_offset_ : tool_;
  if (c.side != ir::CompSide::Off && c.reg > 0 && c.reg != selected && c.reg != comp_register_said_ &&
      !code.uses(Var::Register)) {
    d_.warning(loc, "CUTCOM register " + std::to_string(c.reg) + " is not written: the " +
                        (c.side == ir::CompSide::Left ? "comp_left" : "comp_right") + " code of machine '" + m_.name +
                        "' ('" + code.text + "') takes no register, so the compensation uses offset " +
                        std::to_string(selected) + ", the one the T word selects",
               "tool-offset");
    comp_register_said_ = c.reg;
  }
  comp_pending_ = c;
  comp_pending_set_ = true;
  comp_loc_ = loc;
  if (c.side == ir::CompSide::Off) moved_since_off_ = false;
}

// Before a retract of the post's own in mid-program (the next fixture, a setup stop): G41/G42
// ended first, in a block of its own, where the tool last went up or rapided; the control takes
// it on the retract, up there. Where the tool last cut, or with the CL's compensation still on
// (it would run on into the next fixture or setup), an error: the G40 was written on the
// retract's way, and the tool pulled into the wall (helper-72: certified).
void ProgramWriter::end_comp_before_retract(SourceLoc loc, const std::string& what) {
  if (!comp_on_) return;
  // (Ended, or replaced by the next operation's CUTCOM/LEFT before its approach, which stays
  // waiting for its move across: only G41/G42 in force with nothing after it is left on;
  // helper-73.)
  const bool off = comp_pending_set_ && comp_pending_.side == ir::CompSide::Off;
  if (!comp_pending_set_ || left_in_cut_)
    d_.error(loc, what + " with cutter compensation " + (off ? "ended by a CUTCOM/OFF (line " : "on (CUTCOM at line ") +
                      std::to_string(comp_loc_.line) + ")" + (off ? " with no move after it, where the tool last cut" : "") +
                      ": the post retracts first, and the control would end G41/G42 on that retract, pulling the tool "
                      "by its radius toward the contour; end compensation before it (CUTCOM/OFF, then a move across and "
                      "away from the wall, or straight up the tool axis)");
  left_in_cut_ = false;
  e_.begin(loc);
  e_.code(m_.codes.comp_off);
  e_.end();
  comp_on_ = false;
  if (off) comp_pending_set_ = false;
}

void ProgramWriter::check_comp_end_in_cut() {
  // Fanuc, Haas: a G40 in a block with no move ends the offset on the next move; here that is
  // the post's own (the finish's Z home, a tool change's retract), which goes from the offset
  // point to the contour point, into the wall by the radius, at the cut's depth (helper-67:
  // certified). Said where the CL's compensation ends or is left on.
  if (!left_in_cut_) return;
  left_in_cut_ = false;
  const bool off = comp_pending_set_ && comp_pending_.side == ir::CompSide::Off;
  d_.error(comp_loc_, std::string(off ? "CUTCOM/OFF with no move after it" : "cutter compensation left on to the end") +
                          ", where the tool last cut: the control ends G41/G42 on the post's next move (the retract), "
                          "which pulls the tool by its radius onto the contour, into the wall; give a move after "
                          "CUTCOM/OFF, across and away from the wall, or end it after a retract straight up the tool "
                          "axis");
}

}  // namespace clpc
