// The compile pipeline behind the command line: pre-scan, lowering, passes and a backend,
// one operation at a time, into an atomically replaced output file.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "driver/pipeline.h"
#include "ir/ir.h"
#include "lower/lower.h"
#include "machine/machine.h"
#include "readback/verify.h"

namespace clpc {

// Check: everything a G-code compile does (the backend included, with its checks), the
// program dropped: `clpc check -t`. Nothing: the front end and the passes only.
enum class Emit { Gcode, Ir, Check, Nothing };

struct CompileOptions {
  Emit emit = Emit::Gcode;
  bool werror = false;
  std::string print_after;  // pass name, "lower" or "all"
  bool verify_ir = false;
  std::optional<ir::Units> input_units;
  bool progress = false;  // a progress bar on a terminal's standard error, for large inputs
  bool latin1 = false;    // --input-encoding latin1: comments and text in Latin-1
  bool force_family = false;  // --force-family: post lathe data for a mill, or mill data for a lathe
  std::vector<std::string> no_warnings;  // -Wno-NAME: warnings not given
  bool say_replaced = false;  // a note when the output replaces an earlier program (clpc compile)
  LowerOptions lower;     // how long operations are cut into chunks (tests make them short)
  Schedule schedule = Schedule::Threaded;
  // Certify the program before it is put in place (clpc compile, unless --no-verify): read it
  // back and compare it with the CL (driver/certify.h); a program that fails is not written.
  bool certify = false;
  double tolerance = 0;          // the certificate's; 0: the machine's default
  double axis_tolerance = 0.01;  // degrees
  bool certificate_json = false; // the whole report as JSON on `err` instead of the one line
  // The certificate also times the program with the machine's accelerations (the JSON report
  // has it; the one line does not show it, so a plain compile leaves the planner out).
  bool certificate_cycle_time = false;
};

struct CompileResult {
  bool ok = false;
  size_t errors = 0, warnings = 0;
  long blocks = 0;
  ir::ProgramInfo info;  // the program-wide tables, as the passes left them (tools, offsets)
  std::optional<VerifyReport> certificate;  // when certified
};

// Compiles `input` ("-" = stdin) for `machine` into `output` ("-" = stdout). Diagnostics go
// to `err`. The output file is only created (renamed into place) on success.
// The line clpc compile ends with when there were errors or warnings ("clpc: 2 errors, 1
// warning\n"); "" when there were none.
std::string totals_line(size_t errors, size_t warnings);

CompileResult compile_file(const std::string& input, const std::string& output, const Machine& machine,
                           const CompileOptions& opt, std::ostream& err);

// The same for an input already open (it is read twice: pre-scan, then compile).
class SourceFile;
CompileResult compile_source(SourceFile& src, const std::string& output, const Machine& machine, const CompileOptions& opt,
                             std::ostream& err);

// The default output name: the input's name with the machine's extension.
std::string default_output(const std::string& input, const Machine& machine);

}  // namespace clpc
