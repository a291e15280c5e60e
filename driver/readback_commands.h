// The commands that compile a program to read it back: clpc verify and clpc plot. Each
// compiles the CL file (or takes a program given), then reads the program back: verify runs
// the reference pipeline (the passes that give the CL its meaning) with the comparison as its
// sink; plot draws it.
#pragma once

#include <ostream>
#include <string>

#include "driver/driver.h"
#include "readback/plot.h"
#include "readback/verify.h"
#include "machine/machine.h"
#include "support/output.h"

namespace clpc {

// A temporary file for a program clpc compiles only to read back, removed with this object.
class TempProgram {
 public:
  TempProgram();
  ~TempProgram();
  TempProgram(const TempProgram&) = delete;
  TempProgram& operator=(const TempProgram&) = delete;
  const std::string& path() const { return path_; }  // empty if none could be made

 private:
  std::string path_;
};

// The program to read back: `input` compiled for `m` into `keep` (or a temporary file), or,
// with `given`, that program instead (clpc's compile still gives the tables). False, with the
// reason on `err`, when the input cannot be read or does not compile.
struct CompiledProgram {
  SourceFile source;
  TempProgram temp;
  CompileResult compiled;
  std::string path;  // the program to read
};
bool compile_for_readback(const std::string& input, const Machine& m, CompileOptions opt, const std::string& keep,
                          const std::string& given, std::ostream& err, CompiledProgram& out);

struct VerifyOptions {
  double tolerance = 0;          // output units; 0: the machine's arcs.tolerance + one output increment
  double axis_tolerance = 0.01;  // degrees, tool axis (five-axis)
  CompileOptions compile;
  std::string keep;              // also write the program here (empty: a temporary file)
  std::string program;           // check this program (say, edited by hand) instead of clpc's
  std::string report;            // also write the HTML report here (readback/report_html.h)
};

// Compiles `input` for `m`, reads the program back and compares. Problems are reported as
// diagnostics on `err` (with the CL record's source line) and in the report.
VerifyReport verify_file(const std::string& input, const Machine& m, const VerifyOptions& opt, std::ostream& err);

// Copies the file `from` into `out`, opened by the caller (an OutputFile: "-" is standard
// output), and commits it; false, with the error said, where it cannot.
bool copy_out(const std::string& from, OutputFile& out, std::ostream& err);

// The HTML report of a verification (readback/report_html.h), with the program's backplot,
// written into `out`, opened by the caller, and committed.
bool write_report(OutputFile& out, const VerifyReport& rep, const CompiledProgram& cp, const Machine& m,
                  std::ostream& err);

struct PlotFileOptions {
  CompileOptions compile;
  std::string program;  // plot this program instead of compiling one
  PlotOptions plot;
};

// Compiles `input` for `m` (or takes opt.program) and writes the SVG to `output` ("-" =
// standard output), atomically.
PlotResult plot_file(const std::string& input, const std::string& output, const Machine& m, const PlotFileOptions& opt,
                     std::ostream& err);

}  // namespace clpc
