// A pass: a named transformation of the IR with a one-line summary and a contract (what it
// expects, what it guarantees). Passes run one operation at a time, in the order the machine's
// pipeline names them; state that must cross operations lives in the pass object.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "machine/machine.h"
#include "support/diagnostics.h"
#include "ir/ir.h"

namespace clpc {

struct PassContext {
  ir::ProgramInfo& info;  // passes may fill the program-wide tables (the offset table)
  const Machine& machine;
  Diagnostics& diags;
  // Output units -> program units: machine tolerances are in output units, the IR is in
  // program units.
  double from_output() const { return ir::mm_per_unit(machine.units) / ir::mm_per_unit(info.units); }
  // The machine's arc tolerance in program units.
  double tolerance() const { return machine.arcs.tolerance * from_output(); }
  // One increment of the X address (the output resolution) in program units.
  double resolution() const;
  // The machine's kinematics with its lengths (centres, pivot, retract) in program units, as
  // the kinematic model works on the IR.
  KinematicsSettings kinematics() const;
};

class Pass {
 public:
  virtual ~Pass() = default;
  virtual void begin(PassContext& ctx) {}
  virtual void run(ir::Operation& op, PassContext& ctx) = 0;
};

struct PassInfo {
  std::string_view name;
  std::string_view summary;
  std::string_view contract;
  std::unique_ptr<Pass> (*make)();
};

// Every pass clpc has, in the order they are best run.
const std::vector<PassInfo>& all_passes();
const PassInfo* find_pass(std::string_view name);
std::vector<std::string> pass_names();
// The passes of `pipeline` that give the CL its meaning (arcs decided, cycles made holes), in
// its order: verify's reference is the CL run through these alone.
std::vector<std::string> reference_passes(const std::vector<std::string>& pipeline);

}  // namespace clpc
