// clpc verify's comparison: the CL path (lowered, arcs decided, cycles made holes: the
// reference pipeline) against the program read back (readback/program_reader.h). The driver
// compiles the program and runs the reference pipeline with this comparison as its sink
// (driver/readback_commands.h).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <memory>

#include "ir/sink.h"
#include "readback/program_reader.h"
#include "support/diagnostics.h"
#include "machine/machine.h"

namespace clpc {

struct VerifyProblem {
  SourceLoc loc;
  int gcode_line = 0;
  std::string message;
  double deviation = 0;
};

// One operation (TOOL PATH, FEATNO) of the CL, as checked.
struct OperationCheck {
  uint32_t number = 0;
  std::string name;
  int tool = 0;
  SourceLoc loc;
  long points = 0, arcs = 0, holes = 0, groove_points = 0, problems = 0;
  double max_deviation = 0;
  SourceLoc max_loc;
  int max_gcode_line = 0;
};

// A CL point and how far the program passed from it (for the report's deviation map).
struct DeviationSample {
  ir::Vec3 point;
  double deviation = 0;
};

struct VerifyReport {
  std::string input, machine;
  ir::Units units = ir::Units::Mm;
  bool five_axis = false;
  double tolerance = 0, axis_tolerance = 0;
  bool compiled = false;
  bool ok = false;
  bool written = true;  // the files asked for (-o, --report) were written (or none was asked)
  double max_deviation = 0;  // output units
  SourceLoc max_loc;
  int max_gcode_line = 0;
  double max_axis_deviation = 0;  // degrees
  SourceLoc max_axis_loc;
  int max_axis_gcode_line = 0;
  // Arcs whose CAM-system convention the CL's own geometry contradicts (a tangent move into
  // the arc runs against it): the convention is followed, the report says so.
  long ambiguous_arcs = 0;
  SourceLoc ambiguous_loc;
  long cl_points = 0, cl_arcs = 0, cl_holes = 0, cl_groove_points = 0, cl_thread_cuts = 0;
  ProgramTotals program;
  long problem_count = 0;
  std::vector<VerifyProblem> problems;  // the first ones
  std::vector<OperationCheck> operations;
  // With collect_samples set before the check: the CL points and their deviations, thinned to
  // at most kMaxSamples (every 2nd, 4th, ... once there are more) so memory stays bounded.
  bool collect_samples = false;
  std::vector<DeviationSample> samples;
  size_t sample_stride = 1;
  static constexpr size_t kMaxSamples = 100000;
};

// The comparison, as the sink of the reference pipeline: each CL operation against the
// program `rd` reads. `rep` has the tolerances; problems are reported on `d` (with the CL
// record's source line) and in `rep`.
std::unique_ptr<ProgramSink> make_comparison(const Machine& m, const ir::ProgramInfo& info, ProgramReader& rd, Diagnostics& d,
                                             VerifyReport& rep);

void print_report(std::ostream& out, const VerifyReport& r);
void print_report_json(std::ostream& out, const VerifyReport& r);

// The default tolerance: what linearisation may leave plus what rounding to the output
// resolution may add.
double default_tolerance(const Machine& m);

}  // namespace clpc
