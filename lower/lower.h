// Lowering: CL records -> IR operations. Dialect quirks (parameter orders, CIRCLE layouts,
// unit words) are handled here and nowhere else. Records are lowered as they arrive and each
// finished operation is handed to an OperationSink, so a file of any size is processed one
// operation at a time.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "grammar/record.h"
#include "support/diagnostics.h"
#include "ir/ir.h"
#include "lower/catia_axis_system.h"
#include "lower/prescan.h"

namespace clpc {

// GOFWD, GOLFT, ...: APT contour motion (lower/lower_contour.cpp).
bool is_contour_motion(MajorId id);
bool moves_the_tool(const Record& r);
bool switches_off_only(const Record& r);
std::string head_and_major(const Record& r);
// APT words that move the tool in ways clpc does not read, and what to do instead (lower/lower.cpp).
bool motion_word(std::string_view major);
bool motion_word_exact(std::string_view major);  // the exact names of kMotionWords only
bool says_diameter(const Record& r);          // DIAMTR/ON, XDIAM: X given as a diameter
const Param* diameter_word(const Record& r);  // the word that says so in LATHE/DIAMETER, MODE/..., MACHIN/...
std::string_view motion_hint(std::string_view major);
// The sense of rotation a CIRCLE's axis stands for (lower/lower_motion.cpp).
ir::ArcDir circle_convention(ir::CamSystem cam, ir::ArcLayout layout);

class OperationSink {
 public:
  virtual ~OperationSink() = default;
  // The operation may be modified by the sink; it is cleared after the call.
  virtual void operation(ir::Operation& op) = 0;
};

struct LowerOptions {
  // Instructions per operation chunk; longer operations are handed on in pieces so memory
  // stays bounded whatever the file looks like.
  size_t chunk_size = 1u << 10;
};

class Lowerer : public RecordSink {
 public:
  Lowerer(const ir::ProgramInfo& info, Diagnostics& diags, OperationSink& sink, LowerOptions opt = {});
  void record(const Record& r) override;
  // End of input: closes the open operation and reports what is left unfinished.
  void finish();

 private:
  // lower.cpp: operations and dispatch
  ir::Instr& push(SourceLoc loc, ir::Op op);
  void check_from_gap(SourceLoc loc, const ir::Op& op);
  void approach_from(const ir::Op& op);
  void check_first_cut(SourceLoc loc, const ir::Op& op);
  void check_zero_feed(SourceLoc loc, const ir::Op& op);
  void check_retract(SourceLoc loc, const ir::Op& op);  // the move after a RETRCT
  // An instruction whose text goes in the operation's pool (Comment, Insert, Passthrough):
  // the pool and the instruction land in the same chunk.
  template <class T>
  void push_text(SourceLoc loc, std::string_view text) {
    make_room();
    T t;
    t.text = op_.add_text(text);
    push(loc, t);
  }
  void make_room();  // flushes a full chunk before an instruction that refers to the pools
  void open_operation(std::string name, SourceLoc loc);
  void close_operation();
  void ensure_operation(SourceLoc loc);
  bool tool_ready(SourceLoc loc, ir::MoveKind kind);
  void motion_not_read(const Record& r, std::string_view why);
  void not_read(const Record& r, std::string_view why, std::string_view category);
  void flush_chunk();
  void say_another_diameter(const Record& r);
  void unknown(const Record& r, std::string_view why, bool warn);
  bool blank_joined_record(const Record& r);
  void passthrough(const Record& r);

  // lower_motion.cpp
  void lower_goto(const Record& r);
  int goto_stride(const Record& r) const;
  void goto_point(const Record& r);
  void lower_from(const Record& r);
  void lower_gohome(const Record& r);
  void lower_godlta(const Record& r);
  void lower_circle(const Record& r);

  // lower_contour.cpp
  void lower_movarc(const Record& r);
  void lower_contour(const Record& r);
  void lower_indirv(const Record& r);
  bool indirv_sense(ir::Arc& a, bool sense_said, SourceLoc loc);
  void lower_tlaxis(const Record& r);
  void push_arc(ir::Arc& a, SourceLoc loc, const char* what);
  void move_to(const ir::Vec3& p, SourceLoc loc, ir::MoveKind kind, bool axis_written);
  bool extend_arc(const ir::Vec3& p, SourceLoc loc);
  bool on_circle(const ir::Arc& a, SourceLoc circle, SourceLoc end);

  // lower_machine.cpp
  void lower_tool_change(const Record& r);
  void forget_the_last_tools_state();
  void lower_spindle(const Record& r);
  void lower_feed(const Record& r);
  void lower_coolant(const Record& r);
  void lower_cutcom(const Record& r);
  void lower_delay(const Record& r);
  void lower_stop(const Record& r);
  void lower_origin(const Record& r);
  static bool no_shift(const Record& r);
  bool incremental_points(const Record& r);
  void lower_insert(const Record& r);
  void lower_units(const Record& r);

  // lower_frames.cpp
  void lower_msys(const Record& r);
  void lower_matrix_frame(const Record& r, ir::FrameSource src);
  void lower_set(const Record& r);
  void lower_rotate(const Record& r);
  void lower_ofstno(const Record& r);
  void lower_rotabl(const Record& r);

  // lower_transform.cpp
  void lower_transform(const Record& r);
  void lower_nurbs(const Record& r);
  // The transform in force (TRACUT, a COPY being played) on a point or direction the CL gives.
  ir::Vec3 xf_point(const ir::Vec3& p) const;
  ir::Vec3 xf_dir(const ir::Vec3& v) const;
  void update_xf();

  // lower_cycle.cpp, lower_groove.cpp
  void lower_cycle(const Record& r);
  void lower_groove_cycle(const Record& r);
  void lower_rough_cycle(const Record& r);  // lower_rough.cpp
  void end_rough_cycle(const Record& r);
  void lower_thread(const Record& r);  // lower_thread.cpp
  void start_cycle(const ir::CycleSpec& c, SourceLoc loc, const std::string& name);

  // lower_subs.cpp
  bool record_subroutine(const Record& r);
  void lower_calsub(const Record& r);

  const ir::ProgramInfo& info_;
  Diagnostics& d_;
  OperationSink& sink_;
  LowerOptions opt_;

  ir::Operation op_;
  bool op_open_ = false;
  // The open operation was begun by no operation record (TOOL PATH, FEATNO, OPFEATSTART...):
  // a file of CATIA, Fusion or a generic APT post, where a tool load begins the next one.
  bool op_implicit_ = false;
  bool op_loaded_ = false;  // a tool was loaded in the open operation
  bool tool_path_open_ = false;   // an NX TOOL PATH not yet closed by END-OF-PATH
  SourceLoc tool_path_loc_;
  std::string tool_path_name_;
  bool reported_no_tool_ = false;
  uint32_t op_count_ = 0;
  std::string op_tool_name_;     // tool named by TOOL PATH, if any

  ir::Vec3 pos_ = ir::Vec3::Zero();
  bool has_pos_ = false;
  bool multax_off_ = false;  // MULTAX/OFF in force: a GOTO's six values would be two points
  bool multax_on_ = false;   // MULTAX or MULTAX/ON in force: a GOTO's values are points of six
  bool refused_after_fini_ = false;  // motion after FINI was said: once
  size_t replayed_records_ = 0;  // records CALSUB and COPY replayed, for kMaxReplayedRecords
  char comp_plane_ = 0;  // CUTCOM/XYPLAN (ZXPLAN, YZPLAN) alone: the plane of the compensation after it
  bool cut_since_tool_change_ = false;  // a move or an arc since the last tool change (or the start)
  bool last_move_rapid_ = false;        // the last move was a rapid (RAPID, GOHOME)
  // A FROM after a rapid, elsewhere than the rapid left the tool: the next move must be a
  // rapid too (positioning), since a cut would start from where the tool really is.
  std::optional<SourceLoc> from_gap_;
  std::string from_gap_what_;  // where the cut would start from, and why, for the message
  int loaded_offset_ = -1;      // the length register the loaded tool was loaded with
  bool at_home_ = false;  // the last move was GOHOME
  bool last_move_hole_ = false;  // the last move was a hole of a cycle (the tool is on its axis, returned)
  ir::Vec3 axis_ = ir::Vec3::UnitZ();
  ir::Vec3 indirv_ = ir::Vec3::UnitX();  // INDIRV: where the next contour sets off
  bool has_indirv_ = false;
  SourceLoc indirv_loc_;
  ir::Vec3 direction_ = ir::Vec3::UnitX();  // the way the last motion went at its end
  bool has_direction_ = false;
  ir::Vec3 from_ = ir::Vec3::Zero();
  ir::Vec3 from_axis_ = ir::Vec3::UnitZ();
  bool has_from_ = false;
  // A FROM the tool has made no move since (before its first motion, perhaps before the tool
  // change): a cut next starts there, so the tool is first brought there at rapid.
  bool from_approach_ = false;
  bool same_tool_again_ = false;  // the last tool change loaded the tool already in the spindle
  int last_tool_loaded_ = -1;
  SourceLoc from_loc_;
  bool rapid_next_ = false;
  std::optional<SourceLoc> retract_pending_;  // a RETRCT not yet followed by motion
  int tool_ = -1;                 // tool in the spindle (-1 = none yet)
  int toolno_named_ = -1;         // a TOOLNO's tool with no LOADTL since (-1: none)
  SourceLoc toolno_loc_;
  std::optional<ir::Spindle> last_spindle_;
  std::optional<ir::CoolantKind> last_coolant_;  // the last kind a COOLNT named (a bare ON resumes it)
  std::optional<SourceLoc> comp_on_at_;  // the CUTCOM/LEFT|RIGHT in force (none after CUTCOM/OFF)
  std::optional<ir::CutterComp> last_comp_;  // the last CUTCOM/LEFT|RIGHT, which CUTCOM/ON resumes
  bool inverse_time_ = false;  // the feed in force is inverse time (FEDRAT/INVERS)
  // A FEDRAT/0 in force (until the next FEDRAT): rapids may follow, a cut may not. CAM systems
  // write it before rapid moves; a cut at feed zero never ends, and the feed before is not
  // what the CL asks.
  std::optional<SourceLoc> zero_feed_at_;
  bool section_feed_ = false;  // the open CYCLE, groove, roughing or THREAD gives its own feed
  bool spindle_running_ = false;  // the last SPINDL turned the spindle on
  bool stopped_by_change_ = false;  // the last tool change found the spindle running (the post starts it again)
  double pending_max_rpm_ = 0;    // SPINDL/MAXRPM,n alone: the clamp for surface speeds after it
  // The last FEDRAT's mode and unit (factor to program units), which a FEDRAT without a unit
  // word keeps, and where it was given.
  struct FeedUnit {
    ir::FeedMode mode = ir::FeedMode::PerMinute;
    double to_program = 1;
    SourceLoc loc;
  };
  std::optional<FeedUnit> last_feed_unit_;
  // The first feed word that names a length unit (MMPM, MMPR, IPM, IPR), and where: a UNITS
  // after motion that says the other unit would read the moves before it in the wrong one.
  std::optional<std::pair<ir::Units, SourceLoc>> feed_unit_named_;
  bool units_record_seen_ = false;
  void note_feed_unit(const Record& r);

  struct PendingArc {
    ir::Arc arc;
    SourceLoc loc;
    bool open = false;  // points after its end may go on round it (Creo's 7-value CIRCLE)
  };
  std::optional<PendingArc> pending_arc_;
  bool arc_open_ = false;  // the last instruction is an arc that may take more points

  bool cycle_open_ = false;  // a CYCLE without its CYCLE/OFF yet
  bool drilling_ = false;     // that CYCLE is a drilling cycle (not a lathe groove's)
  bool thread_open_ = false;  // a THREAD without its THREAD/OFF yet
  bool rough_open_ = false;   // a CYCLE/ROUGH without its CYCLE/OFF yet
  static constexpr size_t kMaxRoughInstructions = 10000;
  SourceLoc rough_loc_;
  ir::Vec3 rough_start_ = ir::Vec3::Zero();
  size_t rough_size_ = 0;     // the chunk's size at the CYCLE/ROUGH
  size_t cycle_holes_ = 0;   // GOTOs since it
  SourceLoc cycle_loc_;
  std::string cycle_name_;
  std::optional<ir::CycleSpec> last_cycle_;  // for CYCLE/ON
  bool finished_ = false;  // FINI seen
  CatiaAxisSystems catia_axes_;
  bool warned_after_fini_ = false;

  // Subroutines: DEFSUB bodies are kept as owned copies of their records and replayed.
  struct OwnedRecord {
    Record rec;                  // string views and params are rebuilt by view()
    std::vector<Param> head;
    std::vector<Param> params;
    std::string storage;         // major, text, then each param's text
    std::vector<uint32_t> sizes;
    Record view(std::vector<Param>& scratch) const;
    static OwnedRecord of(const Record& r);
  };
  std::map<int, std::vector<OwnedRecord>> subs_;
  int defining_sub_ = -1;
  SourceLoc defining_loc_;
  int call_depth_ = 0;
  size_t stored_records_ = 0;
  bool replay_one_more(SourceLoc at);  // counts a record replayed; false past the limit
  bool keep_stored(const Record& r);  // counts a record kept for replay; false past the limit

  // TRACUT and INDEX/COPY (lower/lower_transform.cpp).
  ir::Frame tracut_, copy_xf_, xf_;
  ir::Frame msys_;                 // the MSYS in force, in the program frame
  std::optional<ir::Frame> msys0_; // the file's first MSYS: the program frame
  SourceLoc msys0_loc_;
  bool msys0_turn_said_ = false;   // a later MSYS square to the absolute frame, the first turned: said
  bool has_tracut_ = false, has_xf_ = false;
  std::map<int, std::vector<OwnedRecord>> blocks_;
  int recording_index_ = -1;
};

}  // namespace clpc
