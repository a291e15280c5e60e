#include "ir/stage.h"

namespace clpc::ir {

const std::array<FactInfo, 9>& all_facts() {
  static const std::array<FactInfo, 9> facts = {{
      {ArcsDecided, "arcs-decided", "for every CIRCLE's sense", "every arc has a direction and a positive sweep"},
      {ArcsOneTurn, "arcs-one-turn", "for helical and multi-turn arcs",
       "no arc has extra turns or a sweep over 360 degrees"},
      {ArcsLegal, "arcs-legal", "for arcs the control cannot cut as they are",
       "no arc over 360 degrees (an arc in a plane the machine lacks: the backend refuses it)"},
      {CyclesFormed, "cycles-formed", "for CYCLE records: without it their holes would be cut as moves to their tops",
       "no rapid or feed move between a cycle-on and its cycle-off; no cycle open at the end of an operation"},
      {GroovesFormed, "grooves-formed", "for the groove cycle records", "no groove-on or groove mark left"},
      {OffsetsAssigned, "offsets-assigned", "for SET registers and frames", ""},
      {Kinematic, "kinematic", "to turn tool axes into rotary positions",
       "every rapid and feed move has its rotary positions"},
      {LimitsChecked, "limits-checked", "to check every position against the machine's travel", ""},
      {RapidsSplit, "rapids-split", "where motion.rapids_linear is false: each axis rapids at its own rate, so a rapid "
       "down and across would reach the depth before it has crossed (a control whose G00 moves in a straight line: "
       "motion.rapids_linear = true)", ""},
  }};
  return facts;
}

std::string fact_names(Facts f) {
  std::string s;
  for (const FactInfo& i : all_facts())
    if (f & i.fact) s += (s.empty() ? "" : ", ") + std::string(i.name);
  return s.empty() ? "nothing" : s;
}

}  // namespace clpc::ir
