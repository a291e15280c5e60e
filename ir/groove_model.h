// How a Fanuc control executes G74 / G75 (the plunge, peck and shift sequence), as moves.
// The groove-cycles pass accepts a collapse only when this expansion reproduces the CL
// motion; the G-code interpreter reads G74/G75 with it; the tests compare with it.
//
// Lathe coordinates: x is the radius, z the axial position (y = 0).
#pragma once

#include <vector>

#include "ir/ir.h"

namespace clpc::groove {

struct Params {
  bool face = false;     // G74: plunge along Z, shift along X; G75: plunge along X, shift along Z
  double retract = 0;    // e: pull-out after each peck
  double x_amount = 0;   // P: along X (G75 peck depth, G74 shift); 0 = in one go / no shift
  double z_amount = 0;   // Q: along Z (G75 shift, G74 peck depth)
  double relief = 0;     // relief at the bottom, along the shift axis back towards the start
};

struct Step {
  ir::Vec3 to;
  bool cut;  // a feed; else a rapid
};

// From `start` (where the tool is when the cycle starts) to the far corner `end`: plunges to
// end's depth at stations from start to end, stepping by the shift amount (the last step is
// shortened to land on end), then back to start. Empty when the amounts are so small that
// the cycle would take more than kMaxSteps moves.
constexpr double kMaxSteps = 1e6;
std::vector<Step> expand(const ir::Vec3& start, const ir::Vec3& end, const Params& p);

}  // namespace clpc::groove
