// The clpc IR: a Program is header facts and tables (ProgramInfo) plus a stream of
// Operations, each a vector of Instrs. Instructions are plain structs in a std::variant;
// all lengths are in the program's units (ProgramInfo::units), angles in degrees unless a
// name says otherwise. Text lives in the operation's string pool, so an Instr never owns
// heap memory and an Operation can be cleared and refilled without allocating.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "support/source.h"

namespace clpc::ir {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

enum class Units : uint8_t { Mm, Inch };
inline double mm_per_unit(Units u) { return u == Units::Inch ? 25.4 : 1.0; }
std::string_view units_name(Units u);

// A rigid frame: p_program = rotation * p_local + origin.
struct Frame {
  Mat3 rotation = Mat3::Identity();
  Vec3 origin = Vec3::Zero();
  bool is_identity(double tol = 1e-9) const;
  bool same_as(const Frame& o, double lin_tol, double rot_tol = 1e-9) const;
  Vec3 z_axis() const { return rotation.col(2); }
  Vec3 point(const Vec3& p) const { return rotation * p + origin; }
  Frame inverse() const;
};
// outer after inner: the frame of a frame given in `outer`'s coordinates.
Frame compose(const Frame& outer, const Frame& inner);

// A slice of Operation::text.
struct TextRef {
  uint32_t offset = 0;
  uint32_t size = 0;
};

// --- instructions ----------------------------------------------------------------------

enum class MoveKind : uint8_t {
  Rapid,  // RAPID then GOTO (or GOHOME)
  Feed,   // GOTO at the programmed feed
  From,   // FROM: where the tool starts; no motion is programmed for it
};

struct Move {
  Vec3 point;     // tool tip (after the kinematics pass: what the control is given)
  Vec3 axis;      // tool axis (unit), as last given, in the part frame
  MoveKind kind = MoveKind::Feed;
  bool axis_written = false;  // this record wrote i,j,k
  bool has_rotary = false;    // set by the kinematics pass: the rotary positions to write
  std::array<double, 2> rotary{0, 0};
  double inverse_time = 0;    // set by the kinematics pass: F in G93 (1/min); 0 = the feed rate
  double combined_feed = 0;   // set by the kinematics pass: F in degrees-per-minute mode (output units
                              // and degrees along the move, per minute; docs/kinematics.md); 0 = the feed rate
};

// Sense of rotation about Arc::axis: Ccw is the right-hand rule (counter-clockwise seen from
// the tip of the axis).
enum class ArcDir : uint8_t { Unknown, Ccw, Cw };

// Which CL layout the arc came from; each has its own axis convention (docs/arcs.md).
enum class ArcLayout : uint8_t {
  Nx11,     // xc,yc,zc,i,j,k,r,tol,ratio,tool_d,tool_cr: NX CLSF, Makino FFCAM
  Creo7,    // xc,yc,zc,i,j,k,r: Creo / Pro/E NCL, APT
  NoRadius6,  // xc,yc,zc,i,j,k: SolidWorks CAM APT
  Synthetic,  // made by a pass
  Worded,     // CIRCLE/...,CLW|CCLW|CLOCKWISE|COUNTERCLOCKWISE: the sense written (CAMWorks)
  Movarc,     // MOVARC/xc,yc,zc,i,j,k,r,ANGLE,a: Fusion; the end point from the angle
  Contour,    // TLON,GOFWD/(CIRCLE/...),ON,(LINE/...): CATIA; the sense from INDIRV
};

// The CAM system that wrote the file, as far as its first lines tell (the pre-scan): each has
// its own CIRCLE convention and cycle vocabulary (docs/cl-input.md).
enum class CamSystem : uint8_t { Unknown, Nx, Creo, Catia, Fusion, SolidWorks, Ncl };
std::string_view cam_system_name(CamSystem s);

struct Arc {
  Vec3 start;     // previous tool tip
  Vec3 end;       // the last GOTO on the arc
  Vec3 center;    // as written: at the start's height for Creo helices
  Vec3 axis;      // unit axis as written (sign per CAM convention)
  Vec3 tool_axis;
  double radius = 0;
  ArcDir hint = ArcDir::Unknown;  // what the CAM system's convention says
  ArcDir dir = ArcDir::Unknown;   // decided by the arc-direction pass
  ArcLayout layout = ArcLayout::Creo7;
  uint16_t extra_turns = 0;       // NX TIMES,n: n-1 full turns before reaching the end
  uint32_t via_begin = 0;         // intermediate points (Creo) in Operation::points
  uint32_t via_count = 0;
  double sweep = 0;               // degrees (> 0) once the direction is decided
  bool has_rotary = false;        // set by the kinematics pass: the rotaries (fixed) during the arc
  std::array<double, 2> rotary{0, 0};
};

struct ToolChange {
  int tool = 0;
  int length_offset = 0;  // 0 = same as the tool number
  int slot = -1;          // index in ProgramInfo::tools
};

struct ToolPreselect {
  int tool = 0;
};

enum class SpindleDir : uint8_t { Cw, Ccw, Off };
enum class SpindleMode : uint8_t { Rpm, SurfaceSpeed };

struct Spindle {
  double speed = 0;  // rpm, or surface speed in m/min (SFM is converted when it is read)
  SpindleMode mode = SpindleMode::Rpm;
  SpindleDir dir = SpindleDir::Cw;
  double max_rpm = 0;  // clamp for surface speed (0 = none given)
};

enum class FeedMode : uint8_t { PerMinute, PerRev, InverseTime };

struct Feed {
  double value = 0;  // program units per minute / per revolution; 1/min for inverse time
  FeedMode mode = FeedMode::PerMinute;
};

enum class CoolantKind : uint8_t { Off, On, Flood, Mist, Thru, Air, Tap };
struct Coolant {
  CoolantKind kind = CoolantKind::Flood;
};

enum class CompSide : uint8_t { Off, Left, Right };
struct CutterComp {
  CompSide side = CompSide::Off;
  int reg = 0;  // diameter-offset register; 0 = the tool's own
  char plane = 0;  // the CL's plane word where it is not square to the tool axis: 'Z' XYPLAN, 'Y' ZXPLAN, 'X' YZPLAN (its normal); 0: none
};

struct Dwell {
  double value = 0;
  bool revolutions = false;
};

enum class StopKind : uint8_t { Optional, Program };
struct Stop {
  StopKind kind = StopKind::Program;
  // A stop for the operator to set the part up anew (offset-table: a frame a machine without
  // rotaries cannot reach): the tool retracts and the spindle and coolant stop before it and
  // start again after it.
  bool setup = false;
};

struct Comment {
  TextRef text;
};

// INSERT/text: a line written to the output as it is.
struct Insert {
  TextRef text;
};

// A record clpc does not know; kept (as its source text) so it can be seen in the output.
struct Passthrough {
  TextRef text;
};

// SET/..,n: the work-offset register (54..59, or 101.. for extended) for the motion that
// follows. `index` is the machine's register (1 = G54 ... 6 = G59, 7 = the first extended
// one), set by lowering from `reg` or by the offset-table pass.
struct SelectOffset {
  int reg = 0;
  int index = 0;
};

enum class FrameSource : uint8_t { Msys, Csys, Camera };
struct SetFrame {
  Frame frame;
  FrameSource source = FrameSource::Csys;
};

// ROTATE/AAXIS,INCR,a,CCLW: index a rotary axis.
struct RotaryIndex {
  char axis = 'A';
  double angle = 0;  // degrees
  bool incremental = true;
  ArcDir dir = ArcDir::Unknown;
};

// --- canned cycles ----------------------------------------------------------------------

enum class CycleKind : uint8_t {
  Drill,      // G81
  SpotDwell,  // G82: dwell at the bottom (CSINK, FACE, DRILL with DWELL)
  Peck,       // G83: full retract between pecks (DEEP)
  ChipBreak,  // G73: short retract between pecks (BRKCHP)
  Tap,        // G84 (G74 left hand)
  Bore,       // G85: feed in, feed out (BORE, REAM)
  BoreDwell,  // G89: G85 with a dwell
  BoreStop,   // G86: spindle stops at the bottom, rapid out (BORE,DRAG)
  FineBore,   // G76: oriented stop and shift (BORE,ORIENT)
  BackBore,   // G87 (BORE,BACK)
};
std::string_view cycle_kind_name(CycleKind k);

// A CYCLE record's parameters, as distances along the tool axis from each hole's point.
struct CycleSpec {
  CycleKind kind = CycleKind::Drill;
  double depth = 0;       // bottom below the hole point
  double clearance = 0;   // R plane above the hole point
  double retract = -1;    // RTRCTO: return level above the hole point (-1: where the tool started)
  double peck = 0;        // first peck (0: none)
  double peck_next = 0;   // later pecks (DEEP2); 0: same as the first
  double dwell = 0;       // seconds at the bottom
  double pitch = 0;       // tapping: program units per revolution
  double shift = 0;       // fine and back boring: tool shift
  double feed = 0;        // 0: the current FEDRAT
  FeedMode feed_mode = FeedMode::PerMinute;
  bool left_hand = false; // tapping with the spindle counter-clockwise
};

struct CycleOn {
  uint32_t spec = 0;  // index in Operation::cycles
};
struct CycleOff {};

// One hole of a canned cycle (made by the drill-cycles pass from the GOTOs of a cycle).
struct Hole {
  Vec3 point;          // on the hole's top: the CL GOTO
  Vec3 axis;           // tool axis (unit); the hole goes the other way
  uint32_t spec = 0;   // index in Operation::cycles
  double initial = 0;  // where the tool starts the cycle, above the point (for G98 returns)
};

// --- lathe grooving (G74 face, G75 radial) ------------------------------------------------

// Lathe data: x is the radius, z the axial position (the CL's X and Z; Y = 0).
struct GrooveSpec {
  bool face = false;       // G74: plunges along Z, shifts along X; else G75: plunges along X
  double retract = 0;      // e: pull-out after each peck (first block R)
  double x_amount = 0;     // Fanuc P: G75 peck depth / G74 shift, along X (radius)
  double z_amount = 0;     // Fanuc Q: G75 shift / G74 peck depth, along Z
  double relief = 0;       // Fanuc second-block R: relief at the bottom
  double feed = 0;         // 0: the current feed
  FeedMode feed_mode = FeedMode::PerRev;
  bool from_record = false;  // written as CYCLE/FACE|RADIUS in the CL
};

struct GrooveOn {
  uint32_t spec = 0;  // index in Operation::grooves
};

// One G74/G75 cycle: from `start` (where the tool is) to the far corner `end`.
struct Groove {
  Vec3 start, end;
  uint32_t spec = 0;  // index in Operation::grooves
};

// Creo's "$$ GRV ..." and "$$ GRV END" comments around explicit groove motion.
struct GrooveMark {
  bool begin = true;
};

// --- lathe threading (docs/lathe.md) ------------------------------------------------------

// THREAD/TURN|FACE|TAPER,lead ... THREAD/OFF: inside, a feed move along the thread is cut
// synchronised with the spindle (G32), advancing `lead` per revolution.
enum class ThreadKind : uint8_t { Turn, Face, Taper };
struct ThreadMark {
  bool begin = true;
  ThreadKind kind = ThreadKind::Turn;
  double lead = 0;  // program units per revolution
};

// Made by the thread-cycles pass from threading passes it proved equal: one G92 box pass, or
// a whole G76 multiple-pass cycle. Lathe coordinates (x radius, z axial).
struct ThreadCycle {
  Vec3 start;          // where the tool is; every pass returns here
  Vec3 end;            // G92: the pass's far corner; G76: the root at the thread's end
  double lead = 0;
  bool multi = false;  // G76, else one G92 pass
  // G76 (radius values, program units): thread height k, first depth, smallest step,
  // finishing allowance d, finishing passes m; thread_model::depths gives the passes.
  double height = 0, first_depth = 0, min_step = 0, allowance = 0;
  int finish_passes = 1;
};

// --- lathe stock removal (G71 turning, G72 facing, G70 finishing; docs/lathe.md) ------------

// CYCLE/ROUGH,TURN|FACE,DEPTH,d,RETRACT,e[,ALLOW,u,w][,FEED,f][,FINISH] ... CYCLE/OFF: the
// motion inside is the finishing profile, from the start point A (where the tool stands at
// the CYCLE record) to A' along the level axis, then to B; the control roughs the stock between
// A and the profile in levels of d (ir/stock_model.h) and, with FINISH, cuts the profile. After
// the end mark the tool is back at A (the lowering says so with a FROM move).
struct RoughMark {
  bool begin = true;
  bool facing = false;       // G72: levels along Z; else G71: levels along X
  double depth = 0;          // d, radius, program units
  double retract = 0;        // e
  double allow_x = 0;        // u: finishing allowance along X, radius
  double allow_z = 0;        // w: along Z
  double feed = 0;           // 0: the feed in force
  FeedMode feed_mode = FeedMode::PerRev;
  bool finish = false;       // G70 after the roughing
  Vec3 start = Vec3::Zero();  // A
};

// --- five-axis (made by the kinematics pass) ------------------------------------------------

// Position the rotary axes (3+2, or a rotation with the tool retracted), clamped after.
struct RotaryPosition {
  std::array<double, 2> rotary{0, 0};
  bool clamp = true;
  bool rename = false;  // no motion: the control renames a winding axis's position by whole turns (codes.unwind)
};

// Switches of the control's modes around the moves that need them.
// PlaneOn sets a tilted working plane about the part zero: `angles` are its Euler angles
// (degrees, in the machine's kinematics.plane_euler order); X Y Z after it are in that plane.
enum class ModeKind : uint8_t { TcpOn, TcpOff, DwoOn, DwoOff, PlaneOn, PlaneOff };
struct MachineMode {
  ModeKind kind = ModeKind::TcpOn;
  Vec3 angles = Vec3::Zero();
};

using Op = std::variant<Move, Arc, ToolChange, ToolPreselect, Spindle, Feed, Coolant, CutterComp,
                        Dwell, Stop, Comment, Insert, Passthrough, SelectOffset, SetFrame, RotaryIndex,
                        CycleOn, CycleOff, Hole, GrooveOn, Groove, GrooveMark, ThreadMark, ThreadCycle, RoughMark, RotaryPosition,
                        MachineMode>;

struct Instr {
  SourceLoc loc;
  Op op;
};

// --- operations and the program ---------------------------------------------------------

struct Operation {
  uint32_t number = 0;       // 1-based, in file order
  std::string name;          // TOOL PATH name, "FEATNO 32", or empty
  SourceLoc loc;
  bool continued = false;    // a further chunk of the same operation (very long operations)
  bool last_chunk = true;
  std::vector<Instr> body;
  std::string text;          // pool for TextRef
  std::vector<Vec3> points;  // pool for Arc via points
  std::vector<CycleSpec> cycles;  // pool for CycleOn and Hole
  std::vector<GrooveSpec> grooves;  // pool for GrooveOn and Groove

  TextRef add_text(std::string_view s);
  std::string_view str(TextRef r) const { return std::string_view(text).substr(r.offset, r.size); }
  void clear();  // keeps capacity
};

struct ToolInfo {
  int number = 0;
  std::string name;
  std::string kind;            // MILL, DRILL, TURN, ... (TLDATA) or empty
  double diameter = 0;
  double corner_radius = 0;
  double length = 0;
  bool auto_numbered = false;  // the CL gave a name but no number
  SourceLoc first_use;
  // A later CUTTER/TLDATA for this number with another diameter (the first one is kept): where,
  // and the diameter it gave. Invalid when every definition agrees.
  SourceLoc other_diameter_at;
  double other_diameter = 0;
};

// A frame a CL record gives (MSYS, CSYS, $$-> CSYS, CAMERA), with the SET register it pairs
// with, in the order the file gives them (the pre-scan).
struct FrameUse {
  Frame frame;
  FrameSource source = FrameSource::Csys;
  SourceLoc loc;
  int set_register = 0;      // SET/..,n paired with it (0: none)
  bool no_record = false;    // an operation with no frame record: the base frame
};

// The machine register index of a CL register: 54..59 -> 1..6 (G54..G59), 101.. -> 7..
// (the first extended register: G154 P1 / G54.1 P1); 0 if it is neither.
int register_index(int cl_register);

// One entry of the work-offset table (the offset-table pass).
struct WorkOffset {
  int index = 0;             // machine register: 1 = G54 ... 6 = G59, 7.. extended
  int set_register = 0;      // the CL's SET register, or 0 when clpc chose it
  bool base = false;         // the frame of operations with no frame record
  Frame frame;
  FrameSource source = FrameSource::Csys;
  SourceLoc loc;
  bool has_rotary = false;
  std::array<double, 2> rotary{0, 0};  // the rotaries' positions for this frame
  Vec3 machine = Vec3::Zero();  // the frame origin in machine coordinates there (output units)
  double seed_a = 0, seed_c = 0;  // the seed paper's A = |atan2(r32, r33)|, C = atan2(r21, r11)
  int setup = 0;  // machines without rotaries: the setup (part orientation) it belongs to, 1 = Z up
};

struct ProgramInfo {
  std::string part_name;
  std::string source_name;     // input file name, for the header
  Units units = Units::Mm;
  bool units_given = false;    // a UNITS record was present
  std::string units_reason;    // how units were decided when not given
  std::string units_doubt;     // why the numbers look like the other unit ("" if they do not)
  std::vector<ToolInfo> tools;  // in order of first use
  std::vector<int> tool_changes;  // the tool numbers in the order they are loaded (for preselects)
  bool preselects_given = false;  // the CL preselects tools itself (LOADTL/...,PRESEL)
  bool lathe = false;           // the file says it is for a lathe (see family_said)
  // What the file says of the machine it is for, where (docs/cl-input.md, "Mill or lathe"):
  // "" when it says nothing, or both (mill-turn).
  std::string family_said;      // "lathe" or "mill"
  std::string family_record;    // "MACHIN/TURN", "TOOLNO/1,TURN", ...
  SourceLoc family_loc;
  CamSystem cam = CamSystem::Unknown;
  std::string cam_evidence;     // what told: "line 1: $$*CATIA0", ...
  // Operations that name a tool but load none by number (NX TOOL PATH without LOAD/TOOL):
  // the line of their TOOL PATH record and the number the pre-scan gave the tool.
  std::vector<std::pair<uint32_t, int>> named_tool_ops;
  std::vector<FrameUse> frames;        // every frame record, in file order (the pre-scan)
  std::vector<WorkOffset> offsets;     // the work-offset table (the offset-table pass)

  const ToolInfo* tool(int number) const;
  int tool_number_for_name(std::string_view name) const;  // 0 if unknown
  int named_tool_at(uint32_t tool_path_line) const;        // 0 if none
};

}  // namespace clpc::ir
