// The tilted working plane of 3+2 work on controls that have one (Fanuc G68.2, Haas G268):
// a frame whose Z is the tool axis, set by an origin and three Euler angles, in which the
// program's X Y Z are then written. Used by the kinematics pass (the angles for a tool axis),
// the limits pass and the G-code reader (the rotation the angles stand for).
//
// The frame clpc chooses for a tool axis n is the least tilt that takes the part's Z to n: a
// rotation about a horizontal axis (perpendicular to Z and n), so the plane's X and Y stay as
// near the part's as they can. Its origin is the part zero.
#pragma once

#include "ir/ir.h"

namespace clpc {

// The order of the three angles (docs/kinematics.md, "Tilted working planes"):
//   zxz: R = Rz(I) Rx(J) Rz(K), rotations about Z, the new X, the new Z (Fanuc G68.2);
//   xyz: R = Rx(I) Ry(J) Rz(K), rotations about X, the new Y, the new Z.
enum class EulerOrder : uint8_t { Zxz, Xyz };

namespace plane {

// The rotation R (plane -> part: a point q written in the plane is R q in the part frame) the
// angles (degrees) stand for.
ir::Mat3 rotation(const ir::Vec3& angles_deg, EulerOrder order);

// The angles (degrees) of a rotation R, within (-180, 180]; where two angles share one
// freedom (zxz at J = 0, xyz at J = +-90), the third is 0.
ir::Vec3 angles(const ir::Mat3& r, EulerOrder order);

// The least tilt taking +Z to the unit vector n (identity for n = +Z; for n = -Z, half a turn
// about X).
ir::Mat3 least_tilt(const ir::Vec3& n);

}  // namespace plane
}  // namespace clpc
