// A G-code interpreter for the dialects clpc writes (Fanuc/Haas mill, Fanuc lathe system A),
// written independently of the emitter: it knows what the codes mean from the controls'
// documentation, not from the machine description's code tables. The machine description
// supplies only what a control's parameters would: number formats (decimal point rules,
// diameter X), the family, units and the rotary axes. clpc verify, clpc plot and the tests
// read programs back with it.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "machine/machine.h"
#include "ir/ir.h"

namespace clpc::gcode {

using ir::Vec3;

// A tilted working plane (G68.2, G268): X Y Z written in it are origin + rotation * (X Y Z) in
// the work offset's frame.
struct PlaneFrame {
  Vec3 origin = Vec3::Zero();
  ir::Mat3 rotation = ir::Mat3::Identity();
};

struct Segment {
  enum class Kind : uint8_t { Rapid, Feed, Arc };
  Kind kind = Kind::Feed;
  Vec3 start, end;            // tool tip in the work-offset frame, output units (lathe X radius)
  Vec3 center = Vec3::Zero();  // arcs: centre in the plane of the start
  Vec3 normal = Vec3::UnitZ();  // arcs: plane normal (+Z, +Y, +X for G17, G18, G19)
  bool ccw = false;           // arcs: counter-clockwise about normal
  double sweep = 0;           // arcs: degrees
  double start_radius = 0, end_radius = 0;  // arcs: as the control computes them
  double feed = 0;            // output units per minute (0 for rapids; inverse time: 1/min)
  bool inverse_time = false;
  bool per_rev = false;       // feed per revolution (G95 / lathe G99)
  double rpm = 0;             // spindle speed during the segment (0: stopped)
  bool spindle = false;       // the spindle turns (M03/M04 in force, no M05, M00, M01 or M06 since)
  int spindle_code = 0;       // the M code that started it turning (3: M03, 4: M04)
  bool coolant = false;       // a coolant is on (M07, M08, M88, M83 and not its off code since)
  std::array<double, 3> rotary{0, 0, 0};  // A B C at the end (degrees)
  std::array<double, 3> rotary_start{0, 0, 0};
  int work_offset = 1;        // 1 = G54 ... 6 = G59, 7.. = extended
  int tool = 0;
  int length_register = 0;    // the tool length offset in force (G43 H; lathe T's offset), 0: none
  int comp = 0;               // cutter compensation in force: 0 none (G40), 1 left (G41), 2 right (G42)
  int comp_register = 0;      // the D register G41/G42 took (0: none given)
  int line = 0;               // G-code line
  bool from_cycle = false;    // expanded from a canned cycle
  uint8_t cycle = 0;          // that cycle's G code (81 ... 89, 73, 74, 76), 0: none
  float dwell = 0;            // seconds dwelt at the end (a canned cycle's P)
  float dwell_before = 0;     // seconds dwelt before it (G04 blocks since the last segment)
  bool thread = false;        // a thread cut (G32, G92, G76): synchronised with the spindle, feed = the lead per revolution
  bool tcp = false;           // tool centre point control on: X Y Z are the tip in the part frame
  bool dwo = false;           // dynamic work offset on: X Y Z turned with the table about the part zero
  // A tilted working plane in force (G68.2 / G268): X Y Z are in it. Shared: segments outlive
  // the reader that read them (a null one costs nothing to copy).
  std::shared_ptr<const PlaneFrame> plane;
};

// A block's length over all its axes at once (output units and degrees): what a control in
// degrees-per-minute mode takes F along (kinematics.degrees_per_minute). A modulo axis turns
// the short way (C350 to C10 is 20 degrees).
double combined_length(const Segment& s, const KinematicsSettings& k);

// Whether F of this block is over all its axes on a degrees-per-minute machine: a feed move,
// without TCPC or G93, that turns a rotary.
inline bool feeds_combined(const Segment& s) {
  if (s.kind != Segment::Kind::Feed || s.tcp || s.inverse_time) return false;
  for (size_t i = 0; i < 3; ++i)
    if (s.rotary[i] != s.rotary_start[i] && s.rotary[i] == s.rotary[i] && s.rotary_start[i] == s.rotary_start[i]) return true;
  return false;
}

struct Event {
  enum class Kind : uint8_t { ToolChange, Spindle, Coolant, Dwell, Stop, OffsetSet, CycleStart };
  Kind kind;
  int line = 0;
  double value = 0;
  int reg = 0;
  Vec3 v = Vec3::Zero();
};

struct Problem {
  int line = 0;
  std::string message;
};

struct Result {
  std::vector<Segment> segments;
  std::vector<Event> events;
  std::vector<Problem> problems;  // what a control would alarm on, or the reader cannot follow
  int tool_changes = 0;
  int cycles = 0;
  int blocks = 0;
  bool ended = false;             // M30 / M02 seen
  ir::Units units = ir::Units::Mm;
  bool units_set = false;
};

struct Options {
  // Start and end radius may differ by this much (output units) before the control alarms;
  // 0 = one increment of the coarsest of X, I and K.
  double arc_radius_tolerance = 0;
};

Result interpret(std::string_view program, const Machine& m, const Options& opt = {});

// The same, a line at a time, for programs too large to hold: each line's segments, events
// and problems are appended to result(), which the caller may drain between lines.
class Reader {
 public:
  explicit Reader(const Machine& m, const Options& opt = {});
  ~Reader();
  void line(std::string_view text);  // without its line end
  Result& result();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace clpc::gcode
