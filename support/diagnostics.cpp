#include "support/diagnostics.h"

#include <stdexcept>

namespace clpc {

namespace {

const char* severity_name(Severity s) {
  switch (s) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "error";
}

// The source line as shown under a diagnostic: tabs become one space (so the caret lines
// up with the byte column) and unprintable bytes become '?'.
std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (unsigned char c : s) out.push_back(c == '\t' ? ' ' : (c < 0x20 || c >= 0x7f) ? '?' : char(c));
  return out;
}

}  // namespace

const std::vector<WarningName>& warning_names() {
  static const std::vector<WarningName> names = {
      {"after-fini", "records after FINI, which are ignored"},
      {"approach", "a tool's first move a cut, with no FROM or rapid to say where it starts"},
      {"arc-geometry", "an arc whose neighbouring moves say it turns the other way than the CL says"},
      {"coolant", "a COOLNT record that says nothing, or a coolant the machine has no code for"},
      {"empty-record", "a FEDRAT, SPINDL, DELAY, AUXFUN, PREFUN, TLDATA, CUTTER or UNITS with nothing after it"},
      {"cycle", "a CYCLE record's degenerate but real cases: no holes, zero depth, no clearance, no CYCLE/OFF"},
      {"data-comment", "a Creo $$-> data comment that cannot be read"},
      {"feed-unit", "a FEDRAT without a unit word after one per revolution (kept) or in inverse time (per minute)"},
      {"frame", "the first MSYS, taken as the part's setup, turned from the absolute frame a later MSYS is square to"},
      {"force-family", "lathe data posted for a mill, or mill data for a lathe (--force-family)"},
      {"groove", "a groove cycle's cases (no CYCLE/OFF, a groove not collapsed)"},
      {"ignored-word", "a word of a PREFUN, AUXFUN (after its code) or CUTCOM, not read"},
      {"feed-clamped", "a feed above the machine's max_feed: per minute written as max_feed, per revolution said"},
      {"insert", "an INSERT that is no block the control reads, written as a comment; one with axis words, not checked"},
      {"invalid-utf8", "a byte of a one-byte code page in a comment or text"},
      {"machine-code", "an optional stop the machine has no code for, not written"},
      {"malformed-record", "a record that only names or describes (PAINT, INTOL, TOOLNO, ...) written wrong, skipped"},
      {"motion-before-tool", "a rapid before the first tool change, taken as the start point"},
      {"not-a-record", "a line that is no CL record, skipped"},
      {"not-supported", "a record none of clpc's machines can act on"},
      {"rapid-arc", "RAPID before an arc, which is cut at the feed rate"},
      {"rapid-cancelled", "FEDRAT between RAPID and its move: the move is fed"},
      {"rapid-points", "RAPID before a GOTO of several points: only its first point is rapid"},
      {"retract-rotate", "the rotaries jump: the tool retracts, they turn, it re-engages"},
      {"unwind", "a winding rotary would pass its range: the tool retracts, it unwinds, the tool re-engages"},
      {"rotary-index", "a rotary table sent to 0 on a machine without one"},
      {"seed-macro", "the seed paper's G65 macro computing an offset for other angles than the rotaries go to"},
      {"setup", "an operation cut in a setup of its own, after an operator stop"},
      {"spindle-clamp", "constant surface speed without MAXRPM, or with one above the machine's limit: clamped at that limit"},
      {"spindle-orientation", "SPINDL/PARLEL or PERPTO, ignored"},
      {"spindle-stopped", "a cutting move or an arc with the spindle stopped (a hole drilled so is an error)"},
      {"spindle-restart", "the CL gives no SPINDL after a tool change: the spindle M06 stopped is started again at the CL's last speed"},
      {"subroutine", "INDEX and DEFSUB blocks that end or redefine others"},
      {"tool-geometry", "a tool number given another diameter than before (the tool list keeps the first), or a corner radius beyond the radius"},
      {"tool-offset", "a number read as a corrector (TURRET/5,12), or a CUTCOM register the machine's G41 has no place for"},
      {"tool-by-name", "an operation that names a tool without loading it by number"},
      {"tool-number", "a tool loaded as number 0 (not numbered in the CAM system), with its length register"},
      {"toolno", "a TOOLNO naming another tool than the one loaded, with no LOADTL or TURRET after it before the next move"},
      {"unknown-record", "a record without motion that clpc does not know, passed through as a comment"},
      {"units", "units not given, or numbers that look like the other unit"},
  };
  return names;
}

bool is_warning_name(std::string_view name) {
  for (const WarningName& w : warning_names())
    if (name == w.name) return true;
  return false;
}

void Diagnostics::text(std::string_view s) {
  if (deferred_on_) {
    Deferred d{Severity::Note, {}, std::string(s), {}, {}};
    d.text = true;
    deferred_.push_back(std::move(d));
    return;
  }
  if (!out_) return;
  if (before_print_) before_print_();
  *out_ << s;
}

void Diagnostics::replay(const Deferred& d) {
  if (d.text) text(d.message);
  else if (d.severity == Severity::Warning) warning(d.loc, d.message, d.name, d.detail);
  else report(d.severity, d.loc, d.message);
}

void Diagnostics::warning(SourceLoc loc, std::string_view msg, std::string_view name, std::string_view detail) {
  if (!is_warning_name(name)) throw std::logic_error("warning without a name of warning_names(): " + std::string(name));
  if (disabled_.count(name)) return;
  if (deferred_on_) {
    deferred_.push_back({Severity::Warning, loc, std::string(msg), std::string(name), std::string(detail)});
    notes_for_context();
    return;
  }
  if (!werror_) {
    std::string group = std::string(name) + (detail.empty() ? "" : " ") + std::string(detail);
    auto it = repeats_.find(group);
    if (it == repeats_.end()) {
      it = repeats_.emplace(group, 0).first;
      repeat_names_.emplace(group, std::string(name));
    }
    if (++it->second > kRepeatLimit) {
      ++warnings_;
      return;
    }
  }
  report_named(Severity::Warning, loc, msg, name);
  notes_for_context();
}

void Diagnostics::notes_for_context() {
  for (auto it = context_.rbegin(); it != context_.rend(); ++it)
    report(Severity::Note, it->call, it->what + " line " + std::to_string(it->call.line));
}

void Diagnostics::report(Severity sev, SourceLoc loc, std::string_view msg) {
  report_named(sev, loc, msg, {});
  if (sev == Severity::Error) notes_for_context();
}

void Diagnostics::report_named(Severity sev, SourceLoc loc, std::string_view msg, std::string_view name) {
  if (deferred_on_) {
    if (sev != Severity::Warning) deferred_.push_back({sev, loc, std::string(msg), {}, {}});
    if (sev == Severity::Error && ++deferred_errors_ >= kErrorLimit) throw FatalError{};
    return;
  }
  std::string file = source_ ? source_->name() : std::string("<input>");
  std::string text;
  bool have = false;
  if (source_ && loc.valid()) {
    text = source_->line_text(loc.line);
    have = true;
  }
  emit(sev, file, loc, msg, text, have, name);
}

void Diagnostics::report_in(Severity sev, std::string_view file, SourceLoc loc,
                            std::string_view msg, std::string_view line_text) {
  emit(sev, file, loc, msg, line_text, !line_text.empty());
}

void Diagnostics::emit(Severity sev, std::string_view file, SourceLoc loc, std::string_view msg,
                       std::string_view line_text, bool have_line_text, std::string_view name) {
  std::string message(msg);
  std::string tag;  // printed after the message: which warning, how to silence it
  if (sev == Severity::Warning && werror_) {
    sev = Severity::Error;
    tag = name.empty() ? " [-Werror]" : " [-Werror,-W" + std::string(name) + "]";
  } else if (sev == Severity::Warning && !name.empty()) {
    tag = " [-W" + std::string(name) + "]";
  }
  if (sev == Severity::Error) ++errors_;
  if (sev == Severity::Warning) ++warnings_;
  if (keep_) kept_.push_back({sev, std::string(file), loc, message, std::string(name)});
  if (out_) {
    if (before_print_) before_print_();
    std::ostream& o = *out_;
    o << file;
    if (loc.valid()) o << ':' << loc.line << ':' << loc.col;
    o << ": " << severity_name(sev) << ": " << message << tag << '\n';
    if (have_line_text && loc.valid()) {
      std::string num = std::to_string(loc.line);
      o << ' ' << num << " | " << printable(line_text) << '\n';
      o << ' ' << std::string(num.size(), ' ') << " | ";
      if (loc.col > 0) o << std::string(std::min<size_t>(loc.col - 1, line_text.size()), ' ');
      o << "^\n";
    }
  }
  if (sev == Severity::Error && errors_ >= kErrorLimit) {
    if (out_) *out_ << file << ": fatal: too many errors (" << kErrorLimit << "), stopping\n";
    throw FatalError{};
  }
}

void Diagnostics::finish() {
  if (!out_) return;
  for (auto& [group, n] : repeats_)
    if (n > kRepeatLimit)
      *out_ << (source_ ? source_->name() : std::string("<input>")) << ": note: " << (n - kRepeatLimit) << " more warning"
            << (n - kRepeatLimit == 1 ? "" : "s") << " like these not shown (" << group << "; -Wno-" << repeat_names_[group]
            << " silences them)\n";
}

}  // namespace clpc
