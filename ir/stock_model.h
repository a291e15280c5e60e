// How a Fanuc lathe control executes the stock-removal cycles G71 (turning) and G72 (facing),
// type I, as moves: the finishing profile between the blocks N(P) and N(Q), shifted by the
// finishing allowances, is roughed out in levels of the depth of cut, then followed once.
// The G-code interpreter reads G71/G72 with it; the tests compare with it. docs/lathe.md
// ("Stock removal") states the rules and where they come from.
//
// Lathe coordinates: x is the radius, z the axial position (y = 0). Arcs lie in the ZX plane
// (G18): counter-clockwise about +Y, as the interpreter reads them.
#pragma once

#include <string>
#include <vector>

#include "ir/ir.h"

namespace clpc::stock {

// One block of the finishing profile, as the control reads it.
struct Element {
  ir::Vec3 start, end;
  bool arc = false;
  ir::Vec3 center = ir::Vec3::Zero();  // arcs
  bool ccw = false;                    // arcs: G03
  int line = 0;                        // where it stands (G-code line), for the reasons given
};

struct Params {
  bool facing = false;     // G72: levels along Z, cuts along X; G71: levels along X, cuts along Z
  double depth = 0;        // Δd: depth of cut per level (radius), > 0
  double retract = 0;      // e: the pull-out after each level, at 45 degrees
  double allow_x = 0;      // Δu/2: finishing allowance along X (radius), signed
  double allow_z = 0;      // Δw: finishing allowance along Z, signed
  bool infeed_rapid = true;  // the first profile block is G00 (else G01): how each level is entered
};

// A CYCLE/ROUGH record's words, `scale` times (program units to output units); the infeed
// from the profile's first move.
Params params_of(const ir::RoughMark& m, double scale, bool infeed_rapid);

// The cycle as the control reads it once written: its words, its start A and its profile put
// through `written(letter, v)` — the value the program's word X or Z gives for v, NaN when v
// cannot be written. Where a level meets a shallow profile, half an increment moves the cut's
// end far along the profile, and the number of levels may turn on it: the backend's proof, the
// rough-cycles pass and verify all expand these numbers. False when a word cannot be written.
template <class Written>
bool round_as_written(Params& p, ir::Vec3& start, std::vector<Element>& profile, Written written) {
  auto at = [&](const ir::Vec3& v) { return ir::Vec3(written('X', v.x()), v.y(), written('Z', v.z())); };
  p.depth = written('Z', p.depth);
  p.retract = written('Z', p.retract);
  p.allow_x = written('X', p.allow_x);
  p.allow_z = written('Z', p.allow_z);
  start = at(start);
  bool ok = p.depth == p.depth && p.retract == p.retract && p.allow_x == p.allow_x && p.allow_z == p.allow_z &&
            start.allFinite();
  for (Element& e : profile) {
    e.start = at(e.start);
    e.end = at(e.end);
    if (e.arc) e.center = at(e.center);
    ok = ok && e.start.allFinite() && e.end.allFinite() && e.center.allFinite();
  }
  return ok;
}

struct Step {
  enum class Kind : uint8_t { Rapid, Feed, Arc };
  Kind kind = Kind::Feed;
  ir::Vec3 to;
  ir::Vec3 center = ir::Vec3::Zero();  // arcs
  bool ccw = false;
};

// From `start` (A: where the tool is when the cycle is called) over the profile (A to A' first,
// then A' to B): the level cuts, each entered from A's cutting-axis position, cut to the
// shifted profile, pulled out by e at 45 degrees and returned at rapid; then the shifted
// profile from A' to B at feed, and back to A at rapid. Empty with `why` set when the profile
// is not one a type I cycle takes (the first block not along the level axis alone, the
// profile not monotonic along both axes, A not on the stock side), or would take more than
// kMaxSteps moves.
constexpr double kMaxSteps = 1e6;
std::vector<Step> expand(const ir::Vec3& start, const std::vector<Element>& profile, const Params& p, std::string& why);

}  // namespace clpc::stock
