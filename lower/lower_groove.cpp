// Lathe groove cycle records (the seed paper's user-defined feature):
//   CYCLE/FACE,RETRACT,e,XAXIS,p,ZAXIS,q,FEED,f     -> G74 (face groove, pecks along Z)
//   CYCLE/RADIUS,RETRACT,e,XAXIS,p,ZAXIS,q,FEED,f   -> G75 (radial groove, pecks along X)
// Keywords in any order; XAXIS is always the amount along X and ZAXIS along Z, whichever
// of them is the peck and which the shift. The motion up to CYCLE/OFF is the groove.
#include "lower/lower.h"
#include "lower/params.h"

namespace clpc {

void Lowerer::lower_groove_cycle(const Record& r) {
  ParamReader ps(r, d_);
  ir::GrooveSpec g;
  g.from_record = true;
  if (ps[0].is("FACE")) g.face = true;
  else if (!ps[0].is("RADIUS")) {
    d_.error(ps[0].loc, "CYCLE: a groove cycle is FACE or RADIUS, found '" + std::string(ps[0].text) + "'");
    return;
  }
  bool retract = false, x = false, z = false;
  for (size_t i = 1; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (p.is_number()) {
      d_.error(p.loc, "CYCLE: the number " + num_text(p.number) + " has no keyword before it");
      return;
    }
    if (i + 1 >= ps.size() || !ps[i + 1].is_number()) {
      d_.error(i + 1 < ps.size() ? ps[i + 1].loc : r.end, "CYCLE: a number must follow " + std::string(p.text));
      return;
    }
    double v = ps[i + 1].number;
    SourceLoc vloc = ps[i + 1].loc;
    ++i;
    auto positive = [&](const char* what, bool zero_ok) { return positive_value(d_, "CYCLE", what, v, vloc, zero_ok); };
    if (p.is("RETRACT")) {
      if (!positive("RETRACT", true)) return;
      g.retract = v;
      retract = true;
    } else if (p.is("XAXIS")) {
      if (!positive("XAXIS", false)) return;
      g.x_amount = v;
      x = true;
    } else if (p.is("ZAXIS")) {
      if (!positive("ZAXIS", false)) return;
      g.z_amount = v;
      z = true;
    } else if (p.is("RELIEF")) {
      if (!positive("RELIEF", true)) return;
      g.relief = v;
    } else if (is_feed_word(p)) {
      if (!positive("the feed", false)) return;
      read_feed_word(p, v, info_.units, g.feed, g.feed_mode);
    } else {
      d_.error(p.loc, "CYCLE: unknown word '" + std::string(p.text) + "' in a groove cycle");
      return;
    }
  }
  std::string missing;
  if (!retract) missing += " RETRACT";
  if (!x) missing += " XAXIS";
  if (!z) missing += " ZAXIS";
  if (!missing.empty()) {
    d_.error(r.loc, "CYCLE/" + std::string(g.face ? "FACE" : "RADIUS") + ": missing" + missing);
    return;
  }
  ensure_operation(r.loc);
  if (cycle_open_) d_.warning(r.loc, "CYCLE replaces a cycle still on (no CYCLE/OFF before it)", "cycle");
  cycle_open_ = true;
  drilling_ = false;
  section_feed_ = g.feed > 0;
  make_room();
  op_.grooves.push_back(g);
  push(r.loc, ir::GrooveOn{uint32_t(op_.grooves.size() - 1)});
}

}  // namespace clpc
