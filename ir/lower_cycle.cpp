// CYCLE records: the drilling, tapping and boring cycles of NX, Creo and APT, whatever order
// their keywords come in. Distances are along the tool axis from each hole's GOTO point.
//
//   NX    CYCLE/DRILL,RAPTO,r,FEDTO,d,MMPM,f[,RTRCTO,t]
//   Creo  CYCLE/DRILL,DEPTH,d,IPM,f,CLEAR,c        CYCLE/DEEP,DEPTH,d,STEP,s,MMPM,f,CLEAR,c
//         CYCLE/TAP,DEPTH,d,TPI,n,CLEAR,c
//   APT   CYCLE/DEEP2,FEDTO,d,1STPECK,p,2NDPECK,q,IPM,f,RAPTO,r
#include <cmath>

#include "ir/lower.h"
#include "ir/params.h"

namespace clpc {

namespace {
constexpr double kMaxPecks = 10000;
}  // namespace

void Lowerer::lower_cycle(const Record& r) {
  ParamReader ps(r, d_);
  if (ps.size() == 0 || !ps[0].is_word()) {
    d_.error(ps.size() ? ps[0].loc : r.end, "CYCLE: expected the cycle kind (DRILL, DEEP, TAP, BORE, ..., OFF)");
    return;
  }
  ensure_operation(r.loc);
  std::string kind = upper(ps[0].text);
  if (kind == "OFF") {
    if (!cycle_open_) d_.warning(r.loc, "CYCLE/OFF with no cycle on", "cycle off");
    cycle_open_ = false;
    push(r.loc, ir::CycleOff{});
    return;
  }
  if (ps.has("XAXIS") || ps.has("ZAXIS") || (kind == "RADIUS")) {
    lower_groove_cycle(r);
    return;
  }

  ir::CycleSpec c;
  bool orient = false, drag = false, back = false;
  if (kind == "DRILL") c.kind = ir::CycleKind::Drill;
  else if (kind == "DEEP" || kind == "DEEP2") c.kind = ir::CycleKind::Peck;
  else if (kind == "BRKCHP") c.kind = ir::CycleKind::ChipBreak;
  else if (kind == "TAP") c.kind = ir::CycleKind::Tap;
  else if (kind == "BORE" || kind == "REAM") c.kind = ir::CycleKind::Bore;
  else if (kind == "CSINK" || kind == "FACE" || kind == "SPOT") c.kind = ir::CycleKind::SpotDwell;
  else {
    d_.error(ps[0].loc, "CYCLE: unknown cycle '" + std::string(ps[0].text) +
                            "' (DRILL, DEEP, DEEP2, BRKCHP, TAP, BORE, REAM, CSINK, FACE or OFF)");
    return;
  }

  bool depth = false, clear = false, pitch_given = false, feed_word_seen = false;
  for (size_t i = 1; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (p.is_number()) {
      d_.error(p.loc, "CYCLE: the number " + num_text(p.number) + " has no keyword before it");
      return;
    }
    std::string w = upper(p.text);
    // Words that take no value.
    if (w == "ORIENT") { orient = true; continue; }
    if (w == "DRAG") { drag = true; continue; }
    if (w == "BACK") { back = true; continue; }
    if (w == "RIGID" || w == "FLOAT" || w == "NODRAG" || w == "AUTO") continue;
    if (w == "DWELL" && (i + 1 >= ps.size() || !ps[i + 1].is_number())) continue;  // bare DWELL: a modifier
    if (i + 1 >= ps.size() || !ps[i + 1].is_number()) {
      d_.error(i + 1 < ps.size() ? ps[i + 1].loc : r.end, "CYCLE: a number must follow " + std::string(p.text));
      return;
    }
    const Param& vp = ps[i + 1];
    double v = vp.number;
    ++i;
    auto non_negative = [&](const char* what) {
      if (v >= 0) return true;
      d_.error(vp.loc, "CYCLE: " + std::string(what) + " must not be negative, found " + num_text(v));
      return false;
    };
    if (w == "DEPTH" || w == "FEDTO") {
      if (!non_negative("the depth")) return;
      c.depth = v;
      depth = true;
    } else if (w == "CLEAR" || w == "RAPTO") {
      c.clearance = v;
      clear = true;
    } else if (w == "RTRCTO") {
      c.retract = v;
    } else if (w == "STEP" || w == "1STPECK" || w == "PECK") {
      if (!non_negative("the peck")) return;
      c.peck = v;
    } else if (w == "2NDPECK") {
      if (!non_negative("the peck")) return;
      c.peck_next = v;
    } else if (w == "DWELL") {
      if (!non_negative("the dwell")) return;
      c.dwell = v;
    } else if (w == "TPI") {
      if (!(v > 0)) {
        d_.error(vp.loc, "CYCLE: TPI must be greater than zero");
        return;
      }
      c.pitch = 25.4 / v / ir::mm_per_unit(info_.units);
      pitch_given = true;
    } else if (w == "PITCH") {
      if (!(v > 0)) {
        d_.error(vp.loc, "CYCLE: PITCH must be greater than zero");
        return;
      }
      c.pitch = v;
      pitch_given = true;
    } else if (w == "SHIFT") {
      c.shift = v;
    } else if (w == "IPM" || w == "MMPM" || w == "IPR" || w == "MMPR" || w == "PERMIN" || w == "PERREV" || w == "FPM") {
      bool inch = w[0] == 'I' || w == "FPM";
      const double unit_mm = w == "FPM" ? 304.8 : inch ? 25.4 : 1.0;
      double scale = w == "PERMIN" || w == "PERREV" ? 1 : unit_mm / ir::mm_per_unit(info_.units);
      c.feed = v * scale;
      c.feed_mode = (w == "IPR" || w == "MMPR" || w == "PERREV") ? ir::FeedMode::PerRev : ir::FeedMode::PerMinute;
      feed_word_seen = true;
      if (!(c.feed > 0)) {
        d_.error(vp.loc, "CYCLE: the feed must be greater than zero");
        return;
      }
    } else {
      d_.error(p.loc, "CYCLE: unknown word '" + std::string(p.text) + "'");
      return;
    }
  }
  (void)feed_word_seen;
  if (!depth) {
    d_.error(r.loc, "CYCLE/" + kind + ": no depth (DEPTH or FEDTO)");
    return;
  }
  if (!clear) d_.warning(r.loc, "CYCLE/" + kind + ": no clearance (CLEAR or RAPTO); the R plane is at the hole's top", "cycle clearance");
  if (c.kind == ir::CycleKind::Peck || c.kind == ir::CycleKind::ChipBreak) {
    if (!(c.peck > 0)) {
      d_.error(r.loc, "CYCLE/" + kind + ": a peck cycle needs a peck depth (STEP or 1STPECK) greater than zero");
      return;
    }
    // Bounded: a hole written as moves (or read back) takes one peck per step.
    const double smallest = c.peck_next > 0 ? std::min(c.peck, c.peck_next) : c.peck;
    if (std::abs(c.depth) / smallest > kMaxPecks) {
      d_.error(r.loc, "CYCLE/" + kind + ": a peck depth of " + num_text(smallest) + " makes more than " +
                          std::to_string(long(kMaxPecks)) + " pecks per hole of depth " + num_text(std::abs(c.depth)));
      return;
    }
  } else if (c.peck > 0 && c.kind == ir::CycleKind::Drill) {
    c.kind = ir::CycleKind::Peck;
  }
  if (c.kind == ir::CycleKind::Tap) {
    if (!pitch_given) {
      if (c.feed_mode == ir::FeedMode::PerRev && c.feed > 0) c.pitch = c.feed;
      else {
        d_.error(r.loc, "CYCLE/TAP: no thread pitch (TPI, PITCH, or a feed per revolution)");
        return;
      }
    }
    c.left_hand = last_spindle_ && last_spindle_->dir == ir::SpindleDir::Ccw;
  }
  if (c.kind == ir::CycleKind::Bore) {
    if (orient) c.kind = ir::CycleKind::FineBore;
    else if (back) c.kind = ir::CycleKind::BackBore;
    else if (drag) c.kind = ir::CycleKind::BoreStop;
    else if (c.dwell > 0) c.kind = ir::CycleKind::BoreDwell;
  } else if (c.dwell > 0 && c.kind == ir::CycleKind::Drill) {
    c.kind = ir::CycleKind::SpotDwell;
  }
  if ((c.kind == ir::CycleKind::FineBore || c.kind == ir::CycleKind::BackBore) && !(c.shift > 0)) {
    d_.error(r.loc, "CYCLE/BORE," + std::string(orient ? "ORIENT" : "BACK") + ": needs SHIFT,s (the tool's shift off the wall)");
    return;
  }
  if (cycle_open_) d_.warning(r.loc, "CYCLE replaces a cycle still on (no CYCLE/OFF before it)", "cycle without off");
  cycle_open_ = true;
  op_.cycles.push_back(c);
  push(r.loc, ir::CycleOn{uint32_t(op_.cycles.size() - 1)});
}

}  // namespace clpc
