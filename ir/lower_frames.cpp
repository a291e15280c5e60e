// Frame records: NX MSYS, Creo/APT CSYS and $$-> CSYS, CAMERA; SET work offsets; ROTATE.
// (How they read: ir/frame_records.cpp, shared with the pre-scan.)
#include <cmath>

#include "ir/lower.h"
#include "ir/frame_records.h"
#include "ir/params.h"

namespace clpc {

void Lowerer::lower_msys(const Record& r) { lower_matrix_frame(r, ir::FrameSource::Msys); }

void Lowerer::lower_matrix_frame(const Record& r, ir::FrameSource) {
  ir::SetFrame f;
  if (!read_frame(r, &d_, f.frame, f.source)) return;
  ensure_operation(r.loc);
  push(r.loc, f);
}

void Lowerer::lower_set(const Record& r) {
  int reg = read_set_register(r, &d_);
  if (reg <= 0) return;
  ensure_operation(r.loc);
  push(r.loc, ir::SelectOffset{reg, register_index(reg)});
}

void Lowerer::lower_rotate(const Record& r) {
  ParamReader ps(r, d_);
  ir::RotaryIndex ri;
  bool axis = false, angle = false;
  for (size_t i = 0; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (p.is("AAXIS")) { ri.axis = 'A'; axis = true; }
    else if (p.is("BAXIS")) { ri.axis = 'B'; axis = true; }
    else if (p.is("CAXIS")) { ri.axis = 'C'; axis = true; }
    else if (p.is("INCR")) ri.incremental = true;
    else if (p.is("ATANGL") || p.is("ABSOL")) ri.incremental = false;
    else if (p.is("CLW")) ri.dir = ir::ArcDir::Cw;
    else if (p.is("CCLW")) ri.dir = ir::ArcDir::Ccw;
    else if (p.is_number()) { ri.angle = p.number; angle = true; }
    else {
      d_.error(p.loc, "ROTATE: unknown word '" + std::string(p.text) + "'");
      return;
    }
  }
  if (!axis || !angle) {
    d_.error(r.loc, "ROTATE needs an axis (AAXIS, BAXIS, CAXIS) and an angle");
    return;
  }
  ensure_operation(r.loc);
  push(r.loc, ri);
}

}  // namespace clpc
