// How tool records read, shared by the pre-scan (lower/prescan.cpp) and lowering so both agree.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "grammar/record.h"
#include "support/diagnostics.h"
#include "ir/ir.h"
#include "lower/prescan.h"

namespace clpc {

// TOOL PATH/op,TOOL,name -> name ("" when absent).
std::string tool_name_of_tool_path(const Record& r);
// LOADTL/n[,OSETNO,h][,LENGTH,l], LOAD/TOOL,n[,ADJUST,h], TURRET/n, SELECT/TOOL,n.
// With `d`, problems are reported; number stays -1 when the record names no tool.
ToolRecord read_tool_record(const Record& r, Diagnostics* d);
// TLDATA/kind,d,r,l,... and CUTTER/d[,r,...] ($$-> CUTTER/d in Creo).
ToolGeometry read_tool_geometry(const Record& r, Diagnostics* d);
// MM, MILLIMETERS, INCHES, INCH ...
std::optional<ir::Units> units_word(std::string_view w);

}  // namespace clpc
