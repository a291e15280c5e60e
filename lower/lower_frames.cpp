// Frame records: NX MSYS, Creo/APT CSYS and $$-> CSYS, CAMERA; SET work offsets; ROTATE.
// (How they read: ir/frame_records.cpp, shared with the pre-scan.)
#include <cmath>

#include "lower/lower.h"
#include "lower/frame_records.h"
#include "lower/params.h"

namespace clpc {

void Lowerer::lower_msys(const Record& r) { lower_matrix_frame(r, ir::FrameSource::Msys); }

// Frames (docs/cl-input.md, "Frames"). NX writes the points and tool axes after an MSYS in
// that frame, and the file's first MSYS is where the machine's work offset is set: every MSYS
// is taken relative to it, and lowering puts the points in the program frame. Creo and APT
// (CSYS, $$-> CSYS, CAMERA) write their points in the program frame already. Either way a
// GOTO without a tool axis after a frame record has the frame's Z as its tool axis.
void Lowerer::lower_matrix_frame(const Record& r, ir::FrameSource) {
  ir::SetFrame f;
  if (!read_frame(r, &d_, f.frame, f.source)) return;
  if (f.source == ir::FrameSource::Msys) {
    if (!msys0_) {
      // Points before the file's first MSYS: NX writes an MSYS with each operation, so they may
      // be in the absolute frame (no MCS) or in this one (its MSYS left out). Where the two
      // differ the part would be cut in the wrong place either way: both were posted alike.
      if (has_pos_ && !(f.frame.rotation.isIdentity(1e-6) && f.frame.origin.norm() < 1e-4)) {
        d_.error(r.loc, "the file's first MSYS comes after motion and is not the absolute frame: the points before "
                        "it may be in the absolute frame or in this one, and the two put the part in different "
                        "places; give the first operation its MSYS");
        return;
      }
      msys0_ = f.frame;
      msys0_loc_ = r.loc;
    } else if (!msys0_turn_said_ && f.frame.rotation.isIdentity(1e-6) && !msys0_->rotation.isIdentity(1e-6)) {
      // The part's setup is the first MSYS's, as written down. A later operation square to the
      // absolute frame while the first is turned from it says the first may be a local frame
      // (a 3+2 face first): then every face would be cut turned by the first one's tilt.
      msys0_turn_said_ = true;
      d_.warning(r.loc, "this MSYS is square to the absolute frame, but the first one (line " +
                            std::to_string(msys0_loc_.line) + "), which clpc takes as the part's setup on the machine (where "
                            "the work offset is set), is turned from it: if the part is set up square to the absolute "
                            "frame, the first operation's MSYS is a local one and every face would be cut turned by it; "
                            "put an operation in the setup's frame first",
                 "frame");
    }
    f.frame = ir::compose(msys0_->inverse(), f.frame);
    msys_ = f.frame;
    update_xf();
    axis_ = ir::Vec3::UnitZ();  // in the MSYS: xf_dir turns it into the frame's Z
  } else {
    axis_ = f.frame.z_axis();
  }
  ensure_operation(r.loc);
  push(r.loc, f);
}

void Lowerer::lower_set(const Record& r) {
  int reg = read_set_register(r, &d_);
  if (reg <= 0) return;
  ensure_operation(r.loc);
  push(r.loc, ir::SelectOffset{reg, ir::register_index(reg)});
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

namespace {

// An angle written in radians: read as radians it is a round number of degrees to the digits
// given, and read as degrees it is none. The digits given are the significant ones (CATIA
// writes 0.480000 for 0.48 degrees: two). Six or more: within 0.002 degree of a multiple of half
// a degree (22.5, 7.5, 12.5: bolt-circle divisions). Four or five (1.2566, 0.3927): within half
// a unit of the last digit of a multiple of half a degree. Three (1.571): of a multiple of 5
// degrees. Fewer: never. A degree value lands there by chance about once in a hundred draws of
// such digits, and no table is indexed to such angles.
bool looks_like_radians(double a, std::string_view text) {
  constexpr double kPi = 3.14159265358979323846;
  if (std::abs(a) < 0.01 || std::abs(a) > 2 * kPi + 1e-3) return false;
  while (!text.empty() && text.back() == '0') text.remove_suffix(1);
  const size_t point = text.find('.');
  const size_t decimals = point == std::string_view::npos ? 0 : text.size() - point - 1;
  if (decimals < 3) return false;
  const double deg = std::abs(a) * 180 / kPi;
  if (decimals >= 6) return std::abs(deg * 2 - std::round(deg * 2)) < 4e-3;
  const double window = 0.5 * std::pow(10.0, -double(decimals)) * 180 / kPi;
  if (decimals >= 4) return std::abs(deg - 0.5 * std::round(deg * 2)) < window;
  return std::abs(deg - 5 * std::round(deg / 5)) < window;
}

}  // namespace

// ROTABL/angle[,AAXIS|BAXIS|CAXIS][,TABLE][,CLW|CCLW][,INCR|ABSOL|ATANGL]: positions the rotary
// table (CATIA, CAMWorks). The angle is in degrees, except in SolidWorks CAM / CAMWorks files,
// which write radians (docs/cl-input.md). No axis named: the machine's table axis ('?').
void Lowerer::lower_rotabl(const Record& r) {
  ParamReader ps(r, d_);
  ir::RotaryIndex ri;
  ri.axis = '?';
  ri.incremental = false;
  bool angle = false;
  for (size_t i = 0; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (p.is_empty() || p.is("TABLE")) continue;
    if (p.is("AAXIS")) ri.axis = 'A';
    else if (p.is("BAXIS")) ri.axis = 'B';
    else if (p.is("CAXIS")) ri.axis = 'C';
    else if (p.is("INCR")) ri.incremental = true;
    else if (p.is("ATANGL") || p.is("ABSOL")) ri.incremental = false;
    else if (p.is("CLW")) ri.dir = ir::ArcDir::Cw;
    else if (p.is("CCLW")) ri.dir = ir::ArcDir::Ccw;
    else if (p.is_number() && !angle) {
      constexpr double kPi = 3.14159265358979323846;
      // Radians beyond a whole turn (6.2832, rounded, is one) are no angle a CAM system writes:
      // the file is another system's, in degrees, and the two readings turn the part
      // differently. Refused.
      if (info_.cam == ir::CamSystem::SolidWorks && std::abs(p.number) > 2 * kPi + 1e-3) {
        d_.error(p.loc, "ROTABL: SolidWorks CAM / CAMWorks files give the angle in radians (the file was taken for "
                        "one from " + info_.cam_evidence + "), and " + std::string(p.name()) +
                        " radians is more than a whole turn: is the angle in degrees? The two readings turn the part "
                        "differently; have the CAM system write the tool axis on the GOTOs (MULTAX), or remove "
                        "OPFEATSTART if the file is not SolidWorks CAM's");
        return;
      }
      // The other way round: a whole number of degrees to five places when read as radians
      // (1.570796, 0.785398, 3.141593) is SolidWorks CAM's radians in a file that does not say
      // it is SolidWorks CAM's (its .apt flavour has no OPFEATSTART). No shop indexes 1.570796
      // degrees; read as degrees it turned the part 1.57 where 90 was meant, certified.
      if (info_.cam != ir::CamSystem::SolidWorks && looks_like_radians(p.number, p.name())) {
        d_.error(p.loc, "ROTABL: " + std::string(p.name()) + " is " + num_text(std::round(p.number * 360 / kPi) / 2) +
                            " degrees in radians, to the digits given: SolidWorks CAM / CAMWorks write ROTABL in "
                            "radians, other systems in degrees, and nothing in this file says which wrote it (a "
                            "SolidWorks CAM file starts its operations with OPFEATSTART); the two readings turn the "
                            "part differently. Have the CAM system write the tool axis on the GOTOs (MULTAX) instead");
        return;
      }
      ri.angle = p.number * (info_.cam == ir::CamSystem::SolidWorks ? 180 / kPi : 1.0);
      angle = true;
    } else {
      d_.error(p.loc, "ROTABL: unexpected '" + std::string(p.name()) + "'");
      return;
    }
  }
  if (!angle) {
    d_.error(r.loc, "ROTABL needs an angle");
    return;
  }
  ensure_operation(r.loc);
  push(r.loc, ri);
}

}  // namespace clpc
