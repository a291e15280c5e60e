// thread-cycles (lathe): the passes of a THREAD section become G92 box cycles, or one G76
// multiple-pass cycle, when and only when the cycle reproduces them.
//
// A THREAD section's motion is read as passes: from the start point S (where the tool is), an
// infeed at rapid along X to the pass's radius, the synchronised cut along Z, a move out along
// X to S's radius and a move back along Z to S: the G92 box (thread_model::box), to within one
// increment of X. Such a pass is written as G92 where the machine has it.
// If every pass of the section starts from one S and ends at one Z (radial infeed, a straight
// thread), their radii are those of Fanuc's G76 (thread_model::depths: the n-th pass Δd·√n
// below the crest, the last roughing pass at k − d with d > 0, then m finishing passes at k),
// with k and Δd taken from the first two passes and rounded to the P and Q increments, and the
// expansion of the rounded cycle matches every pass within the tolerance, the passes become
// one G76 where the machine has it. Other motion stays as it is: the backend writes its thread
// cuts as G32. Tapered and face threads stay as G32 moves.
//
// Its contract is thread_cycles_pass() at the end of this file.
#include <cmath>

#include "ir/thread_model.h"
#include "machine/format.h"
#include "passes/motion_state.h"
#include "passes/passes.h"

namespace clpc {

namespace {

struct Box {
  ir::Vec3 start, end;
  size_t first = 0;  // index in the section of its infeed move (4 moves)
};

class ThreadCycles : public Pass {
 public:
  void run(ir::Operation& op, PassContext& ctx) override {
    if (!ctx.machine.is_lathe()) return;
    const Codes& c = ctx.machine.codes;
    if (c.thread_box.empty() && c.thread_multi.empty()) return;
    tol_ = std::max(ctx.resolution(), 1e-9);
    auto& body = op.body;
    std::vector<ir::Instr> out;
    out.reserve(body.size());
    size_t i = 0;
    while (i < body.size()) {
      auto* t = std::get_if<ir::ThreadMark>(&body[i].op);
      if (!t || !t->begin) {
        track(body[i]);
        out.push_back(std::move(body[i]));
        ++i;
        continue;
      }
      size_t j = i + 1;
      while (j < body.size() && !std::holds_alternative<ir::ThreadMark>(body[j].op)) ++j;
      const ir::ThreadMark mark = *t;
      track(body[i]);
      out.push_back(std::move(body[i]));
      if (j < body.size() && !std::get<ir::ThreadMark>(body[j].op).begin) section(body, i + 1, j, mark, ctx, out);
      else copy(body, i + 1, j, out);  // a section that goes on in the next chunk: G32 moves
      i = j;
    }
    body.swap(out);
  }

 private:
  void track(const ir::Instr& in) { at_.track(in); }

  void copy(std::vector<ir::Instr>& body, size_t from, size_t to, std::vector<ir::Instr>& out) {
    for (size_t k = from; k < to; ++k) {
      track(body[k]);
      out.push_back(std::move(body[k]));
    }
  }

  bool eq(double a, double b) const { return std::abs(a - b) <= tol_; }

  // What the cycle replaced besides moves stays, after it: a FEDRAT among the passes still sets
  // the feed in force after the thread, a comment is still written.
  void keep_between(std::vector<ir::Instr>& body, size_t first, size_t last, std::vector<ir::Instr>& out) {
    for (size_t q = first; q <= last; ++q)
      if (!std::holds_alternative<ir::Move>(body[q].op)) {
        track(body[q]);
        out.push_back(std::move(body[q]));
      }
  }

  void section(std::vector<ir::Instr>& body, size_t from, size_t to, const ir::ThreadMark& mark, PassContext& ctx,
               std::vector<ir::Instr>& out) {
    // Only plain motion (and feeds) can be read as passes.
    bool plain = mark.kind == ir::ThreadKind::Turn && at_.have_pos;
    double lead = mark.lead;
    for (size_t k = from; k < to && plain; ++k) {
      if (auto* f = std::get_if<ir::Feed>(&body[k].op)) {
        if (!(mark.lead > 0)) plain = false;  // the lead would change with the feed
        (void)f;
      } else if (auto* m = std::get_if<ir::Move>(&body[k].op)) {
        plain = m->kind != ir::MoveKind::From;
      } else if (!std::holds_alternative<ir::Comment>(body[k].op)) {
        plain = false;
      }
    }
    if (!(lead > 0) && at_.feed_known && at_.feed.mode == ir::FeedMode::PerRev) lead = at_.feed.value;
    if (!plain || !(lead > 0)) return copy(body, from, to, out);

    // The moves, and the boxes among them.
    std::vector<size_t> moves;
    for (size_t k = from; k < to; ++k)
      if (std::holds_alternative<ir::Move>(body[k].op)) moves.push_back(k);
    auto mv = [&](size_t n) -> const ir::Move& { return std::get<ir::Move>(body[moves[n]].op); };
    std::vector<Box> boxes;
    ir::Vec3 p = at_.pos;
    for (size_t n = 0; n < moves.size();) {
      if (n + 3 < moves.size()) {
        const ir::Vec3 in = mv(n).point, cut = mv(n + 1).point, out_x = mv(n + 2).point, back = mv(n + 3).point;
        const bool infeed = mv(n).kind == ir::MoveKind::Rapid && eq(in.z(), p.z()) && !eq(in.x(), p.x());
        const bool along = mv(n + 1).kind == ir::MoveKind::Feed && eq(cut.x(), in.x()) && !eq(cut.z(), p.z());
        // The box pulls out and goes back at rapid: a CL that feeds out (it may touch) stays as
        // it is (a fed pull-out was made a rapid, and the certificate refused it).
        const bool out_ok = mv(n + 2).kind == ir::MoveKind::Rapid && eq(out_x.z(), cut.z()) && eq(out_x.x(), p.x());
        const bool back_ok = mv(n + 3).kind == ir::MoveKind::Rapid && eq(back.z(), p.z()) && eq(back.x(), p.x());
        if (infeed && along && out_ok && back_ok) {
          boxes.push_back({p, ir::Vec3(in.x(), 0, cut.z()), n});
          n += 4;
          continue;
        }
      }
      p = mv(n).point;
      ++n;
    }
    if (boxes.empty()) return copy(body, from, to, out);

    const Codes& c = ctx.machine.codes;
    ir::ThreadCycle multi;
    if (!c.thread_multi.empty() && as_multi(boxes, moves.size(), lead, ctx, multi)) {
      // Moves before the first box and after the last stay; the boxes become one G76.
      const size_t first = moves[boxes.front().first], last = moves[boxes.back().first + 3];
      copy(body, from, first, out);
      out.push_back({body[first].loc, multi});
      keep_between(body, first, last, out);
      at_.pos = multi.start;
      copy(body, last + 1, to, out);
      return;
    }
    if (c.thread_box.empty()) return copy(body, from, to, out);
    size_t k = from;
    for (const Box& b : boxes) {
      const size_t first = moves[b.first], last = moves[b.first + 3];
      copy(body, k, first, out);
      ir::ThreadCycle tc;
      tc.start = b.start;
      tc.end = b.end;
      tc.lead = lead;
      out.push_back({body[first].loc, tc});
      keep_between(body, first, last, out);
      at_.pos = b.start;
      k = last + 1;
    }
    copy(body, k, to, out);
  }

  // Whether the boxes are one G76: one start, one end Z, contiguous, radial infeed; the
  // parameters inferred, rounded, and the cycle's expansion compared pass by pass.
  bool as_multi(const std::vector<Box>& boxes, size_t move_count, double lead, PassContext& ctx, ir::ThreadCycle& out) {
    (void)move_count;
    if (boxes.size() < 3) return false;
    const Box& b0 = boxes.front();
    for (size_t n = 0; n < boxes.size(); ++n) {
      const Box& b = boxes[n];
      if (!eq(b.start.x(), b0.start.x()) || !eq(b.start.z(), b0.start.z()) || !eq(b.end.z(), b0.end.z())) return false;
      if (n > 0 && b.first != boxes[n - 1].first + 4) return false;  // other motion between passes
    }
    const double side = b0.start.x() >= b0.end.x() ? 1 : -1;
    const double root = boxes.back().end.x();
    size_t finish = 0;
    while (finish < boxes.size() && eq(boxes[boxes.size() - 1 - finish].end.x(), root)) ++finish;
    const size_t rough = boxes.size() - finish;
    if (rough < 2 || finish > 99) return false;
    const double x1 = boxes[0].end.x(), x2 = boxes[1].end.x(), xr = boxes[rough - 1].end.x();
    const double first = side * (x1 - x2) / (std::sqrt(2.0) - 1);
    const double crest = x1 + side * first;
    const double height = side * (crest - root), allowance = side * (xr - root);
    if (!(first > tol_) || !(allowance > tol_) || !(height > allowance)) return false;

    // The words as the control will read them: P and Q in their increments, R in its format.
    const Machine& m = ctx.machine;
    const double to_out = 1 / ctx.from_output();
    auto rounded = [&](char letter, double v) {
      int64_t q;
      if (!quantize(v * to_out, m.format(letter), q)) return -1.0;
      return dequantize(q, m.format(letter)) / to_out;
    };
    thread_model::Multi p;
    p.height = rounded('P', height);
    p.first = rounded('Q', first);
    p.min_step = std::abs(dequantize(1, m.format('Q'))) / to_out;
    p.allowance = rounded('R', allowance);
    p.finish_passes = int(finish);
    const double root_written = rounded('X', root);
    if (!(p.height > 0) || !(p.first > 0) || !(p.allowance > 0) || std::isnan(root_written)) return false;
    const ir::Vec3 start = b0.start, end(root_written, 0, b0.end.z());
    const std::vector<double> depths = thread_model::depths(p);
    if (depths.size() != boxes.size()) return false;
    const double tol = ctx.tolerance();
    const double crest_written = end.x() + side * p.height;
    for (size_t n = 0; n < boxes.size(); ++n)
      if (std::abs(crest_written - side * depths[n] - boxes[n].end.x()) > tol) return false;
    out.start = start;
    out.end = end;
    out.lead = lead;
    out.multi = true;
    out.height = p.height;
    out.first_depth = p.first;
    out.min_step = p.min_step;
    out.allowance = p.allowance;
    out.finish_passes = p.finish_passes;
    return true;
  }

  double tol_ = 1e-9;
  MotionState at_;
};

}  // namespace

const PassInfo& thread_cycles_pass() {
  static const PassInfo info{
      .name = "thread-cycles",
      .summary = "turn the passes of a lathe THREAD section into G92 box cycles, or one G76 cycle, where the cycle "
                 "reproduces them",
      .expects = "lathe data (x radius, z); THREAD sections as lowered (thread marks around plain motion)",
      .guarantees = "each collapse replaces passes whose moves are exactly the cycle's: a G92 per box pass (to one "
                    "increment of X), or one G76 whose expansion (thread_model) gives every pass's radius within the "
                    "tolerance; other motion stays, its thread cuts written as G32 by the backend",
      .settings = "codes.thread_box, codes.thread_multi (empty: not used), format.X, format.P, format.Q, format.R, "
                  "arcs.tolerance",
      .needs = 0,
      .provides = 0,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<ThreadCycles>()); },
  };
  return info;
}

}  // namespace clpc
