#include "ir/diagnostics.h"

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

void Diagnostics::replay(const Deferred& d) {
  if (d.severity == Severity::Warning) warning(d.loc, d.message, d.category);
  else report(d.severity, d.loc, d.message);
}

void Diagnostics::warning(SourceLoc loc, std::string_view msg, std::string_view category) {
  if (deferred_on_) {
    deferred_.push_back({Severity::Warning, loc, std::string(msg), std::string(category)});
    return;
  }
  if (!werror_ && !category.empty()) {
    auto it = repeats_.find(category);
    if (it == repeats_.end()) it = repeats_.emplace(std::string(category), 0).first;
    if (++it->second > kRepeatLimit) {
      ++warnings_;
      return;
    }
  }
  report(Severity::Warning, loc, msg);
}

void Diagnostics::report(Severity sev, SourceLoc loc, std::string_view msg) {
  if (deferred_on_) {
    deferred_.push_back({sev, loc, std::string(msg), {}});
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
  emit(sev, file, loc, msg, text, have);
}

void Diagnostics::report_in(Severity sev, std::string_view file, SourceLoc loc,
                            std::string_view msg, std::string_view line_text) {
  emit(sev, file, loc, msg, line_text, !line_text.empty());
}

void Diagnostics::emit(Severity sev, std::string_view file, SourceLoc loc, std::string_view msg,
                       std::string_view line_text, bool have_line_text) {
  std::string message(msg);
  if (sev == Severity::Warning && werror_) {
    sev = Severity::Error;
    message += " [-Werror]";
  }
  if (sev == Severity::Error) ++errors_;
  if (sev == Severity::Warning) ++warnings_;
  if (keep_) kept_.push_back({sev, std::string(file), loc, message});
  if (out_) {
    if (before_print_) before_print_();
    std::ostream& o = *out_;
    o << file;
    if (loc.valid()) o << ':' << loc.line << ':' << loc.col;
    o << ": " << severity_name(sev) << ": " << message << '\n';
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
  for (auto& [cat, n] : repeats_)
    if (n > kRepeatLimit)
      *out_ << (source_ ? source_->name() : std::string("<input>")) << ": note: " << (n - kRepeatLimit)
            << " more warning(s) of this kind not shown: " << cat << '\n';
}

}  // namespace clpc
