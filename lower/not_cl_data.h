// Files given where CL data is due that are something else: a G-code program (part.nc or
// part.tap instead of part.cls, the commonest wrong input of a post) or a binary file (a
// binary CLFILE, a CAD file). Without these the user would get an error at the first '%' and a
// warning for every block, or fifty errors about bytes; with them, one error that says what
// the file is.
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

// UTF-16 text (Windows editors save "Unicode" so): its byte-order mark, "FF FE" or "FE FF".
// (UTF-8's mark is read past by the lexer.)
std::optional<std::string> utf16_given(const SourceFile& src);

// A binary file: NUL bytes, at least 16 and one in a thousand of the first 64 KiB (a text file
// with a stray NUL is CL data with an error where the NUL is). The location of the first NUL.
std::optional<SourceLoc> binary_file_given(const SourceFile& src);

}  // namespace clpc
