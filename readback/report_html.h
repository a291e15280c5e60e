// clpc verify --report FILE.html: the report as one self-contained page — the summary, a
// table of the CL's operations (points, arcs and holes checked, the largest deviation of each,
// coloured against the tolerance, with its CL and G-code lines), the problems, the backplot
// (clpc plot's SVG) and a map of the CL points coloured by how far the program passed from
// them. No scripts, no files beside it: it opens anywhere.
#pragma once

#include <ostream>
#include <string>

#include "readback/verify.h"

namespace clpc {

void write_report_html(std::ostream& o, const VerifyReport& r, const std::string& backplot_svg);

}  // namespace clpc
