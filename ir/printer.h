// The IR as text (clpc compile --emit=ir, --print-after=PASS): one line per instruction with
// its source location, stable enough to compare in tests.
#pragma once

#include <ostream>

#include "ir/ir.h"

namespace clpc::ir {

void print_header(std::ostream& o, const ProgramInfo& info);
void print_operation(std::ostream& o, const Operation& op);
void print_instr(std::ostream& o, const Operation& op, const Instr& in);

}  // namespace clpc::ir
