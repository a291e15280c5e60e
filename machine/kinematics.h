// The kinematic model of a machine's rotary axes (from its description's [kinematics]):
// forward transforms and every inverse solution of a tool axis. Pure math, shared by the
// kinematics and offset-table passes, the G-code interpreter and the tests.
//
// A machine has up to two rotary axes, each on the table side (it turns the part) or the head
// side (it turns the tool), listed from the machine base outwards. A table axis turns the part
// by `direction` x angle about `axis` through `center`; a head axis turns the tool likewise.
// Coordinates are the program's frame at all rotaries zero, in output units; the tool points
// along +Z when the head axes are at zero.
#pragma once

#include <optional>

#include <array>
#include <vector>

#include "machine/machine.h"

namespace clpc::kin {

using ir::Mat3;
using ir::Vec3;

constexpr int kMaxRotaries = 2;
using Angles = std::array<double, kMaxRotaries>;  // degrees, as the machine's axis words

Mat3 rotation(const Vec3& axis, double degrees);

// Part to machine: where a part point is after the table axes turn (head axes ignored).
Vec3 table_point(const KinematicsSettings& k, const Angles& a, const Vec3& p);
Mat3 table_rotation(const KinematicsSettings& k, const Angles& a);
// The tool axis in machine coordinates (head axes).
Vec3 head_axis(const KinematicsSettings& k, const Angles& a);
// The tool axis the rotaries give, seen from the part.
Vec3 tool_axis_in_part(const KinematicsSettings& k, const Angles& a);

// Where the programmed point must be, without tool-centre-point control, for the tool tip to
// be at part point `tip`: the table axes move the part; head axes swing the tip about their
// centres, `pivot` = the distance from the tip to the head axes' centres along the tool at zero.
Vec3 machine_point(const KinematicsSettings& k, const Angles& a, const Vec3& tip, double pivot);
// The inverse: the tool tip in part coordinates for a programmed machine point.
Vec3 part_tip(const KinematicsSettings& k, const Angles& a, const Vec3& machine, double pivot);

struct Solution {
  Angles a{0, 0};
  bool free[kMaxRotaries] = {false, false};  // singular: any value of this axis will do
};

// Every solution (angles in (-180, 180]) turning the tool onto `axis` (unit, part frame).
// Empty when no rotary angle can (a 4-axis machine and an axis off its cone).
std::vector<Solution> solve(const KinematicsSettings& k, const Vec3& axis);

// The position to take for `axis`: of the solutions within limits (each angle at every turn a
// limited axis allows, the turn nearest `current` for a winding axis, [0, 360) for a modulo
// one), the least rotary travel from `current` (from zero when null), the axes' preferred sign
// breaking ties — or coming first, with `sign_first` (the first position, the singularity). A
// free (singular) axis stays where it is. `jump`: a cheaper solution exists only beyond the
// limits, so following the path means jumping to this one.
struct Choice {
  Angles a{0, 0};
  bool found = false;
  bool jump = false;
};
Choice choose(const KinematicsSettings& k, const Vec3& axis, const Angles* current, bool sign_first);

// Angular distance between two unit vectors, in degrees.
double angle_between(const Vec3& a, const Vec3& b);

// The rotary that is free where the tool lies along an axis of the chain (the pole: the C of a
// B/C trunnion with the tool vertical, or of a B head over a C table), if the machine has one.
std::optional<size_t> pole_free_axis(const KinematicsSettings& k);

// How far (degrees) the unit vector v lies from the great-circle arc from unit a0 to unit a1:
// the CL's sweep of the tool axis between two points, whatever rate along it was meant.
double off_sweep(const Vec3& v, const Vec3& a0, const Vec3& a1);

// The angle (degrees) the tool axis may leave that sweep halfway through a block. Which path
// the CAM system meant between two points is not in the CL: the great circle, or the rotaries'
// own (a wrap about C at a constant tilt, 15 degree steps at B30, is 0.21 degrees off the great
// circle halfway and is right as the rotaries cut it). One degree is beyond any such choice
// and catches the swing of C near the pole (10 degrees off, certified; helper-63).
constexpr double kMidBlockAxisTolerance = 1.0;

// How far axis r turns from `from` to `to` (degrees, signed), as the control moves it: a
// modulo axis (positions in [0, 360)) the short way, any other by the difference.
double travel(const RotaryAxis& r, double from, double to);

// The angles a fraction t of the way from a0 to a1, as the control interpolates them.
Angles between(const KinematicsSettings& k, const Angles& a0, const Angles& a1, double t);

// ROTATE/AAXIS,INCR,a and ROTABL turn the table between pieces of motion the CL writes the same
// way each time (Creo dwnhole.ncl.3: a subroutine called at ten A positions). The motion after
// them is the CL's as the machine sees it with that table axis turned by the angles so far: in
// the part frame, p = T(index)^-1 q, T the table's rotation for the machine's own axis of that
// name (its direction as the machine description gives it). The signed angle decides; CLW and
// CCLW only say which way round the table goes. Shared by the kinematics pass and verify.
struct RotaryIndexing {
  Angles angles{0, 0};
  Mat3 rotation = Mat3::Identity();  // CL as written -> part frame
  bool on = false;                   // a turn other than none is in force
  // Takes one index record; false with `why` where the machine has no such table axis (an
  // absolute 0 with nothing indexed is then no turn at all, and true).
  bool apply(const KinematicsSettings& k, const ir::RotaryIndex& ri, std::string& why);
};

}  // namespace clpc::kin
