// Every pass's description and factory (each defined at the end of its own file, listed in
// passes/registry.cpp).
#pragma once

#include "passes/pass.h"

namespace clpc {

const PassInfo& arc_direction_pass();
const PassInfo& helix_pass();
const PassInfo& arc_legalise_pass();
const PassInfo& drill_cycles_pass();
const PassInfo& groove_cycles_pass();
const PassInfo& thread_cycles_pass();
const PassInfo& rough_cycles_pass();
const PassInfo& offset_table_pass();
const PassInfo& kinematics_pass();
const PassInfo& limits_pass();
const PassInfo& rapid_split_pass();

}  // namespace clpc
