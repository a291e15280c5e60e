// The record table: which lowering each major word gets, and operation bookkeeping.
#include "ir/lower.h"

#include "ir/params.h"
#include "ir/tool_records.h"

namespace clpc {

Lowerer::Lowerer(const ir::ProgramInfo& info, Diagnostics& diags, OperationSink& sink, LowerOptions opt)
    : info_(info), d_(diags), sink_(sink), opt_(opt) {
  op_.body.reserve(std::min<size_t>(opt_.chunk_size, 4096));
}

void Lowerer::record(const Record& r) {
  if (defining_sub_ >= 0 && record_subroutine(r)) return;
  if (r.kind == Record::Kind::Comment) {
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
  if (finished_) {
    if (!warned_after_fini_)
      d_.warning(r.loc, "records after FINI are ignored");
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
      case MajorId::Cutter: read_tool_geometry(r, &d_); return;
      default: return;
    }
  }

  switch (r.id) {
    case MajorId::Goto: case MajorId::Gohome: case MajorId::Godlta: case MajorId::Circle:
      check_tool_loaded(r.loc);
      break;
    default: break;
  }

  switch (r.id) {
    case MajorId::Goto: lower_goto(r); return;
    case MajorId::From: lower_from(r); return;
    case MajorId::Gohome: lower_gohome(r); return;
    case MajorId::Godlta: lower_godlta(r); return;
    case MajorId::Circle: lower_circle(r); return;
    case MajorId::Rapid: rapid_next_ = true; return;

    case MajorId::ToolPath: {
      close_operation();
      std::string name = r.params.empty() || r.params[0].is_number() ? std::string() : std::string(r.params[0].text);
      open_operation(std::move(name), r.loc);
      tool_path_open_ = true;
      tool_path_loc_ = r.loc;
      tool_path_name_ = std::string(r.params.empty() || r.params[0].is_number() ? std::string_view() : r.params[0].text);
      op_tool_name_ = tool_name_of_tool_path(r);
      // NX often names the tool without loading it by number: load the number the pre-scan
      // gave that name here, before the operation's SPINDL (M06 stops the spindle).
      if (int n = info_.named_tool_at(r.loc.line); n > 0 && n != tool_) {
        d_.warning(r.loc, "operation '" + op_.name + "' names tool '" + op_tool_name_ +
                              "' but loads no tool number; using T" + std::to_string(n),
                   "tool by name");
        ir::ToolChange tc;
        tc.tool = n;
        for (size_t i = 0; i < info_.tools.size(); ++i)
          if (info_.tools[i].number == n) tc.slot = int(i);
        tool_ = n;
        push(r.loc, tc);
      }
      return;
    }
    case MajorId::EndOfPath:
      tool_path_open_ = false;
      close_operation();
      return;

    case MajorId::Loadtl: case MajorId::Load: case MajorId::Turret: case MajorId::Select:
      lower_tool_change(r); return;
    case MajorId::Tldata: case MajorId::Cutter: read_tool_geometry(r, &d_); return;
    case MajorId::Spindl: lower_spindle(r); return;
    case MajorId::Fedrat: lower_feed(r); return;
    case MajorId::Coolnt: lower_coolant(r); return;
    case MajorId::Cutcom: lower_cutcom(r); return;
    case MajorId::Delay: lower_delay(r); return;
    case MajorId::Opstop: ensure_operation(r.loc); push(r.loc, ir::Stop{ir::StopKind::Optional}); return;
    case MajorId::Stop: ensure_operation(r.loc); push(r.loc, ir::Stop{ir::StopKind::Program}); return;
    case MajorId::End: return;  // end of the part program: the program end is written at FINI / end of input
    case MajorId::Fini:
      tool_path_open_ = false;  // FINI ends what is open
      close_operation();
      finished_ = true;
      return;
    case MajorId::Units: case MajorId::Unit: lower_units(r); return;

    case MajorId::Pprint: {
      ensure_operation(r.loc);
      ir::Comment c;
      c.text = op_.add_text(r.text);
      push(r.loc, c);
      return;
    }
    case MajorId::Insert: {
      ensure_operation(r.loc);
      ir::Insert in;
      in.text = op_.add_text(r.text);
      push(r.loc, in);
      return;
    }
    case MajorId::Auxfun: case MajorId::Prefun: {
      ParamReader p(r, d_);
      auto code = p.integer(0, r.id == MajorId::Auxfun ? "an M-code number" : "a G-code number", 0, 999);
      if (!code) return;
      ensure_operation(r.loc);
      ir::Insert in;
      in.text = op_.add_text((r.id == MajorId::Auxfun ? "M" : "G") + std::to_string(*code));
      push(r.loc, in);
      return;
    }

    case MajorId::Msys: lower_msys(r); return;
    case MajorId::Csys: lower_matrix_frame(r, ir::FrameSource::Csys); return;
    case MajorId::Camera: lower_matrix_frame(r, ir::FrameSource::Camera); return;
    case MajorId::Set: lower_set(r); return;
    case MajorId::Rotate: lower_rotate(r); return;

    case MajorId::Defsub: record_subroutine(r); return;
    case MajorId::Endsub: d_.error(r.loc, "ENDSUB without DEFSUB"); return;
    case MajorId::Calsub: lower_calsub(r); return;

    // Header facts read by the pre-scan, and records with no meaning for the output.
    case MajorId::Partno: case MajorId::Machin: case MajorId::Multax: case MajorId::Remark:
    case MajorId::Paint: case MajorId::Ppword: case MajorId::Mfgno: case MajorId::Setstart:
    case MajorId::Clrsrf: case MajorId::Retract:
      return;
    case MajorId::Featno:
      return;  // only meaningful as a Creo "$$->" comment

    case MajorId::Nurbs: case MajorId::Knot: case MajorId::Cntrl:
      d_.error(r.loc, "NURBS motion is not supported: have the CAM system write it as GOTO points");
      return;
    case MajorId::Cycle: lower_cycle(r); return;
    case MajorId::Mode: case MajorId::Head: case MajorId::Origin: case MajorId::Thread:
      unknown(r, "not supported by clpc's machines", true);
      return;
    case MajorId::Unknown:
      unknown(r, "unknown record", true);
      return;
  }
}

void Lowerer::unknown(const Record& r, std::string_view why, bool warn) {
  if (warn)
    d_.warning(r.loc, std::string(why) + " '" + std::string(r.major) + "' (passed through as a comment)",
               std::string(why) + " " + std::string(r.major));
  passthrough(r);
}

void Lowerer::passthrough(const Record& r) {
  ensure_operation(r.loc);
  std::string t(r.major);
  if (r.has_slash || !r.params.empty()) t += "/";
  for (size_t i = 0; i < r.params.size(); ++i) {
    if (i) t += ",";
    const Param& p = r.params[i];
    t += p.is_number() ? num_text(p.number) : std::string(p.text);
  }
  ir::Passthrough pt;
  pt.text = op_.add_text(t);
  push(r.loc, pt);
}

ir::Instr& Lowerer::push(SourceLoc loc, ir::Op op) {
  arc_open_ = false;
  if (op_.body.size() >= opt_.chunk_size) flush_chunk();
  op_.body.push_back(ir::Instr{loc, std::move(op)});
  return op_.body.back();
}

void Lowerer::open_operation(std::string name, SourceLoc loc) {
  op_.clear();
  op_.number = ++op_count_;
  op_.name = std::move(name);
  op_.loc = loc;
  op_.continued = false;
  op_open_ = true;
  op_tool_name_.clear();
}

void Lowerer::ensure_operation(SourceLoc loc) {
  if (!op_open_) open_operation(std::string(), loc);
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

// Motion before any tool is loaded, in a file that loads tools: the machine would cut with
// whatever tool is in the spindle, without its length offset. (Files that load no tool at all
// are programs for the tool already there.)
void Lowerer::check_tool_loaded(SourceLoc loc) {
  if (tool_ >= 0 || info_.tools.empty() || reported_no_tool_) return;
  reported_no_tool_ = true;
  const ir::ToolInfo& first = info_.tools.front();
  d_.error(loc, "motion before any tool is loaded; the file loads T" + std::to_string(first.number) +
                    (first.first_use.valid() ? " at line " + std::to_string(first.first_use.line) : std::string()) +
                    " later");
}

}  // namespace clpc
