// The evidence the arc-direction pass weighs, exposed for tests and for the convention study
// over the corpus (tests/lower/test_arc_conventions.cpp).
#pragma once

#include <string>

#include "ir/ir.h"

namespace clpc {

struct ArcEvidence {
  int ccw_votes = 0, cw_votes = 0;
  std::string ccw_why, cw_why;  // what voted (first reason), for messages
  // The way the CL's own points on the arc (intermediate GOTOs) say it turns: cut the other
  // way it never passes through them.
  ir::ArcDir via = ir::ArcDir::Unknown;
  ir::ArcDir geometry() const {
    if (ccw_votes > 0 && cw_votes == 0) return ir::ArcDir::Ccw;
    if (cw_votes > 0 && ccw_votes == 0) return ir::ArcDir::Cw;
    return ir::ArcDir::Unknown;
  }
  bool conflicting() const { return ccw_votes > 0 && cw_votes > 0; }
};

// `in`/`out`: the direction of the cutting move entering the arc's start / leaving its end
// (zero when there is none). `min_len`: shorter moves say nothing.
ArcEvidence arc_evidence(const ir::Operation& op, const ir::Arc& a, const ir::Vec3& in, const ir::Vec3& out,
                         double min_len);

}  // namespace clpc
