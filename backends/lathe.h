#pragma once

#include "backends/backend.h"

namespace clpc {

// Turning in the ZX plane: X written as a diameter (the X format's scale), T0101 tool words,
// constant surface speed with a G50 clamp, feed per revolution, G18 arcs with I and K.
class LatheBackend : public ProgramWriter {
 public:
  LatheBackend(const Machine& m, OutputFile& out, Diagnostics& d);

 protected:
  void write_move(const ir::Move& m, SourceLoc loc) override;
  void write_arc(const ir::Operation& op, const ir::Arc& a, SourceLoc loc) override;
  void write_tool_change(const ir::ToolChange& t, SourceLoc loc) override;
  void write_spindle(const ir::Spindle& s, SourceLoc loc) override;
  void write_groove(const ir::Operation& op, const ir::Groove& g, SourceLoc loc) override;
  void retract_for_stop(SourceLoc loc) override;

  void motion_code(Motion mo);
  bool in_plane(const ir::Vec3& p, SourceLoc loc);
  bool changed(char letter, double value) const;
};

}  // namespace clpc
