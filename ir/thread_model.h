// How a Fanuc lathe executes its threading cycles, as moves: the G92 box (one pass) and the
// G76 multiple-pass cycle with radial infeed. The thread-cycles pass writes a cycle only when
// this expansion reproduces the CL's passes; the G-code reader runs G92 and G76 with it.
// Written from the control's documentation (CONTROLLERS.md): G76 cuts its n-th pass at
// Δd·√n below the crest (no step smaller than Δdmin), the last roughing pass at k − d, then
// m finishing passes at the full height k; each pass is a G92 box from the start point.
//
// Lathe coordinates: x is the radius, z the axial position (y = 0).
#pragma once

#include <vector>

#include "ir/ir.h"

namespace clpc::thread_model {

// G76's parameters (radius values, one unit): k, Δd, Δdmin, d, m.
struct Multi {
  double height = 0;
  double first = 0;
  double min_step = 0;
  double allowance = 0;
  int finish_passes = 1;
};

// The depth below the crest of each of G76's passes, in order. Empty when the parameters
// make no cycle (height or first depth not positive, allowance not below the height) or more
// than kMaxPasses passes.
constexpr size_t kMaxPasses = 10000;
std::vector<double> depths(const Multi& p);

struct Step {
  ir::Vec3 to;
  bool cut;  // the synchronised thread cut; else a rapid
};

// One G92 box from `start` (where the tool is) to the far corner `end`: rapid along x to
// end's radius, thread to end's z, rapid back out to start's radius, rapid back to start's z.
void box(const ir::Vec3& start, const ir::Vec3& end, std::vector<Step>& out);

// G76 from `start` to the root corner `end` (end.x is the root radius): one box per depth,
// the crest being height outside the root on the side of the start.
std::vector<Step> multi(const ir::Vec3& start, const ir::Vec3& end, const Multi& p);

}  // namespace clpc::thread_model
