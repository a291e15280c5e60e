// The record table: which lowering each major word gets, and operation bookkeeping.
#include "lower/lower.h"

#include "lower/params.h"
#include "lower/tool_records.h"

namespace clpc {

Lowerer::Lowerer(const ir::ProgramInfo& info, Diagnostics& diags, OperationSink& sink, LowerOptions opt)
    : info_(info), d_(diags), sink_(sink), opt_(opt) {
  op_.body.reserve(std::min<size_t>(opt_.chunk_size, 4096));
}

void Lowerer::record(const Record& r) {
  if (defining_sub_ >= 0 && record_subroutine(r)) return;
  // An open INDEX block keeps what COPY will play again (but not its own INDEX or COPY).
  if (recording_index_ >= 0 && r.kind == Record::Kind::Statement && r.id != MajorId::Index && r.id != MajorId::Copy &&
      keep_stored(r))
    blocks_[recording_index_].push_back(OwnedRecord::of(r));
  if (r.kind == Record::Kind::Comment) {
    if (!finished_) catia_axes_.comment(r.text, r.loc, d_);
    // Creo brackets explicit groove motion with "$$ GRV ..." and "$$ GRV END": kept for the
    // groove-cycles pass. Other comments carry nothing clpc uses.
    std::string_view t = r.text;
    while (!t.empty() && t.front() == ' ') t.remove_prefix(1);
    if (t.size() >= 3 && iequals(t.substr(0, 3), "GRV") && (t.size() == 3 || t[3] == ',' || t[3] == ' ')) {
      std::string_view rest = t.substr(3);
      while (!rest.empty() && (rest.front() == ' ' || rest.front() == ',')) rest.remove_prefix(1);
      bool end = rest.size() >= 3 && iequals(rest.substr(0, 3), "END");
      if (!finished_) {
        ensure_operation(r.loc);
        push(r.loc, ir::GrooveMark{!end});
      }
    }
    return;
  }
  catia_axes_.statement(moves_the_tool(r));
  if (finished_) {
    // Motion after FINI (a second program in the file, or a FINI inside an operation) would be
    // lost: it was ignored with a warning and the program certified without its cuts. Refused
    // at the first such record; anything else after FINI is ignored.
    if (moves_the_tool(r)) {
      if (!refused_after_fini_)
        d_.error(r.loc, "'" + head_and_major(r) + "' after FINI: FINI ends the program, and the motion after it "
                        "would be lost; remove the FINI before it, or post each program from a file of its own");
      refused_after_fini_ = true;
      return;
    }
    if (!warned_after_fini_)
      d_.warning(r.loc, "records after FINI are ignored", "after-fini");
    warned_after_fini_ = true;
    return;
  }
  if (r.data_comment) {
    // Creo "$$->" comments: a few carry data; the rest are comments and stay silent.
    switch (r.id) {
      case MajorId::Featno: {
        ParamReader p(r, d_);
        std::string name = "FEATNO";
        if (p.size() > 0 && p[0].is_number()) name += " " + num_text(p[0].number);
        close_operation();
        open_operation(std::move(name), r.loc);
        return;
      }
      case MajorId::End: close_operation(); return;
      case MajorId::Csys: lower_matrix_frame(r, ir::FrameSource::Csys); return;
      case MajorId::Cutter: read_tool_geometry(r, &d_); say_another_diameter(r); return;
      default: return;
    }
  }

  if (!r.head.empty() && !is_contour_motion(r.id)) {
    // Words before the major word are read only before a contour motion (TLON,GOFWD/...).
    // Before a record clpc reads (RAPID,GOTO/...) they may change what it does: not posted as
    // if they were not there. Before a record with nothing to cut, or an unknown one, they are
    // passed through with it.
    if (r.id != MajorId::Unknown && !carries_nothing_to_cut(r.id)) {
      d_.error(r.loc, "'" + head_and_major(r) + "': words before " + upper(r.major) +
                          " are read only before a contour motion (TLON,GOFWD/...); what they change in it is not "
                          "known: write them as records of their own");
      return;
    }
    if (r.id == MajorId::Unknown && motion_word(r.major)) {
      motion_not_read(r, motion_hint(r.major));
      return;
    }
    if (r.id == MajorId::Unknown && blank_joined_record(r)) return;
    if (r.id != MajorId::Unknown) {
      d_.warning(r.loc, "'" + head_and_major(r) + "': the words before " + upper(r.major) +
                            " are not read (the record is passed through as a comment)",
                 "ignored-word");
      passthrough(r);
      return;
    }
    unknown(r, "unknown record", true);
    return;
  }

  // A record of no motion with nothing after its slash says nothing: said, never a stop.
  // (COOLNT/, INSERT/, PPRINT/ were read past while FEDRAT/ stopped the post.)
  if (r.params.empty() && r.head.empty()) {
    switch (r.id) {
      case MajorId::Fedrat: case MajorId::Spindl: case MajorId::Delay: case MajorId::Auxfun: case MajorId::Prefun:
      case MajorId::Tldata: case MajorId::Cutter: case MajorId::Units:
        d_.warning(r.loc, upper(r.major) + " with nothing after it says nothing; ignored", "empty-record");
        return;
      default: break;
    }
  }
  if (r.id == MajorId::Mode || r.id == MajorId::Machin || r.id == MajorId::Unknown)
    if (const Param* w = diameter_word(r); w || says_diameter(r)) {
      d_.error(w ? w->loc : r.loc, (w ? upper(r.major) + " with " + upper(w->text) : upper(r.major)) +
                                       " says X is a diameter: clpc reads a lathe's X as the radius (the CL standard; "
                                       "the machine writes the diameter), so every X would be doubled; have the CAM "
                                       "system output X as the radius");
      return;
    }
  // INDIRV says where the next motion sets off: a motion other than the CIRCLE or contour it
  // decides uses it up (a stale one reversed a later arc).
  switch (r.id) {
    case MajorId::Goto: case MajorId::From: case MajorId::Gohome: case MajorId::Godlta: case MajorId::Movarc:
      has_indirv_ = false;
      break;
    default: break;
  }
  switch (r.id) {
    case MajorId::Goto: lower_goto(r); return;
    case MajorId::From: lower_from(r); return;
    case MajorId::Gohome: lower_gohome(r); return;
    case MajorId::Godlta: lower_godlta(r); return;
    case MajorId::Circle: lower_circle(r); return;
    case MajorId::Movarc: lower_movarc(r); return;
    case MajorId::Gofwd: case MajorId::Golft: case MajorId::Gorgt: case MajorId::Goback: case MajorId::Goup:
    case MajorId::Godown:
      lower_contour(r);
      return;
    case MajorId::Indirv: lower_indirv(r); return;
    case MajorId::Tlaxis: lower_tlaxis(r); return;
    case MajorId::Rapid:
      // RAPID applies to the next motion record and takes no words: one it does not know
      // (RAPID/OFF, RAPID/ON) may ask for the opposite, and the next move at rapid could be a
      // cut at traverse speed.
      if (!r.params.empty()) {
        const Param& w = r.params[0];
        d_.error(w.loc, "RAPID takes no words: '" + (w.is_number() ? num_text(w.number) : std::string(w.text)) +
                            "' may ask for something else than the next move at rapid, which the CL cannot be read "
                            "without; write RAPID alone before the move");
        return;
      }
      rapid_next_ = true;
      return;

    case MajorId::ToolPath: {
      close_operation();
      std::string name = r.params.empty() ? std::string() : std::string(r.params[0].name());
      open_operation(std::move(name), r.loc);
      tool_path_open_ = true;
      tool_path_loc_ = r.loc;
      tool_path_name_ = op_.name;
      op_tool_name_ = tool_name_of_tool_path(r);
      // NX often names the tool without loading it by number: load the number the pre-scan
      // gave that name here, before the operation's SPINDL (M06 stops the spindle).
      if (int n = info_.named_tool_at(r.loc.line); n > 0 && n != tool_) {
        d_.warning(r.loc, "operation '" + op_.name + "' names tool '" + op_tool_name_ +
                              "' but loads no tool number; using T" + std::to_string(n),
                   "tool-by-name");
        ir::ToolChange tc;
        tc.tool = n;
        for (size_t i = 0; i < info_.tools.size(); ++i)
          if (info_.tools[i].number == n) tc.slot = int(i);
        tool_ = n;
        forget_the_last_tools_state();
        push(r.loc, tc);
      }
      return;
    }
    case MajorId::EndOfPath:
      tool_path_open_ = false;
      close_operation();
      return;

    case MajorId::Select:
      // SELECT/TOOL,n preselects; SELECT/HEAD,..., SELECT/OFF and the like choose a head or end
      // a choice on machines with several: no motion, nothing a single-head machine acts on.
      if (r.params.empty() || !r.params[0].is("TOOL")) {
        d_.warning(r.loc, "SELECT without TOOL is not read (clpc's machines have one head and one turret)",
                   "not-supported");
        return;
      }
      lower_tool_change(r);
      return;
    case MajorId::Loadtl: case MajorId::Load: case MajorId::Turret:
      toolno_named_ = -1;
      lower_tool_change(r); return;
    case MajorId::Toolno:
      // CATIA and NX describe a tool with TOOLNO and load it with LOADTL; some older posts
      // change tools on TOOLNO alone. Which tool cuts is said at the next move if they differ.
      if (!r.params.empty() && r.params[0].is_number()) {
        toolno_named_ = int(r.params[0].number);
        toolno_loc_ = r.loc;
      }
      return;
    case MajorId::Tldata: case MajorId::Cutter:
      // CUTTER/OFF ends the cutter's display in APT: no geometry, no motion.
      if (r.id == MajorId::Cutter && r.params.size() == 1 && r.params[0].is("OFF")) return;
      // CUTTER/DISPLY,... (APT, NCL) says how the cutter is drawn: no tool, no motion.
      if (r.id == MajorId::Cutter && !r.params.empty() && r.params[0].is("DISPLY")) return;
      read_tool_geometry(r, &d_);
      say_another_diameter(r);
      return;
    case MajorId::Spindl: lower_spindle(r); return;
    case MajorId::Fedrat: note_feed_unit(r); lower_feed(r); return;
    case MajorId::Coolnt: lower_coolant(r); return;
    case MajorId::Cutcom: lower_cutcom(r); return;
    case MajorId::Delay: lower_delay(r); return;
    case MajorId::Opstop: ensure_operation(r.loc); push(r.loc, ir::Stop{ir::StopKind::Optional}); return;
    case MajorId::Stop: lower_stop(r); return;
    case MajorId::End: return;  // end of the part program: the program end is written at FINI / end of input
    case MajorId::Fini:
      tool_path_open_ = false;  // FINI ends what is open
      close_operation();
      finished_ = true;
      return;
    case MajorId::Units: case MajorId::Unit: lower_units(r); return;

    case MajorId::Pprint: case MajorId::Tprint: case MajorId::Comment: {
      ensure_operation(r.loc);
      std::string_view text = r.text;
      // COMMENT/'text' (Fusion): free text, as PPRINT, less one pair of enclosing quotes (an
      // apostrophe inside, COMMENT/'Operator's note', stopped the post; helper-61).
      if (r.id == MajorId::Comment && text.size() >= 2 && (text.front() == '\'' || text.front() == '"') &&
          text.back() == text.front())
        text = text.substr(1, text.size() - 2);
      push_text<ir::Comment>(r.loc, text);
      return;
    }
    case MajorId::Insert: lower_insert(r); return;
    case MajorId::Auxfun: case MajorId::Prefun: {
      ParamReader p(r, d_);
      auto code = p.integer(0, r.id == MajorId::Auxfun ? "an M-code number" : "a G-code number", 0, 999);
      if (!code) return;
      // ISO 4343: PREFUN/n[,NEXT], AUXFUN/n[,NOW|NEXT]. The code is written as a block of its
      // own before the next move, which is when NEXT would have it; anything else after the
      // code is no part of it and is said to be dropped.
      for (size_t k = 1; k < r.params.size(); ++k) {
        const Param& extra = r.params[k];
        if (extra.is("NEXT") || extra.is("NOW")) continue;
        d_.warning(extra.loc, std::string(r.major) + ": '" + std::string(extra.text) + "' after the code is not read (the code " +
                                  (r.id == MajorId::Auxfun ? "M" : "G") + std::to_string(*code) + " is written alone)",
                   "ignored-word");
        break;
      }
      ensure_operation(r.loc);
      push_text<ir::Insert>(r.loc, (r.id == MajorId::Auxfun ? "M" : "G") + std::to_string(*code));
      return;
    }

    case MajorId::Msys: lower_msys(r); return;
    case MajorId::Csys: lower_matrix_frame(r, ir::FrameSource::Csys); return;
    case MajorId::Camera: lower_matrix_frame(r, ir::FrameSource::Camera); return;
    case MajorId::Set: lower_set(r); return;
    case MajorId::Rotate: lower_rotate(r); return;
    case MajorId::Rotabl: lower_rotabl(r); return;

    case MajorId::Defsub: record_subroutine(r); return;
    case MajorId::Endsub: d_.error(r.loc, "ENDSUB without DEFSUB"); return;
    case MajorId::Calsub: lower_calsub(r); return;

    case MajorId::Retract:
      // RETRCT asks the post to take the tool up to the clearance surface (CLRSRF) before the
      // next move. clpc makes no motion the CL does not give: the next move must be that
      // retract itself (checked in push), or a tool change, which takes the tool up anyway.
      // RETRCT/OFF ends such retracts (NCL, APT posts): nothing to make.
      if (r.params.size() == 1 && r.params[0].is("OFF")) return;
      if (has_pos_) retract_pending_ = r.loc;
      return;

    // Header facts read by the pre-scan, and records with no meaning for the output.
    case MajorId::Multax:
      // MULTAX, MULTAX/ON: tool axes on the GOTOs (read wherever there are six values); OFF: none.
      // Anything else is no guess: MULTAX/OFF,XYZ and MULTAX/OF were read as ON, and the next
      // GOTO's second point taken for a tool axis (helper-64).
      {
        bool on = false, off = false, other = false;
        for (const Param& p : r.params) {
          if (p.is("ON")) on = true;
          else if (p.is("OFF")) off = true;
          else other = true;
        }
        if (other || (on && off)) {
          d_.error(r.loc, "MULTAX: expected ON or OFF (or nothing, for ON): whether the GOTOs carry tool axes cannot "
                          "be told");
          return;
        }
        multax_off_ = off;
        multax_on_ = !off;
      }
      return;
    case MajorId::Partno: case MajorId::Machin: case MajorId::Remark:
    case MajorId::Paint: case MajorId::Ppword: case MajorId::Mfgno: case MajorId::Setstart:
    case MajorId::Clrsrf: case MajorId::Autops:
    case MajorId::Intol: case MajorId::Outtol: case MajorId::Toler:
      return;
    case MajorId::Featno:
      return;  // only meaningful as a Creo "$$->" comment

    case MajorId::Nurbs: case MajorId::Knot: case MajorId::Cntrl: lower_nurbs(r); return;
    case MajorId::Cycle: note_feed_unit(r); lower_cycle(r); return;
    case MajorId::Tracut: case MajorId::Copy: case MajorId::Index: lower_transform(r); return;
    case MajorId::Thread: note_feed_unit(r); lower_thread(r); return;
    case MajorId::Indirp: case MajorId::Psis: case MajorId::Rothed:
      if (switches_off_only(r)) return;
      motion_not_read(r, motion_hint(r.major));
      return;
    case MajorId::Mode:
      if (incremental_points(r)) return;
      // MODE/MILL, MODE/TURN (Fusion, Creo mill-turn): which kind of machine, as MACHIN says;
      // MODE/ABSOL: the absolute points clpc reads.
      if (r.params.size() == 1 && (r.params[0].is("MILL") || r.params[0].is("TURN") || r.params[0].is("LATHE") ||
                                   r.params[0].is("ABSOL")))
        return;
      if (r.params.size() == 2 && r.params[0].is("ABSOL") && r.params[1].is("ON")) return;
      unknown(r, "not supported by clpc's machines", true);
      return;
    case MajorId::Head:
      unknown(r, "not supported by clpc's machines", true);
      return;
    case MajorId::Origin: lower_origin(r); return;
    case MajorId::Unknown:
      if (blank_joined_record(r)) return;
      if (motion_word(r.major)) {
        if (iequals(r.major, "TRANS") && no_shift(r)) return;  // TRANS/0,0,0 shifts nothing, as ORIGIN/0,0,0
        if (switches_off_only(r)) return;
        motion_not_read(r, motion_hint(r.major));
        return;
      }
      // CAMWorks brackets each operation in OPFEATSTART/name ... OPFEATEND/name.
      if (iequals(r.major, "OPFEATSTART")) {
        close_operation();
        open_operation(r.params.empty() ? std::string() : std::string(r.params[0].name()), r.loc);
        return;
      }
      if (iequals(r.major, "OPFEATEND")) {
        close_operation();
        return;
      }
      if (iequals(r.major, "OFSTNO")) {
        lower_ofstno(r);
        return;
      }
      if (iequals(r.major, "BOX")) return;  // the stock (SolidWorks CAM, CAMWorks): nothing to cut
      // NX's optional skip: the blocks between OPSKIP/ON and OFF are to carry the control's
      // block delete ('/'). clpc writes none: they run whatever the operator's switch says.
      if (iequals(r.major, "OPSKIP")) {
        d_.warning(r.loc, "OPSKIP: clpc writes no block delete ('/'): the blocks between OPSKIP/ON and OPSKIP/OFF run "
                          "whatever the operator's block-delete switch says (passed through as a comment)",
                   "not-supported");
        passthrough(r);
        return;
      }
      if (incremental_points(r)) return;
      if (iequals(r.major, "ABSOL")) return;  // ABSOL, ABSOL/ON: the absolute points clpc reads
      // DWELL/t: the dwell some APT generators write for ISO's DELAY/t (seconds, or REV).
      if (iequals(r.major, "DWELL")) {
        lower_delay(r);
        return;
      }
      unknown(r, "unknown record", true);
      return;
  }
}

// A record name of several words (`RAPID GOTO/...`, `TLON GOFWD/...`, `GO TO/...`): APT
// separates the words before the major word with commas, and ignores blanks inside a word. If
// one of the words, or the words run together, name a record that moves the tool or changes how
// it cuts, the record is refused where it stands: passed through as a comment, its motion would
// be lost. True when refused.
bool Lowerer::blank_joined_record(const Record& r) {
  const std::string_view name = r.major;
  if (name.find_first_of(" \t") == std::string_view::npos) return false;
  std::string joined;
  std::vector<std::string_view> words;
  for (size_t i = 0; i < name.size();) {
    while (i < name.size() && (name[i] == ' ' || name[i] == '\t')) ++i;
    size_t j = i;
    while (j < name.size() && name[j] != ' ' && name[j] != '\t') ++j;
    if (j > i) {
      words.push_back(name.substr(i, j - i));
      joined += name.substr(i, j - i);
    }
    i = j;
  }
  words.insert(words.begin(), joined);  // GO TO: the word APT reads
  for (size_t k = 0; k < words.size(); ++k) {
    const std::string_view w = words[k];
    const MajorId id = major_id(w);
    // END does nothing (END OF FILE, END OF PROGRAM: a line of text, refused; helper-61).
    if (id == MajorId::End) continue;
    if ((id != MajorId::Unknown && !carries_nothing_to_cut(id)) || motion_word_exact(w)) {
      d_.error(r.loc, "'" + upper(name) + "': a record name of several words, and " + upper(w) +
                          " moves the tool or changes how it cuts: APT separates the words before the major word with "
                          "commas (TLON,GOFWD/...) and ignores blanks inside a word; write the record as " +
                          (k == 0 ? upper(joined) : "records of their own"));
      return true;
    }
  }
  return false;
}

// ARCSLP/OFF, ROTHED/OFF, PLUNGE/OFF, REFSYS/NOMORE: a record that only switches off what clpc
// never switches on (each one that would is refused) asks for nothing. They stopped the post as
// motion clpc does not read (helper-66).
bool switches_off_only(const Record& r) {
  // (CUT/OFF may say "stop cutting", as DNTCUT does: the motion after it is not to be cut.)
  return !iequals(r.major, "CUT") && !r.params.empty() &&
         std::all_of(r.params.begin(), r.params.end(), [](const Param& p) { return p.is("NOMORE") || p.is("OFF"); });
}

// The record's name as written: its head words, then its major (TLON,GOFWD).
std::string head_and_major(const Record& r) {
  std::string name;
  for (const Param& h : r.head) name += std::string(h.text) + ",";
  return name + std::string(r.major);
}

// A tool number the pre-scan found given another diameter at this record: one pocket holds one
// cutter, and the program's tool list (and a cutting speed's rpm) keep the first.
void Lowerer::say_another_diameter(const Record& r) {
  for (const ir::ToolInfo& t : info_.tools)
    if (t.other_diameter_at == r.loc)
      d_.warning(r.loc, "tool " + std::to_string(t.number) + " is given the diameter " + num_text(t.other_diameter) +
                            " here, but " + num_text(t.diameter) + " where it was first loaded (line " +
                            std::to_string(t.first_use.line) + "): the program's tool list keeps " + num_text(t.diameter) +
                            "; give each cutter a number of its own",
                 "tool-geometry");
}

void Lowerer::unknown(const Record& r, std::string_view why, bool warn) {
  // LOADTL2, UNITSINCHES, RAPIDGOTO/..: a known record glued to what follows. Passed through
  // as a comment, the tool change, the units or the rapid was lost, with a warning (helper-64).
  if (const std::string_view g = glued_record(r.major); !g.empty()) {
    d_.error(r.loc, "'" + upper(r.major) + "' reads as " + std::string(g) + " glued to what follows (a '/' missing?): as "
                        "an unknown record its motion or setting would be lost; write " + std::string(g) + "/...");
    return;
  }
  if (warn)
    d_.warning(r.loc, std::string(why) + " '" + std::string(r.major) + "' (passed through as a comment)",
               why == "unknown record" ? "unknown-record" : "not-supported", upper(r.major));
  passthrough(r);
}

// ORIGIN/x,y,z: APT's postprocessor word for where the part's origin lies from the machine's.
// Posts apply it in opposite senses (added to every coordinate, or subtracted: the machine's
// zero from the part's), and some as a work offset: any shift would move every cut by a
// guess. No shift (no numbers, or all zero) is nothing to do; any other is refused.
void Lowerer::lower_origin(const Record& r) {
  if (no_shift(r)) return;
  d_.error(r.loc, "ORIGIN moves every coordinate after it, and posts apply it in opposite senses: clpc does not guess "
                  "which; set the part's origin in the CAM system's machine coordinate system (MCS, CSYS) or with "
                  "the work offset (SET, CAMERA) instead");
}

// A shift of the coordinates (ORIGIN, TRANS) that shifts nothing: every parameter a zero.
bool Lowerer::no_shift(const Record& r) {
  for (const Param& p : r.params)
    if (!p.is_number() || p.number != 0) return false;
  return true;
}

// A record without motion that clpc cannot act on: a warning, and the record as a comment.
void Lowerer::not_read(const Record& r, std::string_view why, std::string_view category) {
  d_.warning(r.loc, std::string(why) + " (passed through as a comment)", category);
  passthrough(r);
}

// Incremental CL data: MODE/INCR (and INCREM, INCREMENTAL, RELATIVE, ABSOL,OFF), COORD/INCR,
// or a record named INCR (INCREM, INCREMENTAL) or ABSOL/OFF. Every point after it is a step
// from the one before, and clpc reads points as absolute: passed through as a comment, each
// point would be cut at the step's value (10 mm from the origin, not from the last point).
// Refused where it stands (SET/MODE,INCR is refused by the frame records). True when refused.
bool Lowerer::incremental_points(const Record& r) {
  // INCR,OFF and INCR,NOMORE switch it off: the absolute points clpc reads.
  auto incremental = [&](size_t i) {
    const Param& p = r.params[i];
    const bool off = i + 1 < r.params.size() && (r.params[i + 1].is("OFF") || r.params[i + 1].is("NOMORE"));
    return !off && (p.is("INCR") || p.is("INCREM") || p.is("INCREMENTAL") || p.is("RELATIVE"));
  };
  auto absol_off = [&] {
    for (size_t i = 0; i + 1 < r.params.size(); ++i)
      if (r.params[i].is("ABSOL") && r.params[i + 1].is("OFF")) return true;
    return false;
  };
  bool refused = false;
  if (r.id == MajorId::Mode || iequals(r.major, "COORD")) {
    refused = absol_off();
    for (size_t i = 0; i < r.params.size(); ++i) refused |= incremental(i);
  } else if (iequals(r.major, "INCR") || iequals(r.major, "INCREM") || iequals(r.major, "INCREMENTAL")) {
    refused = !(r.params.size() == 1 && (r.params[0].is("OFF") || r.params[0].is("NOMORE")));
  } else if (iequals(r.major, "ABSOL")) {
    refused = r.params.size() == 1 && r.params[0].is("OFF");
    for (size_t i = 0; i < r.params.size(); ++i) refused |= incremental(i);  // ABSOL/INCR
  }
  std::string said = head_and_major(r);
  for (size_t i = 0; i < r.params.size(); ++i) said += (i ? "," : "/") + std::string(r.params[i].name());
  if (refused)
    d_.error(r.loc, "'" + said + "' makes the points that follow incremental (each a step from the one "
                    "before), and clpc reads CL points as absolute: have the CAM system write absolute points");
  return refused;
}

// A record that moves the tool (or the machine) in a way clpc does not read: never dropped, never
// guessed (docs/cl-input.md, "Records that carry motion").
void Lowerer::motion_not_read(const Record& r, std::string_view why) {
  d_.error(r.loc, "'" + head_and_major(r) + "' moves the tool and clpc does not read it: " + std::string(why));
}

namespace {

// APT words that move the tool or change which motion is cut, with what to do instead. A
// record of one of these that clpc does not read is an error, not a comment.
struct MotionWord {
  const char* word;
  const char* hint;
};
constexpr MotionWord kMotionWords[] = {
    {"GO", "APT startup motion to drive surfaces needs the part model; have the CAM system write GOTO points"},
    {"PSIS", "APT contouring on a part surface needs the part model; have the CAM system write GOTO points"},
    {"INDIRP", "APT contouring towards a point; have the CAM system write GOTO points"},
    {"DNTCUT", "the motion after it is not to be cut; have the CAM system leave that motion out"},
    {"CUT", "it ends a DNTCUT block; have the CAM system leave the uncut motion out"},
    {"LOOP", "a repeat of the records that follow; have the CAM system write them out in full"},
    {"LOOPST", "it starts an APT loop (LOOPST ... JUMPTO ... LOOPND); have the CAM system write the records out in full"},
    {"LOOPND", "it ends an APT loop (LOOPST ... JUMPTO ... LOOPND); have the CAM system write the records out in full"},
    {"JUMPTO", "a jump to a label: the records between would run again or not at all; have the CAM system write the "
               "records out in full"},
    {"POCKET", "APT pocketing needs the part model; have the CAM system write the pocket as GOTO and CIRCLE records"},
    {"ARCSLP", "it changes how CIRCLE records are cut; have the CAM system write plain CIRCLE records"},
    {"ROTHED", "a rotary head positioned by record; have the CAM system write the tool axis on the GOTOs (MULTAX)"},
    {"ROTHEAD", "a rotary head positioned by record; have the CAM system write the tool axis on the GOTOs (MULTAX)"},
    {"MOVE", "a move clpc has no rule for; have the CAM system write GOTO points"},
    // APT post-processor words (ISO 4343, the G-Post and IMS vocabularies) that move the
    // machine or shift what follows: passed through as a comment they would change the cut.
    {"POSTN", "it positions machine axes directly; have the CAM system write the move as GOTO points"},
    {"SAFPOS", "a move to a safe position the post would choose; have the CAM system write the move as GOTO points"},
    {"GOCLER", "a move to the clearance plane the post would make; have the CAM system write the retract as GOTO points"},
    {"FIXTURE", "it selects a work offset (a fixture) that clpc does not read: the cuts after it would land in the "
                "register in force; give the frame's register with SET (SET/55) and its frame (CAMERA, MSYS)"},
    {"REFSYS", "a reference system: it moves and turns the coordinates that follow; have the CAM system output the "
               "points in the part's frame (MSYS) or give the frame with SET and CAMERA"},
    {"TRANS", "it shifts the coordinates that follow; set the part's origin in the CAM system or with the work offset (SET, CAMERA)"},
    {"PIVOTZ", "it moves the point the coordinates name along the tool; have the CAM system output the tool tip"},
};

}  // namespace

namespace {

// A name no CAM system's record list has, that reads as motion: a misspelt GOTO (GOTOO, GOT,
// GOTOPT), another system's move (MOVETO, POSITN, RAPTO, PLUNGE, RAMP), an arc, a helix or a
// spline. Passed through as a comment, its move would be lost: refused.
bool reads_as_motion(std::string_view major) {
  static constexpr std::string_view kStarts[] = {"GO", "MOV", "ARC", "CIRC", "HELI", "SPLIN", "BSPL", "POSIT", "RAPTO",
                                                 "FEDTO", "PLUNG", "RAMP"};
  for (std::string_view s : kStarts)
    if (major.size() >= s.size() && iequals(major.substr(0, s.size()), s)) return true;
  return false;
}

}  // namespace

// A record that says the CL's X is a diameter (DIAMTR/ON, XDIAM; the word in LATHE/DIAMETER,
// MODE/TURN,DIAMETER, MACHIN/TURN,1,DIAMETER): passed through or ignored, every X was doubled
// and certified (helper-54). DIAMTR/OFF, RADIUS say the radius clpc reads.
namespace {
bool is_diameter(std::string_view w) {
  return iequals(w, "DIAMETER") || iequals(w, "DIAMTR") || iequals(w, "XDIAM") || iequals(w, "DIAM");
}
}  // namespace

bool says_diameter(const Record& r) {
  return r.id == MajorId::Unknown && is_diameter(r.major) &&
         !(r.params.size() == 1 && (r.params[0].is("OFF") || r.params[0].is("RADIUS")));
}

// (The word followed by OFF turns it off: LATHE/DIAMETER,OFF was refused; helper-55.)
const Param* diameter_word(const Record& r) {
  if (r.id == MajorId::Unknown && !iequals(r.major, "LATHE")) return nullptr;
  for (size_t i = 0; i < r.params.size(); ++i)
    if (r.params[i].is_word() && is_diameter(r.params[i].text) && !(i + 1 < r.params.size() && r.params[i + 1].is("OFF")))
      return &r.params[i];
  return nullptr;
}

bool motion_word_exact(std::string_view major) {
  for (const MotionWord& w : kMotionWords)
    if (iequals(major, w.word)) return true;
  return false;
}

// A record's name of one word: a known motion word, or a name that reads as motion. (The words
// of a line of typed text, "Move clamps clear", are judged by the exact names only.)
bool motion_word(std::string_view major) { return motion_word_exact(major) || reads_as_motion(major); }

// A record that moves the tool itself: a move, an arc, a subroutine call or a repeat, or a name
// that reads as motion. (A CYCLE/OFF or a tool unload moves nothing: after FINI a warning.)
bool moves_the_tool(const Record& r) {
  switch (r.id) {
    case MajorId::Goto: case MajorId::From: case MajorId::Gohome: case MajorId::Godlta: case MajorId::Circle:
    case MajorId::Movarc: case MajorId::Calsub: case MajorId::Copy: case MajorId::Index: case MajorId::Gofwd:
    case MajorId::Golft: case MajorId::Gorgt: case MajorId::Goback: case MajorId::Goup: case MajorId::Godown:
    case MajorId::Indirp:
      return true;
    case MajorId::Unknown: return reads_as_motion(r.major);
    default: return false;
  }
}

std::string_view motion_hint(std::string_view major) {
  for (const MotionWord& w : kMotionWords)
    if (iequals(major, w.word)) return w.hint;
  if (reads_as_motion(major))
    return "no CAM system's record of that name is known, and the name reads as motion (a misspelt GOTO, an arc, a "
           "helix, a spline?); have the CAM system write the motion as GOTO and CIRCLE records";
  return "have the CAM system write the motion as GOTO and CIRCLE records";
}

namespace {

// Parameters as text again: numbers as written (or shortest), groups in parentheses.
void params_text(std::span<const Param> ps, std::string& t) {
  for (size_t i = 0; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (i) t += ",";
    if (p.is_group()) {
      t += "(" + std::string(p.text) + (p.text.empty() ? "" : "/");
      size_t n = std::min<size_t>(p.group_size, ps.size() - i - 1);
      params_text(ps.subspan(i + 1, n), t);
      t += ")";
      i += n;
    } else if (p.kind == Param::Kind::String) {
      t += "'" + std::string(p.text) + "'";
    } else {
      t += p.is_number() && p.text.empty() ? num_text(p.number) : std::string(p.text);
    }
  }
}

}  // namespace

void Lowerer::passthrough(const Record& r) {
  ensure_operation(r.loc);
  std::string t;
  for (const Param& h : r.head) t += std::string(h.text) + ",";
  t += std::string(r.major);
  if (r.has_slash || !r.params.empty()) t += "/";
  params_text(r.params, t);
  push_text<ir::Passthrough>(r.loc, t);
}

// STOP, STOP/(message): the message as a comment before the stop.
void Lowerer::lower_stop(const Record& r) {
  ensure_operation(r.loc);
  std::string msg;
  for (const Param& p : r.params)
    if (!p.is_group() && !p.is_empty()) msg += (msg.empty() ? "" : " ") + std::string(p.name());
  if (!msg.empty()) push_text<ir::Comment>(r.loc, msg);
  push(r.loc, ir::Stop{ir::StopKind::Program});
}

// INSERT/text: a block for the control, checked when written (backends/program_writer.cpp);
// the APT words for stops become stops.
void Lowerer::lower_insert(const Record& r) {
  ensure_operation(r.loc);
  std::string_view t = r.text;
  if (iequals(t, "STOP")) {
    push(r.loc, ir::Stop{ir::StopKind::Program});
    return;
  }
  if (iequals(t, "OPSTOP")) {
    push(r.loc, ir::Stop{ir::StopKind::Optional});
    return;
  }
  push_text<ir::Insert>(r.loc, t);
}

void Lowerer::make_room() {
  // A stock-removal profile stays in one chunk: the cycle is written from the whole of it.
  if (rough_open_ && op_.body.size() - rough_size_ >= kMaxRoughInstructions) {
    d_.error(rough_loc_, "CYCLE/ROUGH: no CYCLE/OFF within " + std::to_string(kMaxRoughInstructions) +
                             " records: a profile that long is not a cycle's");
    rough_open_ = false;
    op_.body.push_back(ir::Instr{op_.body.back().loc, ir::RoughMark{false}});
  }
  // Nor does an open Creo arc: a line of text between its points goes before it, and flushed
  // away it closed the arc (the points after it cut as chords), at chunk boundaries that the
  // compile (1024) and the certificate's reference (256) do not share. Held to twice the chunk.
  if (op_.body.size() >= opt_.chunk_size && !rough_open_ && !(arc_open_ && op_.body.size() < 2 * opt_.chunk_size))
    flush_chunk();
}

ir::Instr& Lowerer::push(SourceLoc loc, ir::Op op) {
  // A line of text between the points of a Creo arc (a PPRINT, a record passed through) is
  // written before the arc, which stays open: it ended the arc, and the points after it were
  // cut as chords up to 0.76 mm inside a 10 mm circle (certified).
  if (arc_open_ && (std::holds_alternative<ir::Comment>(op) || std::holds_alternative<ir::Passthrough>(op)) &&
      !op_.body.empty() && std::holds_alternative<ir::Arc>(op_.body.back().op))
    return *op_.body.insert(op_.body.end() - 1, ir::Instr{loc, std::move(op)});
  arc_open_ = false;
  if (retract_pending_) [[unlikely]]
    check_retract(loc, op);
  if (from_gap_) [[unlikely]]
    check_from_gap(loc, op);
  if (zero_feed_at_) [[unlikely]]
    check_zero_feed(loc, op);
  if (from_approach_) [[unlikely]]
    approach_from(op);
  if (!cut_since_tool_change_) [[unlikely]]
    check_first_cut(loc, op);
  if (const auto* tc = std::get_if<ir::ToolChange>(&op)) {
    cut_since_tool_change_ = false;
    same_tool_again_ = tc->tool == last_tool_loaded_;  // NX loads the tool at every operation
    // Through-spindle coolant is the tool's (its coolant holes): another tool's bare COOLNT/ON
    // is the default coolant, not the last one's THRU.
    if (!same_tool_again_) last_coolant_.reset();
    last_tool_loaded_ = tc->tool;
    if (pending_arc_) [[unlikely]] {
      // A tool change between a CIRCLE and the GOTO that ends it: the arc would start where
      // the change leaves the tool (verify refused it with no word on why).
      d_.error(loc, "a tool change between a CIRCLE (line " + std::to_string(pending_arc_->loc.line) +
                        ") and the GOTO that ends it: the arc cannot be cut across it");
      pending_arc_.reset();
    }
  }
  else if (const auto* m = std::get_if<ir::Move>(&op)) {
    if (m->kind != ir::MoveKind::From) at_home_ = false;
    cut_since_tool_change_ |= m->kind != ir::MoveKind::From;
    if (m->kind != ir::MoveKind::From) {
      last_move_rapid_ = m->kind == ir::MoveKind::Rapid;
      last_move_hole_ = cycle_open_;
    }
  } else if (std::holds_alternative<ir::Arc>(op) || std::holds_alternative<ir::Hole>(op)) {
    cut_since_tool_change_ = true;
    last_move_rapid_ = false;
    last_move_hole_ = false;
  }
  make_room();
  op_.body.push_back(ir::Instr{loc, std::move(op)});
  return op_.body.back();
}

// After a FROM elsewhere than a rapid left the tool, the next motion: a rapid positions (the
// post's business), a tool change takes the tool away; a cut would start where the tool really
// is, not at the FROM, and run along a line the CL does not have (a diagonal plunge where it
// plunges straight down).
void Lowerer::check_from_gap(SourceLoc loc, const ir::Op& op) {
  const auto* m = std::get_if<ir::Move>(&op);
  if (m && m->kind == ir::MoveKind::From) return;
  const bool cut = (m && m->kind == ir::MoveKind::Feed) || std::holds_alternative<ir::Arc>(op) ||
                   std::holds_alternative<ir::Hole>(op);
  if (!m && !cut && !std::holds_alternative<ir::ToolChange>(op)) return;
  if (cut)
    d_.error(loc, "this cut starts " + from_gap_what_ +
                      ": cut from there it would run along a line the CL does not have; have the CAM system "
                      "write the move to where the cut starts (a RAPID GOTO)");
  from_gap_.reset();
}

// A FROM says where the tool stands before its first move. Where the first move is a cut (a
// feed or an arc), the CL's line runs from the FROM point, but after the tool change the tool
// is wherever the change left it: cut from there it fed diagonally from the tool change
// position (certified, since verify too started at the FROM). The tool is brought to the FROM
// point at rapid first, as a first rapid is (X Y, then Z with the length offset). A rapid,
// GOHOME or hole next positions the tool itself; a FROM again replaces this one.
void Lowerer::approach_from(const ir::Op& op) {
  const auto* m = std::get_if<ir::Move>(&op);
  if (std::holds_alternative<ir::ToolChange>(op) || (m && m->kind == ir::MoveKind::From)) return;
  const bool cut = (m && m->kind == ir::MoveKind::Feed) || std::holds_alternative<ir::Arc>(op);
  if (!m && !cut && !std::holds_alternative<ir::Hole>(op)) return;
  from_approach_ = false;
  if (!cut || (tool_ < 0 && !info_.tools.empty())) return;
  ir::Move up;
  up.kind = ir::MoveKind::Rapid;
  up.point = from_;
  up.axis = from_axis_;
  push(from_loc_, up);
}

// A tool's first move a cut, with no FROM or rapid before it: the CL does not say where it
// starts, and the control feeds it straight from where the tool change (or the program's
// start) left the tool. Said; the approach is the CAM system's to write.
void Lowerer::check_first_cut(SourceLoc loc, const ir::Op& op) {
  const auto* m = std::get_if<ir::Move>(&op);
  const bool cut = (m && m->kind == ir::MoveKind::Feed) || std::holds_alternative<ir::Arc>(op);
  if (!cut || tool_ < 0 || same_tool_again_) return;  // a load of the tool in the spindle moves nothing
  d_.warning(loc, "the first move of T" + std::to_string(tool_) + " is a cut, with no FROM or rapid before it to say where it starts: on a mill it is "
                      "positioned over its end at rapid and fed down along Z from where the tool change (or the "
                      "program's start) leaves the tool; a lathe feeds it straight from there",
             "approach");
}

// Under a FEDRAT/0, a cut with no feed of its own (a cycle's, a thread's lead): refused once
// at the cut, naming the FEDRAT. The feed before the FEDRAT/0 would be a guess.
void Lowerer::check_zero_feed(SourceLoc loc, const ir::Op& op) {
  const auto* m = std::get_if<ir::Move>(&op);
  const bool cut = (m && m->kind == ir::MoveKind::Feed) || std::holds_alternative<ir::Arc>(op);
  if (!cut || ((cycle_open_ || rough_open_ || thread_open_) && section_feed_)) return;
  d_.error(loc, "this cut is fed at zero: the FEDRAT/0 at line " + std::to_string(zero_feed_at_->line) +
                    " is in force (a feed of zero never moves the tool; it may stand before rapid moves only); "
                    "give the cut its FEDRAT");
  zero_feed_at_.reset();
}

void Lowerer::check_retract(SourceLoc loc, const ir::Op& op) {
  const SourceLoc retract = *retract_pending_;
  if (std::holds_alternative<ir::ToolChange>(op)) {
    retract_pending_.reset();
    return;
  }
  const char* what = nullptr;
  if (const auto* m = std::get_if<ir::Move>(&op)) {
    const ir::Vec3 d = m->point - pos_;
    const double along = d.dot(m->axis), tol = 0.01 / ir::mm_per_unit(info_.units);
    if (along >= -tol && (d - along * m->axis).norm() <= tol) {
      retract_pending_.reset();  // the CL retracts itself
      return;
    }
    what = "does not go straight up the tool axis";
  } else if (std::holds_alternative<ir::Arc>(op)) {
    what = "is an arc";
  } else {
    return;  // no motion (a spindle, a feed, a comment): the retract is still to come
  }
  retract_pending_.reset();
  d_.error(retract, std::string("RETRCT asks for a retract to the clearance surface, which clpc does not make: the next move (line ") +
                        std::to_string(loc.line) + ") " + what +
                        ", so the tool would cross at the depth it cut; write the retract as motion in the CAM system");
}

void Lowerer::open_operation(std::string name, SourceLoc loc) {
  op_.clear();
  op_.number = ++op_count_;
  op_.name = std::move(name);
  op_.loc = loc;
  op_.continued = false;
  op_open_ = true;
  op_implicit_ = false;
  op_loaded_ = false;
  op_tool_name_.clear();
}

void Lowerer::ensure_operation(SourceLoc loc) {
  if (op_open_) return;
  open_operation(std::string(), loc);
  op_implicit_ = true;
}

void Lowerer::flush_chunk() {
  op_.last_chunk = false;
  // Read before the sink, which may hand back another operation's storage.
  uint32_t number = op_.number;
  std::string name = op_.name;
  SourceLoc loc = op_.loc;
  sink_.operation(op_);
  op_.clear();
  op_.number = number;
  op_.name = std::move(name);
  op_.loc = loc;
  op_.continued = true;
}

void Lowerer::close_operation() {
  cycle_open_ = false;  // the drill-cycles pass cancels (with a warning) what is still on
  if (pending_arc_) {
    d_.error(pending_arc_->loc, "CIRCLE is not followed by a GOTO giving its end point");
    pending_arc_.reset();
  }
  arc_open_ = false;
  if (!op_open_) return;
  if (rough_open_) {
    // Where the profile ends is not known: the cycle cannot be written.
    d_.error(rough_loc_, "CYCLE/ROUGH without CYCLE/OFF before the end of the operation: where its profile ends is unknown");
    rough_open_ = false;
    push(op_.body.empty() ? op_.loc : op_.body.back().loc, ir::RoughMark{false});
  }
  if (thread_open_) {
    // A thread's cuts never run on into the next operation.
    SourceLoc at = op_.body.empty() ? op_.loc : op_.body.back().loc;
    d_.warning(at, "THREAD without THREAD/OFF at the end of the operation: ended here", "cycle");
    push(at, ir::ThreadMark{false, ir::ThreadKind::Turn, 0});
    thread_open_ = false;
  }
  op_.last_chunk = true;
  sink_.operation(op_);
  op_.clear();
  op_open_ = false;
}

void Lowerer::finish() {
  if (defining_sub_ >= 0) {
    d_.error(defining_loc_, "DEFSUB/" + std::to_string(defining_sub_) + " has no ENDSUB");
    defining_sub_ = -1;
  }
  // NX closes every TOOL PATH with END-OF-PATH: a file that ends inside one was cut short, and
  // the program would stop half way through the operation.
  if (tool_path_open_)
    d_.error(tool_path_loc_, "TOOL PATH" + (tool_path_name_.empty() ? std::string() : "/" + tool_path_name_) +
                                 " has no END-OF-PATH: the file ends inside the operation (was it cut short?)");
  close_operation();
}

}  // namespace clpc
