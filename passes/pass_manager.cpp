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

void PassManager::begin() {
  for (auto& [info, pass] : passes_) pass->begin(ctx_);
}

void PassManager::run(ir::Operation& op) {
  if (print_to_ && print_after_ == "lower") {
    *print_to_ << "; after lower\n";
    ir::print_operation(*print_to_, op);
  }
  for (auto& [info, pass] : passes_) {
    pass->run(op, ctx_);
    if (verify_) verify_operation(op, info->name, ctx_.diags);
    if (print_to_ && (print_after_ == info->name || print_after_ == "all")) {
      *print_to_ << "; after " << info->name << "\n";
      ir::print_operation(*print_to_, op);
    }
  }
}

}  // namespace clpc
