// Motion records: GOTO, FROM, GOHOME, GODLTA, CIRCLE (+ the RAPID one-shot).
#include <algorithm>
#include <cmath>

#include "ir/arc_geometry.h"
#include "lower/lower.h"
#include "lower/params.h"

namespace clpc {

namespace {

// Reads x,y,z[,i,j,k]; reports and returns false on a wrong count or a non-number.
bool read_point(const Record& r, Diagnostics& d, ir::Vec3& p, ir::Vec3& axis, bool& has_axis) {
  const auto& ps = r.params;
  for (size_t i = 0; i < ps.size(); ++i)
    if (!ps[i].is_number()) {
      d.error(ps[i].loc, std::string(r.major) + ": expected a number, found " +
                             (ps[i].is_group() ? "a parameter group (" + std::string(ps[i].text) + (ps[i].text.empty() ? "...)" : "/...)")
                                               : "'" + std::string(ps[i].text) + "'"));
      return false;
    }
  if (ps.size() != 3 && ps.size() != 6) {
    d.error(ps.size() > 6 || ps.size() == 4 || ps.size() == 5 ? ps[3].loc : r.end,
            std::string(r.major) + " needs 3 or 6 values (x,y,z[,i,j,k]), found " + std::to_string(ps.size()));
    return false;
  }
  p = {ps[0].number, ps[1].number, ps[2].number};
  has_axis = ps.size() == 6;
  if (has_axis) {
    ir::Vec3 a{ps[3].number, ps[4].number, ps[5].number};
    double n = a.norm();
    if (!(n > 1e-9)) {
      d.error(ps[3].loc, std::string(r.major) + ": the tool axis (i,j,k) must not be zero");
      return false;
    }
    // CAM systems write the axis as a unit vector, to however few digits (one digit, 0.7,0,0.7,
    // leaves it within 1.1 %). One far from length 1 (over 5 %) is no axis (six values read as two points, a
    // MULTAX/OFF file's own form): made one, it would tilt the tool at a guess.
    if (std::abs(n - 1) > 0.05) {
      d.error(ps[3].loc, std::string(r.major) + ": the tool axis (i,j,k) is not a unit vector (its length is " +
                             num_text(std::round(n * 1e4) / 1e4) + "): these are not a tool axis's values");
      return false;
    }
    axis = a / n;
  }
  return true;
}

}  // namespace

void Lowerer::move_to(const ir::Vec3& p, SourceLoc loc, ir::MoveKind kind, bool axis_written) {
  ensure_operation(loc);
  if (pending_arc_) {
    PendingArc pa = std::move(*pending_arc_);
    pending_arc_.reset();
    if (kind == ir::MoveKind::Rapid)
      d_.warning(loc, "RAPID before a CIRCLE's end point is ignored: arcs are cut at the feed rate", "rapid-arc");
    pa.arc.end = p;
    pa.arc.tool_axis = xf_dir(axis_);
    if (!on_circle(pa.arc, pa.loc, loc)) {
      pos_ = p;
      return;
    }
    push(pa.loc, pa.arc);
    arc_open_ = pa.open;
    pos_ = p;
    return;
  }
  // Creo writes every GOTO with its tool axis under MULTAX/ON: one that gives the arc's own
  // axis again still goes on round the arc (only the first was joined, and the rest cut as
  // chords 0.034 in off a 1 in arc, certified: verify read them so too).
  const auto* open_arc = arc_open_ ? std::get_if<ir::Arc>(&op_.body.back().op) : nullptr;
  const bool same_axis = !axis_written || (open_arc && (xf_dir(axis_) - open_arc->tool_axis).norm() < 1e-6);
  if (arc_open_ && kind == ir::MoveKind::Feed && same_axis && extend_arc(p, loc)) {
    pos_ = p;
    return;
  }
  if (kind == ir::MoveKind::Feed && has_pos_ && (p - pos_).norm() > 1e-9) {
    direction_ = (p - pos_).normalized();
    has_direction_ = true;
  }
  if (cycle_open_) ++cycle_holes_;
  ir::Move m;
  m.point = p;
  m.axis = xf_dir(axis_);
  m.kind = kind;
  m.axis_written = axis_written;
  push(loc, m);
  pos_ = p;
  has_pos_ = true;
}

// The CL must put the arc's start and end on its circle: a mismatch would make the control
// alarm or cut a different arc. Allowed: 0.01 mm, or 1e-6 of the radius.
bool Lowerer::on_circle(const ir::Arc& a, SourceLoc circle, SourceLoc end) {
  const double tol = std::max(0.01 / ir::mm_per_unit(info_.units), 1e-6 * a.radius);
  auto off = [&](const ir::Vec3& p) {
    ir::Vec3 v = p - a.center;
    return (v - v.dot(a.axis) * a.axis).norm() - a.radius;
  };
  double s = off(a.start), e = off(a.end);
  // In the file's units, without an exponent: "4e-04 off its circle of radius 1" said neither
  // the unit nor the limit (helper-66).
  const std::string unit = " " + std::string(ir::units_name(info_.units));
  auto length = [&](double x) {
    std::string t = fixed_text(x, 6);
    while (t.size() > 1 && t.back() == '0') t.pop_back();
    if (t.back() == '.') t.pop_back();
    return t + unit;
  };
  const std::string limit = " (at most " + length(tol) + " is taken: the control alarms, or cuts another arc)";
  if (std::abs(s) > tol) {
    d_.error(circle, "CIRCLE: the arc's start point (the previous position) is " + length(std::abs(s)) +
                         " off its circle of radius " + length(a.radius) + limit);
    return false;
  }
  if (std::abs(e) > tol) {
    d_.error(circle, "CIRCLE: the arc's end point (GOTO at line " + std::to_string(end.line) + ") is " +
                         length(std::abs(e)) + " off its circle of radius " + length(a.radius) + limit);
    return false;
  }
  return true;
}

// Creo may write intermediate points of an arc as further GOTOs. A point joins the arc when it
// lies on the circle, in the arc's plane, and carries the rotation on in the same sense;
// otherwise it is a move of its own (see docs/arcs.md).
bool Lowerer::extend_arc(const ir::Vec3& p, SourceLoc loc) {
  auto* arc = std::get_if<ir::Arc>(&op_.body.back().op);
  if (!arc || arc->extra_turns != 0) return false;
  const ir::Vec3 n = arc->axis;
  auto radial = [&](const ir::Vec3& q) {
    ir::Vec3 v = q - arc->center;
    return ir::Vec3(v - v.dot(n) * n);
  };
  double tol = std::max(1e-6, 1e-5 * arc->radius);
  double h_start = (arc->start - arc->center).dot(n);
  double h_end = (arc->end - arc->center).dot(n);
  double h_p = (p - arc->center).dot(n);
  ir::Vec3 rp = radial(p), re = radial(arc->end), rs = radial(arc->start);
  if (std::abs(rp.norm() - arc->radius) > tol) return false;
  if ((p - arc->end).norm() < tol) return false;
  const double step = std::atan2(std::abs(n.dot(re.cross(rp))), re.dot(rp));  // this step's angle
  const bool within_chord_tolerance = arc->radius * (1 - std::cos(step / 2)) <= 0.01 / ir::mm_per_unit(info_.units);
  // A Creo point on the arc's circle, far round it, that cannot join the arc: the CL does not
  // tell the straight move it would be from the arc carried on, and cut straight where the arc
  // was meant, it leaves the circle by the chord's sagitta.
  const bool creo_wide = info_.cam == ir::CamSystem::Creo && !within_chord_tolerance;
  auto refuse_wide = [&](const std::string& why) {
    d_.error(loc, "this point lies on the circle of the arc before it, " + fixed_text(step * 180 / 3.14159265358979323846, 1) +
                      " degrees round from its end, but " + why +
                      ": the CL does not tell the arc carried on from a straight move across, and cut straight it "
                      "would leave the circle by " + fixed_text(arc->radius * (1 - std::cos(step / 2)), 4) +
                      "; have the CAM system write the arc with its own CIRCLE records");
    return true;  // taken: refused, not cut either way
  };
  if (std::abs(h_end - h_start) > tol || std::abs(h_p - h_start) > tol) {
    if (creo_wide) return refuse_wide("at another height along its axis (a helix goes on by its own CIRCLE records)");
    return false;
  }
  // Same sense: every step along the arc turns the same way about the axis, and the whole
  // stays within one turn. A half turn (a step to the point opposite, as from one quadrant
  // point to the next but one) has no sense of its own, whatever sign the CL's rounding gives
  // it. Inside the arc (its first step, CIRCLE to its end) it follows the other steps, or the
  // CAM system's convention about the CIRCLE's axis; a half turn after the end is refused below.
  auto sense = [&](const ir::Vec3& a, const ir::Vec3& b) {
    double s = n.dot(a.cross(b));
    if (std::abs(s) > tol * arc->radius) return s > 0 ? 1 : -1;
    return a.dot(b) < 0 ? 0 : 2;  // 0: a half turn; 2: no step at all
  };
  // An arc given by its end alone turns the way the CL's convention says, however far (a
  // 270-degree CIRCLE is not the short way round); its points, where it has them, tell.
  int arc_sense = 0;
  const int hint_sense = arc->hint == ir::ArcDir::Ccw ? 1 : arc->hint == ir::ArcDir::Cw ? -1 : 0;
  if (arc->via_count == 0) arc_sense = hint_sense;
  ir::Vec3 from = rs;
  for (uint32_t k = 0; k <= arc->via_count && arc_sense == 0; ++k) {
    ir::Vec3 to = k < arc->via_count ? radial(op_.points[arc->via_begin + k]) : re;
    arc_sense = sense(from, to);
    from = to;
  }
  if (arc_sense == 0) arc_sense = hint_sense;
  const int step_sense = sense(re, rp);
  if (arc_sense == 2 || step_sense == 2) return false;
  if (arc_sense != 0 && step_sense != 0 && arc_sense != step_sense) return false;
  // Creo writes an arc's intermediate points as far apart as it likes (the evidence for joining
  // them). Other systems' CL (APT's points after a CIRCLE) keeps each chord within the CAM
  // tolerance of the arc, so a step whose chord leaves the arc by more than 0.01 mm is a
  // straight move that ends on the circle (a hexagon's edge after a corner arc), never an
  // arc: cut round, it would gouge by its sagitta. A closer step is the same cut either way.
  if (info_.cam != ir::CamSystem::Creo && !within_chord_tolerance) return false;
  // How far round the arc has come, each step the way the arc turns (the first may be the long
  // way), and this step with it. A point back on the start within rounding is a full turn.
  constexpr double kTwoPi = 2 * 3.14159265358979323846;
  auto directed = [&](const ir::Vec3& a, const ir::Vec3& b) {
    double ang = std::atan2(n.dot(a.cross(b)), a.dot(b)) * (arc_sense < 0 ? -1 : 1);
    return ang < -1e-12 ? ang + kTwoPi : std::max(ang, 0.0);
  };
  double turned = 0;
  ir::Vec3 q = rs;
  for (uint32_t k = 0; k < arc->via_count; ++k) {
    ir::Vec3 v = radial(op_.points[arc->via_begin + k]);
    turned += arc_sense != 0 ? directed(q, v) : std::atan2(std::abs(n.dot(q.cross(v))), q.dot(v));
    q = v;
  }
  turned += (arc_sense != 0 ? directed(q, re) : std::atan2(std::abs(n.dot(q.cross(re))), q.dot(re))) + step;
  if (turned >= kTwoPi - 1e-6) {
    if (creo_wide) return refuse_wide("joined, the arc would close a full turn or pass it");
    return false;  // no arc: a move of its own (a step within the chord tolerance)
  }
  if (step_sense == 0) {
    // The next point opposite the arc's end: half a turn further round, or a straight move
    // across the centre (a pass over a round face). The CL does not tell them apart, and each
    // cut where the other was meant leaves the path by the radius.
    d_.error(loc, "this point lies opposite the end of the arc before it, on its circle: half a turn further round or a "
                  "straight move through the centre, which the CL does not tell apart; have the CAM system write the "
                  "arc's points closer, or another point between");
    return true;  // taken: refused, not cut either way
  }
  if (inverse_time_) {
    // Under FEDRAT/INVERS each CL move has its own time (one over its minutes): moves joined
    // into one block would share one. A step whose chord stays within 0.01 mm of the arc is
    // its own move; a wider one (Creo's) is the arc, which no one F can time.
    if (within_chord_tolerance) return false;
    d_.error(loc, "an inverse-time feed (FEDRAT/INVERS) on an arc given by more than one point: the arc is one block, "
                  "and one F cannot give each point's move its time; have the CAM system write a feed per minute here");
    return true;  // taken: refused, not cut as a chord
  }
  op_.points.push_back(arc->end);
  if (arc->via_count == 0) arc->via_begin = uint32_t(op_.points.size() - 1);
  ++arc->via_count;
  arc->end = p;
  return true;
}

// Motion before any tool is loaded, in a file that loads tools later: no tool length offset is
// in force to move by. A rapid there is where the tool starts (CATIA writes its start point
// before the first tool change), taken as FROM with a warning; cutting motion is an error.
// (A file that loads no tool at all is the backend's to judge: a mill refuses its first cut, a lathe
// cuts with the tool the turret holds.)
bool Lowerer::tool_ready(SourceLoc loc, ir::MoveKind kind) {
  if (toolno_named_ >= 0) {
    if (toolno_named_ != tool_ && tool_ >= 0)
      d_.warning(toolno_loc_, "TOOLNO names tool " + std::to_string(toolno_named_) + ", and no LOADTL or TURRET follows it "
                              "before the move at line " + std::to_string(loc.line) + ": the moves after it are cut with T" +
                              std::to_string(tool_) + ", the tool loaded (TOOLNO describes a tool; a post that changes "
                              "tools on it would cut them with T" + std::to_string(toolno_named_) + ")",
                 "toolno");
    else if (tool_ < 0 && info_.tools.empty())  // (a file that loads none: its first cut is refused; this says which record meant one)
      d_.warning(toolno_loc_, "TOOLNO names tool " + std::to_string(toolno_named_) + ", and no LOADTL or TURRET follows it "
                              "before the move at line " + std::to_string(loc.line) + ": no tool is loaded (TOOLNO "
                              "describes a tool; LOADTL/" + std::to_string(toolno_named_) + " or TURRET/" +
                              std::to_string(toolno_named_) + " loads it): a mill refuses the cut, a lathe's program "
                              "writes no T word and cuts with the tool and offset the turret holds",
                 "toolno");
    toolno_named_ = -1;
  }
  if (tool_ >= 0 || info_.tools.empty()) return true;
  const ir::ToolInfo& first = info_.tools.front();
  const std::string later = "T" + std::to_string(first.number) +
                            (first.first_use.valid() ? " at line " + std::to_string(first.first_use.line) : std::string());
  if (kind != ir::MoveKind::Feed) {
    d_.warning(loc, "rapid motion before the first tool change (" + later +
                        ") is taken as the start point (as FROM): no motion is written for it",
               "motion-before-tool");
    return true;
  }
  if (!reported_no_tool_)
    d_.error(loc, "motion before any tool is loaded; the file loads " + later + " later");
  reported_no_tool_ = true;
  return false;
}

// How many values one point of a GOTO takes (3, or 6 with its tool axis), or 0 with the error
// said. APT's GOTO carries a list of points (ISO 3592): three values each under MULTAX/OFF,
// six under MULTAX/ON. A count that reads two ways is refused, not read at a guess: six under
// MULTAX/OFF whose last three make a unit vector (a CAM system that means a point and its
// axis has left MULTAX/OFF in force), or a multiple of six above six with no MULTAX said.
int Lowerer::goto_stride(const Record& r) const {
  const size_t n = r.params.size();
  if (n == 3 || n < 6 || !std::all_of(r.params.begin(), r.params.end(), [](const Param& p) { return p.is_number(); }))
    return 3;  // (read_point says what is wrong)
  auto unit = [&](size_t i) {
    const double l = std::hypot(r.params[i].number, r.params[i + 1].number, r.params[i + 2].number);
    return std::abs(l - 1) <= 0.05;
  };
  if (multax_off_) {
    if (n % 3 != 0) {
      d_.error(r.params[n - n % 3].loc, "GOTO: " + std::to_string(n) + " values under MULTAX/OFF, which are not whole points of three");
      return 0;
    }
    if (n == 6 && unit(3)) {
      d_.error(r.params[3].loc, "GOTO: six values under MULTAX/OFF: APT reads two points, a tool axis needs "
                                "MULTAX/ON; have the CAM system write MULTAX/ON before points with a tool axis");
      return 0;
    }
    return 3;
  }
  if (n == 6) return 6;
  if (multax_on_) {
    if (n % 6 != 0) {
      d_.error(r.params[n - n % 6].loc, "GOTO: " + std::to_string(n) + " values under MULTAX/ON, which are not whole points "
                                        "of six (x,y,z,i,j,k)");
      return 0;
    }
    return 6;
  }
  if (n % 6 == 0) {
    d_.error(r.params[3].loc, "GOTO: " + std::to_string(n) + " values and no MULTAX said: " + std::to_string(n / 3) +
                                  " points, or " + std::to_string(n / 6) + " with their tool axes? Have the CAM system "
                                  "write MULTAX/ON or MULTAX/OFF before it");
    return 0;
  }
  if (n % 3 != 0) {
    d_.error(r.params[n - n % 3].loc, "GOTO: " + std::to_string(n) + " values, which are not whole points of three");
    return 0;
  }
  return 3;
}

void Lowerer::lower_goto(const Record& r) {
  const int stride = goto_stride(r);
  if (stride == 0) return;
  const size_t n = r.params.size();
  if (n <= size_t(stride) || n % size_t(stride) != 0) {
    goto_point(r);
    return;
  }
  // Several points in one record: each is a GOTO of its own. RAPID before it is taken for its
  // first point only, the reading that cannot traverse through the part (the rest are fed).
  const bool rapid = rapid_next_;
  for (size_t i = 0; i < n; i += size_t(stride)) {
    Record one = r;
    one.params = r.params.subspan(i, size_t(stride));
    one.loc = r.params[i].loc;
    if (i > 0 && rapid && i == size_t(stride))
      d_.warning(one.loc, "RAPID before a GOTO of several points is taken for its first point: the rest are fed (some "
                          "posts make them all rapid; give each its own RAPID and GOTO if that is meant)",
                 "rapid-points");
    goto_point(one);
  }
}

void Lowerer::goto_point(const Record& r) {
  ir::Vec3 p, a;
  bool has_axis = false;
  if (!read_point(r, d_, p, a, has_axis)) return;
  p = xf_point(p);
  if (has_axis) axis_ = a;
  ir::MoveKind kind = rapid_next_ ? ir::MoveKind::Rapid : ir::MoveKind::Feed;
  rapid_next_ = false;
  if (!tool_ready(r.loc, kind)) return;
  if (tool_ < 0 && !info_.tools.empty()) kind = ir::MoveKind::From;
  if (kind == ir::MoveKind::Rapid && cycle_open_ && drilling_) {
    // APT drills every GOTO while a cycle is on; some posts take a RAPID GOTO as a move between
    // holes (round a boss, up over a hole). Read as a hole, a via point was drilled 2 mm deep.
    d_.error(r.loc, "a RAPID GOTO while CYCLE/" + cycle_name_ + " (line " + std::to_string(cycle_loc_.line) +
                        ") is on: a hole, or a move between holes? The CL does not say; end the cycle (CYCLE/OFF) "
                        "before the move and give it again after it");
    pos_ = p;
    return;
  }
  move_to(p, r.loc, kind, has_axis);
}

void Lowerer::lower_from(const Record& r) {
  ir::Vec3 p, a;
  bool has_axis = false;
  if (!read_point(r, d_, p, a, has_axis)) return;
  p = xf_point(p);
  // FROM says where the tool stands; it moves nothing. After a cut (the tool is where the CL
  // left it, maybe in the material: not after a tool change, a rapid or a GOHOME) a FROM
  // elsewhere asks for a jump no post can make: the move between is not in the CL. Refused
  // rather than guessed (the next move, made from where the tool is, could cut the part).
  const double tol = 0.001 / ir::mm_per_unit(info_.units);
  // After a cycle's hole the tool is not at the hole's GOTO but returned up its axis: a FROM
  // on that line says where (drill-cycles checks it against the level the cycle returns to).
  const ir::Vec3 up = xf_dir(axis_);
  const bool over_hole = last_move_hole_ && has_pos_ && (p - pos_).dot(up) > 0 &&
                         ((p - pos_) - up * (p - pos_).dot(up)).norm() <= tol;
  if (cut_since_tool_change_ && !last_move_rapid_ && !over_hole && has_pos_ && (p - pos_).norm() > tol) {
    d_.error(r.loc, "FROM after motion puts the tool at (" + num_text(p.x()) + ", " + num_text(p.y()) + ", " +
                        num_text(p.z()) + "), but the CL left it at (" + num_text(pos_.x()) + ", " + num_text(pos_.y()) +
                        ", " + num_text(pos_.z()) + "): the move between is not in the CL; have the CAM system write "
                        "it (a GOTO)");
    return;
  }
  // FROM is a motion record (APT's CLDATA): a RAPID before it is used up by it, and the move
  // after it is a feed unless a RAPID of its own says otherwise. Carried on, it made the plunge
  // after FROM a rapid into the part.
  rapid_next_ = false;
  if (cut_since_tool_change_ && !at_home_ && !over_hole && has_pos_ && (p - pos_).norm() > tol) {
    from_gap_ = r.loc;
    from_gap_what_ = "by the FROM at line " + std::to_string(r.loc.line) + ", elsewhere than the rapid before it left the tool, at (" +
                     num_text(pos_.x()) + ", " + num_text(pos_.y()) + ", " + num_text(pos_.z()) + ")";
  }
  if (has_axis) axis_ = a;
  from_ = p;
  has_from_ = true;
  from_approach_ = !cut_since_tool_change_;
  from_loc_ = r.loc;
  from_axis_ = xf_dir(axis_);
  if (pending_arc_) {
    d_.error(r.loc, "FROM cannot end a CIRCLE");
    pending_arc_.reset();
  }
  move_to(p, r.loc, ir::MoveKind::From, has_axis);
}

void Lowerer::lower_gohome(const Record& r) {
  ir::Vec3 p = from_, a;
  bool has_axis = false;
  const bool by_axis = !r.params.empty() && std::all_of(r.params.begin(), r.params.end(), [](const Param& q) {
    return q.is("XAXIS") || q.is("YAXIS") || q.is("ZAXIS");
  });
  if (by_axis) {
    // GOHOME/ZAXIS (APT posts): home along the named axes only, the others where the tool is
    // (it stopped the post). Home is the FROM point, as for GOHOME alone. Z is the tool's way
    // up only while the tool stands along Z: tilted, the move would not be a retract.
    if (!has_from_ || !has_pos_) {
      d_.error(r.loc, std::string("GOHOME/") + std::string(r.params[0].text) + " needs an earlier FROM (home) and a position");
      return;
    }
    if (std::abs(xf_dir(axis_).z() - 1) > 1e-9) {
      d_.error(r.loc, "GOHOME by axis with the tool tilted: a move along the machine's axes to home would not take the "
                      "tool up its axis; have the CAM system write the retract as a GOTO");
      return;
    }
    p = pos_;
    for (const Param& q : r.params) {
      const int i = q.is("XAXIS") ? 0 : q.is("YAXIS") ? 1 : 2;
      p[i] = from_[i];
    }
  } else if (r.params.empty()) {
    if (!has_from_) {
      d_.error(r.loc, "GOHOME without a point needs an earlier FROM");
      return;
    }
  } else if (!read_point(r, d_, p, a, has_axis)) {
    return;
  } else {
    p = xf_point(p);
  }
  if (has_axis) axis_ = a;
  rapid_next_ = false;
  ir::MoveKind kind = tool_ < 0 && !info_.tools.empty() ? ir::MoveKind::From : ir::MoveKind::Rapid;
  tool_ready(r.loc, kind);
  move_to(p, r.loc, kind, has_axis);
  at_home_ = true;  // where the machine's home is, the CL may not know: a FROM after it says
}

void Lowerer::lower_godlta(const Record& r) {
  ParamReader ps(r, d_);
  if (!ps.all_numbers() || (ps.size() != 1 && ps.size() != 3)) {
    d_.error(ps.size() ? ps[0].loc : r.end, "GODLTA needs dx,dy,dz or one distance along the tool axis");
    return;
  }
  if (!has_pos_) {
    d_.error(r.loc, "GODLTA needs a previous position");
    return;
  }
  ir::Vec3 delta = xf_dir(ps.size() == 1 ? ir::Vec3(axis_ * ps[0].number) : ir::Vec3(ps[0].number, ps[1].number, ps[2].number));
  ir::MoveKind kind = rapid_next_ ? ir::MoveKind::Rapid : ir::MoveKind::Feed;
  rapid_next_ = false;
  if (!tool_ready(r.loc, kind)) return;
  if (tool_ < 0 && !info_.tools.empty()) kind = ir::MoveKind::From;
  move_to(pos_ + delta, r.loc, kind, false);
}

// The sense a CIRCLE's axis means, by the CAM system that wrote it (docs/arcs.md, with the
// evidence): NX documents its axis "assuming a clockwise direction" (Makino FFCAM writes the
// same CLSF form); APT, Creo, CATIA, SolidWorks CAM and the rest use the right-hand rule. A
// file whose system is not recognised goes by its layout: 11 values are NX's CLSF form.
ir::ArcDir circle_convention(ir::CamSystem cam, ir::ArcLayout layout) {
  if (cam == ir::CamSystem::Nx) return ir::ArcDir::Cw;
  if (cam == ir::CamSystem::Unknown && layout == ir::ArcLayout::Nx11) return ir::ArcDir::Cw;
  return ir::ArcDir::Ccw;
}

// INDIRV before a CIRCLE gives the way the tool sets off round it (APT: the direction of the
// next motion). It was dropped, and an arc INDIRV sent clockwise the long way round was cut
// counter-clockwise by the axis's right-hand rule, certified (helper-48). It decides the sense
// where nothing else does (a file of no known CAM system, no sense word); where the circle's
// own sense says the other way, or INDIRV points along the radius or the axis, the CL does not
// say which way the tool goes: an error at the CIRCLE.
bool Lowerer::indirv_sense(ir::Arc& a, bool sense_said, SourceLoc loc) {
  has_indirv_ = false;
  const ir::Vec3 radial = a.start - a.center;
  const ir::Vec3 in_plane = radial - radial.dot(a.axis) * a.axis;
  const double turn = in_plane.normalized().cross(indirv_).dot(a.axis);
  const std::string where = "INDIRV at line " + std::to_string(indirv_loc_.line);
  if (!(std::abs(turn) > 1e-3)) {
    d_.error(loc, "CIRCLE: " + where + " points along the circle's radius or axis: which way round the tool goes "
                  "is not said; give INDIRV along the circle, or the sense (CLW, CCLW)");
    return false;
  }
  const ir::ArcDir by_indirv = turn > 0 ? ir::ArcDir::Ccw : ir::ArcDir::Cw;
  if (sense_said && by_indirv != a.hint) {
    d_.error(loc, "CIRCLE: " + where + " sets off " + (by_indirv == ir::ArcDir::Ccw ? "counter-clockwise" : "clockwise") +
                      " about the circle's axis, the circle's own sense is the other way: which way the tool goes is "
                      "ambiguous");
    return false;
  }
  a.hint = by_indirv;
  a.layout = ir::ArcLayout::Contour;  // (said so in the arc-direction pass's messages)
  return true;
}

void Lowerer::lower_circle(const Record& r) {
  ParamReader ps(r, d_);
  size_t n = 0;
  while (n < ps.size() && ps[n].is_number()) ++n;
  int times = 1;
  ir::ArcDir worded = ir::ArcDir::Unknown;
  if (n < ps.size()) {
    if (ps[n].is("TIMES") && n + 2 == ps.size()) {
      auto t = ps.integer(n + 1, "the number of turns after TIMES", 1, 10000);
      if (!t) return;
      times = *t;
    } else if (n + 1 == ps.size() && (ps[n].is("CLW") || ps[n].is("CLOCKWISE"))) {
      worded = ir::ArcDir::Cw;  // CAMWorks writes the sense
    } else if (n + 1 == ps.size() && (ps[n].is("CCLW") || ps[n].is("COUNTERCLOCKWISE"))) {
      worded = ir::ArcDir::Ccw;
    } else {
      d_.error(ps[n].loc, "CIRCLE: unexpected '" + std::string(ps[n].name()) +
                              "' (only TIMES,n or the sense, CLW or CCLW, may follow the values)");
      return;
    }
  }
  if (n != 6 && n != 7 && n != 11) {
    d_.error(n > 0 ? ps[std::min<size_t>(n, ps.size()) - 1].loc : r.end,
             "CIRCLE needs 6, 7 or 11 values (xc,yc,zc,i,j,k[,r[,...]]), found " + std::to_string(n));
    return;
  }
  if (pending_arc_) {
    d_.error(pending_arc_->loc, "CIRCLE is not followed by a GOTO giving its end point");
    pending_arc_.reset();
  }
  if (!tool_ready(r.loc, ir::MoveKind::Feed)) return;
  if (!has_pos_) {
    d_.error(r.loc, "CIRCLE needs a start point: no motion comes before it");
    return;
  }
  ir::Arc a;
  a.start = pos_;
  a.center = xf_point({ps[0].number, ps[1].number, ps[2].number});
  ir::Vec3 axis = xf_dir({ps[3].number, ps[4].number, ps[5].number});
  double len = axis.norm();
  if (!(len > 1e-9)) {
    d_.error(ps[3].loc, "CIRCLE: the axis (i,j,k) must not be zero");
    return;
  }
  a.axis = axis / len;
  a.extra_turns = uint16_t(times - 1);
  if (n == 6) {
    a.layout = ir::ArcLayout::NoRadius6;
    ir::Vec3 v = pos_ - a.center;
    a.radius = (v - v.dot(a.axis) * a.axis).norm();
    if (!(a.radius > 1e-9)) {
      d_.error(r.loc, "CIRCLE: the start point lies on the circle's axis, so the radius (not given) is zero");
      return;
    }
  } else {
    a.radius = ps[6].number;
    if (!(a.radius > 0)) {
      d_.error(ps[6].loc, "CIRCLE: the radius must be greater than zero, found " + num_text(a.radius));
      return;
    }
    a.layout = n == 11 ? ir::ArcLayout::Nx11 : ir::ArcLayout::Creo7;
  }
  a.hint = worded != ir::ArcDir::Unknown ? worded : circle_convention(info_.cam, a.layout);
  if (worded != ir::ArcDir::Unknown) a.layout = ir::ArcLayout::Worded;
  const bool open = a.layout == ir::ArcLayout::Creo7;
  if (has_indirv_ && !indirv_sense(a, worded != ir::ArcDir::Unknown || info_.cam != ir::CamSystem::Unknown, r.loc)) return;
  if (rapid_next_) {
    d_.warning(r.loc, "RAPID before a CIRCLE is ignored: arcs are cut at the feed rate", "rapid-arc");
    rapid_next_ = false;
  }
  ensure_operation(r.loc);
  arc_open_ = false;
  pending_arc_ = PendingArc{a, r.loc, open};
}

}  // namespace clpc
