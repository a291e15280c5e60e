// A machine description, as read from TOML (machines.toml, --machines FILE). Everything a
// control differs in lives here; docs/machines.md documents every key and its default.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "machine/code_template.h"
#include "machine/tilted_plane.h"
#include "ir/ir.h"

namespace clpc {

enum class Family : uint8_t { Mill, Lathe };

// How one address letter's value is written.
struct AddressFormat {
  enum class Point : uint8_t { Always, Never, IfFraction };
  int decimals = 4;             // digits after the point (or implied, with Point::Never)
  Point point = Point::Always;  // Never: the value in least-input units, no point (X12500)
  bool leading_zero = true;     // 0.5 rather than .5
  bool trailing_zeros = false;  // 1.5000 rather than 1.5
  int digits = 0;               // zero-pad the integer part to this many digits (T01, O01234)
  double scale = 1.0;           // e.g. 2 for a lathe's diameter X
  bool plus = false;            // write + on positive values
};

struct SequenceSettings {
  bool enabled = true;
  long start = 10;
  long step = 10;
  long max = 99999;
  long wrap_to = 0;             // after max, continue from this (0 = from start)
  bool tool_change_only = false;
};

struct CommentSettings {
  bool enabled = true;
  std::string open = "(";
  std::string close = ")";
  int max_length = 0;           // 0 = no limit
  bool upper_case = true;
  std::string replacement = " ";  // for characters the control cannot take
};

enum class ArcCenter : uint8_t { Incremental, Absolute, Radius };

struct ArcSettings {
  bool xy = true, zx = true, yz = true;  // planes the control can do (G17, G18, G19)
  bool helical = true;
  double max_sweep = 360;       // degrees per block
  double helix_max_sweep = 360; // degrees per helical block
  double min_radius = 0;        // output units; 0 = none
  double max_radius = 0;        // output units; 0 = none
  ArcCenter center = ArcCenter::Incremental;
  double tolerance = 0.0005;    // output units: chord error allowed when linearising
};

struct ModalSettings {
  bool motion = true;       // drop G00/G01/G02/G03 when unchanged
  bool coordinates = true;  // drop unchanged axis words
  bool feed = true;         // drop an unchanged F
};

struct LatheSettings {
  // G02/G03 are defined as seen from +Y (ISO, Fanuc: right for front and rear tool posts
  // alike, since X is written positive either way). True for a control that views them from
  // -Y: G02 and G03 swap. See docs/machines.md, [lathe].
  bool arcs_from_minus_y = false;
  double max_rpm = 0;       // spindle limit: caps the G50 S clamp written with surface speed (0 = none)
  int tip = 3;              // the imaginary tool tip (0-9) for tool nose radius compensation ({tip})
};

enum class Cyclic : uint8_t {
  No,      // limited: min..max
  Wind,    // continuous; angles accumulate past 360 (the control winds)
  Modulo,  // continuous; angles written in [0, 360), the control takes the short way
};

struct RotaryAxis {
  std::string name;                   // A, B or C: the address it is written with
  ir::Vec3 axis = ir::Vec3::UnitZ();  // direction in machine coordinates, at all rotaries zero
  bool table = true;                  // turns the part (true) or the tool (head)
  double direction = 1;               // +1: a positive angle turns right-handed about `axis`
  double min = -360, max = 360;       // limits (limited axes)
  Cyclic cyclic = Cyclic::No;
  bool wind_range = false;            // a winding axis with min / max given: unwound before it passes them
  ir::Vec3 center = ir::Vec3::Zero(); // a point on the axis; program frame, output units
  double prefer = 0;                  // +1 / -1: the sign preferred when solutions tie
  double rate = 0;                    // degrees per minute (inverse-time caps; 0: unknown)
  std::string clamp, unclamp;         // codes (M10 / M11), empty if none
  ir::Vec3 effective() const { return axis * direction; }
};

struct LinearLimits {
  double min[3] = {0, 0, 0};
  double max[3] = {0, 0, 0};
  bool set = false;
};

enum class Simultaneous : uint8_t { Tcp, Transform };  // 5-axis moves: TCPC, or clpc transforms
enum class Indexed : uint8_t { Transform, Dwo, Tcp, Plane };  // 3+2: transform, Haas G254, TCPC, tilted plane (G68.2)

// How fast the axes may go and speed up, for cycle times a shop can trust (verify's dynamic
// estimate, readback/motion_time.h). Zero: unknown (no dynamic estimate).
struct MotionSettings {
  ir::Vec3 velocity = ir::Vec3::Zero();      // X Y Z, output units per minute
  ir::Vec3 acceleration = ir::Vec3::Zero();  // X Y Z, output units per second squared
  ir::Vec3 rotary_velocity = ir::Vec3::Zero();  // A B C, degrees per second
  double junction_deviation = 0;             // output units: how far the control may cut a corner at speed
  // G00 moves along a straight line (interpolated). False: each axis at its own rate (Fanuc's
  // non-linear positioning), and the rapid-split pass must split rapids that go down and across.
  bool rapids_linear = true;
  bool known() const { return velocity.minCoeff() > 0 && acceleration.minCoeff() > 0; }
};

struct KinematicsSettings {
  std::vector<RotaryAxis> rotaries;   // from the machine base outwards (table and head axes)
  Simultaneous simultaneous = Simultaneous::Transform;
  Indexed indexed = Indexed::Transform;
  EulerOrder plane_euler = EulerOrder::Zxz;  // indexed = "plane": the order of codes.plane_on's angles
  bool inverse_time = false;          // G93 for moves that turn a rotary axis
  bool degrees_per_minute = false;    // F for such moves over X Y Z A B C together (no G93, no TCPC)
  double max_inverse_time = 0;        // cap on F in G93 (1/min); 0: none
  bool retract_on_limit = false;      // retract, rotate and re-engage where limits force a jump
  double retract_distance = 0;        // output units, along the tool axis
  double pivot = 0;                   // head machines: tip to head axes at zero, output units
  LinearLimits travel;                // machine X Y Z travel (output units)
  bool work_zero_set = false;
  ir::Vec3 work_zero = ir::Vec3::Zero();  // machine position of the program zero (at all rotaries 0)
  bool has_rotaries() const { return !rotaries.empty(); }
};

enum class OffsetTable : uint8_t { None, G10, G65Macro };

struct OffsetSettings {
  int standard_first = 54, standard_last = 59;  // G54..G59
  int extended_count = 0;                       // G154 P1..Pn / G54.1 P1..Pn
  int default_index = 1;                        // register used without SET: 1 = G54
  OffsetTable table = OffsetTable::None;        // how the program sets the registers it uses
  bool per_frame = false;        // one register per distinct MSYS / CSYS frame, not only SET ones
  double reference_height = 0;   // output units: the reference base above the table centre (#503)
  long macro = 2013;             // g65-macro: the macro's program number
  bool macro_program = false;    // g65-macro: append the macro program after the main one
};

// Every code the backends write, as templates (machine/code_template.h).
struct Codes {
  CodeTemplate units_inch, units_mm;
  CodeTemplate rapid, linear, arc_cw, arc_ccw;
  CodeTemplate plane_xy, plane_zx, plane_yz;
  CodeTemplate absolute, incremental;
  CodeTemplate feed_per_minute, feed_per_rev, inverse_time;
  CodeTemplate tool_change, tool_preselect;
  CodeTemplate length_offset, length_cancel;
  CodeTemplate spindle_cw, spindle_ccw, spindle_off;
  CodeTemplate spindle_rpm_mode, spindle_css_mode, spindle_clamp;
  CodeTemplate coolant_flood, coolant_mist, coolant_thru, coolant_air, coolant_tap, coolant_off;
  CodeTemplate coolant_thru_off, coolant_air_off;  // where coolant_off does not stop them (Haas M89, M84)
  CodeTemplate dwell;
  CodeTemplate optional_stop, stop;
  CodeTemplate comp_left, comp_right, comp_off;
  CodeTemplate work_offset, work_offset_extended;
  CodeTemplate offset_set, offset_set_extended;  // "G90 G10 L2 P{number}" (+ X Y Z), "G90 G10 L20 P{number}"
  CodeTemplate macro_call;                       // "G65 P{number}" (+ B X Y Z A C)
  CodeTemplate safe_retract;
  // Canned cycles; an empty code means the machine lacks the cycle (holes become moves).
  CodeTemplate cycle_drill, cycle_dwell, cycle_peck, cycle_chip_break, cycle_tap, cycle_tap_left, cycle_bore,
      cycle_bore_dwell, cycle_bore_stop, cycle_fine_bore, cycle_back_bore;
  CodeTemplate cycle_cancel, cycle_return_initial, cycle_return_r;
  CodeTemplate cycle_dwell_word;  // the dwell word in a cycle block, e.g. "P{milliseconds}"
  CodeTemplate rigid_tap;         // a block before G84, e.g. "M29 S{speed}"
  CodeTemplate groove_face, groove_radial;  // lathe: G74, G75 (two-block form)
  // Lathe threading (docs/lathe.md): a synchronised move (G32), the one-pass box cycle (G92),
  // the multiple-pass cycle (G76, two-block form); empty: the machine lacks it.
  CodeTemplate thread, thread_box, thread_multi;
  // Lathe stock removal (docs/lathe.md): G71 turning, G72 facing (two-block form, type I),
  // G70 finishing; empty: the machine lacks it (CYCLE/ROUGH is refused).
  CodeTemplate rough_turn, rough_face, rough_finish;
  CodeTemplate tcp_on, tcp_off;              // tool centre point control: G00 G234 H{offset} / G49
  CodeTemplate dwo_on, dwo_off;              // dynamic work offset (Haas G254 / G255)
  // Tilted working plane (indexed = "plane"): "G68.2 X{x} Y{y} Z{z} I{i} J{j} K{k}" (origin,
  // Euler angles), then plane_orient where the control turns the rotaries to it ("G53.1"),
  // cancelled by plane_off ("G69").
  CodeTemplate plane_on, plane_orient, plane_off;
  // Unwinding a winding axis without motion: the control renames its position by whole turns,
  // e.g. "G92 C{angle}"; empty: the axis turns back, with the tool retracted.
  CodeTemplate unwind;
  CodeTemplate smoothing_on, smoothing_off;  // Haas "G187 P{level} E{tolerance}" / "G187"; Fanuc "G05.1 Q1" / "G05.1 Q0"
};

// Each kind of feed has its own F format (docs/machines.md, [NAME.feeds]): a feed per
// revolution needs more decimals than one per minute, a tap's feed must keep its pitch. A
// rounded feed that is zero or off by more than max_rounding is an error naming the CL record.
struct FeedSettings {
  AddressFormat per_minute, per_rev, inverse_time, tap;
  AddressFormat lead;  // the F of a thread (G32, G92, G76): the lead per revolution
  double max_rounding = 0.05;  // fraction (feed overrides step by 10%); a tap keeps its pitch (no setting)
};

struct CycleSettings {
  bool return_initial = true;  // G98 between holes (to the level the cycle started at); false: G99
  bool tap_per_rev = false;    // tapping feed as F = pitch with G95 (true) or F = pitch x S (false)
  double peck_clearance = 0;   // output units: re-entry clearance for pecking written as moves
};

struct Machine {
  std::string name;
  std::string description;
  std::string source;           // file the description came from
  Family family = Family::Mill;
  ir::Units units = ir::Units::Mm;
  std::string extension = ".nc";
  std::vector<std::string> pipeline;

  long program_number = 0;      // 0 = no program number line
  std::vector<std::string> program_start;   // lines before the program number ("%")
  std::vector<std::string> program_end;     // lines after the last block ("%")
  bool header = true;                       // part, machine, units and tool table comments
  std::vector<CodeTemplate> safe_start;     // blocks after the header
  std::vector<CodeTemplate> finish;         // blocks at the end of the program
  // The options programmers set per job (docs/machines.md, "Per-job options"): keys of
  // [NAME.program], set in a machine or per job with clpc compile --set / --job.
  bool number_from_name = true;             // O number from the CL file's name (O1234.cls, 1234_x.cls)
  enum class OptionalStop : uint8_t { Off, ToolChange, Operation };
  OptionalStop optional_stop = OptionalStop::Off;  // M01 before each tool change, or each operation
  bool preselect = false;                   // the next tool's T after each tool change
  bool coolant_around_tool_change = false;  // coolant off before each tool change, on again after
  int smoothing = 0;                        // 0 off, 1 rough, 2 medium, 3 finish (codes.smoothing_on)
  double smoothing_tolerance = 0;           // output units; 0: the control's own (the word is left out)
  bool park = false;                        // park_blocks before the program end
  std::vector<CodeTemplate> park_blocks;    // e.g. G53 G00 Y0., rotaries home
  std::string date;                         // "": no DATE line; "today"; or the text to write
  std::string programmer, stock;            // header lines (none when empty)
  double max_rpm = 0;                       // spindle speed limit, rpm; S above it is an error (0: none)
  // INSERT text that is no block the control reads: written as a comment (with a warning),
  // as it is (the user vouches for it), or refused.
  enum class Inserts : uint8_t { Comment, Raw, Error };
  Inserts inserts = Inserts::Comment;

  SequenceSettings sequence;
  CommentSettings comments;
  std::string separator = " ";
  std::string block_end;                    // e.g. ";" (a line end always follows)
  std::array<AddressFormat, 26> formats{};
  ArcSettings arcs;
  ModalSettings modal;
  LatheSettings lathe;
  KinematicsSettings kinematics;
  MotionSettings motion;
  OffsetSettings offsets;
  CycleSettings cycles;
  FeedSettings feeds;
  Codes codes;
  double rapid_rate = 0;        // output units per minute; for cycle-time estimates (0 = unknown)
  double tool_change_time = 0;  // seconds per tool change; for cycle-time estimates (0 = unknown)
  double max_feed = 0;          // output units per minute; caps feeds (0 = none)

  const AddressFormat& format(char letter) const { return formats[size_t(letter - 'A')]; }
  const AddressFormat& feed_format(ir::FeedMode mode) const {
    return mode == ir::FeedMode::PerRev ? feeds.per_rev : mode == ir::FeedMode::InverseTime ? feeds.inverse_time : feeds.per_minute;
  }
  bool is_lathe() const { return family == Family::Lathe; }
  // The fastest the spindle may turn (0: no limit): max_rpm, else a lathe's lathe.max_rpm.
  double spindle_limit() const { return max_rpm > 0 ? max_rpm : lathe.max_rpm; }
};

}  // namespace clpc
