// IR invariants, checked between passes with --verify-ir (and always in the tests).
#pragma once

#include <string_view>

#include "support/diagnostics.h"
#include "ir/ir.h"

namespace clpc {

// Reports each broken invariant as an internal error naming the pass that ran last.
bool verify_operation(const ir::Operation& op, std::string_view after_pass, Diagnostics& d);

}  // namespace clpc
