// The lathe's retract home, at a tool change, a stop that retracts, and the program's end.
//
// The machine's retract (Fanuc's `G28 U0. W0.`) sends the turret to its reference point, at
// plus X and plus Z, in both axes at once. The CAM system's retract is the one that knows the
// part, and the post cannot prove a diagonal safe without the stock. This is a guard against
// the plain crash, not a proof: the tool's last motion a cut toward the spindle axis or the
// chuck (-X or -Z: a face down a shoulder, a bore's floor), and the tool short of the reach of
// its cuts in both X and Z (any of them, their start points included, went further out and one
// went further forward). From there the diagonal drags it through the part (helper-59: a face
// down a shoulder, then LOADTL, was certified). It stays silent at the axis (a face cut to the
// centre), after a rapid (the CAM system's own clearance move), a cut going out (a facing pass
// ending at the bar's diameter: NIST turn_op10.ncl.4 changes tool there) and a cycle (it
// returns to its start). A straight plunge from the reach leaves the tool at it in the other
// axis and passes (docs/lathe.md lists what it misses). It never guesses which axis to retract
// first: that depends on whether the tool is in a groove or a bore.
#include <algorithm>
#include <cmath>

#include "backends/lathe.h"
#include "ir/arc_geometry.h"
#include "support/text.h"

namespace clpc {

namespace {
double rounded(double v) { return std::round(v * 1e4) / 1e4; }
}  // namespace

void LatheBackend::note_cut_to(const ir::Vec3& to, SourceLoc loc) {
  note_cut(pos_, loc);
  note_cut(to, loc);
  const double eps = 1e-6 * std::max(1.0, to.norm());
  reach_.went_in = to.x() < pos_.x() - eps || to.z() < pos_.z() - eps;
}

void LatheBackend::note_cut(const ir::Vec3& p, SourceLoc loc) {
  if (!reach_.any) {
    reach_.x = p.x();
    reach_.z = p.z();
  }
  reach_.any = true;
  reach_.x = std::max(reach_.x, p.x());
  reach_.z = std::max(reach_.z, p.z());
  reach_.last = loc;
}

// An arc reaches past its ends where it passes through its circle's top (+X) or front (+Z).
void LatheBackend::note_arc(const ir::Arc& a, SourceLoc loc) {
  note_cut_to(a.end, loc);
  const double r = (a.end - a.center).norm();
  for (const ir::Vec3& dir : {ir::Vec3(1, 0, 0), ir::Vec3(0, 0, 1)}) {
    const ir::Vec3 far = a.center + r * dir;
    if (arcgeo::distance_to_arc(a, far) <= 1e-6 * std::max(1.0, far.norm())) note_cut(far, loc);
  }
}

bool LatheBackend::clear_to_retract(SourceLoc loc, const char* before) {
  // A tool working on the minus-X side (a gang-tool lathe) has its own way home: not judged.
  if (!reach_.any || !reach_.went_in || !position_known_ || side_ < 0) return true;
  const double eps = 1e-6 * std::max(1.0, std::max(std::abs(reach_.x), std::abs(reach_.z)));
  if (pos_.x() >= reach_.x - eps || pos_.z() >= reach_.z - eps) return true;
  // At the axis (a face cut to the centre, a part-off): the face is behind the tool.
  if (pos_.x() <= 1.0 / ir::mm_per_unit(m_.units) / k_) return true;
  const double sx = k_ * m_.format('X').scale;
  const std::string retract = m_.codes.safe_retract.empty() ? "" : m_.codes.safe_retract.text;
  d_.error(loc.line > 0 ? loc : reach_.last,
           std::string(before) + " at X" + num_text(rounded(pos_.x() * sx)) + " Z" +
               num_text(rounded(pos_.z() * k_)) + " after a cut toward the spindle axis or the chuck, inside the reach of its cuts (out to X" +
               num_text(rounded(reach_.x * sx)) + ", forward to Z" + num_text(rounded(reach_.z * k_)) + "): " +
               (retract.empty() ? std::string("the turret would index there")
                                : "the machine's retract " + retract + " goes home in X and Z at once and would "
                                  "drag it through the part") +
               "; the CL must retract the tool clear of the part (a GOTO out of the groove, bore or shoulder) first");
  return false;
}

void LatheBackend::before_finish() {
  if (clear_to_retract({}, "the program ends")) return;
  reach_ = {};
}

}  // namespace clpc
