// Rewriting arcs: splitting into equal pieces and linearising within a chord tolerance.
// Shared by the helix and arc-legalise passes.
#pragma once

#include <vector>

#include "ir/ir.h"

namespace clpc::arcedit {

// `n` arcs of equal sweep that together make `a` (a decided arc; helices rise evenly).
void split(const ir::Arc& a, int n, SourceLoc loc, std::vector<ir::Instr>& out);
// Feed moves along `a` whose chords stay within `tol` of it.
void linearise(const ir::Arc& a, double tol, SourceLoc loc, std::vector<ir::Instr>& out);
// Rebuilds op.body, replacing each instruction by what `edit` writes for it (returns false
// to keep the instruction as it is).
template <class Edit>
void rewrite(ir::Operation& op, Edit edit) {
  std::vector<ir::Instr> out;
  out.reserve(op.body.size());
  bool changed = false;
  for (ir::Instr& in : op.body) {
    if (edit(in, out)) {
      changed = true;
      continue;
    }
    out.push_back(std::move(in));
  }
  if (changed) op.body.swap(out);
}

}  // namespace clpc::arcedit
