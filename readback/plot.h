// clpc plot: a backplot of the emitted program in SVG — top, front, side and isometric views
// of the tool tip's path in the part frame, feeds and rapids in their own colours, arcs drawn
// as (elliptical) arcs, tool changes marked.
#pragma once

#include <ostream>
#include <string>

#include "ir/ir.h"
#include "machine/machine.h"

namespace clpc {

struct PlotOptions {
  int width = 1200, height = 900;  // pixels
};

struct PlotResult {
  bool ok = false;
  long feeds = 0, rapids = 0, arcs = 0, tool_changes = 0;
};

// Reads `program` back (compiled from the CL file `input`, whose compile left `info`) and
// writes the SVG to `output` ("-" = standard output), atomically.
PlotResult plot_program(const std::string& program, const std::string& input, const ir::ProgramInfo& info,
                        const std::string& output, const Machine& m, const PlotOptions& opt, std::ostream& err);

}  // namespace clpc
