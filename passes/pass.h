// A pass: a named transformation of the IR with a one-line summary and a contract (what it
// expects and guarantees, in words and as IR facts). Passes run in the order the machine's
// pipeline names them, which the machine loader has checked against their contracts.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "machine/machine.h"
#include "support/diagnostics.h"
#include "ir/ir.h"
#include "ir/stage.h"

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
  // The chord error an arc made into lines may have: the tolerance, or half of it where clpc
  // turns points through the machine's chain itself (kinematics "transform"): the rounding of
  // the written rotary angles then moves the tip too (0.0005 degrees is 0.001 mm at 115 mm
  // from the axis), and takes the other half.
  double chord_tolerance() const;
  // The machine's kinematics with its lengths (centres, pivot, retract) in program units, as
  // the kinematic model works on the IR.
  KinematicsSettings kinematics() const;
};

// A pass sees a program one operation at a time, in file order, and an operation may arrive
// in chunks (very long operations: Operation::continued / last_chunk): state that crosses
// operations or chunks lives in the pass object. begin() is called once, before the first
// operation. A pass never sees two operations at once, on any schedule.
class Pass {
 public:
  virtual ~Pass() = default;
  virtual void begin(PassContext& ctx) {}
  virtual void run(ir::Operation& op, PassContext& ctx) = 0;
};

// What a pass is and promises (Yosys's help() in spirit): defined at the end of the pass's own
// file, listed by passes/registry.cpp, printed by `clpc passes`, copied into docs/passes.md.
struct PassInfo {
  std::string_view name;        // as pipelines name it
  std::string_view summary;     // one line
  std::string_view expects;     // what it needs of the IR, in words
  std::string_view guarantees;  // what is true after it, in words
  std::string_view settings;    // the machine keys it reads
  ir::Facts needs = 0;          // the facts (ir/stage.h) that must hold before it
  ir::Facts provides = 0;       // the facts it establishes
  ir::Facts breaks = 0;         // facts that held before and may not after
  bool costly = false;          // most of the work: the threaded schedule splits after it
  std::unique_ptr<Pass> (*make)() = nullptr;
};

// Every pass clpc has, in the order they are best run.
const std::vector<PassInfo>& all_passes();
const PassInfo* find_pass(std::string_view name);
// Makes a pass known to find_pass (and so to pipelines) beside clpc's own: a test double of a
// pass (the certification tests give the compile a pass that is wrong on purpose). Call before
// any compile starts; the name must be new.
void register_extra_pass(const PassInfo& p);
// The contracts the machine loader checks pipelines with.
ir::PassContracts pass_contracts();

}  // namespace clpc
