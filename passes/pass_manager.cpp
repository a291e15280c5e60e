#include "passes/pass_manager.h"

#include <sstream>

#include "ir/printer.h"
#include "ir/verify.h"
#include "machine/format.h"
#include "machine/pipeline_check.h"

namespace clpc {

double PassContext::resolution() const {
  const AddressFormat& f = machine.format('X');
  double inc = dequantize(1, f);  // one increment, output units (scale folded in)
  if (inc <= 0) inc = 1e-4;
  return std::abs(inc) * from_output();
}

double PassContext::chord_tolerance() const {
  const KinematicsSettings& k = machine.kinematics;
  const bool transforms = k.has_rotaries() && (k.simultaneous == Simultaneous::Transform || k.indexed == Indexed::Transform);
  return transforms ? 0.5 * tolerance() : tolerance();
}

KinematicsSettings PassContext::kinematics() const {
  KinematicsSettings k = machine.kinematics;
  const double f = from_output();
  for (RotaryAxis& r : k.rotaries) r.center *= f;
  k.pivot *= f;
  k.retract_distance *= f;
  return k;
}

namespace {

class PrintAfter : public PassInstrument {
 public:
  explicit PrintAfter(std::string name) : name_(std::move(name)) {}
  void after_lower(const ir::Operation& op, PassContext& ctx) override {
    if (name_ == "lower") print("lower", op, ctx);
  }
  void after_pass(const PassInfo& pass, ir::Facts, const ir::Operation& op, PassContext& ctx) override {
    if (name_ == pass.name || name_ == "all") print(pass.name, op, ctx);
  }

 private:
  static void print(std::string_view after, const ir::Operation& op, PassContext& ctx) {
    std::ostringstream o;
    o << "; after " << after << "\n";
    ir::print_operation(o, op);
    ctx.diags.text(o.str());
  }
  std::string name_;
};

class VerifyIr : public PassInstrument {
 public:
  void after_pass(const PassInfo& pass, ir::Facts established, const ir::Operation& op, PassContext& ctx) override {
    verify_operation(op, pass.name, established, ctx.diags);
  }
};

}  // namespace

std::unique_ptr<PassInstrument> make_print_after(std::string name) { return std::make_unique<PrintAfter>(std::move(name)); }
std::unique_ptr<PassInstrument> make_verify_ir() { return std::make_unique<VerifyIr>(); }

PassManager::PassManager(PassContext& ctx, const std::vector<std::string>& pipeline, std::vector<PassInstrument*> instruments)
    : ctx_(ctx), instruments_(std::move(instruments)) {
  const ir::Facts given = given_facts(ctx.machine);
  ir::Facts facts = 0;
  for (const std::string& n : pipeline)
    if (const PassInfo* p = find_pass(n)) {
      passes_.emplace_back(p, p->make());
      facts = ((facts & ~p->breaks) | p->provides) & ~given;
      established_.push_back(facts);
    }
}

size_t PassManager::split_point() const {
  for (size_t i = 0; i < passes_.size(); ++i)
    if (passes_[i].first->costly) return i + 1;
  return passes_.size();
}

void PassManager::begin() {
  for (auto& [info, pass] : passes_) pass->begin(ctx_);
}

void PassManager::run(ir::Operation& op) { run(op, 0, passes_.size(), ctx_); }

void PassManager::run(ir::Operation& op, size_t from, size_t to, PassContext& ctx) {
  if (from == 0)
    for (PassInstrument* i : instruments_) i->after_lower(op, ctx);
  for (size_t k = from; k < to && k < passes_.size(); ++k) {
    auto& [info, pass] = passes_[k];
    pass->run(op, ctx);
    for (PassInstrument* i : instruments_) i->after_pass(*info, established_[k], op, ctx);
  }
}

}  // namespace clpc
