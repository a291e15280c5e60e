// Geometry of CL arcs and helices, shared by the arc passes and the verifier.
#pragma once

#include <vector>

#include "ir/ir.h"

namespace clpc::arcgeo {

using ir::Arc;
using ir::Vec3;

constexpr double kPi = 3.14159265358979323846;

// Part of p - centre perpendicular to the axis.
Vec3 radial(const Arc& a, const Vec3& p);
// Height of p along the axis, measured from the centre.
double axial(const Arc& a, const Vec3& p);
// Angle in [0, 2*pi) turning from u to v right-handed about unit n.
double ccw_angle(const Vec3& u, const Vec3& v, const Vec3& n);
// True when start and end coincide in the arc's plane (a full circle, or whole turns).
bool closes(const Arc& a, double tol);
// Sweep in degrees if the arc turns `dir` about its axis (full turns included).
double sweep_deg(const Arc& a, ir::ArcDir dir, double close_tol);
// Sign of rotation about a.axis: +1 for Ccw, -1 for Cw.
inline double sense(ir::ArcDir d) { return d == ir::ArcDir::Cw ? -1.0 : 1.0; }
// A decided arc with what every point and distance query needs worked out once: the
// verifier asks a program arc for the distance of a dozen points, and a CL arc for as many
// points, so each query costs a sine and cosine or one arc tangent, no more.
class ArcProbe {
 public:
  explicit ArcProbe(const Arc& a);
  // The point a fraction t in [0, 1] along the arc.
  Vec3 point(double t) const;
  // The points at fractions 1/n, 2/n, .. (n-1)/n into `out` (resized; its storage reused):
  // one sine and cosine for them all, each next point turned from the last by the step.
  void interior_points(int n, std::vector<Vec3>& out) const;
  // Distance from p to the arc (helix), within its sweep.
  double distance(const Vec3& p) const;

 private:
  Vec3 start_, end_, center_, axis_, rs_, u_, w_;
  double r0_, r1_, h0_, h1_, sweep_deg_, phi_total_;
  bool cw_;
};

// The point a fraction t in [0, 1] along a decided arc (helices rise linearly with angle;
// the radius moves linearly from the start's to the end's).
Vec3 point_at(const Arc& a, double t);
// Unit tangent of the decided arc at fraction t, projected into the arc's plane.
Vec3 tangent_at(const Arc& a, double t);
// Distance from p to a decided arc (helix), within its sweep.
double distance_to_arc(const Arc& a, const Vec3& p);
// The largest sweep (degrees) whose chord stays within `tol` of an arc of radius r.
double sweep_for_chord_error(double r, double tol);

}  // namespace clpc::arcgeo
