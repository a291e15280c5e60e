// Compiler-style diagnostics: "file:line:col: error: message", the source line, a caret.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <ostream>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "support/source.h"

namespace clpc {

enum class Severity { Note, Warning, Error };

struct Diagnostic {
  Severity severity;
  std::string file;
  SourceLoc loc;
  std::string message;
  std::string name;  // a warning's name (-Wname), "" for errors and notes
};

// Every warning has a name, to silence it alone (-Wno-NAME) or to look it up (docs).
struct WarningName {
  const char* name;
  const char* summary;
};
const std::vector<WarningName>& warning_names();
bool is_warning_name(std::string_view name);

// Thrown when a run must stop at once (too many errors). Caught by the driver.
struct FatalError {};

class Diagnostics {
 public:
  explicit Diagnostics(std::ostream* out) : out_(out) {}

  // Diagnostics without an explicit file name refer to this source.
  void set_source(const SourceFile* src) { source_ = src; }
  const SourceFile* source() const { return source_; }
  void set_werror(bool on) { werror_ = on; }
  // Keep every diagnostic in `all()` (tests); printing still happens when out != nullptr.
  void set_keep(bool on) { keep_ = on; }
  // Deferred: diagnostics are recorded (with their category) instead of printed or counted
  // against the limits, to be replayed in order into another Diagnostics — the compile's front
  // end runs on its own thread, and its diagnostics must come out where a one-thread compile
  // would print them. Past kErrorLimit recorded errors the run stops (FatalError) all the same.
  struct Deferred {
    Severity severity;
    SourceLoc loc;
    std::string message;
    std::string name;
    std::string detail;
    bool text = false;  // a line of text() rather than a diagnostic
  };
  void set_deferred(bool on) { deferred_on_ = on; }
  std::vector<Deferred> take_deferred() { return std::move(deferred_); }
  void replay(const Deferred& d);

  // Called before each diagnostic is printed (a progress bar clears its line).
  void set_before_print(std::function<void()> f) { before_print_ = std::move(f); }

  void error(SourceLoc loc, std::string_view msg) { report(Severity::Error, loc, msg); }
  // `name` is one of warning_names() (printed as [-Wname]); `name` and `detail` together group
  // repeated warnings: after kRepeatLimit of one group the rest are counted, not printed, so a
  // million-line file cannot bury the first ones.
  void warning(SourceLoc loc, std::string_view msg, std::string_view name, std::string_view detail = {});
  void disable(std::string_view name) { disabled_.emplace(name); }
  // While a subroutine is played (CALSUB), each diagnostic is followed by a note naming the
  // call: "called from line N". Calls nest.
  void push_context(SourceLoc call, std::string what) { context_.push_back({call, std::move(what)}); }
  void pop_context() { context_.pop_back(); }
  void note(SourceLoc loc, std::string_view msg) { report(Severity::Note, loc, msg); }
  // Text that must keep its place among the diagnostics (the IR printed after a pass): written
  // to the stream as it is, or, deferred, replayed in order with them.
  void text(std::string_view s);
  void report(Severity sev, SourceLoc loc, std::string_view msg);
  // A diagnostic about another file (e.g. a machine description): file:line:col given.
  void report_in(Severity sev, std::string_view file, SourceLoc loc, std::string_view msg,
                 std::string_view line_text = {});

  size_t error_count() const { return errors_; }
  size_t warning_count() const { return warnings_; }
  bool has_errors() const { return errors_ != 0; }
  const std::vector<Diagnostic>& all() const { return kept_; }
  // Prints the "N warnings suppressed" summary lines; call once at the end of a run.
  void finish();

  static constexpr size_t kErrorLimit = 50;
  static constexpr size_t kRepeatLimit = 3;

 private:
  void emit(Severity sev, std::string_view file, SourceLoc loc, std::string_view msg,
            std::string_view line_text, bool have_line_text, std::string_view name = {});
  void report_named(Severity sev, SourceLoc loc, std::string_view msg, std::string_view name);
  void notes_for_context();

  std::ostream* out_;
  const SourceFile* source_ = nullptr;
  bool werror_ = false;
  bool keep_ = false;
  size_t errors_ = 0;
  size_t warnings_ = 0;
  std::map<std::string, size_t, std::less<>> repeats_;
  std::map<std::string, std::string, std::less<>> repeat_names_;  // group -> warning name
  std::set<std::string, std::less<>> disabled_;
  struct Context {
    SourceLoc call;
    std::string what;
  };
  std::vector<Context> context_;
  std::vector<Diagnostic> kept_;
  std::function<void()> before_print_;
  bool deferred_on_ = false;
  size_t deferred_errors_ = 0;
  std::vector<Deferred> deferred_;
};

}  // namespace clpc
