// The list of passes. Explicit rather than self-registering so the linker cannot drop one.
#include <deque>

#include "passes/passes.h"

namespace clpc {

const std::vector<PassInfo>& all_passes() {
  static const std::vector<PassInfo> passes = {arc_direction_pass(), helix_pass(),        arc_legalise_pass(),
                                               drill_cycles_pass(),  rapid_split_pass(),   thread_cycles_pass(), rough_cycles_pass(), groove_cycles_pass(), offset_table_pass(),
                                               kinematics_pass(),    limits_pass()};
  return passes;
}

namespace {
std::deque<PassInfo>& extra_passes() {  // a deque: find_pass's pointers stay valid
  static std::deque<PassInfo> extra;
  return extra;
}
}  // namespace

const PassInfo* find_pass(std::string_view name) {
  for (const PassInfo& p : all_passes())
    if (p.name == name) return &p;
  for (const PassInfo& p : extra_passes())
    if (p.name == name) return &p;
  return nullptr;
}

void register_extra_pass(const PassInfo& p) {
  if (!find_pass(p.name)) extra_passes().push_back(p);
}

ir::PassContracts pass_contracts() {
  ir::PassContracts c;
  for (const PassInfo& p : all_passes()) c.push_back({std::string(p.name), p.needs, p.provides, p.breaks});
  return c;
}

}  // namespace clpc
