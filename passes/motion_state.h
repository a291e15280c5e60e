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

}  // namespace clpc
