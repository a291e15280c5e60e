// The verify report as text (`clpc verify`) and as JSON (`--json`): what was checked, the
// largest deviations and where, the cycle time, and the problems found.
#include <cmath>
#include <cstdio>
#include <ostream>

#include "readback/verify.h"
#include "support/text.h"

namespace clpc {

namespace {

std::string minutes_text(double min) {
  long s = std::lround(min * 60);
  char b[48];
  if (s >= 3600) std::snprintf(b, sizeof b, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else std::snprintf(b, sizeof b, "%ld:%02ld", s / 60, s % 60);
  return b;
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char b[48];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace

void print_report(std::ostream& o, const VerifyReport& r) {
  const char* u = r.units == ir::Units::Inch ? "in" : "mm";
  const int dec = r.units == ir::Units::Inch ? 5 : 4;
  o << "clpc verify: " << r.input << " on " << r.machine << ", tolerance " << fixed_text(r.tolerance, dec) << " " << u;
  if (r.five_axis) o << ", tool axis " << r.axis_tolerance << " deg";
  o << "\n";
  if (!r.compiled) {
    o << "  result: FAIL (the CL file does not compile)\n";
    return;
  }
  const ProgramTotals& p = r.program;
  o << "  CL path:    " << r.cl_points << " points, " << r.cl_arcs << " arcs, " << r.cl_holes << " holes";
  if (r.cl_groove_points) o << ", " << r.cl_groove_points << " groove cuts";
  if (r.cl_thread_cuts) o << ", " << r.cl_thread_cuts << " thread cuts";
  o << "\n";
  o << "  program:    " << p.lines << " lines (" << p.bytes << " bytes), " << p.blocks << " blocks; " << p.rapids << " rapids, "
    << p.feeds << " feeds, " << p.arcs << " arcs, " << p.cycle_holes << " cycles, " << p.tool_changes << " tool changes\n";
  o << "  path:       " << fixed_text(p.feed_length, 1) << " " << u << " cutting, " << fixed_text(p.rapid_length, 1) << " " << u << " rapid\n";
  o << "  cycle time: " << minutes_text(p.total_minutes()) << (p.time_complete() ? "" : "+") << " (cutting "
    << minutes_text(p.feed_minutes) << (p.feed_time_known ? "" : "+, some feeds unknown") << ", rapids "
    << minutes_text(p.rapid_minutes) << (p.rapid_time_known ? "" : "+, rapid rate unknown") << ", dwells "
    << minutes_text(p.dwell_minutes) << ", tool changes " << minutes_text(p.tool_change_minutes)
    << (p.tool_change_time_known ? "" : "+, tool change time unknown") << ")\n";
  if (p.dynamic_known)
    o << "  dynamic:    " << minutes_text(p.dynamic_minutes) << (p.tool_change_time_known ? "" : "+")
      << " (each axis's velocity and acceleration, corners slowed; the cycle time above is its lower bound)\n";
  else
    o << "  dynamic:    unknown (the machine's [motion] table gives no velocities and accelerations)\n";
  o << "  deviation:  max ";
  if (std::isinf(r.max_deviation)) o << "unbounded (a CL point never reached)";
  else o << fixed_text(r.max_deviation, dec) << " " << u;
  if (r.max_loc.valid()) o << " at " << r.input << ":" << r.max_loc.line << ":" << r.max_loc.col;
  if (r.max_gcode_line) o << " (G-code line " << r.max_gcode_line << ")";
  if (r.max_axis_deviation > 0) {
    o << "; tool axis max " << fixed_text(r.max_axis_deviation, 4) << " deg";
    if (r.max_axis_loc.valid()) o << " at " << r.input << ":" << r.max_axis_loc.line << ":" << r.max_axis_loc.col;
    if (r.max_axis_gcode_line) o << " (G-code line " << r.max_axis_gcode_line << ")";
  }
  o << "\n";
  if (r.ambiguous_arcs)
    o << "  CL:         " << r.ambiguous_arcs << " arc" << (r.ambiguous_arcs == 1 ? "" : "s")
      << " where the CAM system's convention and the CL's geometry disagree (first at " << r.input << ":"
      << r.ambiguous_loc.line << "); the convention was followed\n";
  if (r.ok) o << "  result: PASS\n";
  else o << "  result: FAIL (" << r.problem_count << " problem" << (r.problem_count == 1 ? "" : "s") << ")\n";
}

void print_report_json(std::ostream& o, const VerifyReport& r) {
  const ProgramTotals& p = r.program;
  o << "{\n";
  o << "  \"input\": " << json_text(r.input) << ",\n";
  o << "  \"machine\": " << json_text(r.machine) << ",\n";
  o << "  \"units\": \"" << (r.units == ir::Units::Inch ? "inch" : "mm") << "\",\n";
  o << "  \"tolerance\": " << json_number(r.tolerance) << ",\n";
  o << "  \"axis_tolerance_deg\": " << json_number(r.axis_tolerance) << ",\n";
  o << "  \"compiled\": " << (r.compiled ? "true" : "false") << ",\n";
  o << "  \"ok\": " << (r.ok ? "true" : "false") << ",\n";
  o << "  \"max_deviation\": {\"value\": " << json_number(r.max_deviation) << ", \"line\": " << r.max_loc.line
    << ", \"column\": " << r.max_loc.col << ", \"gcode_line\": " << r.max_gcode_line << "},\n";
  o << "  \"max_axis_deviation_deg\": {\"value\": " << json_number(r.max_axis_deviation) << ", \"line\": " << r.max_axis_loc.line
    << ", \"column\": " << r.max_axis_loc.col << ", \"gcode_line\": " << r.max_axis_gcode_line << "},\n";
  o << "  \"ambiguous_arcs\": {\"count\": " << r.ambiguous_arcs << ", \"first_line\": " << r.ambiguous_loc.line << "},\n";
  o << "  \"cl\": {\"points\": " << r.cl_points << ", \"arcs\": " << r.cl_arcs << ", \"holes\": " << r.cl_holes
    << ", \"groove_cuts\": " << r.cl_groove_points << ", \"thread_cuts\": " << r.cl_thread_cuts << "},\n";
  o << "  \"program\": {\"lines\": " << p.lines << ", \"bytes\": " << p.bytes << ", \"blocks\": " << p.blocks
    << ", \"rapids\": " << p.rapids << ", \"feeds\": " << p.feeds << ", \"arcs\": " << p.arcs << ", \"cycles\": " << p.cycle_holes
    << ", \"tool_changes\": " << p.tool_changes << ", \"feed_length\": " << json_number(p.feed_length)
    << ", \"rapid_length\": " << json_number(p.rapid_length) << "},\n";
  o << "  \"cycle_time_s\": {\"total\": " << json_number(p.total_minutes() * 60)
    << ", \"cutting\": " << json_number(p.feed_minutes * 60) << ", \"rapid\": " << json_number(p.rapid_minutes * 60)
    << ", \"dwell\": " << json_number(p.dwell_minutes * 60) << ", \"tool_change\": " << json_number(p.tool_change_minutes * 60)
    << ", \"complete\": " << (p.time_complete() ? "true" : "false")
    << ", \"dynamic\": " << (p.dynamic_known ? json_number(p.dynamic_minutes * 60) : std::string("null")) << "},\n";
  o << "  \"problem_count\": " << r.problem_count << ",\n";
  o << "  \"problems\": [";
  for (size_t i = 0; i < r.problems.size(); ++i) {
    const VerifyProblem& q = r.problems[i];
    o << (i ? ",\n    " : "\n    ") << "{\"line\": " << q.loc.line << ", \"column\": " << q.loc.col << ", \"gcode_line\": " << q.gcode_line
      << ", \"message\": " << json_text(q.message) << ", \"deviation\": " << json_number(q.deviation) << "}";
  }
  o << (r.problems.empty() ? "]\n" : "\n  ]\n") << "}\n";
}

}  // namespace clpc
