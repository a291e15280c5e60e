// rough-cycles (lathe): roughing written as plain CL motion becomes one G71 (turning) or G72
// (facing) stock-removal cycle, with G70 where the CL finishes the profile right after, when
// and only when the control's expansion of the cycle (ir/stock_model) makes the CL's moves,
// move for move, within the tolerance.
//
// The motion is read as the control's type I cycle runs (docs/lathe.md, "Stock removal"): from
// the start point A, levels (an infeed along the level axis from A's cutting-axis position, a
// cut along the other axis, a pull-out at 45 degrees, a rapid back), each Δd deeper; then an
// infeed to the shifted profile and the last cut along it; a rapid back to A. Optionally the
// finishing pass: from A along the level axis to A', the profile, a rapid back to A: its
// distance from the last cut gives the allowances. The words are rounded as they will be
// written, the cycle expanded and compared with the CL; anything else (another pull-out, a
// level cut that climbs the profile as Creo's do, a feed that changes) keeps the motion, and
// where the motion looked like roughing a note says why. A CYCLE/ROUGH section is the
// backend's already and is left alone, as are THREAD sections.
//
// Its contract is rough_cycles_pass() at the end of this file.
#include <cmath>
#include <string>

#include "ir/stock_model.h"
#include "machine/format.h"
#include "passes/motion_state.h"
#include "passes/passes.h"
#include "support/text.h"

namespace clpc {

namespace {

// One motion instruction of a run, as the cycle model sees it.
struct Motion {
  size_t index = 0;  // in the operation's body
  stock::Step::Kind kind = stock::Step::Kind::Feed;
  ir::Vec3 to, center;
  bool ccw = false;  // arcs: about +Y
  ir::Feed feed;     // in force for it
};

// What the motion says the cycle is, before the proof.
struct Candidate {
  stock::Params params;
  std::vector<stock::Element> profile;
  size_t cycle_end = 0;       // motions of the roughing (levels, last cut, return)
  size_t profile_first = 0;   // the motion that makes the profile's first block
  size_t end = 0;             // motions replaced (with the finishing pass)
  bool finish = false;
  int levels = 0;
  size_t roughing_end = 0;    // motions of the levels read (of any shape)
};

class RoughCycles : public Pass {
 public:
  void run(ir::Operation& op, PassContext& ctx) override {
    if (!ctx.machine.is_lathe()) return;
    const Codes& c = ctx.machine.codes;
    if (c.rough_turn.empty() && c.rough_face.empty()) return;
    tol_ = std::max(ctx.tolerance(), 1e-9);
    auto& body = op.body;
    std::vector<ir::Instr> out;
    out.reserve(body.size());
    size_t i = 0;
    while (i < body.size()) {
      // Sections the lowering marked are someone else's: as they are.
      if (const size_t j = marked_section_end(body, i); j != i) {
        for (; i < j; ++i) keep(body[i], out);
        continue;
      }
      size_t next = 0;
      if (at_.have_pos && level_starts(body, i) && collapse(body, i, ctx, out, next)) {
        i = next;
        continue;
      }
      // Past roughing that stays as moves at once: each of its moves would start no cycle.
      for (const size_t stop = std::max(next, i + 1); i < stop && i < body.size(); ++i) keep(body[i], out);
    }
    body.swap(out);
  }

 private:
  void keep(ir::Instr& in, std::vector<ir::Instr>& out) {
    // A move that goes nowhere starts nothing: the compensation waits on.
    if (const auto* c = std::get_if<ir::CutterComp>(&in.op)) comp_waits_ = c->side != ir::CompSide::Off;
    else if (const auto* m = std::get_if<ir::Move>(&in.op);
             (m && m->kind != ir::MoveKind::From && (!at_.have_pos || (m->point - at_.pos).norm() > 1e-9)) ||
             std::holds_alternative<ir::Arc>(in.op))
      comp_waits_ = false;
    at_.track(in);
    out.push_back(std::move(in));
  }

  bool eq(double a, double b) const { return std::abs(a - b) <= tol_; }

  // Whether the moves from `i` begin as a roughing level does, along X or along Z: an infeed
  // along one axis from where the tool is, a feed along the other, a feed out. Cheap, so that
  // only such places read the whole run.
  bool level_starts(const std::vector<ir::Instr>& body, size_t i) const {
    const ir::Move* m[3];
    size_t n = 0;
    for (size_t k = i; k < body.size() && n < 3; ++k) {
      if (const auto* mv = std::get_if<ir::Move>(&body[k].op)) {
        if (mv->kind == ir::MoveKind::From) return false;
        m[n++] = mv;
      } else if (std::holds_alternative<ir::Arc>(body[k].op) && n == 2) {
        return true;  // the cut, then an arc out
      } else if (!std::holds_alternative<ir::Feed>(body[k].op) && !std::holds_alternative<ir::Comment>(body[k].op)) {
        return false;
      }
    }
    if (n < 3 || m[1]->kind != ir::MoveKind::Feed || m[2]->kind != ir::MoveKind::Feed) return false;
    const ir::Vec3 a = at_.pos;
    const bool turning = eq(m[0]->point.z(), a.z()) && !eq(m[0]->point.x(), a.x()) && eq(m[1]->point.x(), m[0]->point.x());
    const bool facing = eq(m[0]->point.x(), a.x()) && !eq(m[0]->point.z(), a.z()) && eq(m[1]->point.z(), m[0]->point.z());
    return turning || facing;
  }

  // The run of plain motion from `i`: moves and arcs, with feeds and comments between.
  std::vector<Motion> run_from(const std::vector<ir::Instr>& body, size_t i) const {
    std::vector<Motion> ms;
    ir::Feed feed = at_.feed;
    for (size_t k = i; k < body.size(); ++k) {
      const ir::Op& o = body[k].op;
      if (const auto* f = std::get_if<ir::Feed>(&o)) {
        feed = *f;
      } else if (const auto* m = std::get_if<ir::Move>(&o)) {
        if (m->kind == ir::MoveKind::From) break;
        ms.push_back({k, m->kind == ir::MoveKind::Rapid ? stock::Step::Kind::Rapid : stock::Step::Kind::Feed, m->point,
                      ir::Vec3::Zero(), false, feed});
      } else if (const auto* a = std::get_if<ir::Arc>(&o)) {
        if (std::abs(std::abs(a->axis.y()) - 1) > 1e-9 || a->dir == ir::ArcDir::Unknown || a->extra_turns > 0) break;
        ms.push_back({k, stock::Step::Kind::Arc, a->end, a->center, (a->dir == ir::ArcDir::Ccw) == (a->axis.y() > 0), feed});
      } else if (!std::holds_alternative<ir::Comment>(o)) {
        break;
      }
    }
    return ms;
  }

  // Reads the run as a cycle (the words still unproved). `why` is set when levels were found
  // but the rest is not the cycle's.
  bool read(const std::vector<Motion>& ms, const ir::Vec3& a, bool facing, Candidate& c, std::string& why) const {
    auto L = [&](const ir::Vec3& v) { return facing ? v.z() : v.x(); };
    auto C = [&](const ir::Vec3& v) { return facing ? v.x() : v.z(); };
    const double l0 = L(a), c0 = C(a);
    double sl = 0, sc = 0, depth = 0, e = 0;
    stock::Step::Kind infeed = stock::Step::Kind::Rapid;
    size_t k = 0;
    int levels = 0;
    ir::Vec3 cur = a;
    const auto Feed = stock::Step::Kind::Feed, Rapid = stock::Step::Kind::Rapid, Arc = stock::Step::Kind::Arc;
    // Levels as any roughing writes them: an infeed along the level axis from A's cutting-axis
    // position, a cut along the other axis, moves out, a rapid back to that position. The
    // cycle's are one 45-degree pull-out each, evenly deep, entered alike.
    int roughing = 0;  // levels of any shape
    const std::string name = facing ? "G72" : "G71";
    double prev_l = l0;
    while (k + 3 < ms.size()) {
      const Motion &m1 = ms[k], &m2 = ms[k + 1];
      const double lk = L(m1.to), ck = C(m2.to);
      if (!(m1.kind != Arc && eq(C(m1.to), c0) && !eq(lk, L(cur)) && m2.kind == Feed && eq(L(m2.to), lk) && !eq(ck, c0)))
        break;
      size_t r = k + 2;
      while (r < ms.size() && ms[r].kind != Rapid) ++r;
      if (r == k + 2 || r >= ms.size() || !eq(C(ms[r].to), c0)) break;
      if (roughing > 0 && eq(L(ms[r].to), l0)) break;  // back to A itself: the last cut, not a level
      ++roughing;
      const Motion& m3 = ms[k + 2];
      const double dl = L(m3.to) - lk, dc = C(m3.to) - ck;
      if (roughing == 1) {
        sl = l0 > lk ? 1 : -1;
        sc = ck > c0 ? 1 : -1;
        depth = sl * (l0 - lk);
        e = std::abs(dl);
        infeed = m1.kind;
      }
      if (why.empty()) {
        const std::string n = "level " + std::to_string(roughing);
        if (r != k + 3 || m3.kind != Feed)
          why = n + " follows the profile after its cut (" + name + " cuts to the profile, pulls out at 45 degrees and " +
                "follows the profile only in its last cut)";
        else if (!(std::abs(dl) > tol_) || !eq(std::abs(dl), std::abs(dc)) || (dl > 0 ? 1 : -1) != sl || (dc > 0 ? 1 : -1) != -sc)
          why = n + " pulls out " + (std::abs(dc) <= tol_ ? std::string("along ") + (facing ? "Z" : "X") + " alone" : "at another angle") +
                " (" + name + " pulls out at 45 degrees)";
        else if (!eq(std::abs(dl), e))
          why = n + " pulls out by " + num_text(std::abs(dl)) + " where the first pulls out by " + num_text(e);
        else if (m1.kind != infeed)
          why = n + " is entered at " + (m1.kind == Rapid ? "rapid" : "feed") + " where the first is not";
        else if (!eq(lk, l0 - sl * roughing * depth))
          why = n + " is " + num_text(sl * (prev_l - lk)) + " deeper than the one before it where the first is " +
                num_text(depth) + " (" + name + "'s levels are evenly deep)";
        else if (!eq(L(ms[r].to), L(m3.to)))
          why = n + " returns at another " + (facing ? "Z" : "X") + " than its pull-out reached";
        else
          ++levels;
      }
      prev_l = lk;
      cur = ms[r].to;
      k = r + 1;
      c.roughing_end = k;
    }
    if (roughing < 2) {
      why.clear();
      return false;  // not roughing: nothing to say
    }
    c.levels = roughing;
    if (!why.empty()) return false;
    k = size_t(levels) * 4;
    // The last cut: entered as the levels are, along the shifted profile, then back to A.
    if (k >= ms.size() || ms[k].kind != infeed) {
      why = "after its " + std::to_string(levels) + " levels no last cut along the profile follows";
      return false;
    }
    const ir::Vec3 shifted_start = ms[k].to;
    const size_t contour_first = k++;
    while (k < ms.size() && ms[k].kind != Rapid) ++k;
    if (k == contour_first + 1 || k >= ms.size() || !eq(L(ms[k].to), l0) || !eq(C(ms[k].to), c0)) {
      why = "the last cut along the profile does not end with a rapid back to the start point";
      return false;
    }
    const size_t contour_end = k++;  // the rapid back
    c.cycle_end = k;
    // The finishing pass: from A along the level axis to A', the same moves as the last cut
    // less the allowances, a rapid back to A.
    double al = 0, ac = 0;
    const size_t n = contour_end - contour_first - 1;
    if (k < ms.size() && ms[k].kind != Arc && eq(C(ms[k].to), c0) && k + n + 1 < ms.size()) {
      al = L(shifted_start) - L(ms[k].to);
      ac = C(shifted_start) - c0;
      bool same = ms[k + n + 1].kind == Rapid && eq(L(ms[k + n + 1].to), l0) && eq(C(ms[k + n + 1].to), c0);
      for (size_t j = 1; j <= n && same; ++j) {
        const Motion &f = ms[k + j], &g = ms[contour_first + j];
        same = f.kind == g.kind && eq(L(f.to) + al, L(g.to)) && eq(C(f.to) + ac, C(g.to)) &&
               (f.kind != Arc || (f.ccw == g.ccw && eq(L(f.center) + al, L(g.center)) && eq(C(f.center) + ac, C(g.center))));
      }
      if (same) {
        c.finish = true;
        c.profile_first = k;
        c.end = k + n + 2;
      }
    }
    if (!c.finish) {
      if (!eq(C(shifted_start), c0)) {
        why = std::string("its last cut starts off the start point's ") + (facing ? "X" : "Z") +
              " and no finishing pass follows it in the same run of motion to give the allowance (a record other "
              "than motion, a feed or a comment, such as a SPINDL, ends the run)";
        return false;
      }
      c.profile_first = contour_first;
      c.end = c.cycle_end;
    }
    // The profile: A to A', then the finishing pass's (or the last cut's) moves.
    const size_t last = c.finish ? c.end - 1 : contour_end;
    ir::Vec3 p = a;
    for (size_t j = c.profile_first; j < last; ++j) {
      c.profile.push_back({p, ms[j].to, ms[j].kind == Arc, ms[j].center, ms[j].ccw, 0});
      p = ms[j].to;
    }
    c.params.facing = facing;
    c.params.depth = depth;
    c.params.retract = e;
    c.params.allow_x = facing ? ac : al;
    c.params.allow_z = facing ? al : ac;
    c.params.infeed_rapid = infeed == Rapid;
    return true;
  }

  // Tries the run from `i` as G71, then as G72; on success the cycle is in `out` and `next` is
  // past the motion it replaced.
  bool collapse(std::vector<ir::Instr>& body, size_t i, PassContext& ctx, std::vector<ir::Instr>& out, size_t& next) {
    const std::vector<Motion> ms = run_from(body, i);
    if (ms.size() < 10) return false;
    next = ms[3].index + 1;  // if no cycle: past the first level
    const Codes& codes = ctx.machine.codes;
    const ir::Vec3 a = at_.pos;
    for (bool facing : {false, true}) {
      if ((facing ? codes.rough_face : codes.rough_turn).empty()) continue;
      Candidate c;
      std::string why;
      // Roughing that stays as moves is passed whole: one note for it, not one per level.
      const bool read_ok = read(ms, a, facing, c, why);
      if (read_ok && comp_waits_) {
        // The G41/G42 would start on a profile block (a taper along its first cut) and the
        // roughing would run uncompensated: the moves keep the CL's start.
        remark(ctx, body[ms[0].index].loc, facing, c.levels,
               "cutter compensation starts at its first level, and would start on a profile block of the cycle");
        next = std::max(next, ms[c.roughing_end - 1].index + 1);
        continue;
      }
      if (!read_ok) {
        if (!why.empty()) remark(ctx, body[ms[0].index].loc, facing, c.levels, why);
        if (c.roughing_end > 0) next = std::max(next, ms[c.roughing_end - 1].index + 1);
        continue;
      }
      if (!prove(ms, a, c, ctx, why)) {
        remark(ctx, body[ms[0].index].loc, facing, c.levels, why);
        next = std::max(next, ms[c.roughing_end - 1].index + 1);
        continue;
      }
      // What stands before the first move (a FEDRAT after the approach) still stands: it was
      // dropped, and the moves after the cycle had no feed (helper-54).
      for (size_t k = i; k < ms[0].index; ++k) keep(body[k], out);
      write(body, ms, a, c, out);
      next = ms[c.end - 1].index + 1;
      at_.pos = a;
      return true;
    }
    return false;
  }

  void remark(PassContext& ctx, SourceLoc loc, bool facing, int levels, const std::string& why) const {
    ctx.diags.note(loc, std::string("roughing of ") + std::to_string(levels) + " levels kept as moves, not " +
                            (facing ? "G72" : "G71") + ": " + why);
  }

  // The words rounded as written, the cycle expanded, every move of the roughing compared; and
  // one feed for all of it (the cycle has one F).
  bool prove(const std::vector<Motion>& ms, const ir::Vec3& a, Candidate& c, PassContext& ctx, std::string& why) const {
    const Machine& m = ctx.machine;
    const double to_out = 1 / ctx.from_output();
    stock::Params& p = c.params;
    ir::Vec3 start = a;
    if (!stock::round_as_written(p, start, c.profile,
                                 [&](char letter, double v) { return as_written(v * to_out, m.format(letter)) / to_out; }) ||
        !(p.depth > 0) || !(p.retract >= 0)) {
      why = "its depth of cut, pull-out, allowances or profile cannot be written";
      return false;
    }
    const ir::Feed& f = ms[1].feed;
    for (size_t j = 0; j < c.cycle_end; ++j)
      if (ms[j].kind != stock::Step::Kind::Rapid && (ms[j].feed.value != f.value || ms[j].feed.mode != f.mode)) {
        why = "its feed changes within the roughing, and the cycle has one F";
        return false;
      }
    const std::vector<stock::Step> steps = stock::expand(start, c.profile, p, why);
    if (steps.empty()) return false;
    if (steps.size() != c.cycle_end) {
      why = "the cycle makes " + std::to_string(steps.size()) + " moves where the CL has " + std::to_string(c.cycle_end);
      return false;
    }
    for (size_t j = 0; j < steps.size(); ++j) {
      const stock::Step& s = steps[j];
      const Motion& mv = ms[j];
      const bool same = s.kind == mv.kind && (s.to - mv.to).norm() <= tol_ &&
                        (s.kind != stock::Step::Kind::Arc || (s.ccw == mv.ccw && (s.center - mv.center).norm() <= tol_));
      if (!same) {
        why = "the cycle's move " + std::to_string(j + 1) + " goes to " + point_text(s.to) + " where the CL's goes to " +
              point_text(mv.to);
        return false;
      }
    }
    return true;
  }

  static std::string point_text(const ir::Vec3& v) { return "(x " + num_text(v.x()) + ", z " + num_text(v.z()) + ")"; }

  // The cycle in the IR: what stood between the roughing's moves (feeds, comments) first, then
  // the CYCLE/ROUGH section the backend writes, the tool back at A after it.
  void write(std::vector<ir::Instr>& body, const std::vector<Motion>& ms, const ir::Vec3& a, const Candidate& c,
             std::vector<ir::Instr>& out) {
    const size_t first = ms[0].index, profile_first = ms[c.profile_first].index, last = ms[c.end - 1].index;
    for (size_t k = first; k < profile_first; ++k)
      if (!std::holds_alternative<ir::Move>(body[k].op) && !std::holds_alternative<ir::Arc>(body[k].op)) keep(body[k], out);
    ir::RoughMark mark;
    mark.facing = c.params.facing;
    mark.depth = c.params.depth;
    mark.retract = c.params.retract;
    mark.allow_x = c.params.allow_x;
    mark.allow_z = c.params.allow_z;
    mark.feed = ms[1].feed.value;
    mark.feed_mode = ms[1].feed.mode;
    mark.finish = c.finish;
    mark.start = a;
    out.push_back({body[first].loc, mark});
    // The profile: the finishing pass without its rapid back (or the last cut without it).
    const size_t profile_last = c.finish ? ms[c.end - 2].index : ms[c.cycle_end - 2].index;
    for (size_t k = profile_first; k <= profile_last; ++k) keep(body[k], out);
    out.push_back({body[last].loc, ir::RoughMark{false}});
    ir::Move back;
    back.kind = ir::MoveKind::From;
    back.point = a;
    back.axis = ir::Vec3::UnitZ();
    out.push_back({body[last].loc, back});
    // Feeds and comments after the profile (the rapid back's FEDRAT, say) still stand.
    for (size_t k = profile_last + 1; k <= last; ++k)
      if (!std::holds_alternative<ir::Move>(body[k].op) && !std::holds_alternative<ir::Arc>(body[k].op)) keep(body[k], out);
  }

  double tol_ = 1e-9;
  MotionState at_;
  bool comp_waits_ = false;  // a CUTCOM/LEFT|RIGHT with no move since: it starts on the next one
};

}  // namespace

const PassInfo& rough_cycles_pass() {
  static const PassInfo info{
      .name = "rough-cycles",
      .summary = "turn lathe roughing written as plain motion into one G71 or G72 stock-removal cycle (and G70 where "
                 "the CL finishes the profile next) where the cycle reproduces it",
      .expects = "lathe data (x radius, z); arcs' directions decided",
      .guarantees = "each collapse replaces roughing whose moves are exactly the cycle's (ir/stock_model, type I, the "
                    "words rounded as written) within the tolerance, as a CYCLE/ROUGH section; other motion stays, "
                    "with a note where it looked like roughing",
      .settings = "codes.rough_turn, codes.rough_face (empty: not used), codes.rough_finish, format.X, format.Z, "
                  "arcs.tolerance",
      .needs = ir::ArcsDecided,
      .provides = 0,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<RoughCycles>()); },
  };
  return info;
}

}  // namespace clpc
