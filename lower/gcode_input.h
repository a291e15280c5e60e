// A G-code program given where CL data is due (part.nc or part.tap instead of part.cls): the
// commonest wrong input of a post. Without this the user would get an error at the first '%'
// or '!' and a warning for every block; with it, one error that says what the file is.
#pragma once

#include <optional>
#include <string>

#include "support/source.h"

namespace clpc {

struct GcodeInput {
  SourceLoc loc;      // the first block that is G-code
  std::string block;  // its text (for the message)
};

// The first kilobytes of `src` read as G-code blocks (N.. G.. X.., %, O1234) and not one CL
// record (a MAJOR/ word, a $$ comment, PARTNO, FINI, ...): the file is a program, not CL data.
// Three blocks at least, among the first 200 lines that say anything.
std::optional<GcodeInput> gcode_program_given(const SourceFile& src);

}  // namespace clpc
