#include "passes/cycle_expand.h"

#include <algorithm>

namespace clpc {

bool expand_hole(const ir::Hole& h, const ir::CycleSpec& c, const ExpandContext& x, SourceLoc loc,
                 std::vector<ir::Instr>& out, Diagnostics& d) {
  using ir::CycleKind;
  if (c.kind == CycleKind::Tap || c.kind == CycleKind::FineBore || c.kind == CycleKind::BackBore) {
    // Say which code would post it: the machine key a user can set in the TOML.
    const char* key = c.kind == CycleKind::FineBore ? "codes.cycle_fine_bore"
                      : c.kind == CycleKind::BackBore ? "codes.cycle_back_bore"
                      : c.left_hand                   ? "codes.cycle_tap_left"
                                                      : "codes.cycle_tap";
    d.error(loc, std::string("a ") + std::string(ir::cycle_kind_name(c.kind)) +
                     " cycle cannot be written as plain moves: the machine needs the canned cycle for it, " +
                     (x.lathe ? std::string("and a lathe writes every drilling cycle as moves (its G83/G84 are "
                                            "live-tool cycles clpc does not post)")
                      : x.why_moves ? std::string("but ") + x.why_moves
                                    : "and the machine has none (" + std::string(key) + " is empty)"));
    return false;
  }
  const ir::Vec3 a = h.axis;
  auto at = [&](double height) { return ir::Vec3(h.point + a * height); };
  auto move = [&](double height, ir::MoveKind k) {
    ir::Move m;
    m.point = at(height);
    m.axis = h.axis;
    m.kind = k;
    out.push_back({loc, m});
  };
  auto feed = [&](double value, ir::FeedMode mode) {
    ir::Feed f;
    f.value = value;
    f.mode = mode;
    out.push_back({loc, f});
  };
  const double r = c.clearance, bottom = -c.depth;
  const double ret = x.return_initial ? std::max(h.initial, r) : r;
  move(std::max(h.initial, r), ir::MoveKind::Rapid);  // over the hole, at the level the tool is at
  move(r, ir::MoveKind::Rapid);
  if (c.feed > 0) feed(c.feed, c.feed_mode);
  switch (c.kind) {
    case CycleKind::Drill:
    case CycleKind::SpotDwell:
      move(bottom, ir::MoveKind::Feed);
      if (c.kind == CycleKind::SpotDwell) out.push_back({loc, ir::Dwell{c.dwell, false}});
      move(ret, ir::MoveKind::Rapid);
      break;
    case CycleKind::Peck:
    case CycleKind::ChipBreak: {
      double reached = 0;  // depth below the hole point cut so far
      double peck = c.peck;
      bool first = true;
      // The R plane may lie below the hole's top: pecks count from wherever cutting starts.
      double start = std::min(0.0, r);
      reached = -start;
      while (reached < c.depth - 1e-12) {
        double target = std::min(c.depth, reached + peck);
        if (!first && c.kind == CycleKind::Peck) move(-reached + x.peck_clearance, ir::MoveKind::Rapid);
        move(-target, ir::MoveKind::Feed);
        reached = target;
        if (reached < c.depth - 1e-12)
          move(c.kind == CycleKind::Peck ? r : -reached + x.peck_clearance, ir::MoveKind::Rapid);
        first = false;
        if (c.peck_next > 0) peck = c.peck_next;
      }
      move(ret, ir::MoveKind::Rapid);
      break;
    }
    case CycleKind::Bore:
    case CycleKind::BoreDwell:
      move(bottom, ir::MoveKind::Feed);
      if (c.kind == CycleKind::BoreDwell) out.push_back({loc, ir::Dwell{c.dwell, false}});
      move(r, ir::MoveKind::Feed);
      if (ret != r) move(ret, ir::MoveKind::Rapid);
      break;
    case CycleKind::BoreStop: {
      move(bottom, ir::MoveKind::Feed);
      ir::Spindle off;
      off.dir = ir::SpindleDir::Off;
      out.push_back({loc, off});
      move(ret, ir::MoveKind::Rapid);
      if (x.spindle_rpm > 0) {
        ir::Spindle on;
        on.speed = x.spindle_rpm;
        on.dir = x.spindle_dir;
        out.push_back({loc, on});
      }
      break;
    }
    default: break;
  }
  if (c.feed > 0 && x.have_feed) feed(x.current_feed, x.current_mode);
  return true;
}

}  // namespace clpc
