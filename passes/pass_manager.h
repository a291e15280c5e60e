// Runs a machine's pipeline over each operation, with instruments that look on (LLVM's pass
// instrumentation): the IR printed after a pass, its invariants checked.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "passes/pass.h"

namespace clpc {

// Looks at the IR as the passes leave it. Instruments run on whichever thread runs the pass,
// so they report through the context's Diagnostics (text() for the IR), which keeps their
// output in order with the diagnostics whatever the schedule.
class PassInstrument {
 public:
  virtual ~PassInstrument() = default;
  virtual void after_lower(const ir::Operation& op, PassContext& ctx) {}
  // `established`: the facts (ir/stage.h) the passes so far have made true, beyond those the
  // machine gives (machine/pipeline_check.h).
  virtual void after_pass(const PassInfo& pass, ir::Facts established, const ir::Operation& op, PassContext& ctx) {}
};

// --print-after: the IR after the pass `name` ("lower", a pass name, or "all").
std::unique_ptr<PassInstrument> make_print_after(std::string name);
// --verify-ir: the IR's invariants after every pass (ir/verify.h).
std::unique_ptr<PassInstrument> make_verify_ir();

class PassManager {
 public:
  PassManager(PassContext& ctx, const std::vector<std::string>& pipeline, std::vector<PassInstrument*> instruments = {});
  void begin();
  void run(ir::Operation& op);
  // Passes [from, to) of the pipeline, with another context (the same program and machine,
  // its own diagnostics): the pipeline may be split between two threads.
  void run(ir::Operation& op, size_t from, size_t to, PassContext& ctx);
  size_t size() const { return passes_.size(); }
  // Where a two-thread split balances best: after the first costly pass (PassInfo::costly),
  // else at the end.
  size_t split_point() const;

 private:
  PassContext& ctx_;
  std::vector<std::pair<const PassInfo*, std::unique_ptr<Pass>>> passes_;
  std::vector<ir::Facts> established_;  // after each pass
  std::vector<PassInstrument*> instruments_;
};

}  // namespace clpc
