// The compile pipeline behind the command line: pre-scan, lowering, passes and a backend,
// one operation at a time, into an atomically replaced output file.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "backends/machine.h"
#include "ir/ir.h"
#include "ir/lower.h"

namespace clpc {

enum class Emit { Gcode, Ir, Nothing };

struct CompileOptions {
  Emit emit = Emit::Gcode;
  bool werror = false;
  std::string print_after;  // pass name, "lower" or "all"
  bool verify_ir = false;
  std::optional<ir::Units> input_units;
  bool progress = false;  // a progress bar on a terminal's standard error, for large inputs
  bool latin1 = false;    // --input-encoding latin1: comments and text in Latin-1
  LowerOptions lower;     // how long operations are cut into chunks (tests make them short)
};

struct CompileResult {
  bool ok = false;
  size_t errors = 0, warnings = 0;
  long blocks = 0;
  ir::ProgramInfo info;  // the program-wide tables, as the passes left them (tools, offsets)
};

// Compiles `input` ("-" = stdin) for `machine` into `output` ("-" = stdout). Diagnostics go
// to `err`. The output file is only created (renamed into place) on success.
CompileResult compile_file(const std::string& input, const std::string& output, const Machine& machine,
                           const CompileOptions& opt, std::ostream& err);

// The same for an input already open (it is read twice: pre-scan, then compile).
class SourceFile;
CompileResult compile_source(SourceFile& src, const std::string& output, const Machine& machine, const CompileOptions& opt,
                             std::ostream& err);

// The default output name: the input's name with the machine's extension.
std::string default_output(const std::string& input, const Machine& machine);

}  // namespace clpc
