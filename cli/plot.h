// clpc plot: a backplot of the emitted program in SVG — top, front, side and isometric views
// of the tool tip's path in the part frame, feeds and rapids in their own colours, arcs drawn
// as (elliptical) arcs, tool changes marked.
#pragma once

#include <ostream>
#include <string>

#include "backends/machine.h"
#include "cli/driver.h"

namespace clpc {

struct PlotOptions {
  CompileOptions compile;
  std::string program;  // plot this program instead of compiling one
  int width = 1200, height = 900;  // pixels
};

struct PlotResult {
  bool ok = false;
  long feeds = 0, rapids = 0, arcs = 0, tool_changes = 0;
};

// Compiles `input` for `m` (or takes opt.program) and writes the SVG to `output` ("-" =
// standard output), atomically.
PlotResult plot_file(const std::string& input, const std::string& output, const Machine& m, const PlotOptions& opt,
                     std::ostream& err);

}  // namespace clpc
