// clpc verify: compile, read the program back, and compare the tool's path with the CL path.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "backends/machine.h"
#include "cli/driver.h"
#include "cli/readback.h"

namespace clpc {

struct VerifyOptions {
  double tolerance = 0;          // output units; 0: the machine's arcs.tolerance + one output increment
  double axis_tolerance = 0.01;  // degrees, tool axis (five-axis)
  CompileOptions compile;
  std::string keep;              // also write the program here (empty: a temporary file)
  std::string program;           // check this program (say, edited by hand) instead of clpc's
  bool progress = false;         // a progress bar on standard error
};

struct VerifyProblem {
  SourceLoc loc;
  int gcode_line = 0;
  std::string message;
  double deviation = 0;
};

struct VerifyReport {
  std::string input, machine;
  ir::Units units = ir::Units::Mm;
  bool five_axis = false;
  double tolerance = 0, axis_tolerance = 0;
  bool compiled = false;
  bool ok = false;
  double max_deviation = 0;  // output units
  SourceLoc max_loc;
  int max_gcode_line = 0;
  double max_axis_deviation = 0;  // degrees
  long cl_points = 0, cl_arcs = 0, cl_holes = 0, cl_groove_points = 0;
  ProgramTotals program;
  long problem_count = 0;
  std::vector<VerifyProblem> problems;  // the first ones
};

// Compiles `input` for `m`, reads the program back and compares. Problems are reported as
// diagnostics on `err` (with the CL record's source line) and in the report.
VerifyReport verify_file(const std::string& input, const Machine& m, const VerifyOptions& opt, std::ostream& err);

void print_report(std::ostream& out, const VerifyReport& r);
void print_report_json(std::ostream& out, const VerifyReport& r);

// The default tolerance: what linearisation may leave plus what rounding to the output
// resolution may add.
double default_tolerance(const Machine& m);

}  // namespace clpc
