// Factories of every pass (registered in passes/registry.cpp).
#pragma once

#include <memory>

#include "passes/pass.h"

namespace clpc {

std::unique_ptr<Pass> make_arc_direction();
std::unique_ptr<Pass> make_helix();
std::unique_ptr<Pass> make_arc_legalise();
std::unique_ptr<Pass> make_drill_cycles();
std::unique_ptr<Pass> make_groove_cycles();
std::unique_ptr<Pass> make_offset_table();
std::unique_ptr<Pass> make_kinematics();
std::unique_ptr<Pass> make_limits();

}  // namespace clpc
