// IR invariants, checked between passes with --verify-ir (and always in the tests): those of
// every IR, and those of each fact (ir/stage.h) the passes so far have established.
#pragma once

#include <string_view>

#include "support/diagnostics.h"
#include "ir/ir.h"
#include "ir/stage.h"

namespace clpc {

// Reports each broken invariant as an internal error naming the pass that ran last.
bool verify_operation(const ir::Operation& op, std::string_view after_pass, ir::Facts established, Diagnostics& d);

}  // namespace clpc
