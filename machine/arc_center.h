// The centre words of an arc block, chosen so the control's start and end radii agree and
// the arc it cuts stays on the CL arc.
#pragma once

#include "machine/machine.h"

namespace clpc {

struct ArcCenterChoice {
  double cu, cv;         // centre (absolute, in-plane), exactly as the control will take it
  double mismatch;       // |start radius - end radius| the control computes
  double deviation;      // distance of the arc's midpoint from the true midpoint
};

struct ArcCenterInput {
  double su, sv, eu, ev;  // start and end as the control holds them (rounded)
  double cu, cv;          // the true centre
  double mu, mv;          // the true arc's midpoint (in-plane)
  bool ccw;               // direction in the (u, v) plane
  bool full;              // a whole circle (start == end)
};

// Tries the centres the I/J/K words can express around the ideal one (on the perpendicular
// bisector of the rounded chord, nearest the true centre): the chosen one has a radius
// mismatch of at most one increment where any has, and of those the smallest midpoint
// deviation. fu, fv: formats of the centre words; `incremental`: words relative to the start.
ArcCenterChoice choose_arc_center(const ArcCenterInput& in, const AddressFormat& fu, const AddressFormat& fv,
                                  bool incremental);

}  // namespace clpc
