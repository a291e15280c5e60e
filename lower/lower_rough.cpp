// Lathe stock-removal records (docs/lathe.md, "Stock removal"): a CAM template (Creo's MUDF,
// an NX user-defined event) writes the roughing cycle as a command that brackets the
// finishing profile, as the groove cycles are written:
//   CYCLE/ROUGH,TURN|FACE,DEPTH,d,RETRACT,e[,ALLOW,u,w][,FEED,f|MMPR,f|IPR,f|MMPM,f|IPM,f][,FINISH]
//     ... the profile: from the start point A to A' along the level axis, then to B ...
//   CYCLE/OFF
// Keywords after TURN|FACE in any order; lengths in program units, radius values (the CL's X is
// a radius). After CYCLE/OFF the tool is back at A, as the control leaves it.
#include "lower/lower.h"
#include "lower/params.h"

namespace clpc {

void Lowerer::lower_rough_cycle(const Record& r) {
  ParamReader ps(r, d_);
  ir::RoughMark m;
  if (ps.size() < 2 || !(ps[1].is("TURN") || ps[1].is("FACE"))) {
    d_.error(ps.size() > 1 ? ps[1].loc : r.end, "CYCLE/ROUGH: expected TURN (G71, levels along X) or FACE (G72, levels along Z)");
    return;
  }
  m.facing = ps[1].is("FACE");
  bool depth = false, retract = false;
  for (size_t i = 2; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (p.is_number()) {
      d_.error(p.loc, "CYCLE/ROUGH: the number " + num_text(p.number) + " has no keyword before it");
      return;
    }
    if (p.is("FINISH")) {
      m.finish = true;
      continue;
    }
    const size_t count = p.is("ALLOW") ? 2 : 1;
    for (size_t k = 1; k <= count; ++k)
      if (i + k >= ps.size() || !ps[i + k].is_number()) {
        d_.error(i + k < ps.size() ? ps[i + k].loc : r.end,
                 "CYCLE/ROUGH: " + std::string(count == 2 ? "two numbers" : "a number") + " must follow " + std::string(p.text));
        return;
      }
    const double v = ps[i + 1].number;
    const SourceLoc vloc = ps[i + 1].loc;
    auto positive = [&](const char* what, bool zero_ok) { return positive_value(d_, "CYCLE/ROUGH", what, v, vloc, zero_ok); };
    if (p.is("DEPTH")) {
      if (!positive("DEPTH", false)) return;
      m.depth = v;
      depth = true;
    } else if (p.is("RETRACT")) {
      if (!positive("RETRACT", true)) return;
      m.retract = v;
      retract = true;
    } else if (p.is("ALLOW")) {
      m.allow_x = v;  // signed: the side of the profile the stock is on
      m.allow_z = ps[i + 2].number;
    } else if (is_feed_word(p)) {
      if (!positive("the feed", false)) return;
      read_feed_word(p, v, info_.units, m.feed, m.feed_mode);
    } else {
      d_.error(p.loc, "CYCLE/ROUGH: unknown word '" + std::string(p.text) +
                          "' (read: TURN, FACE, DEPTH, RETRACT, ALLOW, FEED, MMPR, IPR, MMPM, IPM, FINISH)");
      return;
    }
    i += count;
  }
  std::string missing;
  if (!depth) missing += " DEPTH";
  if (!retract) missing += " RETRACT";
  if (!missing.empty()) {
    d_.error(r.loc, "CYCLE/ROUGH: missing" + missing);
    return;
  }
  if (!has_pos_) {
    d_.error(r.loc, "CYCLE/ROUGH with no tool position before it: the cycle starts where the tool stands");
    return;
  }
  if (cycle_open_ || thread_open_ || rough_open_) {
    d_.error(r.loc, std::string("CYCLE/ROUGH inside ") + (thread_open_ ? "a THREAD" : "another CYCLE") + " (no OFF before it)");
    return;
  }
  ensure_operation(r.loc);
  m.start = pos_;
  rough_open_ = true;
  section_feed_ = m.feed > 0;
  rough_loc_ = r.loc;
  rough_start_ = pos_;
  rough_size_ = op_.body.size();
  push(r.loc, m);
}

void Lowerer::end_rough_cycle(const Record& r) {
  rough_open_ = false;
  push(r.loc, ir::RoughMark{false});
  // The control returns to the start point: the CL's next move starts there.
  ir::Move back;
  back.kind = ir::MoveKind::From;
  back.point = rough_start_;
  back.axis = axis_;
  push(r.loc, back);
  pos_ = rough_start_;
}

}  // namespace clpc
