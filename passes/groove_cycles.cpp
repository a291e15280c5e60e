// groove-cycles (lathe): groove motion becomes one Fanuc G74 (face) or G75 (radial) cycle,
// when and only when the cycle reproduces it.
//
// Where grooves come from:
//   - CYCLE/FACE|RADIUS,RETRACT,e,XAXIS,p,ZAXIS,q,FEED,f ... CYCLE/OFF (the seed paper's
//     records): the motion inside is the groove, the record gives the cycle's parameters;
//   - Creo's "$$ GRV" ... "$$ GRV END" sections of explicit plunges;
//   - any run of at least three plunges from one level, evenly spaced, to one bottom.
//
// The motion is read as stations: at each, a plunge from the retract level to the bottom (in
// one feed or in pecks) and back, along the plunge axis only, with shifts along the other
// axis at the retract level in between. Of the stations, those with one bottom and even
// spacing make the cycle; groove::expand (ir/groove_model) then runs the cycle as a control
// would, and the collapse is made only if every cut of the expansion is a cut of the CL (same
// stations, same bottom, same pecks), and every other move stays between the retract level
// and the bottom. Other stations stay as motion.
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and provides)
// is groove_cycles_pass() at the end of this file.
#include <algorithm>
#include <cmath>
#include <map>

#include "ir/groove_model.h"
#include "passes/motion_state.h"
#include "passes/passes.h"
#include "support/text.h"

namespace clpc {

namespace {

struct Station {
  double shift = 0;       // position along the shift axis
  double level = 0;       // retract level (plunge axis)
  double bottom = 0;      // deepest point (plunge axis)
  std::vector<std::pair<double, double>> cuts;  // feeds toward the bottom: [from, to] on the plunge axis
  size_t first = 0, last = 0;  // items of the plunge (and of the shift moves leading to it)
  double feed = 0;
  ir::FeedMode feed_mode = ir::FeedMode::PerRev;
  bool feed_known = false;
};

struct Item {
  size_t instr;           // index in the region
  ir::Vec3 from, to;
  bool rapid;
  double feed;
  ir::FeedMode mode;
  bool feed_known;
};

class GrooveCycles : public Pass {
 public:
  void run(ir::Operation& op, PassContext& ctx) override {
    if (!ctx.machine.is_lathe()) return;
    tol_ = std::max(ctx.resolution(), 1e-9);
    std::vector<ir::Instr> out;
    out.reserve(op.body.size());
    auto& body = op.body;
    size_t i = 0;
    while (i < body.size()) {
      ir::Instr& in = body[i];
      if (auto* g = std::get_if<ir::GrooveOn>(&in.op)) {
        size_t j = i + 1;
        while (j < body.size() && !std::holds_alternative<ir::CycleOff>(body[j].op)) ++j;
        ir::GrooveSpec spec = op.grooves.at(g->spec);
        std::vector<ir::Instr> region(std::make_move_iterator(body.begin() + long(i) + 1),
                                      std::make_move_iterator(body.begin() + long(j)));
        process(op, region, &spec, in.loc, ctx, out);
        if (j == body.size())
          ctx.diags.warning(in.loc, "groove CYCLE without CYCLE/OFF at the end of the operation: ended here",
                            "cycle");
        i = j + 1;
        continue;
      }
      if (auto* m = std::get_if<ir::GrooveMark>(&in.op); m && m->begin) {
        size_t j = i + 1;
        while (j < body.size() && !(std::holds_alternative<ir::GrooveMark>(body[j].op) &&
                                    !std::get<ir::GrooveMark>(body[j].op).begin))
          ++j;
        std::vector<ir::Instr> region(std::make_move_iterator(body.begin() + long(i) + 1),
                                      std::make_move_iterator(body.begin() + long(std::min(j, body.size()))));
        process(op, region, nullptr, in.loc, ctx, out, 2);
        i = j + 1;
        continue;
      }
      if (std::holds_alternative<ir::GrooveMark>(in.op)) {
        ++i;
        continue;
      }
      // A thread's passes are never a groove (thread-cycles reads them); a stock-removal
      // profile is the control's to cut (the backend writes G71/G72): both pass as they are.
      if (const size_t j = marked_section_end(body, i); j != i) {
        for (; i < j; ++i) {
          track(body[i]);
          out.push_back(std::move(body[i]));
        }
        continue;
      }
      // A run of plain motion: collapse only clear groove patterns (three stations or more).
      if (std::holds_alternative<ir::Move>(in.op) || std::holds_alternative<ir::Feed>(in.op)) {
        size_t j = i;
        while (j < body.size() && (std::holds_alternative<ir::Move>(body[j].op) || std::holds_alternative<ir::Feed>(body[j].op)))
          ++j;
        std::vector<ir::Instr> region(std::make_move_iterator(body.begin() + long(i)),
                                      std::make_move_iterator(body.begin() + long(j)));
        process(op, region, nullptr, in.loc, ctx, out, 3);
        i = j;
        continue;
      }
      track(in);
      out.push_back(std::move(in));
      ++i;
    }
    body.swap(out);
  }

 private:
  void track(const ir::Instr& in) { at_.track(in); }

  double pl(const ir::Vec3& v, bool face) const { return face ? v.z() : v.x(); }
  double sh(const ir::Vec3& v, bool face) const { return face ? v.x() : v.z(); }
  bool eq(double a, double b) const { return std::abs(a - b) <= tol_; }

  // Reads the region's motion as stations; false if it is not plunges from one level.
  bool stations(const std::vector<Item>& items, bool face, std::vector<Station>& out, size_t& prefix_end) const {
    out.clear();
    size_t k = 0;
    const size_t n = items.size();
    // Groups of moves along the plunge axis only, joined by shifts at the retract level.
    std::vector<std::pair<size_t, size_t>> groups;
    while (k < n) {
      size_t b = k;
      while (k < n && eq(sh(items[k].from, face), sh(items[k].to, face))) ++k;
      if (k > b) groups.emplace_back(b, k);
      if (k < n) {
        if (!eq(pl(items[k].from, face), pl(items[k].to, face))) return false;  // diagonal: not a groove
        ++k;
      }
    }
    if (groups.empty()) return false;
    double level = pl(items[groups.back().second - 1].to, face);
    prefix_end = 0;
    for (size_t g = 0; g < groups.size(); ++g) {
      auto [b, e] = groups[g];
      if (!eq(pl(items[e - 1].to, face), level)) return false;  // must come back to the level
      // The deepest point, and where the plunge starts: the last time at the level before it.
      size_t deepest = b;
      double depth = 0;
      for (size_t t = b; t < e; ++t) {
        double d = std::abs(pl(items[t].to, face) - level);
        if (d > depth + tol_) {
          depth = d;
          deepest = t;
        }
      }
      if (depth <= tol_) continue;  // no plunge here (a move along the level)
      size_t start = b;
      bool at_level = eq(pl(items[b].from, face), level);
      for (size_t t = b; t < deepest; ++t)
        if (eq(pl(items[t].to, face), level)) start = t + 1, at_level = true;
      if (!at_level) return false;
      if (g == 0) prefix_end = start;
      else if (start != b) return false;  // only the first station may have an approach
      Station s;
      s.shift = sh(items[b].from, face);
      s.level = level;
      s.bottom = pl(items[deepest].to, face);
      const double dir = s.bottom > level ? 1 : -1;
      for (size_t t = start; t < e; ++t) {
        double f = pl(items[t].from, face), to = pl(items[t].to, face);
        // Nothing may go past the level or the bottom.
        if ((to - level) * dir < -tol_ || (to - s.bottom) * dir > tol_) return false;
        if (!items[t].rapid && (to - f) * dir > tol_) {
          if (!s.cuts.empty() && eq(s.cuts.back().second, f)) s.cuts.back().second = to;  // one straight cut
          else s.cuts.emplace_back(f, to);
          if (s.feed_known && (items[t].feed != s.feed || items[t].mode != s.feed_mode)) return false;
          s.feed = items[t].feed;
          s.feed_mode = items[t].mode;
          s.feed_known = items[t].feed_known;
        } else if (items[t].rapid && (to - f) * dir > tol_) {
          return false;  // a rapid into the material
        }
      }
      s.first = out.empty() ? start : out.back().last + 1;
      s.last = e - 1;
      out.push_back(s);
    }
    return !out.empty();
  }

  // The cycle's cuts, per station, from the model.
  static std::vector<std::vector<std::pair<double, double>>> model_cuts(const std::vector<groove::Step>& steps,
                                                                        const ir::Vec3& start, bool face) {
    std::vector<std::vector<std::pair<double, double>>> per;
    ir::Vec3 at = start;
    double station = std::nan("");
    for (const groove::Step& s : steps) {
      double st = face ? s.to.x() : s.to.z();
      double f = face ? at.z() : at.x(), t = face ? s.to.z() : s.to.x();
      if (s.cut) {
        if (per.empty() || st != station) per.emplace_back();
        station = st;
        per.back().emplace_back(f, t);
      }
      at = s.to;
    }
    return per;
  }

  void process(ir::Operation& op, std::vector<ir::Instr>& region, const ir::GrooveSpec* record, SourceLoc loc,
               PassContext& ctx, std::vector<ir::Instr>& out, size_t min_stations = 1) {
    // The region's moves, with where each starts and the feed in effect.
    std::vector<Item> items;
    ir::Vec3 p = at_.pos;
    bool have = at_.have_pos;
    ir::Feed f = at_.feed;
    bool fk = at_.feed_known;
    bool other = false;
    for (size_t k = 0; k < region.size(); ++k) {
      if (auto* fe = std::get_if<ir::Feed>(&region[k].op)) {
        f = *fe;
        fk = true;
      } else if (auto* m = std::get_if<ir::Move>(&region[k].op)) {
        if (have && m->kind != ir::MoveKind::From) items.push_back({k, p, m->point, m->kind == ir::MoveKind::Rapid, f.value, f.mode, fk});
        p = m->point;
        have = true;
      } else {
        other = true;  // arcs, tool changes, ...: not a groove
      }
    }
    bool done = false;
    why_.clear();
    if (!other && !items.empty()) {
      for (bool face : {false, true}) {
        if (record && record->face != face) continue;
        std::vector<Station> st;
        size_t prefix_end = 0;
        if (!stations(items, face, st, prefix_end)) continue;
        done = collapse(op, region, items, st, prefix_end, face, record, loc, ctx, out, min_stations);
        if (done) break;
      }
    }
    if (!done) {
      if (record)
        ctx.diags.warning(loc, std::string("CYCLE/") + (record->face ? "FACE" : "RADIUS") +
                                   ": the motion is not a groove the cycle reproduces" + (why_.empty() ? "" : " (" + why_ + ")") +
                                   "; it is written as motion",
                          "groove");
      for (ir::Instr& in : region) {
        if (std::holds_alternative<ir::GrooveMark>(in.op)) continue;
        track(in);
        out.push_back(std::move(in));
      }
    }
  }

  bool collapse(ir::Operation& op, std::vector<ir::Instr>& region, const std::vector<Item>& items,
                const std::vector<Station>& st, size_t prefix_end, bool face, const ir::GrooveSpec* record, SourceLoc loc,
                PassContext& ctx, std::vector<ir::Instr>& out, size_t min_stations) {
    // Stations to one bottom, evenly spaced: the cycle. Records: all of them.
    std::map<long, std::vector<size_t>> by_bottom;
    for (size_t s = 0; s < st.size(); ++s) by_bottom[std::lround(st[s].bottom / tol_)].push_back(s);
    std::vector<size_t> chosen;
    for (auto& [key, idx] : by_bottom)
      if (idx.size() > chosen.size()) chosen = idx;
    if (record && chosen.size() != st.size()) return false;  // a cycle has one bottom
    if (chosen.size() < min_stations) return false;
    std::vector<size_t> sorted = chosen;
    std::sort(sorted.begin(), sorted.end(), [&](size_t a, size_t b) { return st[a].shift < st[b].shift; });
    double spacing = sorted.size() > 1 ? st[sorted[1]].shift - st[sorted[0]].shift : 0;
    for (size_t k = 1; k < sorted.size(); ++k)
      if (!eq(st[sorted[k]].shift - st[sorted[k - 1]].shift, spacing) || spacing <= tol_) {
        if (!record) return false;
      }
    const Station& s0 = st[chosen.front()];
    for (size_t c : chosen)
      if (st[c].feed != s0.feed || st[c].feed_mode != s0.feed_mode || !eq(st[c].level, s0.level)) return false;
    // The cycle shifts at rapid. Without a record asking for the cycle, a shift the CL feeds
    // (it may touch the stock) keeps its motion: no collapse.
    if (!record)
      for (size_t c : chosen)
        for (size_t t = st[c].first; t <= st[c].last; ++t)
          if (!items[t].rapid && !eq(sh(items[t].from, face), sh(items[t].to, face))) return false;

    // Start at the end of the run nearest where the tool is.
    double here = sh(items[std::min(prefix_end, items.size() - 1)].from, face);
    bool from_low = std::abs(st[sorted.front()].shift - here) <= std::abs(st[sorted.back()].shift - here);
    double s_start = from_low ? st[sorted.front()].shift : st[sorted.back()].shift;
    double s_end = from_low ? st[sorted.back()].shift : st[sorted.front()].shift;
    auto at = [&](double plunge, double shift) { return face ? ir::Vec3(shift, 0, plunge) : ir::Vec3(plunge, 0, shift); };

    ir::GrooveSpec spec;
    spec.face = face;
    spec.feed = s0.feed;
    spec.feed_mode = s0.feed_mode;
    double depth = std::abs(s0.bottom - s0.level);
    if (record) {
      // The record's words against its motion. Its FEED is the cycle's (the seed paper writes
      // its records under another FEDRAT), but in another mode it is a contradiction: FEED has
      // no unit word (F0.12 per revolution was cut where every plunge was 50 mm/min, certified).
      // A peck the motion does not make is not the CL's cut either.
      auto differs = [](double a, double b) { return std::abs(a - b) > 1e-9 * std::max(1.0, std::abs(b)); };
      if (record->feed > 0 && record->feed_mode != s0.feed_mode) {
        why_ = std::string("its FEED is per ") + (record->feed_mode == ir::FeedMode::PerRev ? "revolution" : "minute") +
               ", and the motion plunges per " + (s0.feed_mode == ir::FeedMode::PerRev ? "revolution" : "minute");
        return false;
      }
      if (record->feed > 0 && differs(record->feed, s0.feed))
        ctx.diags.warning(loc, std::string("CYCLE/") + (face ? "FACE" : "RADIUS") + ": the cycle cuts at its FEED " +
                                   num_text(record->feed) + ", not at the feed the motion plunges at (" + num_text(s0.feed) + ")",
                          "groove");
      const double record_peck = face ? record->z_amount : record->x_amount;
      if (s0.cuts.size() > 1 && differs(record_peck, std::abs(s0.cuts[0].second - s0.cuts[0].first))) {
        why_ = "its peck is not the depth the motion pecks by";
        return false;
      }
      spec = *record;
      spec.face = face;
      if (spec.feed <= 0) {
        spec.feed = s0.feed;
        spec.feed_mode = s0.feed_mode;
      }
    } else {
      // Pecks as the CL makes them: the first cut's depth and the pull-out between cuts.
      double peck = depth, retract = 0;
      if (s0.cuts.size() > 1) {
        peck = std::abs(s0.cuts[0].second - s0.cuts[0].first);
        retract = std::abs(s0.cuts[0].second - s0.cuts[1].first);
      }
      (face ? spec.z_amount : spec.x_amount) = peck;
      (face ? spec.x_amount : spec.z_amount) = std::abs(spacing);
      spec.retract = retract;
    }
    ir::Vec3 start = at(s0.level, s_start), end = at(s0.bottom, s_end);
    groove::Params gp{face, spec.retract, spec.x_amount, spec.z_amount, spec.relief};
    std::vector<groove::Step> steps = groove::expand(start, end, gp);

    // The check: the cycle's cuts are the CL's (plain motion), or lie within the groove and
    // cover it (records); every other move stays between the level and the bottom.
    auto model = model_cuts(steps, start, face);
    double lo = std::min(s0.level, s0.bottom) - tol_, hi = std::max(s0.level, s0.bottom) + tol_;
    double slo = st[sorted.front()].shift - tol_, shi = st[sorted.back()].shift + tol_;
    for (const groove::Step& s : steps)
      if (pl(s.to, face) < lo || pl(s.to, face) > hi || sh(s.to, face) < slo || sh(s.to, face) > shi) return false;
    if (!record) {
      if (model.size() != sorted.size()) return false;
      std::vector<size_t> order = sorted;
      if (!from_low) std::reverse(order.begin(), order.end());
      for (size_t k = 0; k < order.size(); ++k) {
        const auto& cl = st[order[k]].cuts;
        if (cl.size() != model[k].size()) return false;
        for (size_t c = 0; c < cl.size(); ++c)
          if (!eq(cl[c].first, model[k][c].first) || !eq(cl[c].second, model[k][c].second)) return false;
      }
    } else {
      // Every plunge of the cycle reaches the CL's bottom; its stations span the CL's and are no
      // further apart than the CL's were.
      double max_gap = 0;
      for (size_t k = 1; k < sorted.size(); ++k) max_gap = std::max(max_gap, st[sorted[k]].shift - st[sorted[k - 1]].shift);
      if (model.empty()) return false;
      for (const auto& m : model)
        if (m.empty() || !eq(m.back().second, s0.bottom)) return false;
      std::vector<double> stations_model;
      for (const groove::Step& s : steps)
        if (s.cut) stations_model.push_back(sh(s.to, face));
      std::sort(stations_model.begin(), stations_model.end());
      stations_model.erase(std::unique(stations_model.begin(), stations_model.end(), [&](double a, double b) { return eq(a, b); }),
                           stations_model.end());
      if (!eq(stations_model.front(), st[sorted.front()].shift) || !eq(stations_model.back(), st[sorted.back()].shift))
        return false;
      for (size_t k = 1; k < stations_model.size(); ++k)
        if (stations_model[k] - stations_model[k - 1] > max_gap + tol_ && sorted.size() > 1) return false;
    }

    // Write: everything that is not a collapsed station, in order; the cycle where the first
    // collapsed station was.
    std::vector<bool> drop(region.size(), false);
    for (size_t c : chosen)
      for (size_t t = st[c].first; t <= st[c].last; ++t) drop[items[t].instr] = true;
    size_t first_dropped = region.size();
    for (size_t k = 0; k < region.size(); ++k)
      if (drop[k]) {
        first_dropped = k;
        break;
      }
    op.grooves.push_back(spec);
    uint32_t spec_index = uint32_t(op.grooves.size() - 1);
    for (size_t k = 0; k < region.size(); ++k) {
      if (k == first_dropped) {
        ir::Move m;
        m.point = start;
        m.axis = ir::Vec3::UnitZ();
        m.kind = ir::MoveKind::Rapid;
        if (!at_.have_pos || (at_.pos - start).norm() > tol_) out.push_back({region[k].loc, m});
        out.push_back({record ? loc : region[k].loc, ir::Groove{start, end, spec_index}});
        at_.pos = start;
        at_.have_pos = true;
      }
      if (drop[k] || std::holds_alternative<ir::GrooveMark>(region[k].op)) {
        if (auto* fe = std::get_if<ir::Feed>(&region[k].op)) {  // keep the modal feed
          track(region[k]);
          out.push_back(std::move(region[k]));
          (void)fe;
        }
        continue;
      }
      track(region[k]);
      out.push_back(std::move(region[k]));
    }
    (void)ctx;
    return true;
  }

  double tol_ = 1e-6;
  std::string why_;  // why a record's motion was not its cycle, for the warning
  MotionState at_;
};

}  // namespace

const PassInfo& groove_cycles_pass() {
  static const PassInfo info{
      .name = "groove-cycles",
      .summary = "collapse lathe groove motion into one G74 (face) or G75 (radial) cycle where the cycle "
                 "reproduces it",
      .expects = "lathe data (x radius, z); groove records and marks as lowered",
      .guarantees = "groove records are gone; each collapse is a move to the cycle's start and a groove whose "
                    "G74/G75 expansion equals the motion it replaced; motion that does not match stays as it was "
                    "(a warning where a CYCLE record asked for a cycle)",
      .settings = "format.X (the resolution groove stations are compared at)",
      .needs = 0,
      .provides = ir::GroovesFormed,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<GrooveCycles>()); },
  };
  return info;
}

}  // namespace clpc
