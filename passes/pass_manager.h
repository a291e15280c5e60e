// Runs a machine's pipeline over each operation; can print the IR after a named pass and
// check the IR's invariants between passes.
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "passes/pass.h"

namespace clpc {

class PassManager {
 public:
  // `print_after`: a pass name, or "all"; the IR after it is printed to `print_to`.
  PassManager(PassContext& ctx, const std::vector<std::string>& pipeline, std::string print_after = {},
              std::ostream* print_to = nullptr, bool verify = false);
  void begin();
  void run(ir::Operation& op);
  // Passes [from, to) of the pipeline, with another context (the same program and machine,
  // its own diagnostics): the pipeline may be split between two threads.
  void run(ir::Operation& op, size_t from, size_t to, PassContext& ctx);
  size_t size() const { return passes_.size(); }
  // Where a two-thread split balances best: after the costliest pass ('kinematics'), else at
  // the end.
  size_t split_point() const;

 private:
  PassContext& ctx_;
  std::vector<std::pair<const PassInfo*, std::unique_ptr<Pass>>> passes_;
  std::string print_after_;
  std::ostream* print_to_;
  bool verify_;
};

}  // namespace clpc
