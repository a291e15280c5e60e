#pragma once

#include "backends/backend.h"

namespace clpc {

class MillBackend : public ProgramWriter {
 public:
  MillBackend(const Machine& m, OutputFile& out, Diagnostics& d);

 protected:
  void write_move(const ir::Move& m, SourceLoc loc) override;
  void write_arc(const ir::Operation& op, const ir::Arc& a, SourceLoc loc) override;
  void write_tool_change(const ir::ToolChange& t, SourceLoc loc) override;
  void write_hole(const ir::Operation& op, const ir::Hole& h, SourceLoc loc) override;
  void cancel_cycle(SourceLoc loc) override;
  void write_rotary_position(const ir::RotaryPosition& r, SourceLoc loc) override;
  void write_mode(const ir::MachineMode& m, SourceLoc loc) override;

  void rotary_words(const std::array<double, 2>& a, bool modal);
  void unclamp(SourceLoc loc);
  void turn_rotaries(const std::array<double, 2>& angles, bool modal, SourceLoc loc);
  void say_rotaries(SourceLoc loc);
  bool rotaries_unsaid_ = false;  // after another tool's change: the next rotary block says every rotary
  void clamp(SourceLoc loc);
  void inverse_time_words(const ir::Move& m, SourceLoc loc);

  void start_program() override;
  void after_finish() override;

  void work_offset_code();
  void retract(SourceLoc loc);  // codes.safe_retract
  void moved();                 // after a block that moved the tool
  // The code selecting work-offset register `index` (1 = G54 ...) and its number word.
  std::pair<const CodeTemplate*, TemplateVars> offset_select(int index) const;
  // The offset table (backends/mill_offsets.cpp).
  void write_offset_table();
  void write_offset_macro();
  void motion_code(Motion mo);
  bool check_axis(const ir::Vec3& axis, SourceLoc loc);
  bool comp_tilt_said_ = false;  // compensation with the tool tilted in the program's coordinates refused (said once)
  bool changed(char letter, double value) const;

  // The canned cycle the control has active, as last written.
  struct ActiveCycle {
    const CodeTemplate* code = nullptr;
    double bottom = 0, r = 0, peck = 0, dwell = 0, feed = 0, top = 0;
    bool left_hand = false;
  };
  bool cycle_active_ = false;
  ActiveCycle cycle_;
  bool clamped_ = false;
  bool tcp_on_ = false;
  bool tcp_in_force() const override { return tcp_on_; }
  bool at_safe_height_ = true;  // nothing moved since the last safe retract
  template <class RotaryWords>
  void position_across(const Emitter::Rounded& x, const Emitter::Rounded& y, bool rotaries, const RotaryWords& rotary_words,
                       SourceLoc loc);
  // Rotaries clamped in a position (3+2) when a raw block that may move the axes came: the next
  // move positions them again as the post does (retract, unclamp, rotaries alone, clamp).
  // Restated with the move they were unclamped and never clamped again.
  bool reposition_rotaries_ = false;
  // A raw block that may move axes (G53 Z0., G28, a macro) leaves the tool where the CL does not
  // know: the next rapid positions X Y first and then comes down along Z, as after a retract
  // (written whole it went down and across at once from machine home into the part). Where the
  // blocks only took Z home (returns_z_home), X Y stand over the CL's last point: a rapid up
  // from there goes up first (from a pallet change or a G28 X Y, up first went down at an
  // unknown X Y).
  bool after_raw_move_ = false, raw_z_only_ = false;
  void after_raw_motion(bool z_home) override {
    reposition_rotaries_ = clamped_;
    raw_z_only_ = after_raw_move_ ? raw_z_only_ && z_home : z_home;  // every block since the last move
    after_raw_move_ = true;
  }
  void retract_for_stop(SourceLoc loc) override {
    if (!at_safe_height_ && tool_ >= 0) retract(loc);
  }
  // Another fixture: up to the safe height in the old offset first, the cycle cancelled. Its
  // XY and Z in the new offset came in one rapid at the height the tool was at, or a cycle's
  // holes stayed in the old offset (helper-70: both certified).
  void before_offset_change(SourceLoc loc) override {
    cancel_cycle(loc);
    if (at_safe_height_ || tool_ < 0) return;
    end_comp_before_retract(loc, "another work offset (the next fixture)");
    retract(loc);
  }
};

}  // namespace clpc
