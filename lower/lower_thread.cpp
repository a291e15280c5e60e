// Lathe threading records (docs/lathe.md, "Threads"):
//   THREAD/TURN|FACE|TAPER[,LEAD|PITCH],l[,MMPR|IPR]  ... motion ...  THREAD/OFF
// The APT form (ISO 4343): a thread along Z (TURN), across the face along X (FACE) or along a
// cone (TAPER), cut at lead l (program units per revolution; MMPR / IPR name the unit). Without
// a number the lead is the feed per revolution in force at each cut. Inside, a feed move along
// the thread is a synchronised cut; the thread-cycles pass turns whole passes into G92 / G76.
#include "lower/lower.h"
#include "lower/params.h"

namespace clpc {

void Lowerer::lower_thread(const Record& r) {
  ParamReader ps(r, d_);
  if (ps.size() == 0 || !ps[0].is_word()) {
    d_.error(ps.size() ? ps[0].loc : r.end, "THREAD: expected TURN, FACE, TAPER or OFF");
    return;
  }
  ensure_operation(r.loc);
  if (ps[0].is("OFF") && ps.size() == 1) {
    if (!thread_open_) {
      d_.warning(r.loc, "THREAD/OFF with no thread on", "cycle");
      return;
    }
    thread_open_ = false;
    push(r.loc, ir::ThreadMark{false, ir::ThreadKind::Turn, 0});
    return;
  }
  ir::ThreadMark t;
  if (ps[0].is("TURN")) t.kind = ir::ThreadKind::Turn;
  else if (ps[0].is("FACE")) t.kind = ir::ThreadKind::Face;
  else if (ps[0].is("TAPER")) t.kind = ir::ThreadKind::Taper;
  else {
    d_.error(ps[0].loc, "THREAD: a thread is TURN, FACE or TAPER (or THREAD/OFF), found '" + std::string(ps[0].text) + "'");
    return;
  }
  double scale = 1;
  bool have_lead = false;
  for (size_t i = 1; i < ps.size(); ++i) {
    const Param& p = ps[i];
    if (p.is_number()) {
      if (have_lead) {
        d_.error(p.loc, "THREAD: a second number " + num_text(p.number) + " (only the lead is read)");
        return;
      }
      if (!(p.number > 0)) {
        d_.error(p.loc, "THREAD: the lead must be greater than zero, found " + num_text(p.number));
        return;
      }
      t.lead = p.number;
      have_lead = true;
    } else if (p.is("LEAD") || p.is("PITCH")) {
      if (i + 1 >= ps.size() || !ps[i + 1].is_number()) {
        d_.error(i + 1 < ps.size() ? ps[i + 1].loc : r.end, "THREAD: a number must follow " + std::string(p.text));
        return;
      }
    } else if (p.is("MMPR") || p.is("IPR")) {
      scale = (p.is("IPR") ? 25.4 : 1.0) / ir::mm_per_unit(info_.units);
    } else {
      d_.error(p.loc, "THREAD: unknown word '" + std::string(p.text) +
                          "' (read: TURN, FACE, TAPER, LEAD, PITCH, MMPR, IPR, the lead, OFF)");
      return;
    }
  }
  t.lead *= scale;
  if (rough_open_) {
    d_.error(r.loc, "THREAD inside a CYCLE/ROUGH (no CYCLE/OFF before it)");
    return;
  }
  if (thread_open_) {
    d_.warning(r.loc, "THREAD replaces a thread still on (no THREAD/OFF before it)", "cycle");
    push(r.loc, ir::ThreadMark{false, ir::ThreadKind::Turn, 0});  // the first section ends here
  }
  thread_open_ = true;
  section_feed_ = true;  // the lead is the feed
  push(r.loc, t);
}

}  // namespace clpc
