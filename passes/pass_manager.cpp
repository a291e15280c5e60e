#include "passes/pass_manager.h"

#include "backends/format.h"
#include "ir/printer.h"
#include "ir/verify.h"

namespace clpc {

double PassContext::resolution() const {
  const AddressFormat& f = machine.format('X');
  double inc = dequantize(1, f);  // one increment, output units (scale folded in)
  if (inc <= 0) inc = 1e-4;
  return std::abs(inc) * from_output();
}

PassManager::PassManager(PassContext& ctx, const std::vector<std::string>& pipeline, std::string print_after,
                         std::ostream* print_to, bool verify)
    : ctx_(ctx), print_after_(std::move(print_after)), print_to_(print_to), verify_(verify) {
  for (const std::string& n : pipeline)
    if (const PassInfo* p = find_pass(n)) passes_.emplace_back(p, p->make());
}

KinematicsSettings PassContext::kinematics() const {
  KinematicsSettings k = machine.kinematics;
  const double f = from_output();
  for (RotaryAxis& r : k.rotaries) r.center *= f;
  k.pivot *= f;
  k.retract_distance *= f;
  return k;
}

size_t PassManager::split_point() const {
  for (size_t i = 0; i < passes_.size(); ++i)
    if (passes_[i].first->name == "kinematics") return i + 1;
  return passes_.size();
}

void PassManager::begin() {
  for (auto& [info, pass] : passes_) pass->begin(ctx_);
}

void PassManager::run(ir::Operation& op) { run(op, 0, passes_.size(), ctx_); }

void PassManager::run(ir::Operation& op, size_t from, size_t to, PassContext& ctx) {
  if (from == 0 && print_to_ && print_after_ == "lower") {
    *print_to_ << "; after lower\n";
    ir::print_operation(*print_to_, op);
  }
  for (size_t i = from; i < to && i < passes_.size(); ++i) {
    auto& [info, pass] = passes_[i];
    pass->run(op, ctx);
    if (verify_) verify_operation(op, info->name, ctx.diags);
    if (print_to_ && (print_after_ == info->name || print_after_ == "all")) {
      *print_to_ << "; after " << info->name << "\n";
      ir::print_operation(*print_to_, op);
    }
  }
}

}  // namespace clpc
