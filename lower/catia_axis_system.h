// CATIA's machining axis system: CATIA writes it as a comment block, "$$*CATIA0", a line or
// a few naming it ("$$ Manufacturing Program.1", "$$ MSYS/"), then three rows of four numbers
// (each axis's direction and the origin). The points after it are in that axis system. The
// one in force at the first motion is the program's frame; a later block with another matrix (a Machining Axis
// Change, or a Part Operation of its own) puts the points after it elsewhere, and was read as
// a comment: the cuts ran in the first frame, certified (helper-56). It is refused at its
// "$$*CATIA0" line. A later block with the same matrix (karlo_DEMO3) changes nothing.
#pragma once

#include <array>
#include <string_view>

#include "support/diagnostics.h"

namespace clpc {

class CatiaAxisSystems {
 public:
  // A "$$" comment's text (what follows the "$$").
  void comment(std::string_view text, SourceLoc loc, Diagnostics& d);
  // Any record that is no comment ends a block still being read; the axis system in force at
  // the first one that moves the tool is the program's (one given before it and replaced before
  // any motion changes nothing; helper-58).
  void statement(bool moves) {
    rows_ = kNone;
    if (moves) locked_ = true;
  }

 private:
  static constexpr int kNone = -1;
  using Matrix = std::array<double, 12>;
  int rows_ = kNone;     // rows of the block being read, or kNone
  int other_lines_ = 0;  // its lines that are no row (names), before the rows
  SourceLoc at_;         // its "$$*CATIA0"
  Matrix reading_{};
  Matrix first_{};
  bool have_first_ = false;
  bool locked_ = false;  // motion seen: first_ is the program's
};

}  // namespace clpc
