// CYCLE records: the drilling, tapping and boring cycles of every CAM system's vocabulary,
// read into one model (ir::CycleSpec). Distances are along the tool axis from each hole's GOTO
// point. The table of forms, with the files that show them, is in docs/cl-input.md ("Cycles").
//
//   NX          CYCLE/DRILL,RAPTO,r,FEDTO,d,MMPM,f[,RTRCTO,t|AUTO]
//               CYCLE/DRILL,DEEP|BRKCHP,FEDTO,d,INCR,s,...   CYCLE/DRILL,DWELL,t,...
//   Creo        CYCLE/DRILL,DEPTH,d,IPM,f,CLEAR,c     CYCLE/DEEP,DEPTH,d,STEP,s,MMPM,f,CLEAR,c
//               CYCLE/TAP,DEPTH,d,TPI,n,CLEAR,c
//   CATIA       CYCLE/DRILL,DEPTH,d,MMPR,f,CLEAR,c,RETURN,t   (ICAM PP table: keywords)
//               CYCLE/DRILL,d,c[,f,MMPM]                     (default PP table: by position)
//   APT         CYCLE/DRILL,d,IPM,f,c                        (by position: depth, feed, clearance)
//   APT, SolidWorks CAM
//               CYCLE/INIT ... CYCLE/DEEP2,FEDTO,d,1STPECK,p,SUBPECK,q,MMPM,f,RAPTO,r,RTRCTO,t
//               CYCLE/DEEP,FEDTO,d,INCR,q,...  ... CYCLE/OFF (or CYCLE/CLEAR)
//   CAMWorks    CYCLE/DRILL,... defines; CYCLE/ON starts the last one again; CYCLE/OFF
#include <cmath>

#include "lower/lower.h"
#include "lower/params.h"

namespace clpc {

namespace {

constexpr double kMaxPecks = 10000;

bool feed_word(const std::string& w) {
  return w == "IPM" || w == "MMPM" || w == "IPR" || w == "MMPR" || w == "PERMIN" || w == "PERREV" || w == "FPM";
}

}  // namespace

void Lowerer::lower_cycle(const Record& r) {
  ParamReader ps(r, d_);
  if (ps.size() == 0 || !ps[0].is_word()) {
    d_.error(ps.size() ? ps[0].loc : r.end, "CYCLE: expected the cycle kind (DRILL, DEEP, TAP, BORE, ..., OFF)");
    return;
  }
  ensure_operation(r.loc);
  std::string kind = upper(ps[0].text);
  if (kind == "ROUGH") {
    lower_rough_cycle(r);
    return;
  }
  if ((kind == "OFF" || kind == "CLEAR") && ps.size() == 1 && rough_open_) {
    end_rough_cycle(r);
    return;
  }
  if (rough_open_) {
    d_.error(r.loc, "CYCLE/" + kind + " inside a CYCLE/ROUGH (no CYCLE/OFF before it)");
    return;
  }
  if ((kind == "OFF" || kind == "CLEAR") && ps.size() == 1) {
    if (!cycle_open_) d_.warning(r.loc, "CYCLE/" + kind + " with no cycle on", "cycle");
    else if (cycle_holes_ == 0)
      d_.warning(cycle_loc_, "CYCLE/" + cycle_name_ + " drills no hole: no GOTO before its CYCLE/" + kind, "cycle");
    cycle_open_ = false;
    push(r.loc, ir::CycleOff{});
    return;
  }
  if (kind == "INIT" && ps.size() == 1) return;  // SolidWorks CAM: the cycle records follow
  if (kind == "ON" && ps.size() == 1) {
    if (!last_cycle_) {
      d_.error(r.loc, "CYCLE/ON with no cycle defined before it");
      return;
    }
    start_cycle(*last_cycle_, r.loc, cycle_name_);
    return;
  }
  if (kind == "AUTO") {
    motion_not_read(r, "CYCLE/AUTO leaves the choice of cycle to the post; have the CAM system write the cycle "
                       "(DRILL, DEEP, TAP, ...) with its depth");
    return;
  }
  if (ps.has("XAXIS") || ps.has("ZAXIS") || (kind == "RADIUS")) {
    lower_groove_cycle(r);
    return;
  }

  ir::CycleSpec c;
  bool orient = false, drag = false, back = false;
  std::optional<ir::SpindleDir> record_dir;  // a tap's CLW or CCLW word
  SourceLoc record_dir_loc;
  if (kind == "DRILL") c.kind = ir::CycleKind::Drill;
  else if (kind == "DEEP" || kind == "DEEP2") c.kind = ir::CycleKind::Peck;
  else if (kind == "BRKCHP") c.kind = ir::CycleKind::ChipBreak;
  else if (kind == "TAP") c.kind = ir::CycleKind::Tap;
  else if (kind == "BORE" || kind == "REAM") c.kind = ir::CycleKind::Bore;
  else if (kind == "CSINK" || kind == "FACE" || kind == "SPOT") c.kind = ir::CycleKind::SpotDwell;
  else {
    d_.error(ps[0].loc, "CYCLE: unknown cycle '" + std::string(ps[0].name()) +
                            "' (DRILL, DEEP, DEEP2, BRKCHP, TAP, BORE, REAM, CSINK, FACE, SPOT, ON, INIT or OFF)");
    return;
  }

  bool depth = false, clear = false, pitch_given = false;
  size_t first = 1, skip = ps.size();  // the keyword pairs are read from `first`, past `skip`
  // CATIA's default PP table writes the values by position: depth, clearance, then perhaps the
  // feed and its unit (karlo_DEMO2: CYCLE/TAP, 50.786017, 1.000000 after an approach 1.0 above the
  // hole). A peck cycle's positions are not documented: refused.
  if (ps.size() > 1 && ps[1].is_number()) {
    if (c.kind == ir::CycleKind::Peck || c.kind == ir::CycleKind::ChipBreak) {
      d_.error(ps[1].loc, "CYCLE/" + kind + ": the values have no keywords, and which is the peck is not known; "
                          "have the CAM system write keywords (DEPTH, STEP, CLEAR, ...)");
      return;
    }
    // By position: depth, clearance[, f, unit] (CATIA); APT's own form puts the feed between
    // them: depth, unit, f, clearance.
    const bool apt = ps.size() >= 5 && ps[2].is_word() && feed_word(upper(ps[2].text)) && ps[3].is_number() &&
                     ps[4].is_number();
    if (!apt && (ps.size() < 3 || !ps[2].is_number())) {
      d_.error(ps.loc(2), "CYCLE/" + kind + ": by position, the depth and the clearance come first (d,c[,f,MMPM]), or "
                          "the depth, the feed and the clearance (d,MMPM,f,c)");
      return;
    }
    if (!apt && ps.size() > 3 && !(ps.size() == 5 && ps[3].is_number() && ps[4].is_word() && feed_word(upper(ps[4].text)))) {
      d_.error(ps[3].loc, "CYCLE/" + kind + ": by position, only a feed and its unit (MMPM, IPM, MMPR, IPR) may "
                          "follow the depth and the clearance");
      return;
    }
    c.depth = ps[1].number;
    c.clearance = apt ? ps[4].number : ps[2].number;
    if (c.depth < 0) {
      d_.error(ps[1].loc, "CYCLE: the depth must not be negative, found " + num_text(c.depth));
      return;
    }
    depth = clear = true;
    first = apt ? 2 : 3;  // the feed pair reads below (CATIA's turned round: f, unit)
    if (apt) skip = 4;    // the clearance, read; keywords may follow it (DWELL,t)
  }

  for (size_t i = first; i < ps.size(); ++i) {
    if (i == skip) continue;
    const Param& p = ps[i];
    double v = 0;
    const Param* vp = nullptr;
    std::string w;
    if (p.is_number() && i + 1 < ps.size() && ps[i + 1].is_word() && feed_word(upper(ps[i + 1].text))) {
      w = upper(ps[i + 1].text);  // f,MMPM: the value before its unit
      v = p.number;
      vp = &p;
      ++i;
    } else if (p.is_number()) {
      d_.error(p.loc, "CYCLE: the number " + num_text(p.number) + " has no keyword before it");
      return;
    } else if (p.is_empty()) {
      continue;
    } else {
      w = upper(p.text);
      // Words that take no value.
      if (w == "ORIENT") { orient = true; continue; }
      if (w == "DRAG") { drag = true; continue; }
      if (w == "BACK") { back = true; continue; }
      if (w == "CLW" || w == "CCLW") {
        record_dir = w == "CLW" ? ir::SpindleDir::Cw : ir::SpindleDir::Ccw;
        record_dir_loc = p.loc;
        continue;
      }
      if (w == "RIGID" || w == "FLOAT" || w == "NODRAG" || w == "AUTO") continue;
      // NX names the kind of a drilling cycle in a second word: CYCLE/DRILL,DEEP,... and
      // CYCLE/DRILL,BRKCHP,... are the peck and chip-break cycles.
      if (i == 1 && c.kind == ir::CycleKind::Drill && (w == "DEEP" || w == "BRKCHP")) {
        c.kind = w == "DEEP" ? ir::CycleKind::Peck : ir::CycleKind::ChipBreak;
        kind += "," + w;
        continue;
      }
      // NX's RTRCTO,AUTO: back to where the tool was when the cycle began, as with no RTRCTO.
      if ((w == "RTRCTO" || w == "RETURN") && i + 1 < ps.size() && ps[i + 1].is_word() && upper(ps[i + 1].text) == "AUTO") {
        ++i;
        continue;
      }
      if (w == "DWELL" && (i + 1 >= ps.size() || !ps[i + 1].is_number())) continue;  // bare DWELL: a modifier
      if (i + 1 >= ps.size() || !ps[i + 1].is_number()) {
        d_.error(i + 1 < ps.size() ? ps[i + 1].loc : r.end, "CYCLE: a number must follow " + std::string(p.text));
        return;
      }
      vp = &ps[i + 1];
      v = vp->number;
      ++i;
    }
    auto non_negative = [&](const char* what) {
      if (v >= 0) return true;
      d_.error(vp->loc, "CYCLE: " + std::string(what) + " must not be negative, found " + num_text(v));
      return false;
    };
    if (w == "DEPTH" || w == "FEDTO") {
      // NX writes FEDTO as a signed distance along the tool axis from the hole's top, so a hole
      // below it is negative (its posts take the bottom as the point + FEDTO x the tool axis);
      // a positive one would put the bottom above the top, where no hole is: refused, not read
      // as a depth (other systems write FEDTO as the depth, positive).
      if (w == "FEDTO" && info_.cam == ir::CamSystem::Nx) {
        if (v > 0) {
          d_.error(vp->loc, "CYCLE: in NX's CL, FEDTO is signed along the tool axis from the hole's top, so " +
                                num_text(v) + " puts the bottom above the top; a hole " + num_text(v) +
                                " deep is FEDTO," + num_text(-v));
          return;
        }
        v = -v;
      }
      if (!non_negative("the depth")) return;
      c.depth = v;
      depth = true;
    } else if (w == "CLEAR" || w == "RAPTO") {
      c.clearance = v;
      clear = true;
    } else if (w == "RTRCTO" || w == "RETURN") {
      c.retract = v;
    } else if (w == "STEP" || w == "1STPECK" || w == "PECK" || w == "INCR") {
      if (!non_negative("the peck")) return;
      c.peck = v;
    } else if (w == "2NDPECK" || w == "SUBPECK") {
      if (!non_negative("the peck")) return;
      c.peck_next = v;
    } else if (w == "DWELL") {
      if (!non_negative("the dwell")) return;
      c.dwell = v;
    } else if (w == "TPI") {
      if (!(v > 0)) {
        d_.error(vp->loc, "CYCLE: TPI must be greater than zero");
        return;
      }
      c.pitch = 25.4 / v / ir::mm_per_unit(info_.units);
      pitch_given = true;
    } else if (w == "PITCH") {
      if (!(v > 0)) {
        d_.error(vp->loc, "CYCLE: PITCH must be greater than zero");
        return;
      }
      c.pitch = v;
      pitch_given = true;
    } else if (w == "SHIFT") {
      c.shift = v;
    } else if (feed_word(w)) {
      bool inch = w[0] == 'I' || w == "FPM";
      const double unit_mm = w == "FPM" ? 304.8 : inch ? 25.4 : 1.0;
      double scale = w == "PERMIN" || w == "PERREV" ? 1 : unit_mm / ir::mm_per_unit(info_.units);
      c.feed = v * scale;
      c.feed_mode = (w == "IPR" || w == "MMPR" || w == "PERREV") ? ir::FeedMode::PerRev : ir::FeedMode::PerMinute;
      if (!(c.feed > 0)) {
        d_.error(vp->loc, "CYCLE: the feed must be greater than zero");
        return;
      }
    } else {
      d_.error(p.loc, "CYCLE: unknown word '" + std::string(p.name()) + "'");
      return;
    }
  }
  if (!depth) {
    d_.error(r.loc, "CYCLE/" + kind + ": no depth (DEPTH or FEDTO)");
    return;
  }
  if (c.depth == 0)
    d_.warning(r.loc, "CYCLE/" + kind + ": the depth is zero: each hole is a touch of its top", "cycle");
  if (!clear) d_.warning(r.loc, "CYCLE/" + kind + ": no clearance (CLEAR or RAPTO); the R plane is at the hole's top", "cycle", "clearance");
  // Below the top: the tool rapids into the hole, right only where it is already there (a pilot,
  // a counterbore). Said, not refused: NX's RAPTO,-15 after a pilot drill is a shop's way
  // (helper-62 found CLEAR,-2 written as R-2. without a word).
  if (clear && c.clearance < 0)
    d_.warning(r.loc, "CYCLE/" + kind + ": the clearance " + num_text(c.clearance) + " puts the R plane " +
                          num_text(-c.clearance) + " below the hole's top: the tool goes there at rapid, into the "
                          "hole (right only where a pilot or a counterbore is already there)",
               "cycle");
  // RETURN/RTRCTO at or below the clearance plane: back to the R plane.
  if (c.retract >= 0 && c.retract <= c.clearance) c.retract = c.clearance;
  if (c.kind == ir::CycleKind::Peck || c.kind == ir::CycleKind::ChipBreak) {
    if (!(c.peck > 0)) {
      if (c.kind == ir::CycleKind::Peck && c.peck == 0 && c.peck_next == 0) {
        d_.warning(r.loc, "CYCLE/" + kind + " with no peck depth (STEP, 1STPECK, INCR): drilled to the depth in one go",
                   "cycle");
        c.kind = ir::CycleKind::Drill;
      } else {
        d_.error(r.loc, "CYCLE/" + kind + ": a peck cycle needs a peck depth (STEP, 1STPECK or INCR) greater than zero");
        return;
      }
    } else {
      // Bounded: a hole written as moves (or read back) takes one peck per step.
      const double smallest = c.peck_next > 0 ? std::min(c.peck, c.peck_next) : c.peck;
      if (std::abs(c.depth) / smallest > kMaxPecks) {
        d_.error(r.loc, "CYCLE/" + kind + ": a peck depth of " + num_text(smallest) + " makes more than " +
                            std::to_string(long(kMaxPecks)) + " pecks per hole of depth " + num_text(std::abs(c.depth)));
        return;
      }
    }
  } else if (c.peck > 0 && c.kind == ir::CycleKind::Drill) {
    c.kind = ir::CycleKind::Peck;
  }
  if (c.kind == ir::CycleKind::Tap) {
    if (!pitch_given) {
      // The pitch from the cycle's own feed: per revolution it is the pitch; per minute
      // (NX's CYCLE/TAP,...,MMPM,f) it is the feed over the spindle speed in force, which is
      // how the CAM system made it and how the control's G84 in G94 reads F and S.
      const bool rpm = last_spindle_ && last_spindle_->mode == ir::SpindleMode::Rpm && last_spindle_->speed > 0;
      if (c.feed_mode == ir::FeedMode::PerRev && c.feed > 0) c.pitch = c.feed;
      else if (c.feed_mode == ir::FeedMode::PerMinute && c.feed > 0 && rpm) c.pitch = c.feed / last_spindle_->speed;
      else {
        d_.error(r.loc, "CYCLE/TAP: no thread pitch (TPI, PITCH, a feed per revolution, or a feed per minute "
                        "with the spindle's rpm before the cycle)");
        return;
      }
    }
    c.left_hand = last_spindle_ && last_spindle_->dir == ir::SpindleDir::Ccw;
    // The tap's hand from the record's CLW/CCLW too: against the spindle's direction the CL
    // contradicts itself, and a tap turned the wrong way breaks (it was tapped by the SPINDL's).
    if (record_dir && last_spindle_ && last_spindle_->dir != ir::SpindleDir::Off && *record_dir != last_spindle_->dir) {
      d_.error(record_dir_loc, "CYCLE/TAP says the spindle turns " +
                                   std::string(*record_dir == ir::SpindleDir::Cw ? "clockwise (a right-hand tap)" : "counter-clockwise (a left-hand tap)") +
                                   ", but the SPINDL in force turns it the other way: which hand the thread is, is not known");
      return;
    }
    if (record_dir) c.left_hand = *record_dir == ir::SpindleDir::Ccw;
  }
  if (c.kind == ir::CycleKind::Bore) {
    if (orient) c.kind = ir::CycleKind::FineBore;
    else if (back) c.kind = ir::CycleKind::BackBore;
    else if (drag) c.kind = ir::CycleKind::BoreStop;
    else if (c.dwell > 0) c.kind = ir::CycleKind::BoreDwell;
  } else if (c.dwell > 0 && c.kind == ir::CycleKind::Drill) {
    c.kind = ir::CycleKind::SpotDwell;
  }
  if (c.kind == ir::CycleKind::BackBore) {
    // G87 bores up from the bottom: its R is the hole's bottom and Z the level it bores up to,
    // the other way round from every other cycle. clpc writes it as the others (R above Z), a
    // program the control would run wrong; until that is written and read back, refused.
    d_.error(r.loc, "CYCLE/BORE,BACK: back boring (G87) is not posted by clpc; have the CAM system write it as motion");
    return;
  }
  // A dwell only the spot-drilling and dwell-boring cycles write (G82, G89 P): with another
  // cycle it would be dropped without a word.
  if (c.dwell > 0 && c.kind != ir::CycleKind::SpotDwell && c.kind != ir::CycleKind::BoreDwell)
    d_.warning(r.loc, "CYCLE/" + kind + ": the dwell of " + num_text(c.dwell) + " s is not written: clpc writes a dwell with "
                          "the DRILL (G82) and BORE (G89) cycles only",
               "cycle");
  if ((c.kind == ir::CycleKind::FineBore || c.kind == ir::CycleKind::BackBore) && !(c.shift > 0)) {
    d_.error(r.loc, "CYCLE/BORE," + std::string(orient ? "ORIENT" : "BACK") + ": needs SHIFT,s (the tool's shift off the wall)");
    return;
  }
  // A cycle with no feed of its own is cut at the feed in force; an inverse-time F is one
  // move's time, not a cycle's feed (G81 in G93: the control alarms or cuts each hole in the
  // time of the move before).
  if (!(c.feed > 0) && inverse_time_) {
    d_.error(r.loc, "CYCLE/" + kind + " with no feed of its own under an inverse-time feed (FEDRAT/INVERS): one "
                    "move's time is no drilling feed; give the cycle its feed (MMPM, IPM, MMPR, IPR)");
    return;
  }
  if (cycle_open_) d_.warning(r.loc, "CYCLE replaces a cycle still on (no CYCLE/OFF before it)", "cycle");
  last_cycle_ = c;
  start_cycle(c, r.loc, kind);
}

void Lowerer::start_cycle(const ir::CycleSpec& c, SourceLoc loc, const std::string& name) {
  cycle_open_ = true;
  drilling_ = true;
  section_feed_ = c.feed > 0;
  cycle_holes_ = 0;
  cycle_loc_ = loc;
  cycle_name_ = name;
  make_room();
  op_.cycles.push_back(c);
  push(loc, ir::CycleOn{uint32_t(op_.cycles.size() - 1)});
}

}  // namespace clpc
