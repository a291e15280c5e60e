// The options programmers set per job (docs/machines.md, "Per-job options"): the program
// number from the file name, header lines, optional stops, tool preselect, coolant around a
// tool change, the control's smoothing mode and parking at the end. Each is a key of
// [NAME.program], set in the machine or with clpc compile --set / --job.
#include <cctype>
#include <cstdlib>
#include <ctime>

#include "backends/backend.h"
#include "support/text.h"
#include "machine/format.h"

namespace clpc {

namespace {

// The number a CL file's name gives a program: "O1234.cls", "1234.cls", "1234_pocket.cls",
// "o1234 rev B.ncl". The digits must stand alone: "3axis.cls" and "5x_test.cls" are names,
// not numbers. 0 when the name has none.
long number_in_file_name(std::string_view path) {
  if (size_t s = path.find_last_of("/\\"); s != std::string_view::npos) path.remove_prefix(s + 1);
  size_t i = 0;
  if (path.size() > 1 && (path[0] == 'O' || path[0] == 'o') && std::isdigit(static_cast<unsigned char>(path[1]))) i = 1;
  size_t j = i;
  while (j < path.size() && std::isdigit(static_cast<unsigned char>(path[j]))) ++j;
  if (j == i || j - i > 8) return 0;
  if (j < path.size() && path[j] != '.' && path[j] != '_' && path[j] != '-' && path[j] != ' ') return 0;
  return std::strtol(std::string(path.substr(i, j - i)).c_str(), nullptr, 10);
}

// "today": the date the program is written (SOURCE_DATE_EPOCH, when set, for reproducible
// output), as YYYY-MM-DD. Anything else is written as it is.
std::string date_text(const std::string& option) {
  if (option != "today") return option;
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch && *epoch) {
    t = std::time_t(std::strtoll(epoch, nullptr, 10));
    gmtime_r(&t, &tm);
  } else {
    localtime_r(&t, &tm);
  }
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &tm);
  return buf;
}

// `t` less every word that uses `v`: a smoothing code written without a tolerance leaves the
// control's own.
CodeTemplate without(const CodeTemplate& t, Var v) {
  CodeTemplate out;
  out.text = t.text;
  for (const CodeTemplate::Word& w : t.words) {
    bool uses = false;
    for (const CodeTemplate::Piece& p : w) uses = uses || p.var == int(v);
    if (!uses) out.words.push_back(w);
  }
  return out;
}

}  // namespace

long ProgramWriter::program_number(const ir::ProgramInfo& info) const {
  if (m_.program_number <= 0 || !m_.number_from_name) return m_.program_number;
  const long n = number_in_file_name(info.source_name);
  const AddressFormat& f = m_.format('O');
  long most = 99999999;
  if (f.digits > 0 && f.digits < 9) {
    most = 1;
    for (int i = 0; i < f.digits; ++i) most *= 10;
    --most;
  }
  // O8000-O9999 are a Fanuc's (and Haas's) macro programs, often the tool-change macro, kept
  // under a protection switch: a file named 9001_part.cls was numbered O9001 (helper-67).
  if (n >= 8000 && n <= 9999) return m_.program_number;
  return n >= 1 && n <= most ? n : m_.program_number;
}

void ProgramWriter::write_header(const ir::ProgramInfo& info) {
  if (m_.header) {
    e_.comment("MACHINE: " + m_.name + (m_.description.empty() ? "" : " - " + m_.description));
    if (!info.source_name.empty()) {
      std::string base = info.source_name;
      if (size_t s = base.rfind('/'); s != std::string::npos) base = base.substr(s + 1);
      e_.comment("SOURCE: " + base);
    }
  }
  // Asked for by name: written whether or not the machine writes a header.
  if (!m_.date.empty()) e_.comment("DATE: " + date_text(m_.date));
  if (!m_.programmer.empty()) e_.comment("PROGRAMMER: " + m_.programmer);
  if (!m_.stock.empty()) e_.comment("STOCK: " + m_.stock);
  if (m_.header) {
    e_.comment(std::string("UNITS: ") + (m_.units == ir::Units::Inch ? "INCH" : "MM"));
    for (const ir::ToolInfo& t : info.tools) e_.comment(tool_comment(t));
  }
}

void ProgramWriter::write_smoothing(bool on) {
  if (m_.smoothing == 0) return;
  e_.begin({});
  if (!on) {
    e_.code(m_.codes.smoothing_off);
  } else if (m_.smoothing_tolerance > 0) {
    e_.code(m_.codes.smoothing_on,
            TemplateVars().with(Var::Level, m_.smoothing).with(Var::Tolerance, m_.smoothing_tolerance));
  } else {
    e_.code(without(m_.codes.smoothing_on, Var::Tolerance), TemplateVars().with(Var::Level, m_.smoothing));
  }
  e_.end();
  after_template(on ? m_.codes.smoothing_on : m_.codes.smoothing_off);
}

// Called after the retract, before the tool-change block: coolant off (the operator may
// open the door at the M01), then the optional stop.
void ProgramWriter::before_tool_change(SourceLoc loc) {
  if (m_.coolant_around_tool_change && coolant_ != ir::CoolantKind::Off) {
    coolant_after_ = coolant_;
    coolant_restore_ = true;
    write_coolant(ir::Coolant{ir::CoolantKind::Off}, loc);
  }
  // "operation" stops at tool changes too: a tool change starts an operation however the CL
  // marks its operations (a plain APT file marks none).
  if (m_.optional_stop != Machine::OptionalStop::Off && tool_ >= 0 && cut_since_stop_) {
    e_.begin(loc);
    e_.code(m_.codes.optional_stop);
    e_.end();
    control_stopped(true, false);
    cut_since_stop_ = false;
  }
  stop_pending_ = false;
}

void ProgramWriter::optional_stop_between_operations(SourceLoc loc) {
  stop_pending_ = false;
  cancel_cycle(loc);
  end_comp_before_retract(loc, "an optional stop between operations");
  retract_for_stop(loc);
  e_.begin(loc);
  e_.code(m_.codes.optional_stop);
  e_.end();
  control_stopped(true, false);
  cut_since_stop_ = false;
}

// The next tool into the changer's ready position while this one cuts. The T word in the
// tool-change block still says which tool is loaded: a preselect only saves time.
void ProgramWriter::after_tool_change(int tool, SourceLoc loc) {
  comp_register_said_ = 0;
  if (!m_.preselect || !info_ || info_->preselects_given) return;
  const std::vector<int>& seq = info_->tool_changes;
  // The next load of `tool` from where the last change was (a subroutine may repeat loads).
  size_t at = seq.size();
  for (size_t i = tool_change_at_; i < seq.size() && at == seq.size(); ++i)
    if (seq[i] == tool) at = i;
  for (size_t i = 0; i < tool_change_at_ && at == seq.size(); ++i)
    if (seq[i] == tool) at = i;
  if (at == seq.size()) return;
  tool_change_at_ = at;
  if (at + 1 >= seq.size() || seq[at + 1] == tool) return;
  e_.begin(loc);
  e_.code(m_.codes.tool_preselect, TemplateVars().with(Var::Tool, seq[at + 1]));
  e_.end();
}

void ProgramWriter::control_stopped(bool coolant_too, bool tool_change) {
  if (spindle_ != ir::SpindleDir::Off && spindle_on_) {
    spindle_restore_ = true;
    spindle_restore_warn_ = tool_change;
  } else if (tool_change && spindle_restore_) {
    spindle_restore_warn_ = true;  // an M01 before the M06 stopped it first
  }
  spindle_ = ir::SpindleDir::Off;
  if (coolant_too && coolant_ != ir::CoolantKind::Off) {
    coolant_after_ = coolant_;
    coolant_restore_ = true;
    coolant_ = ir::CoolantKind::Off;
  }
}

void ProgramWriter::restore_after_stop(SourceLoc loc, bool cut) {
  // The spindle before the first cut, not before the rapids to it: the CL may start it there
  // (FFCAM writes the SPINDL after the approach), at the new tool's speed.
  if (spindle_restore_ && (cut || spindle_restore_before_move_)) {
    spindle_restore_ = spindle_restore_before_move_ = false;
    if (spindle_restore_warn_)
      d_.warning(loc, "the spindle is started again for T" + std::to_string(tool_) + " as the CL left it running (" +
                          num_text(spindle_on_->speed) + (spindle_on_->mode == ir::SpindleMode::Rpm ? " rpm" : " m/min") +
                          "): the CL gives no SPINDL after the tool change, which stops it",
                 "spindle-restart");
    write_spindle(*spindle_on_, loc);
    tool_turned_ = true;
  }
  restore_coolant(loc);
}

void ProgramWriter::restore_coolant(SourceLoc loc) {
  if (!coolant_restore_) return;
  coolant_restore_ = false;
  write_coolant(ir::Coolant{coolant_after_}, loc);
}

}  // namespace clpc
