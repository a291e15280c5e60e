// How frame and work-offset records read, shared by the pre-scan and lowering.
#pragma once

#include "grammar/record.h"
#include "support/diagnostics.h"
#include "ir/ir.h"

namespace clpc {

// MSYS/origin,x,y (9 values), CSYS/12, $$-> CSYS/12, CAMERA/12 (3x4 by rows). False (and,
// with `d`, an error) when the record is not a valid right-handed orthonormal frame.
bool read_frame(const Record& r, Diagnostics* d, ir::Frame& f, ir::FrameSource& source);

// SET/word,n: the register number n; 0 for SET/MODE,ABSOL; -1 on error (reported with `d`).
int read_set_register(const Record& r, Diagnostics* d);

}  // namespace clpc
