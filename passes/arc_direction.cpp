// arc-direction: decides which way each CL arc turns.
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and provides)
// is arc_direction_pass() at the end of this file.
#include "passes/arc_direction.h"

#include <cmath>

#include "ir/arc_geometry.h"
#include "passes/passes.h"

namespace clpc {

namespace {

constexpr double kTangentCos = 0.985;  // within ~10 degrees counts as tangent

const char* dir_word(ir::ArcDir d) { return d == ir::ArcDir::Ccw ? "counter-clockwise" : "clockwise"; }

std::string convention_text(const ir::Arc& a, ir::CamSystem cam) {
  switch (a.layout) {
    case ir::ArcLayout::Worded: return "the CIRCLE's sense word";
    case ir::ArcLayout::Movarc: return "MOVARC's angle (right-hand rule about its axis)";
    case ir::ArcLayout::Contour: return "the direction it sets off in (INDIRV)";
    default: break;
  }
  if (a.hint == ir::ArcDir::Cw) return "the NX CLSF convention (the axis of clockwise rotation)";
  return "the right-hand rule about the CIRCLE's axis (" + std::string(ir::cam_system_name(cam)) + ")";
}

// The sense comes from the right-hand rule clpc assumes for a CIRCLE axis when the file does
// not say which CAM system wrote it (not from a sense word, an angle or an INDIRV).
bool assumed_convention(const ir::Arc& a, ir::CamSystem cam) {
  return cam == ir::CamSystem::Unknown &&
         (a.layout == ir::ArcLayout::Creo7 || a.layout == ir::ArcLayout::NoRadius6 || a.layout == ir::ArcLayout::Nx11);
}

// The move leaving the arc is a chord of the same circle, going on round the way `dir` turns:
// the arc carries on past its end (an APT system writing a circle as CIRCLE, then points).
bool goes_on_round(const ir::Arc& a, const ir::Vec3& out, ir::ArcDir dir) {
  if (out.norm() == 0 || std::abs(out.dot(a.axis)) > 1e-6 * (1 + a.radius)) return false;
  const ir::Vec3 re = arcgeo::radial(a, a.end), rn = arcgeo::radial(a, a.end + out);
  if (std::abs(rn.norm() - a.radius) > std::max(0.001, 1e-6 * a.radius)) return false;
  const double turn = a.axis.dot(re.cross(rn));
  return dir == ir::ArcDir::Ccw ? turn > 0 : turn < 0;
}

void vote(ArcEvidence& e, ir::ArcDir d, const char* why) {
  if (d == ir::ArcDir::Ccw) {
    if (e.ccw_votes++ == 0) e.ccw_why = why;
  } else {
    if (e.cw_votes++ == 0) e.cw_why = why;
  }
}

// Votes from a move direction `v` against the arc's counter-clockwise tangent `t_ccw`.
void tangent_vote(ArcEvidence& e, const ir::Arc& a, const ir::Vec3& v, const ir::Vec3& t_ccw, double min_len,
                  const char* why) {
  ir::Vec3 plane = v - v.dot(a.axis) * a.axis;
  double len = plane.norm();
  if (len < min_len || len < 0.25 * v.norm() || t_ccw.norm() == 0) return;
  double c = plane.dot(t_ccw) / (len * t_ccw.norm());
  if (c >= kTangentCos) vote(e, ir::ArcDir::Ccw, why);
  else if (c <= -kTangentCos) vote(e, ir::ArcDir::Cw, why);
}

class ArcDirection : public Pass {
 public:
  void run(ir::Operation& op, PassContext& ctx) override {
    const double min_len = 20 * ctx.resolution();
    const double close_tol = 1e-7;
    auto& body = op.body;
    for (size_t i = 0; i < body.size(); ++i) {
      auto* a = std::get_if<ir::Arc>(&body[i].op);
      if (!a) {
        update_incoming(body[i]);
        continue;
      }
      ir::Vec3 in = incoming_;
      ir::Vec3 out = outgoing(body, i, a->end);
      if (a->dir == ir::ArcDir::Unknown) decide(op, *a, in, out, body[i].loc, ctx, min_len);
      if (a->dir != ir::ArcDir::Unknown && !(a->sweep > 0)) a->sweep = arcgeo::sweep_deg(*a, a->dir, close_tol);
      if (a->dir != ir::ArcDir::Unknown) {
        ir::Vec3 t = arcgeo::tangent_at(*a, 1.0);
        incoming_ = t * 1e9;  // a tangent direction, as long as any move
      } else {
        incoming_.setZero();
      }
      last_ = a->end;
      have_last_ = true;
    }
  }

 private:
  void update_incoming(const ir::Instr& in) {
    auto* m = std::get_if<ir::Move>(&in.op);
    if (!m) return;
    if (m->kind == ir::MoveKind::Feed && have_last_) incoming_ = m->point - last_;
    else incoming_.setZero();
    last_ = m->point;
    have_last_ = true;
  }

  static ir::Vec3 outgoing(const std::vector<ir::Instr>& body, size_t i, const ir::Vec3& end) {
    for (size_t j = i + 1; j < body.size(); ++j) {
      if (auto* m = std::get_if<ir::Move>(&body[j].op))
        return m->kind == ir::MoveKind::Feed ? ir::Vec3(m->point - end) : ir::Vec3::Zero();
      if (std::holds_alternative<ir::Arc>(body[j].op)) return ir::Vec3::Zero();
      if (std::holds_alternative<ir::ToolChange>(body[j].op)) return ir::Vec3::Zero();
    }
    return ir::Vec3::Zero();
  }

  void decide(const ir::Operation& op, ir::Arc& a, const ir::Vec3& in, const ir::Vec3& out, SourceLoc loc,
              PassContext& ctx, double min_len) {
    ArcEvidence e = arc_evidence(op, a, in, out, min_len);
    ir::ArcDir geo = e.geometry();
    if (a.hint != ir::ArcDir::Unknown) {
      a.dir = a.hint;
      if (e.via != ir::ArcDir::Unknown && e.via != a.hint) {
        // The CL's own points on the arc lie on the side the convention's arc does not pass:
        // either reading misses CL points (a tangent alone may be a cusp; a point is a point).
        ctx.diags.error(loc, "arc: " + convention_text(a, ctx.info.cam) + " says " + dir_word(a.hint) +
                                 ", but the CL's points on the arc (the GOTOs between the CIRCLE and its end) lie "
                                 "where it passes only if it turns " + dir_word(e.via) +
                                 ": the CL contradicts itself, and either way some of its points are missed");
        return;
      }
      if (geo != ir::ArcDir::Unknown && geo != a.hint && assumed_convention(a, ctx.info.cam) &&
          ((geo == ir::ArcDir::Ccw ? e.ccw_votes : e.cw_votes) >= 2 || goes_on_round(a, out, geo))) {
        // The convention is the one clpc assumes for a file whose CAM system it does not know
        // (the corpus shows no arc of a known system against its convention, and an APT system
        // may write the circle's canonical axis, whatever the way round): the geometry is the
        // better evidence where more than a tangent says so (a tangent alone may be a cusp): both
        // tangents, or the move after the arc going on round its circle. The two readings are
        // different cuts (a 45-degree arc against a 315-degree one through the pocket): refused.
        const std::string& why = geo == ir::ArcDir::Ccw ? e.ccw_why : e.cw_why;
        ctx.diags.error(loc, "arc: " + convention_text(a, ctx.info.cam) + " says " + dir_word(a.hint) + ", but " + why +
                                 " only if it turns " + dir_word(geo) + ", and " + (goes_on_round(a, out, geo) ? "the move after it goes on round its circle that way" : "so is the move leaving it") + ": the file does not say which CAM system wrote "
                                 "it, so whether its CIRCLE axes follow the right-hand rule is not known; have the CAM "
                                 "system write the arc's sense (CLW/CCLW) or name itself in the file");
        return;
      }
      if (geo != ir::ArcDir::Unknown && geo != a.hint) {
        const std::string& why = geo == ir::ArcDir::Ccw ? e.ccw_why : e.cw_why;
        ctx.diags.warning(loc,
                          "arc: " + convention_text(a, ctx.info.cam) + " says " + dir_word(a.hint) + ", and it is cut " +
                              dir_word(a.hint) + "; but " + why + " only if it turns " + dir_word(geo) +
                              " (a cusp or a plunge onto the arc?)",
                          "arc-geometry");
      }
      return;
    }
    if (geo != ir::ArcDir::Unknown) {
      a.dir = geo;
      return;
    }
    if (e.conflicting())
      ctx.diags.error(loc, "cannot decide which way this arc turns: " + e.ccw_why + " if counter-clockwise but " + e.cw_why +
                               " if clockwise, and this CIRCLE layout has no axis convention");
    else
      ctx.diags.error(loc,
                      "cannot decide which way this arc turns: this CIRCLE layout (no radius) has no axis convention "
                      "and no tangent move or point on the arc tells");
    a.dir = ir::ArcDir::Ccw;  // keep going to find further errors; no output is written
  }

  ir::Vec3 incoming_ = ir::Vec3::Zero();
  ir::Vec3 last_ = ir::Vec3::Zero();
  bool have_last_ = false;
};

}  // namespace

ArcEvidence arc_evidence(const ir::Operation& op, const ir::Arc& a, const ir::Vec3& in, const ir::Vec3& out,
                         double min_len) {
  ArcEvidence e;
  ir::Vec3 rs = arcgeo::radial(a, a.start), re = arcgeo::radial(a, a.end);
  // Points on the arc: each must lie within the sweep of the true direction.
  if (a.via_count > 0) {
    double end_ccw = arcgeo::ccw_angle(rs, re, a.axis);
    bool all_ccw = true, all_cw = true;
    for (uint32_t k = 0; k < a.via_count; ++k) {
      double v = arcgeo::ccw_angle(rs, arcgeo::radial(a, op.points[a.via_begin + k]), a.axis);
      if (!(v > 0 && v < end_ccw)) all_ccw = false;
      if (!(v > end_ccw)) all_cw = false;
    }
    if (all_ccw && !all_cw) vote(e, e.via = ir::ArcDir::Ccw, "the arc passes through its intermediate points");
    if (all_cw && !all_ccw) vote(e, e.via = ir::ArcDir::Cw, "the arc passes through its intermediate points");
  }
  tangent_vote(e, a, in, a.axis.cross(rs), min_len, "the arc is tangent to the move entering it");
  tangent_vote(e, a, out, a.axis.cross(re), min_len, "the arc is tangent to the move leaving it");
  return e;
}

const PassInfo& arc_direction_pass() {
  static const PassInfo info{
      .name = "arc-direction",
      .summary = "decide which way each CL arc turns (CW or CCW)",
      .expects = "arcs as lowered: start, end, centre, axis, and the sense the CL gives (the CAM system's CIRCLE "
                 "convention, a sense word, MOVARC's angle, INDIRV)",
      .guarantees = "every arc has a direction (CW or CCW about its axis) and a sweep, full turns included; the "
                    "CL's sense decides and geometry (intermediate points, tangent moves) only confirms it, with "
                    "a warning naming both readings where they disagree; an arc nothing decides is an error",
      .settings = "format.X (one output increment: how near a point must lie to the arc)",
      .needs = 0,
      .provides = ir::ArcsDecided,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<ArcDirection>()); },
  };
  return info;
}

}  // namespace clpc
