// The list of passes. Explicit rather than self-registering so the linker cannot drop one.
#include "passes/passes.h"

namespace clpc {

const std::vector<PassInfo>& all_passes() {
  static const std::vector<PassInfo> passes = {arc_direction_pass(), helix_pass(),        arc_legalise_pass(),
                                               drill_cycles_pass(),  groove_cycles_pass(), offset_table_pass(),
                                               kinematics_pass(),    limits_pass()};
  return passes;
}

const PassInfo* find_pass(std::string_view name) {
  for (const PassInfo& p : all_passes())
    if (p.name == name) return &p;
  return nullptr;
}

ir::PassContracts pass_contracts() {
  ir::PassContracts c;
  for (const PassInfo& p : all_passes()) c.push_back({std::string(p.name), p.needs, p.provides, p.breaks});
  return c;
}

std::vector<std::string> reference_passes(const std::vector<std::string>& pipeline) {
  std::vector<std::string> out;
  for (const std::string& n : pipeline)
    if (const PassInfo* p = find_pass(n); p && p->reference) out.push_back(n);
  return out;
}

}  // namespace clpc
