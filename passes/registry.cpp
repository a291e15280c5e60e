// The list of passes. Explicit rather than self-registering so the linker cannot drop one.
#include "passes/passes.h"

namespace clpc {

const std::vector<PassInfo>& all_passes() {
  static const std::vector<PassInfo> passes = {
      {"arc-direction", "decide which way each CL arc turns (CW or CCW)",
       "expects: arcs as lowered, with the CAM convention's hint. guarantees: every arc has a direction and "
       "a sweep; geometry (tangent moves, points on the arc) overrules the convention with a warning; an arc "
       "nothing decides is an error",
       make_arc_direction},
      {"helix", "keep, split or linearise helical and multi-turn arcs as the machine allows",
       "expects: decided arcs. guarantees: no extra turns; helical arcs within arcs.helix_max_sweep where "
       "arcs.helical, none where not (linearised within arcs.tolerance)",
       make_helix},
      {"arc-legalise", "make every arc one the machine can do, or lines within tolerance",
       "expects: decided arcs without extra turns. guarantees: arcs in the machine's planes, radii within "
       "its limits, sweep within arcs.max_sweep, no full circle in R format, no arc too short to survive "
       "rounding",
       make_arc_legalise},
      {"drill-cycles", "turn the GOTOs of a CYCLE into canned-cycle holes, or moves where the machine lacks the cycle",
       "expects: CYCLE records lowered to cycle-on / moves / cycle-off. guarantees: every move inside a cycle is a "
       "hole or expanded into plain moves; every cycle ends (a warning and an implicit cancel at the end of an "
       "operation without CYCLE/OFF)",
       make_drill_cycles},
      {"groove-cycles", "collapse lathe groove motion into one G74 (face) or G75 (radial) cycle where the cycle reproduces it",
       "expects: lathe data, groove records and marks as lowered. guarantees: groove records are gone; each collapse is "
       "a move to the cycle's start and a groove whose G74/G75 expansion equals the motion it replaced; motion that "
       "does not match stays as it was",
       make_groove_cycles},
      {"offset-table", "gather SET/CAMERA (and per-frame MSYS/CSYS) frames into a work-offset table; select each operation's register and "
       "position its 3+2 work",
       "expects: frame and SET records as lowered, the pre-scan's frame list. guarantees: ProgramInfo::offsets holds one "
       "entry per distinct frame (equal frames share a register; SET registers kept, others in order of first use; "
       "running out is an error); each operation selects its register; 3+2 operations have their rotaries positioned "
       "and their points in the frame's coordinates",
       make_offset_table},
      {"kinematics", "turn tool axes into rotary positions and points into what the control is given (five-axis, 3+2)",
       "expects: legal arcs, holes, tool axes in the part frame. guarantees (machines with rotaries): every move has "
       "its rotary positions within limits, chosen for the least travel and continuity; indexed operations position "
       "once and cut 3-axis in the tilted frame; holes along Z or expanded; TCPC / dynamic work offset modes switched "
       "around the moves that need them; no-solution and forced jumps are errors (or retract-rotate-re-engage)",
       make_kinematics},
      {"limits", "check every rotary and linear position against the machine's travel",
       "expects: the kinematics pass's output. guarantees: an error naming the CL record for any rotary beyond its "
       "limits, or linear position beyond kinematics.travel (absolute with kinematics.work_zero, else the program's "
       "extent)",
       make_limits},
  };
  return passes;
}

const PassInfo* find_pass(std::string_view name) {
  for (const PassInfo& p : all_passes())
    if (p.name == name) return &p;
  return nullptr;
}

std::vector<std::string> pass_names() {
  std::vector<std::string> n;
  for (const PassInfo& p : all_passes()) n.emplace_back(p.name);
  return n;
}

}  // namespace clpc

namespace clpc {

std::vector<std::string> reference_passes(const std::vector<std::string>& pipeline) {
  std::vector<std::string> out;
  for (const std::string& p : pipeline)
    if (p == "arc-direction" || p == "drill-cycles") out.push_back(p);
  return out;
}

}  // namespace clpc
