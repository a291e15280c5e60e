// Where the tool is and the feed in force, as a lathe cycle pass walks an operation's
// instructions (groove-cycles, thread-cycles): what a collapse starts from.
#pragma once

#include "ir/ir.h"

namespace clpc {

struct MotionState {
  ir::Vec3 pos = ir::Vec3::Zero();
  bool have_pos = false;
  ir::Feed feed;
  bool feed_known = false;

  void track(const ir::Instr& in) {
    if (auto* m = std::get_if<ir::Move>(&in.op)) {
      pos = m->point;
      have_pos = true;
    } else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
      pos = a->end;
      have_pos = true;
    } else if (auto* f = std::get_if<ir::Feed>(&in.op)) {
      feed = *f;
      feed_known = true;
    } else if (auto* g = std::get_if<ir::Groove>(&in.op)) {
      pos = g->start;  // a cycle ends where it started
    } else if (auto* t = std::get_if<ir::ThreadCycle>(&in.op)) {
      pos = t->start;
    } else if (std::holds_alternative<ir::ToolChange>(in.op)) {
      have_pos = false;  // the new tool is wherever the change left it
    }
  }
};

// Where a section the lowering marked ends (a THREAD or a CYCLE/ROUGH, whose motion is some
// other pass's or the backend's): the index of its end mark, or the body's end if it goes on
// in the next chunk. `i` itself when body[i] begins no such section.
inline size_t marked_section_end(const std::vector<ir::Instr>& body, size_t i) {
  const auto* t = std::get_if<ir::ThreadMark>(&body[i].op);
  const auto* r = std::get_if<ir::RoughMark>(&body[i].op);
  if (!(t && t->begin) && !(r && r->begin)) return i;
  size_t j = i + 1;
  while (j < body.size() &&
         !(t ? std::holds_alternative<ir::ThreadMark>(body[j].op) : std::holds_alternative<ir::RoughMark>(body[j].op)))
    ++j;
  return j;
}

}  // namespace clpc
