#pragma once

#include <optional>

#include "backends/backend.h"

namespace clpc {

// Turning in the ZX plane: X written as a diameter (the X format's scale), T0101 tool words,
// constant surface speed with a G50 clamp, feed per revolution, G18 arcs with I and K.
class LatheBackend : public ProgramWriter {
 public:
  LatheBackend(const Machine& m, OutputFile& out, Diagnostics& d);

 protected:
  void write_move(const ir::Move& m, SourceLoc loc) override;
  void write_arc(const ir::Operation& op, const ir::Arc& a, SourceLoc loc) override;
  void write_tool_change(const ir::ToolChange& t, SourceLoc loc) override;
  void write_spindle(const ir::Spindle& s, SourceLoc loc) override;
  void write_groove(const ir::Operation& op, const ir::Groove& g, SourceLoc loc) override;
  void retract_for_stop(SourceLoc loc) override;
  void write_thread_mark(const ir::ThreadMark& t, SourceLoc loc) override;
  void write_thread_cycle(const ir::ThreadCycle& t, SourceLoc loc) override;
  void write_rough(const ir::Operation& op, size_t at, SourceLoc loc) override;  // backends/lathe_rough.cpp
  void before_finish() override;

  // The retract home (backends/lathe_retract.cpp). The reach of this tool's cuts: how far out
  // in X and how far toward +Z any of them went. The machine's retract (G28 U0. W0.) takes
  // the tool to home, out in X and Z at once; it leaves the part only from beyond that reach.
  struct CutReach {
    bool any = false;
    double x = 0, z = 0;  // program units
    SourceLoc last;       // the last cut's record
    bool went_in = false; // the last motion was a cut toward the axis or the chuck (-X, -Z)
  };
  CutReach reach_;
  void note_cut(const ir::Vec3& p, SourceLoc loc);
  void note_cut_to(const ir::Vec3& to, SourceLoc loc);  // a feed from pos_ to `to`
  void note_arc(const ir::Arc& a, SourceLoc loc);
  bool clear_to_retract(SourceLoc loc, const char* before);

  void motion_code(Motion mo);
  bool stays_on_its_side(double x, bool feed, SourceLoc loc, const char* what = "a feed to");
  int side_ = 0;  // the side of the spindle axis the tool works on: +1, -1, 0 not yet known
  bool in_plane(const ir::Vec3& p, SourceLoc loc);
  SourceLoc off_plane_said_;  // the CL record whose motion off the XZ plane was said
  bool changed(char letter, double value) const;

  // Threading (backends/lathe_thread.cpp).
  bool is_thread_cut(const ir::Vec3& from, const ir::Vec3& to) const;
  void write_thread_move(const ir::Move& mv, SourceLoc loc);
  double thread_lead(SourceLoc loc) const;  // program units per revolution; 0 (an error) if none
  bool write_lead(double lead, double length, SourceLoc loc);
  void fix_spindle_speed(double radius, SourceLoc loc);
  void restore_surface_speed(SourceLoc loc);
  double surface_rpm(double radius) const;
  double dwell_rpm() const override;
  bool speed_on_centre(const ir::Move& mv, SourceLoc loc);  // a drill on the spindle's axis

  std::optional<ir::ThreadMark> thread_;  // the THREAD in force
  std::optional<ir::Spindle> surface_;    // the constant surface speed in force
  double surface_clamp_ = 0;              // its G50 clamp (rpm)
  bool rpm_fixed_ = false;                // G97 written for a thread or a drill under surface_
  double fixed_rpm_ = 0;                  // its S
  double cl_max_rpm_ = 0;                 // the last MAXRPM the CL gave (0: none yet)
  bool drill_fixed_ = false;              // that G97 is a drill's on the axis (speed_on_centre)
  void end_drill_speed(SourceLoc loc);    // G96 back after a drill, before anything else cuts
  SourceLoc thread_loc_;                  // its THREAD record
  bool lead_refused_ = false;             // its lead's rounding reported (once)
};

}  // namespace clpc
