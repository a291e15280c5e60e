// The pre-scan: program-wide facts gathered before any output is written (the tool list for
// the header, the units, the part name). It reads only the records it needs; everything else
// is skipped without being tokenised (grammar/parse.h prescan_cl).
#pragma once

#include <optional>

#include "ir/ir.h"
#include "support/source.h"

namespace clpc {

struct PrescanOptions {
  std::optional<ir::Units> units;  // --input-units: overrides UNITS and the guess
};

ir::ProgramInfo prescan_program(SourceFile& src, const PrescanOptions& opt = {});

// Shared with lowering so both read tool records the same way.
struct ToolRecord {
  int number = -1;          // -1: none given
  int length_offset = 0;
  double length = 0;        // LENGTH,l: the tool's gauge length (0: not given)
  bool preselect = false;   // SELECT/TOOL: names the next tool, does not load it
};
struct ToolGeometry {
  std::string kind;
  double diameter = 0, corner_radius = 0, length = 0;
  bool any = false;
  SourceLoc loc;  // the record that gave it
};

}  // namespace clpc
