// Rewriting arcs: splitting into equal pieces and linearising within a chord tolerance.
// Shared by the helix and arc-legalise passes.
#pragma once

#include <iterator>
#include <vector>

#include "support/diagnostics.h"
#include "ir/ir.h"

namespace clpc::arcedit {

// `n` arcs of equal sweep that together make `a` (a decided arc; helices rise evenly).
void split(const ir::Arc& a, int n, SourceLoc loc, std::vector<ir::Instr>& out);
// Feed moves along `a` whose chords stay within `tol` of it: false (an error reported, nothing
// written) when that would take more than kMaxPieces lines — an absurd radius or tolerance.
constexpr double kMaxPieces = 1e6;
bool linearise(const ir::Arc& a, double tol, SourceLoc loc, std::vector<ir::Instr>& out, Diagnostics& d);
// Rebuilds op.body, replacing each instruction by what `edit` writes for it (returns false
// to keep the instruction as it is).
// Nothing is copied until the first edit; the buffers are kept for the next operation.
template <class Edit>
void rewrite(ir::Operation& op, Edit edit) {
  static thread_local std::vector<ir::Instr> out, replacement;
  bool changed = false;
  for (size_t i = 0; i < op.body.size(); ++i) {
    ir::Instr& in = op.body[i];
    replacement.clear();
    if (edit(in, replacement)) {
      if (!changed) {
        out.clear();
        out.reserve(op.body.size() + replacement.size());
        std::move(op.body.begin(), op.body.begin() + std::ptrdiff_t(i), std::back_inserter(out));
        changed = true;
      }
      std::move(replacement.begin(), replacement.end(), std::back_inserter(out));
      continue;
    }
    if (changed) out.push_back(std::move(in));
  }
  if (changed) op.body.swap(out);
}

}  // namespace clpc::arcedit
