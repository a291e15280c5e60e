// Backends turn legal IR into a program for one machine. ProgramWriter holds what every
// family shares (program frame, header, spindle, coolant, stops, comments, feeds); the mill
// and lathe backends add motion and tool changes, the structure tables cannot express.
#pragma once

#include <memory>

#include "backends/emitter.h"
#include "machine/machine.h"
#include "support/diagnostics.h"
#include "ir/ir.h"
#include "ir/sink.h"

namespace clpc {

// A backend is the sink that writes G-code for one machine.
class Backend : public ProgramSink {
 public:
  void begin(const ir::ProgramInfo& info) override = 0;
  void operation(const ir::Operation& op) override = 0;
  void end() override = 0;
};

std::unique_ptr<Backend> make_backend(const Machine& m, OutputFile& out, Diagnostics& d);

class ProgramWriter : public Backend {
 public:
  ProgramWriter(const Machine& m, OutputFile& out, Diagnostics& d);
  void begin(const ir::ProgramInfo& info) override;
  void operation(const ir::Operation& op) override;
  void end() override;

 protected:
  // Family-specific hooks.
  virtual void write_move(const ir::Move& m, SourceLoc loc) = 0;
  virtual void write_arc(const ir::Operation& op, const ir::Arc& a, SourceLoc loc) = 0;
  virtual void write_tool_change(const ir::ToolChange& t, SourceLoc loc) = 0;
  virtual void write_spindle(const ir::Spindle& s, SourceLoc loc);
  virtual void write_feed_mode(ir::FeedMode mode);
  virtual void start_program() {}
  virtual void before_finish() {}  // after the last operation, before the finish blocks
  virtual void after_finish() {}  // after the finish blocks, before program_end (e.g. subprograms)
  virtual void write_rotary_index(const ir::RotaryIndex& r, SourceLoc loc);
  virtual void write_hole(const ir::Operation& op, const ir::Hole& h, SourceLoc loc);
  virtual void write_groove(const ir::Operation& op, const ir::Groove& g, SourceLoc loc);
  virtual void write_thread_mark(const ir::ThreadMark& t, SourceLoc loc);
  virtual void write_thread_cycle(const ir::ThreadCycle& t, SourceLoc loc);
  // A CYCLE/ROUGH section: op.body[at] is its begin mark; the backend writes the section whole
  // and sets resume_at_ past its end mark.
  virtual void write_rough(const ir::Operation& op, size_t at, SourceLoc loc);
  virtual void write_rotary_position(const ir::RotaryPosition& r, SourceLoc loc);
  virtual void write_mode(const ir::MachineMode& m, SourceLoc loc);
  virtual void write_stop(const ir::Stop& s, SourceLoc loc);
  virtual void retract_for_stop(SourceLoc loc) {}
  virtual void before_offset_change(SourceLoc loc) {}  // another work offset (fixture) is selected
  // A raw block that may have moved the axes was written (`z_home`: it took Z alone to its home).
  virtual void after_raw_motion(bool /*z_home*/) {}
  // Ends a run of canned-cycle holes (G80) if one is active.
  virtual void cancel_cycle(SourceLoc loc) {}

  void visit(const ir::Operation& op, const ir::Instr& in);
  // The per-job options around a tool change (docs/machines.md, "Per-job options"): the
  // backends call these around their own tool-change blocks.
  void before_tool_change(SourceLoc loc);
  void optional_stop_between_operations(SourceLoc loc);
  void after_tool_change(int tool, SourceLoc loc);
  // Before motion: the coolant a tool change turned off, on again (unless the CL said).
  void restore_coolant(SourceLoc loc);
  // Before motion: the spindle and the coolant a tool change or a stop turned off, on again.
  void restore_after_stop(SourceLoc loc, bool cut);
  // The control stopped the spindle (M06 on a mill; M00, M01 with the coolant too).
  void control_stopped(bool coolant_too, bool tool_change);
  void write_smoothing(bool on);
  // In a straight move's block: G41/G42/G40 where a CUTCOM changed it.
  void comp_code();
  // A G40 still waiting for a move across (a mill cancels on one) written in a block of its
  // own, before what must not run with compensation on: a tool change, a hole, a turn of the
  // rotaries, a raw block that may move axes.
  void end_pending_comp();
  // False (an error naming the SPINDL) when `rpm` is above the machine's spindle limit.
  bool spindle_within_limit(double rpm, SourceLoc loc);
  bool tool_changer_for(const ir::ToolChange& t, SourceLoc loc);  // false: the machine cannot change to t
  void check_lathe_frame(const ir::SetFrame& x, SourceLoc loc);  // one setup: frames shifted along Z only
  std::optional<ir::Mat3> first_csys_;                           // a lathe's first CSYS, the setup's turn
  // True (and an error at loc) when the machine's TOML leaves `code` empty: it lacks the
  // function (codes.<key>), and what the CL asks for cannot be written.
  bool lacks(const CodeTemplate& code, SourceLoc loc, const char* key, const std::string& what,
             const std::string& why = {});
  bool tool_loaded_for_cut(SourceLoc loc);  // false (and an error, once) when no tool is loaded
  void write_header(const ir::ProgramInfo& info);
  long program_number(const ir::ProgramInfo& info) const;
  void write_coolant(const ir::Coolant& c, SourceLoc loc);
  void write_dwell(const ir::Dwell& d, SourceLoc loc);
  void write_cutter_comp(const ir::CutterComp& c, SourceLoc loc);
  void blocks(const std::vector<CodeTemplate>& list, SourceLoc loc);
  void after_template(const CodeTemplate& t);
  // Follows the plane codes in a template's or an inserted block's words (off_xy_plane_).
  void note_plane_codes(std::string_view text);
  // Why an inserted block may not be written (a state it sets that the post does not keep), or "".
  std::string unkept_code(std::string_view text) const;
  // A cut (a feed move, an arc, a hole) with the spindle stopped: a warning (-Wspindle-stopped).
  void warn_spindle_stopped(SourceLoc loc, const char* what, bool away = false);
  virtual bool tcp_in_force() const { return false; }
  // The spindle's rpm a dwell in revolutions is timed by (0: none known).
  virtual double dwell_rpm() const { return spindle_ == ir::SpindleDir::Off ? 0 : spindle_rpm_; }
  // A mill's cycles and compensation: G17 first where the control may be in another plane.
  void xy_plane_code();
  // Motion blocks are absolute: restores G90 after a template left the control incremental.
  void absolute_code();
  // For a cutting block: the feed-mode code when it changed (before the motion code) and
  // the F word when the feed changed (after the coordinates).
  void feed_mode_code();
  // A cycle's own feed mode (CYCLE/...,MMPR), written where it changes. The CL's mode stays what
  // its FEDRAT set, so the plain moves after the cycle go back to it.
  void feed_mode_code(ir::FeedMode mode);
  bool feed_word(SourceLoc loc);
  // F in the format of its kind (feeds.*), refused where rounding makes it zero or changes it by
  // more than feeds.max_rounding; `cl` is the record the feed came from.
  bool write_feed(double value, ir::FeedMode mode, SourceLoc cl);
  // A tap's F (its pitch per revolution, or pitch x S per minute): refused where rounding would
  // lose sync over the tap's depth by half an output increment or more.
  bool write_tap_feed(double value, double pitch, double rpm, double depth, SourceLoc cl);
  std::string tool_comment(const ir::ToolInfo& t) const;
  std::string length_text(double program_units) const;

  const Machine& m_;
  Emitter e_;
  Diagnostics& d_;
  const ir::ProgramInfo* info_ = nullptr;
  double k_ = 1;  // program units -> output units

  int tool_ = -1;
  int length_offset_ = 0;
  bool need_length_offset_ = false;
  bool need_work_offset_ = true;
  int work_offset_ = 0;  // 0 = the machine's default register
  enum class Motion : uint8_t { None, Rapid, Linear, Cw, Ccw } motion_ = Motion::None;
  enum class Plane : uint8_t { None, XY, ZX, YZ } plane_ = Plane::None;
  // The control may be in G18/G19 (an arc, a template or an inserted block put it there). A
  // mill's drilling cycles and cutter compensation work in G17: they write it first. plane_
  // forgets after a template; this does not.
  bool off_xy_plane_ = false;
  ir::FeedMode feed_mode_ = ir::FeedMode::PerMinute;  // as programmed
  ir::FeedMode written_feed_mode_ = ir::FeedMode::PerMinute;  // as the control has it
  bool feed_mode_known_ = false;
  double feed_ = 0;  // program units
  bool feed_known_ = false;
  bool no_feed_said_ = false;  // "no feed rate" was said: once per program
  SourceLoc feed_loc_;      // the FEDRAT the feed came from
  // The CL record whose move the last inverse-time F (FEDRAT/INVERS) was written for, and the
  // last one refused: a record's move split into blocks must not give each block its time.
  SourceLoc inverse_for_{}, inverse_refused_{};
  bool in_cycle_ = false;  // between a CycleOn and its CycleOff
  SourceLoc feed_clamp_said_;  // the FEDRAT whose clamp to max_feed was warned
  size_t resume_at_ = 0;   // the operation's next instruction to write (past a section written whole)
  bool feed_written_ = false;
  ir::SpindleDir spindle_ = ir::SpindleDir::Off;
  double spindle_rpm_ = 0;  // last programmed speed (rpm mode)
  ir::CoolantKind coolant_ = ir::CoolantKind::Off;
  ir::CutterComp comp_pending_;
  bool comp_pending_set_ = false;
  bool comp_on_ = false;  // G41/G42 written and no G40 since
  bool moved_since_off_ = false;  // a move written since the last CUTCOM/OFF
  SourceLoc comp_loc_;  // the CUTCOM written last (on or off)
  // The last move was a cut that may have left the tool against the wall it cut (a mill's feed
  // other than straight up its axis, an arc): a G40 with no move of its own here is taken on
  // the retract after it, and pulls the tool by its radius onto the contour.
  bool left_in_cut_ = false;
  void check_comp_end_in_cut();  // before such a G40
  void end_comp_before_retract(SourceLoc loc, const std::string& what);
  bool sets_distance_mode(const CodeTemplate& t) const;  // holds codes.absolute or codes.incremental
  void absolute_before(const std::vector<CodeTemplate>& list, SourceLoc loc);  // G90 before a fixed list, if needed
  void write_block(const CodeTemplate& t, SourceLoc loc);  // one fixed block
  ir::CutterComp comp_now_;  // the compensation written last
  int comp_register_said_ = 0;  // the CUTCOM register last said not to be written (0: none), for this tool
  bool no_tool_reported_ = false;  // "cutting with no tool loaded" said once
  bool incremental_ = false;  // a template (G91 G28 Z0.) left the control incremental
  bool position_known_ = false;
  bool cut_since_stop_ = false;     // something moved since the program start or the last M01
  bool stop_pending_ = false;       // optional_stop = "operation": M01 before the operation's first action
  bool coolant_restore_ = false;    // turn coolant_after_ on before motion (a tool change or a stop turned it off)
  // The CL's spindle runs until SPINDL/OFF; M06 (on a mill), M00 and M01 stop it on the
  // machine. The last SPINDL that started it is started again before the next motion, unless
  // the CL gives a SPINDL of its own first.
  std::optional<ir::Spindle> spindle_on_;
  bool tool_turned_ = false;           // the CL turned the spindle for the tool loaded (or the post did again)
  SourceLoc cl_stopped_spindle_at_;    // the CL's SPINDL/OFF that stopped it, until a spindle starts
  bool spindle_stop_refused_ = false;  // a cut after it was refused: no warning for each move after
  bool spindle_restore_ = false;
  bool spindle_restore_before_move_ = false;  // restored before the next move, a rapid too (a lathe's index)
  bool spindle_restore_warn_ = false;  // the restore follows a tool change: the new tool runs at the last one's speed
  ir::CoolantKind coolant_after_ = ir::CoolantKind::Off;
  size_t tool_change_at_ = 0;       // where in info_->tool_changes the last change was
  ir::Vec3 pos_ = ir::Vec3::Zero();  // last programmed tool tip, program units
};

}  // namespace clpc
