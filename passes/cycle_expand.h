// A canned-cycle hole written out as the plain moves a control would make for it: for machines
// without the cycle, and for holes whose axis is not the machine's Z.
#pragma once

#include <vector>

#include "machine/machine.h"
#include "support/diagnostics.h"
#include "ir/ir.h"

namespace clpc {

struct ExpandContext {
  double peck_clearance;   // program units: how far above the last depth a peck re-enters
  double current_feed;     // program units/min (or per rev); the feed to restore afterwards
  ir::FeedMode current_mode;
  bool have_feed;
  bool return_initial;     // G98 (true) or G99
  double spindle_rpm;      // for BoreStop's restart (0: unknown)
  ir::SpindleDir spindle_dir;
  bool lathe = false;      // a lathe expands every cycle (why a tap cannot be written, said)
  const char* why_moves = nullptr;  // why a machine with the cycle writes this hole as moves
};

// Appends the moves for hole `h` of cycle `c`. False (and an error) for cycles that cannot
// be written as moves (tapping, oriented boring).
bool expand_hole(const ir::Hole& h, const ir::CycleSpec& c, const ExpandContext& x, SourceLoc loc,
                 std::vector<ir::Instr>& out, Diagnostics& d);

}  // namespace clpc
