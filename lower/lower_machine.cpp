// Machine-state records: tools, spindle, feed, coolant, cutter compensation, dwell, units.
#include <cmath>

#include "lower/lower.h"
#include "lower/params.h"
#include "lower/tool_records.h"

namespace clpc {

void Lowerer::lower_tool_change(const Record& r) {
  // A preselection moves nothing: one whose tool number cannot be read is said and skipped
  // (it stopped the post); the tool change still loads the tool.
  if (r.id == MajorId::Select && read_tool_record(r, nullptr).number < 0) {
    d_.warning(r.loc, "SELECT/TOOL with no tool number clpc can read: no preselection is written (the tool change "
                      "still loads the tool)", "not-supported");
    return;
  }
  ToolRecord t = read_tool_record(r, &d_);
  if (t.number < 0) return;
  // In a file with no operation records each load begins an operation (CATIA loads the tool
  // again at each of its operations): one five-axis move put the whole file under TCPC, its
  // arcs cut as lines and a vertical tap refused (helper-56). Not within a cycle, a contour or
  // a thread, which run on across it.
  if (!t.preselect && op_open_ && op_implicit_ && op_loaded_ && !cycle_open_ && !rough_open_ && !thread_open_ &&
      !pending_arc_ && !arc_open_)
    close_operation();
  ensure_operation(r.loc);
  if (t.preselect) {
    push(r.loc, ir::ToolPreselect{t.number});
    return;
  }
  // Tool 0: NX's number for a tool nobody numbered (nx-course/APT_Zig_Zag_Smoothed.cls, with
  // ADJUST,1). Its length register must come from the record: offset 0 (H00, T0000) is none,
  // and every cut would be off by the tool's length.
  if (t.number == 0 && t.length_offset <= 0) {
    d_.error(r.loc, "tool 0 with no length register: its offset would be 0 (H00, T0000), which is none, so every cut "
                    "after it would be off by the tool's length; number the tool in the CAM system, or give the "
                    "register (LOAD/TOOL,n,ADJUST,h; LOADTL/n,OSETNO,h)");
    tool_ = 0;  // (no cascade of "no tool" errors after it)
    return;
  }
  if (t.number == 0)
    d_.warning(r.loc, "tool number 0 (the CAM system's tool was not numbered): T0 is written, which many controls "
                      "refuse or take as 'no tool'; the length offset is register " + std::to_string(t.length_offset) +
                      "; number the tool in the CAM system",
               "tool-number");
  const int offset = t.length_offset > 0 ? t.length_offset : t.number;
  if (cycle_open_ && (t.number != tool_ || offset != loaded_offset_)) {
    // The GOTOs after it: holes for the new tool (APT: the cycle is on until CYCLE/OFF), or moves
    // to where the new tool starts? The CL does not say, and either reading cuts wrongly if it
    // is the other (a hole drilled at a positioning move, or holes never drilled).
    d_.error(r.loc, "a tool change while a CYCLE is on (no CYCLE/OFF before it): whether the GOTOs after it "
                    "are holes for the new tool or its moves is not known; end the cycle with CYCLE/OFF before the "
                    "change, and give the CYCLE again after it for the new tool's holes");
    cycle_open_ = false;
    push(r.loc, ir::CycleOff{});
  }
  if (comp_on_at_ && t.number != tool_) {
    d_.error(r.loc, "a tool change with cutter compensation on (CUTCOM at line " + std::to_string(comp_on_at_->line) +
                        "): the control keeps it with the last tool's register, so the new tool would cut offset by "
                        "the last one's radius; CUTCOM/OFF before the change, CUTCOM/LEFT or RIGHT after it");
    comp_on_at_.reset();
  }
  // The tool in the spindle loaded again with another length register, after a move (a cut or
  // a rapid) the CL left it at: the post takes the tool up and brings it back with the new
  // offset, so a cut next would start from up there (a diagonal feed back into the part where
  // the CL feeds on from where the tool was). After GOHOME the tool is up there already.
  const bool reloaded_in_cut = t.number == tool_ && offset != loaded_offset_ && cut_since_tool_change_ && !at_home_;
  loaded_offset_ = offset;
  ir::ToolChange tc;
  tc.tool = t.number;
  tc.length_offset = t.length_offset;
  for (size_t i = 0; i < info_.tools.size(); ++i)
    if (info_.tools[i].number == t.number && !info_.tools[i].auto_numbered) tc.slot = int(i);
  tool_ = t.number;
  forget_the_last_tools_state();
  push(r.loc, tc);
  op_loaded_ = true;
  if (reloaded_in_cut) {
    from_gap_ = r.loc;
    from_gap_what_ = "after the reload of T" + std::to_string(t.number) + " with another length register at line " +
                     std::to_string(r.loc.line) + ", which takes the tool up from where the CL left it and back";
  }
}

// The new tool starts from nothing of the last one's: its spindle is started by a SPINDL of
// its own (a mill's M06 stops it), and CUTCOM/ON has no side of its own to resume (the last
// tool's register would be another tool's diameter).
void Lowerer::forget_the_last_tools_state() {
  stopped_by_change_ = spindle_running_;
  spindle_running_ = false;
  last_comp_.reset();
}

void Lowerer::lower_spindle(const Record& r) {
  ParamReader ps(r, d_);
  ir::Spindle s;
  bool have_speed = false, off = false, on = false, dir_given = false;
  double per_unit = 1;  // surface speed words convert to m/min
  std::string kind_word, dir_word;  // the first of RPM/SFM/SMM, of CLW/CCLW
  for (size_t i = 0; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (p.is_number()) {
      if (have_speed) {
        d_.error(p.loc, "SPINDL: more than one speed");
        return;
      }
      s.speed = p.number;
      have_speed = true;
      continue;
    }
    std::string w = upper(p.text);
    // CW and CCW (and the words in full) are the ISO 4343 words' plain spellings, written by
    // generic and home-grown posts (helper-66: refused as unknown words).
    if (w == "CW" || w == "CLOCKWISE") w = "CLW";
    else if (w == "CCW" || w == "COUNTERCLOCKWISE") w = "CCLW";
    // Two words that say opposite things: the last one won (SPINDL/1000,RPM,SMM turned at
    // 31831 rpm). Which one the CAM system meant is not known.
    std::string& first = (w == "RPM" || w == "SFM" || w == "SMM") ? kind_word : (w == "CLW" || w == "CCLW") ? dir_word : w;
    if (&first != &w) {
      if (!first.empty() && first != w) {
        d_.error(p.loc, "SPINDL: " + first + " and " + w + " say opposite things in one record; which is meant is not known");
        return;
      }
      first = w;
    }
    if ((w == "ON" && off) || (w == "OFF" && on)) {
      d_.error(p.loc, "SPINDL: ON and OFF in one record; which is meant is not known");
      return;
    }
    if (w == "RPM") s.mode = ir::SpindleMode::Rpm;
    else if (w == "SFM") { s.mode = ir::SpindleMode::SurfaceSpeed; per_unit = 0.3048; }
    else if (w == "SMM") { s.mode = ir::SpindleMode::SurfaceSpeed; per_unit = 1; }
    else if (w == "CLW") { s.dir = ir::SpindleDir::Cw; dir_given = true; }
    else if (w == "CCLW") { s.dir = ir::SpindleDir::Ccw; dir_given = true; }
    else if (w == "OFF") off = true;
    else if (w == "ON") on = true;
    else if (w == "MAXRPM") {
      auto v = ps.after("MAXRPM");
      if (!v) return;
      if (*v < 0) {
        d_.error(ps[i + 1 < ps.size() ? i + 1 : i].loc, "SPINDL: MAXRPM must not be negative, found " + num_text(*v));
        return;
      }
      s.max_rpm = *v;  // 0: no clamp given (the machine's limit holds)
      ++i;
    } else if (w == "RANGE") {
      ++i;  // gear range: the control chooses
    } else if (w == "LOW" || w == "MEDIUM" || w == "HIGH" || w == "AUTO") {
      // ISO 4343's gear range words: the control chooses the range from the speed.
    } else if (w == "PARLEL" || w == "PERPTO") {
      d_.warning(r.loc, "SPINDL/" + w + " (live-tool orientation) is ignored: the machine has no such head",
                 "spindle-orientation");
      return;
    } else if (w == "ORIENT" || w == "LOCK") {
      // ISO 4343's oriented stop (M19) and spindle lock. The moves after one rely on it (a
      // boring bar shifted off the wall before it comes out): left out, they would be made
      // with the spindle turning. clpc's machines have no code for them.
      d_.error(p.loc, "SPINDL/" + w + " (" + (w == "ORIENT" ? "an oriented spindle stop" : "a spindle lock") +
                          "): clpc's machines have no code for it, and the moves after it would be made with the "
                          "spindle turning; have the CAM system use a cycle that orients the spindle itself "
                          "(CYCLE/BORE with ORIENT, G76)");
      return;
    } else {
      d_.error(p.loc, "SPINDL: unknown word '" + std::string(p.text) + "'");
      return;
    }
  }
  ensure_operation(r.loc);
  if (off) {
    s.dir = ir::SpindleDir::Off;
    spindle_running_ = stopped_by_change_ = false;
    push(r.loc, s);
    return;
  }
  if (!have_speed && !on && ps.has("MAXRPM")) {
    // SPINDL/MAXRPM,n alone (a record of its own before the SPINDL/SMM|SFM it clamps): the
    // clamp for every surface speed after it that names none; a surface speed running now
    // takes it at once (a new G50 S).
    pending_max_rpm_ = s.max_rpm;
    if (last_spindle_ && last_spindle_->mode == ir::SpindleMode::SurfaceSpeed && last_spindle_->max_rpm != s.max_rpm) {
      last_spindle_->max_rpm = s.max_rpm;
      // (Also where the tool change stopped it, or a lathe's index left it running: the post
      // starts it again for the new tool with the clamp it had, and the CL's lower one was lost,
      // SPINDL/MAXRPM,1500 written G50 S2500; helper-73.)
      if (spindle_running_ || stopped_by_change_) {
        spindle_running_ = true;
        push(r.loc, *last_spindle_);
      }
    }
    return;
  }
  if (s.mode == ir::SpindleMode::SurfaceSpeed && !(s.max_rpm > 0)) s.max_rpm = pending_max_rpm_;
  if (!have_speed) {
    if (on && last_spindle_) {
      if (ps.has("MAXRPM")) last_spindle_->max_rpm = s.max_rpm;  // SPINDL/ON,MAXRPM,n: the new clamp
      if (dir_given) last_spindle_->dir = s.dir;                 // SPINDL/ON,CCLW: the last speed, this way
      spindle_running_ = true;
      push(r.loc, *last_spindle_);
      return;
    }
    // A gear range alone (SPINDL/RANGE,2, SPINDL/HIGH): the control chooses it from the speed.
    if (!on && !dir_given && !ps.has("MAXRPM") && ps.size() > 0 && !ps.has("RPM") && !ps.has("SFM") && !ps.has("SMM"))
      return;
    d_.error(r.loc, on ? "SPINDL/ON with no earlier speed" : "SPINDL: no speed given");
    return;
  }
  if (!(s.speed > 0)) {
    d_.error(r.loc, "SPINDL: the speed must be greater than zero, found " + num_text(s.speed));
    return;
  }
  s.speed *= per_unit;
  // No CLW/CCLW: the direction last given holds (a new speed is no reversal); clockwise when
  // the file has given none.
  if (!dir_given && last_spindle_) s.dir = last_spindle_->dir;
  last_spindle_ = s;
  spindle_running_ = true;
  push(r.loc, s);
}

void Lowerer::lower_feed(const Record& r) {
  ParamReader ps(r, d_);
  // FEDRAT/RAPID: the next move at rapid, as RAPID; for it alone, the reading that cannot
  // traverse through the part (the moves after it are fed at the feed in force).
  if (ps.size() == 1 && ps[0].is("RAPID")) {
    rapid_next_ = true;
    return;
  }
  // FEDRAT/LOCK[,ON|OFF]: the feed locked against the operator's override, by posts that have
  // it. clpc's machines have no code for it; the feed stays what it is.
  if (ps.size() >= 1 && ps[0].is("LOCK") &&
      (ps.size() == 1 || (ps.size() == 2 && (ps[1].is("ON") || ps[1].is("OFF"))))) {
    d_.warning(r.loc, "FEDRAT/LOCK: clpc's machines have no code to lock the feed override; the feed is unchanged",
               "not-supported");
    return;
  }
  ir::Feed f;
  bool have = false, worded = false;
  double to_program = 1;  // factor from the record's length unit to program units
  const double prog_mm = ir::mm_per_unit(info_.units);
  std::string unit_word, mode_word;  // the first unit word (MMPM...), the first mode word (PERMIN...)
  for (size_t i = 0; i < ps.size(); ++i) {
    const Param& p = ps[i];
    // MAXIPM,n / MAXMMPM,n: the most a post may feed the moves whose feed it computes (inverse
    // time); clpc computes none, and the machine's own limit holds (limits.max_feed).
    if ((p.is("MAXIPM") || p.is("MAXMMPM")) && i + 1 < ps.size() && ps[i + 1].is_number()) {
      d_.warning(p.loc, "FEDRAT: " + upper(p.text) + "," + num_text(ps[i + 1].number) + " is a limit for feeds a post "
                        "computes; clpc writes the CL's feeds and does not apply it", "ignored-word");
      ++i;
      if (ps.size() == 2) return;  // the record says nothing else
      continue;
    }
    if (!p.is_number()) worded = true;
    if (p.is_number()) {
      if (have) {
        d_.error(p.loc, "FEDRAT: more than one value");
        return;
      }
      f.value = p.number;
      have = true;
      continue;
    }
    std::string w = upper(p.text);
    // Two words that say opposite things (MMPM and IPM, MMPR and MMPM, INVERS and MMPM): the
    // last one won, a feed 25.4 times off or in another mode. PERMIN or PERREV with a unit of
    // its own mode agree.
    {
      auto mode_of = [](const std::string& x) {
        return x == "MMPM" || x == "IPM" || x == "FPM" || x == "PERMIN" ? 'M' : x == "MMPR" || x == "IPR" || x == "PERREV" ? 'R'
               : x == "INVERS"                                                                               ? 'I'
                                                                                                               : 0;
      };
      const char mode = mode_of(w);
      const bool unit = w == "MMPM" || w == "IPM" || w == "FPM" || w == "MMPR" || w == "IPR";
      const std::string& other = !unit_word.empty() ? unit_word : mode_word;
      if (mode && !other.empty() && ((unit && !unit_word.empty() && unit_word != w) || mode_of(other) != mode)) {
        d_.error(p.loc, "FEDRAT: " + other + " and " + w + " say opposite things in one record; which is meant is not known");
        return;
      }
      if (unit && unit_word.empty()) unit_word = w;
      else if (mode && !unit && mode_word.empty()) mode_word = w;
    }
    if (w == "MMPM") { f.mode = ir::FeedMode::PerMinute; to_program = 1 / prog_mm; }
    else if (w == "IPM") { f.mode = ir::FeedMode::PerMinute; to_program = 25.4 / prog_mm; }
    else if (w == "FPM") { f.mode = ir::FeedMode::PerMinute; to_program = 304.8 / prog_mm; }
    else if (w == "MMPR") { f.mode = ir::FeedMode::PerRev; to_program = 1 / prog_mm; }
    else if (w == "IPR") { f.mode = ir::FeedMode::PerRev; to_program = 25.4 / prog_mm; }
    else if (w == "PERMIN") f.mode = ir::FeedMode::PerMinute;
    else if (w == "PERREV") f.mode = ir::FeedMode::PerRev;
    else if (w == "INVERS") f.mode = ir::FeedMode::InverseTime;
    else if (w == "IPT" || w == "MMPT" || w == "PERTTH") {
      // A feed per tooth is feed x teeth x rpm per minute; no CL record clpc reads gives the
      // number of teeth, and a guess would be a wrong feed.
      d_.error(p.loc, "FEDRAT: a feed per tooth (" + w + ") needs the cutter's number of teeth, which the CL data does not give; "
                      "have the CAM system write the feed per minute or per revolution");
      return;
    }
    else {
      d_.error(p.loc, "FEDRAT: unknown word '" + std::string(p.text) + "'");
      return;
    }
  }
  if (!have) {
    d_.error(r.end, "FEDRAT: no feed value");
    return;
  }
  if (f.value == 0) {
    // Only the cuts after it are wrong (check_zero_feed): a FEDRAT/0 before rapids is read.
    zero_feed_at_ = r.loc;
    return;
  }
  if (!(f.value > 0)) {
    d_.error(r.loc, "FEDRAT: the feed must be greater than zero, found " + num_text(f.value));
    return;
  }
  zero_feed_at_.reset();
  // A FEDRAT without a unit word keeps the unit the last one named (APT's feed mode is modal:
  // FEDRAT/0.2,MMPR then FEDRAT/0.3 is 0.3 mm per revolution). Before any, per minute in the
  // program's units. Inverse time is never kept: it belongs to the moves it was written for.
  if (!worded && last_feed_unit_ && last_feed_unit_->mode != ir::FeedMode::InverseTime) {
    f.mode = last_feed_unit_->mode;
    to_program = last_feed_unit_->to_program;
    if (f.mode == ir::FeedMode::PerRev)
      d_.warning(r.loc, "FEDRAT/" + num_text(f.value) + " has no unit word: per revolution, as the FEDRAT at line " +
                            std::to_string(last_feed_unit_->loc.line) + " set it (the feed mode stays until a FEDRAT names another)",
                 "feed-unit");
  }
  if (!worded && last_feed_unit_ && last_feed_unit_->mode == ir::FeedMode::InverseTime)
    d_.warning(r.loc, "FEDRAT/" + num_text(f.value) + " has no unit word after the inverse-time FEDRAT at line " +
                          std::to_string(last_feed_unit_->loc.line) +
                          ": per minute in the file's units (inverse time belongs to the moves it was written for)",
               "feed-unit");
  if (worded) last_feed_unit_ = FeedUnit{f.mode, to_program, r.loc};
  if (f.mode != ir::FeedMode::InverseTime) f.value *= to_program;
  if (cycle_open_ && drilling_ && section_feed_ && !op_.cycles.empty() &&
      (f.mode != op_.cycles.back().feed_mode ||
       std::abs(f.value - op_.cycles.back().feed) > 1e-9 * std::max(1.0, std::abs(op_.cycles.back().feed)))) {
    // The cycle drills at its own feed; posts differ on whether a FEDRAT between its holes
    // changes it (ICAM-style posts take it as the cycle's new feed). Ignored, the holes after
    // it were drilled at the record's feed.
    d_.error(r.loc, "a FEDRAT while CYCLE/" + cycle_name_ + " (line " + std::to_string(cycle_loc_.line) +
                        ") is on, which has a feed of its own: whether the holes after it take this feed is not known; "
                        "end the cycle, and give it again with the feed");
    return;
  }
  inverse_time_ = f.mode == ir::FeedMode::InverseTime;
  if (rapid_next_) {
    // RAPID, then FEDRAT, then the move: APT posts read RAPID as the next move's only (the move
    // is rapid) or as in force until a FEDRAT (it is fed). Fed is the reading that cannot drive
    // the tool into the part at rapid.
    d_.warning(r.loc, "FEDRAT after RAPID and before the move: the move is fed, not rapid (some posts keep RAPID "
                      "for the next move; write the FEDRAT after it if that is meant)",
               "rapid-cancelled");
    rapid_next_ = false;
  }
  ensure_operation(r.loc);
  push(r.loc, f);
}

void Lowerer::lower_coolant(const Record& r) {
  // Coolant carries no motion: a record clpc cannot read is a warning, never a stop. Every word
  // is read: OFF anywhere turns the coolant off (COOLNT/MIST,OFF is no M07), ON with a kind is
  // that kind, a second kind is said and not turned on, and a word left over is said
  // (-Wignored-word).
  ir::Coolant c;
  if (r.params.empty()) {
    d_.warning(r.loc, "COOLNT with no word (ON, OFF, FLOOD, ...) says nothing; ignored", "coolant");
    return;
  }
  std::optional<ir::CoolantKind> kind;
  const Param* kind_word = nullptr;
  bool on = false, off = false;
  std::vector<const Param*> ignored;
  for (const Param& p : r.params) {
    std::optional<ir::CoolantKind> k;
    if (p.is("ON")) on = true;
    else if (p.is("OFF")) off = true;
    else if (p.is("FLOOD")) k = ir::CoolantKind::Flood;
    else if (p.is("MIST")) k = ir::CoolantKind::Mist;
    else if (p.is("THRU") || p.is("THROUGH")) k = ir::CoolantKind::Thru;
    else if (p.is("AIR")) k = ir::CoolantKind::Air;
    else if (p.is("TAP") || p.is("TAPKUL")) k = ir::CoolantKind::Tap;  // TAPKUL: ISO 4343's word
    else ignored.push_back(&p);
    if (!k) continue;
    if (kind && *kind != *k) {
      // Never none where the CL asks for two: the first is turned on, the other said.
      d_.warning(p.loc, "COOLNT: two coolants, '" + std::string(kind_word->text) + "' and '" + std::string(p.text) +
                            "': only '" + std::string(kind_word->text) + "' is turned on",
                 "coolant");
      continue;
    }
    kind = k;
    kind_word = &p;
  }
  if (on && off) {
    not_read(r, "COOLNT: both ON and OFF", "coolant");
    return;
  }
  if (!on && !off && !kind) {
    not_read(r, ignored.front()->is_word() ? "COOLNT: unknown coolant '" + std::string(ignored.front()->text) + "'"
                                           : std::string("COOLNT: expected ON, OFF, FLOOD, MIST, THRU, AIR or TAP"),
             "coolant");
    return;
  }
  for (const Param* p : ignored)
    d_.warning(p->loc, "COOLNT: '" + std::string(p->text) + "' is not read", "ignored-word");
  // A bare ON turns on the coolant last chosen, as SPINDL/ON and CUTCOM/ON resume theirs: after
  // COOLNT/THRU, OFF, ON the cut went on with flood.
  if (kind && !off) last_coolant_ = *kind;
  c.kind = off ? ir::CoolantKind::Off : kind ? *kind : last_coolant_.value_or(ir::CoolantKind::On);
  ensure_operation(r.loc);
  push(r.loc, c);
}

void Lowerer::lower_cutcom(const Record& r) {
  ParamReader ps(r, d_);
  ir::CutterComp c;
  bool side = false, on = false;
  for (size_t i = 0; i < ps.size(); ++i) {
    const Param& p = ps[i];
    const ir::CompSide said = p.is("LEFT") ? ir::CompSide::Left : p.is("RIGHT") ? ir::CompSide::Right : ir::CompSide::Off;
    if (side && (p.is("LEFT") || p.is("RIGHT") || p.is("OFF")) && said != c.side) {
      // CUTCOM/LEFT,RIGHT: the last one won. Which side is meant is not known.
      d_.error(p.loc, "CUTCOM: " + std::string(c.side == ir::CompSide::Left ? "LEFT" : c.side == ir::CompSide::Right ? "RIGHT" : "OFF") +
                          " and " + upper(p.text) + " in one record; which is meant is not known");
      return;
    }
    if (p.is("ON")) on = true;
    else if (p.is("LEFT")) { c.side = ir::CompSide::Left; side = true; }
    else if (p.is("RIGHT")) { c.side = ir::CompSide::Right; side = true; }
    else if (p.is("OFF")) { c.side = ir::CompSide::Off; side = true; }
    else if (p.is_number()) {
      auto reg = ps.integer(i, "the offset register", 0, 9999);
      if (!reg) return;
      c.reg = *reg;
    }
    else if (p.is("XYPLAN")) c.plane = 'Z';
    else if (p.is("ZXPLAN")) c.plane = 'Y';
    else if (p.is("YZPLAN")) c.plane = 'X';
    // ADJUST marks the register that follows.
    else if (!(p.is_empty() || p.is("ADJUST")))
      d_.warning(p.loc, "CUTCOM: '" + std::string(p.name()) + "' is not read", "ignored-word");
  }
  if (!side && on && last_comp_) {
    // CUTCOM/ON alone turns back on the side (and register) the last CUTCOM/LEFT|RIGHT named,
    // as SPINDL/ON restarts the last speed.
    int reg = c.reg;  // CUTCOM/ON,n: another register
    c = *last_comp_;
    if (reg != 0) c.reg = reg;
    side = true;
  }
  if (!side && !on && c.plane != 0 && c.reg == 0) {
    // CUTCOM/XYPLAN alone: the plane of the compensation turned on later (APT); it turns
    // nothing on. It was refused; forgotten, a later CUTCOM/LEFT would take the plane square
    // to the tool.
    comp_plane_ = c.plane;
    return;
  }
  if (!side) {
    d_.error(r.loc, on ? "CUTCOM/ON with no earlier CUTCOM/LEFT or RIGHT: which side is not known"
                       : "CUTCOM: expected LEFT, RIGHT or OFF");
    return;
  }
  if (c.plane == 0 && c.side != ir::CompSide::Off) c.plane = comp_plane_;
  if (c.plane != 0) {
    // The plane square to the tool is the one compensation works in, whatever the CL calls it
    // (a 3+2 side face is the CL's ZX plane): only another plane is kept, for the backend.
    const ir::Vec3 normal = c.plane == 'Z' ? ir::Vec3::UnitZ() : c.plane == 'Y' ? ir::Vec3::UnitY() : ir::Vec3::UnitX();
    if (std::abs(normal.dot(axis_.normalized())) > 1 - 1e-6) c.plane = 0;
  }
  if (c.side != ir::CompSide::Off) last_comp_ = c;
  if (c.side != ir::CompSide::Off) comp_on_at_ = r.loc;
  else comp_on_at_.reset();
  ensure_operation(r.loc);
  push(r.loc, c);
}

void Lowerer::lower_delay(const Record& r) {
  ParamReader ps(r, d_);
  ir::Dwell dw;
  bool have = false, sec = false;
  // One time in one unit: DELAY/2,3 dwelled 3 s and DELAY/SEC,2,REV two revolutions, silently
  // (helper-61); a FEDRAT refuses the same.
  for (size_t i = 0; i < ps.size(); ++i) {
    if (ps[i].is_number()) {
      if (have) {
        d_.error(ps[i].loc, upper(r.major) + ": more than one time (" + num_text(dw.value) + ", then " +
                                num_text(ps[i].number) + "): which one is meant cannot be told");
        return;
      }
      dw.value = ps[i].number;
      have = true;
    } else if (ps[i].is("REV") || ps[i].is("SEC")) {
      (ps[i].is("REV") ? dw.revolutions : sec) = true;
      if (dw.revolutions && sec) {
        d_.error(ps[i].loc, upper(r.major) + ": both SEC and REV: seconds or revolutions of the spindle cannot be told");
        return;
      }
    } else {
      d_.error(ps[i].loc, upper(r.major) + ": unknown word '" + std::string(ps[i].text) + "'");
      return;
    }
  }
  if (!have || dw.value < 0) {
    d_.error(have ? r.loc : r.end, upper(r.major) + " needs a time of zero or more");
    return;
  }
  ensure_operation(r.loc);
  push(r.loc, dw);
}

// The first length unit a feed word names (a FEDRAT's, a CYCLE's feed, a THREAD's lead), for
// a UNITS record after motion (lower_units).
void Lowerer::note_feed_unit(const Record& r) {
  if (feed_unit_named_) return;
  for (const Param& p : r.params) {
    if (p.is("MMPM") || p.is("MMPR")) feed_unit_named_ = {ir::Units::Mm, r.loc};
    else if (p.is("IPM") || p.is("IPR")) feed_unit_named_ = {ir::Units::Inch, r.loc};
    else continue;
    return;
  }
}

void Lowerer::lower_units(const Record& r) {
  if (r.params.empty() || !r.params[0].is_word() || !units_word(r.params[0].text)) {
    d_.error(r.params.empty() ? r.end : r.params[0].loc, std::string(r.major) + ": expected MM or INCHES");
    return;
  }
  ir::Units u = *units_word(r.params[0].text);
  for (size_t i = 1; i < r.params.size(); ++i)
    if (r.params[i].is_word() && units_word(r.params[i].text) && *units_word(r.params[i].text) != u) {
      // UNITS/INCHES,MM: every number is 25.4 times off one way or the other.
      d_.error(r.params[i].loc, std::string(r.major) + ": " + upper(r.params[0].text) + " and " + upper(r.params[i].text) +
                                    " in one record; which unit the file is in is not known");
      return;
    }
  // The file's unit is its UNITS record's, wherever it stands. After motion whose feed named the
  // other unit, the moves before it were written in that one: read in this, they would be 25.4
  // times off (a8: 10 mm became 10 inches, certified).
  const bool first = !units_record_seen_;
  units_record_seen_ = true;
  if (first && has_pos_ && feed_unit_named_ && feed_unit_named_->first != u && info_.units_reason != "--input-units") {
    d_.error(r.params[0].loc, std::string(r.major) + " says " + std::string(ir::units_name(u)) + " after motion whose feed (line " +
                                  std::to_string(feed_unit_named_->second.line) + ") is in " +
                                  std::string(ir::units_name(feed_unit_named_->first)) +
                                  ": the moves before it would be read in the wrong unit; put the UNITS record first, or "
                                  "give --input-units");
    return;
  }
  if (u != info_.units) {
    if (info_.units_reason == "--input-units") return;  // the user said so
    d_.error(r.params[0].loc, std::string("UNITS changes to ") + std::string(ir::units_name(u)) +
                                  " but the program is in " + std::string(ir::units_name(info_.units)) +
                                  ": clpc needs one unit per file");
  }
}

// OFSTNO/n (ISO 4343): the offset register what follows is cut with, the tool's length or its
// radius by the post that reads it. As a comment (an unknown record) the cuts after
// OFSTNO/24, CUTCOM/LEFT were written G41 D4, certified (helper-51). The loaded tool's own
// number, which clpc uses for both, asks for nothing; any other register is refused, as it
// cannot be told which offset it is.
void Lowerer::lower_ofstno(const Record& r) {
  ParamReader ps(r, d_);
  static const char* const kWhat = "an offset register for the tool's length or its radius by the post, which clpc does not read";
  if (ps.size() >= 1 && ps[0].is("OFF")) {
    d_.error(ps[0].loc, std::string("OFSTNO/OFF: cancels ") + kWhat + "; clpc applies the tool's length offset from "
                        "LOADTL and its radius offset from CUTCOM (CUTCOM/OFF cancels it)");
    return;
  }
  auto n = ps.integer(0, "the offset register", 0, 9999);
  if (!n) return;
  if (ps.size() > 1) {
    d_.error(ps[1].loc, "OFSTNO: expected OFSTNO/n (one register)");
    return;
  }
  if (tool_ >= 0 && *n == tool_ && loaded_offset_ == tool_) return;
  const std::string reg = std::to_string(*n);
  // What to write instead: only what the file does not say already, and never register 0,
  // which is no offset at all (helper-55).
  auto instead = [&](bool radius, bool length, const std::string& t) {
    if (*n == 0) return std::string("; register 0 is no offset at all: remove the OFSTNO");
    std::string s;
    if (radius) s += "the radius register on the CUTCOM (CUTCOM/LEFT," + reg + ")";
    if (length) s += std::string(s.empty() ? "" : " and ") + "the length register on the tool change (LOADTL/" + t + ",OSETNO," + reg + ")";
    return "; if it is " + std::string(radius && length ? "either" : radius ? "the radius" : "the length") + ", give " + s;
  };
  if (tool_ < 0) {
    d_.error(ps[0].loc, "OFSTNO/" + reg + " before any tool is loaded: " + kWhat + instead(true, true, "n"));
    return;
  }
  const std::string t = std::to_string(tool_);
  d_.error(ps[0].loc, "OFSTNO/" + reg + ": " + kWhat + ": it cuts T" + t + " with length register " +
                      std::to_string(loaded_offset_) + " and radius register " + t +
                      instead(*n != tool_, *n != loaded_offset_, t));
}

}  // namespace clpc
