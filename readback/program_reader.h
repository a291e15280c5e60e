// An emitted program read back, a line at a time, as tool-tip segments in the part frame (the
// CL's frame, in output units): through the work offsets the program sets — or, where the
// machine's offsets are set by hand (offsets.table = "none"), the ones clpc computed — the
// rotary positions and the machine's kinematics. Shared by clpc verify and clpc plot; memory
// is bounded by the longest line, whatever the program's size.
#pragma once

#include <cstdio>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>
#include <map>
#include <optional>
#include <set>
#include <ostream>
#include <string>

#include "readback/gcode_interp.h"
#include "readback/motion_time.h"
#include "machine/kinematics.h"
#include "machine/machine.h"
#include "support/handoff.h"
#include "support/source.h"
#include "support/text_channel.h"
#include "ir/ir.h"

namespace clpc {

struct TipSegment {
  gcode::Segment raw;       // as the control reads it (work-offset frame, machine axes)
  ir::Vec3 start, end;      // tool tip, part frame
  ir::Vec3 axis;            // tool axis at the end, part frame
  ir::Vec3 center, normal;  // arcs, part frame
  bool rotates = false;     // the rotaries turn during it
  ir::Vec3 shift = ir::Vec3::Zero();  // the work offset in force when it was read (the offset table)
  int index = 0;            // 0, 1, ... in program order
};

// A program arc as an IR arc (part frame), for the arc geometry functions (ir/arc_geometry.h).
ir::Arc arc_of(const TipSegment& s);

// What the program does besides moving, as read.
struct ProgramTotals {
  long lines = 0, bytes = 0, blocks = 0;
  long rapids = 0, feeds = 0, arcs = 0, cycle_holes = 0, tool_changes = 0;
  double rapid_length = 0, feed_length = 0;      // output units (tool tip in the program's frame)
  double feed_minutes = 0, rapid_minutes = 0, dwell_minutes = 0, tool_change_minutes = 0;
  bool rapid_time_known = true, feed_time_known = true, tool_change_time_known = true;
  // The dynamic estimate (readback/motion_time.h): motion with the machine's velocities and
  // accelerations, plus the dwells and tool changes; known when the machine gives them.
  bool dynamic_known = false;
  double dynamic_minutes = 0;

  double total_minutes() const { return feed_minutes + rapid_minutes + dwell_minutes + tool_change_minutes; }
  bool time_complete() const { return feed_time_known && rapid_time_known && tool_change_time_known; }
};

class ProgramReader {
 public:
  // `info`: the compile's program tables (tools for lengths, the offset table).
  ProgramReader(const Machine& m, const ir::ProgramInfo& info);
  ~ProgramReader();
  bool open(const std::string& path, std::string& error);
  // Reads the program from `c` as its writer hands it over (a compile's output, read back
  // beside the compile); the end of the program is the channel's close.
  void open(TextChannel& c) { channel_ = &c; }
  // From now on the program is read ahead on a thread of its own, segments handed over in
  // batches through a bounded queue (the comparison, the longest stage of a certificate,
  // then does only its own work). next(), take_problems() and totals() give the same as
  // without; totals() waits for the thread.
  void read_ahead();
  // Leaves out the dynamic cycle-time estimate (totals().dynamic_known stays false): a
  // compile's certificate line does not show it, and the planner is a tenth of the reading.
  void skip_dynamic_time() { dynamic_time_ = false; }
  // The next segment, false at the end of the program.
  bool next(TipSegment& s);
  // The tool tip (part frame) a fraction t through a segment, rotaries turning with the axes.
  ir::Vec3 tip_at(const TipSegment& s, double t) const;
  // The tool axis (part frame) a fraction t through a segment, the rotaries turning at
  // proportional rates as the control turns them.
  ir::Vec3 axis_at(const TipSegment& s, double t) const;
  // Whether the rotaries go from one branch to the other (the tilt's sign changes), the tool
  // axis passing the pole (where one rotary is free) on the way.
  bool through_pole(const TipSegment& s) const;
  // Whether tip_at() is a straight line whatever the rotaries do: with tool-centre-point
  // control or in a tilted plane the control moves the tip, not the axes (part_point()).
  static bool tip_moves_straight(const TipSegment& s) { return s.raw.tcp || s.raw.plane; }
  const ProgramTotals& totals();
  // Problems the reader found (a control would alarm, or the reader cannot follow), drained.
  std::vector<gcode::Problem> take_problems();

 private:
  bool read_next(TipSegment& s);
  std::vector<gcode::Problem> take_reader_problems();
  void ahead();
  void stop_ahead();
  bool read_line(std::string& line);
  void take_events();
  void account(const gcode::Segment& s);
  ir::Vec3 part_point(const gcode::Segment& s, const ir::Vec3& p, const kin::Angles& a, const ir::Vec3& shift) const;
  kin::Angles angles(const std::array<double, 3>& abc) const;

  const Machine& m_;
  const ir::ProgramInfo& info_;
  gcode::Reader reader_;
  std::FILE* file_ = nullptr;
  TextChannel* channel_ = nullptr;
  std::string buf_, line_;
  size_t buf_pos_ = 0;
  bool eof_ = false;
  size_t next_segment_ = 0;  // in reader_.result().segments
  int index_ = 0;
  bool use_offsets_ = false;           // the offset table is in force
  std::map<int, ir::Vec3> offsets_;    // register -> machine offset (output units)
  // Machines without rotaries: register -> the turn of its setup (a frame cut with its Z up)
  std::map<int, ir::Mat3> setup_turns_;
  std::optional<size_t> pole_free_;  // kin::pole_free_axis
  const ir::Mat3& setup_turn(int reg) const;
  double reference_height_ = 0;
  // The work offset registers whose zero is known: the machine's default, those the setup
  // lists (the offset table), those the program sets (G10, the G65 macro). A program working
  // in another register cuts wherever that register's zero happens to be.
  std::set<int> known_registers_, reported_registers_;
  ProgramTotals totals_;
  MotionTimer timer_;
  bool dynamic_time_ = true;
  // The tool axis in the part frame at the last segment's angles (at zero: +Z).
  kin::Angles axis_angles_{0, 0};
  ir::Vec3 axis_in_part_ = ir::Vec3::UnitZ();

  // Reading ahead: batches of segments, each with the problems found up to it.
  struct Item {
    TipSegment segment;
    std::vector<gcode::Problem> problems;
    bool end = false;
  };
  static constexpr size_t kBatch = 256, kBatches = 8;
  bool ahead_ = false, stop_ = false;
  bool last_batch_in_ = false;  // the batch with the end is in batches_
  std::thread thread_;
  std::mutex lock_;
  Handoff handoff_{kBatches};
  std::deque<std::vector<Item>> batches_;
  std::vector<Item> current_;
  size_t current_at_ = 0;
  bool ended_ = false;
  bool end_said_ = false;  // a program without M30/M02 reported
  bool table_turned_said_ = false;  // a move with the table turned outside the part's frame reported
  bool turned_without_part_frame(const gcode::Segment& s, const kin::Angles& a0, const kin::Angles& a1) const;
  std::string table_turned_problem() const;
  std::vector<gcode::Problem> problems_;  // of the segments handed over so far
};

}  // namespace clpc
