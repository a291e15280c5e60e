// The stages of the IR as facts: what is true of an operation once a pass has run. Each pass
// declares the facts it requires, provides and breaks (passes/<pass>.cpp); the machine loader
// walks a pipeline through them and refuses one that does not reach a legal program for its
// machine, naming the missing pass (machine/pipeline_check.cpp); --verify-ir checks the
// invariants of every fact established so far (ir/verify.cpp). docs/passes.md lists them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace clpc::ir {

enum Fact : uint32_t {
  ArcsDecided = 1u << 0,      // every arc has a direction and a sweep
  ArcsOneTurn = 1u << 1,      // no arc has extra turns; helices as the machine allows
  ArcsLegal = 1u << 2,        // every arc is one the control can cut (plane, radius, sweep)
  CyclesFormed = 1u << 3,     // a CYCLE's GOTOs are holes (or the plain moves of the cycle)
  GroovesFormed = 1u << 4,    // no groove record left: G74/G75 cycles or plain motion
  OffsetsAssigned = 1u << 5,  // SET/CAMERA/frames made into work-offset registers
  Kinematic = 1u << 6,        // tool axes turned into rotary positions
  LimitsChecked = 1u << 7,    // every position checked against the machine's travel
  RapidsSplit = 1u << 8,      // no rapid goes along and across the tool axis at once (non-linear rapids)
};
using Facts = uint32_t;

struct FactInfo {
  Fact fact;
  std::string_view name;  // as docs/passes.md and `clpc passes` write it
  std::string_view why;   // why a machine needs it: "for every CIRCLE's sense"
  std::string_view checked;  // what --verify-ir checks of it ("" where only the pass can tell)
};
// Every fact, in the order a pipeline establishes them.
const std::array<FactInfo, 9>& all_facts();
// "arcs-decided, cycles-formed" (empty: "nothing").
std::string fact_names(Facts f);

// What the machine loader needs of a pass to check a pipeline.
struct PassContract {
  std::string name;
  Facts needs = 0;  // required before it
  Facts provides = 0;
  Facts breaks = 0;
};
using PassContracts = std::vector<PassContract>;

}  // namespace clpc::ir
