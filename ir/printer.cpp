#include "ir/printer.h"

#include "support/text.h"

namespace clpc::ir {

namespace {

std::string vec(const Vec3& v) { return "(" + num_text(v.x()) + ", " + num_text(v.y()) + ", " + num_text(v.z()) + ")"; }

const char* dir_name(ArcDir d) {
  switch (d) {
    case ArcDir::Ccw: return "ccw";
    case ArcDir::Cw: return "cw";
    case ArcDir::Unknown: break;
  }
  return "?";
}

const char* layout_name(ArcLayout l) {
  switch (l) {
    case ArcLayout::Nx11: return "nx11";
    case ArcLayout::Creo7: return "creo7";
    case ArcLayout::NoRadius6: return "noradius6";
    case ArcLayout::Synthetic: return "synthetic";
    case ArcLayout::Worded: return "worded";
    case ArcLayout::Movarc: return "movarc";
    case ArcLayout::Contour: return "contour";
  }
  return "?";
}

struct Printer {
  std::ostream& o;
  const Operation& op;

  void operator()(const Move& m) {
    o << (m.kind == MoveKind::Rapid ? "rapid " : m.kind == MoveKind::Feed ? "feed " : "from ") << vec(m.point);
    if (m.axis_written || m.axis != Vec3::UnitZ()) o << " axis " << vec(m.axis);
    if (m.has_rotary) o << " rotary (" << num_text(m.rotary[0]) << ", " << num_text(m.rotary[1]) << ")";
    if (m.inverse_time > 0) o << " inverse-time " << num_text(m.inverse_time);
  }
  void operator()(const RotaryPosition& r) {
    o << "rotary-position (" << num_text(r.rotary[0]) << ", " << num_text(r.rotary[1]) << ")" << (r.clamp ? " clamp" : "") << (r.rename ? " rename" : "");
  }
  void operator()(const MachineMode& m) {
    static const char* names[] = {"tcp-on", "tcp-off", "dwo-on", "dwo-off", "plane-on", "plane-off"};
    o << names[int(m.kind)];
    if (m.kind == ModeKind::PlaneOn) o << " angles " << vec(m.angles);
  }
  void operator()(const Arc& a) {
    o << "arc " << dir_name(a.dir) << " to " << vec(a.end) << " center " << vec(a.center) << " axis " << vec(a.axis)
      << " r " << num_text(a.radius) << " hint " << dir_name(a.hint) << " " << layout_name(a.layout);
    if (a.extra_turns) o << " turns+" << a.extra_turns;
    if (a.sweep > 0) o << " sweep " << num_text(a.sweep);
    for (uint32_t i = 0; i < a.via_count; ++i) o << " via " << vec(op.points[a.via_begin + i]);
  }
  void operator()(const ToolChange& t) {
    o << "tool-change T" << t.tool;
    if (t.length_offset) o << " H" << t.length_offset;
  }
  void operator()(const ToolPreselect& t) { o << "tool-preselect T" << t.tool; }
  void operator()(const Spindle& s) {
    if (s.dir == SpindleDir::Off) {
      o << "spindle off";
      return;
    }
    o << "spindle " << num_text(s.speed) << (s.mode == SpindleMode::Rpm ? " rpm" : " m/min")
      << (s.dir == SpindleDir::Cw ? " cw" : " ccw");
    if (s.max_rpm > 0) o << " max " << num_text(s.max_rpm);
  }
  void operator()(const Feed& f) {
    o << "feed-rate " << num_text(f.value)
      << (f.mode == FeedMode::PerMinute ? " /min" : f.mode == FeedMode::PerRev ? " /rev" : " inverse-time");
  }
  void operator()(const Coolant& c) {
    static const char* names[] = {"off", "on", "flood", "mist", "thru", "air", "tap"};
    o << "coolant " << names[int(c.kind)];
  }
  void operator()(const CutterComp& c) {
    o << "cutter-comp " << (c.side == CompSide::Off ? "off" : c.side == CompSide::Left ? "left" : "right");
    if (c.reg) o << " D" << c.reg;
  }
  void operator()(const Dwell& d) { o << "dwell " << num_text(d.value) << (d.revolutions ? " rev" : " s"); }
  void operator()(const Stop& s) { o << (s.kind == StopKind::Optional ? "optional-stop" : "stop"); }
  void operator()(const Comment& c) { o << "comment \"" << op.str(c.text) << "\""; }
  void operator()(const Insert& c) { o << "insert \"" << op.str(c.text) << "\""; }
  void operator()(const Passthrough& c) { o << "passthrough \"" << op.str(c.text) << "\""; }
  void operator()(const SelectOffset& s) { o << "work-offset " << s.reg << " (register " << s.index << ")"; }
  void operator()(const SetFrame& f) {
    static const char* names[] = {"msys", "csys", "camera"};
    o << "frame " << names[int(f.source)] << " origin " << vec(f.frame.origin) << " x " << vec(f.frame.rotation.col(0))
      << " y " << vec(f.frame.rotation.col(1)) << " z " << vec(f.frame.rotation.col(2));
  }
  void operator()(const CycleOn& c) {
    const CycleSpec& s = op.cycles.at(c.spec);
    o << "cycle-on " << cycle_kind_name(s.kind) << " depth " << num_text(s.depth) << " clear " << num_text(s.clearance);
    if (s.retract >= 0) o << " retract " << num_text(s.retract);
    if (s.peck > 0) o << " peck " << num_text(s.peck);
    if (s.peck_next > 0) o << " then " << num_text(s.peck_next);
    if (s.dwell > 0) o << " dwell " << num_text(s.dwell);
    if (s.pitch > 0) o << " pitch " << num_text(s.pitch);
    if (s.shift > 0) o << " shift " << num_text(s.shift);
    if (s.feed > 0) o << " feed " << num_text(s.feed) << (s.feed_mode == FeedMode::PerRev ? " /rev" : " /min");
    if (s.left_hand) o << " left-hand";
  }
  void operator()(const CycleOff&) { o << "cycle-off"; }
  void operator()(const Hole& h) {
    o << "hole " << cycle_kind_name(op.cycles.at(h.spec).kind) << " at " << vec(h.point);
    if (h.axis != Vec3::UnitZ()) o << " axis " << vec(h.axis);
    o << " initial " << num_text(h.initial);
  }
  void operator()(const GrooveOn& g) {
    const GrooveSpec& s = op.grooves.at(g.spec);
    o << "groove-on " << (s.face ? "face" : "radial") << " retract " << num_text(s.retract) << " x " << num_text(s.x_amount)
      << " z " << num_text(s.z_amount);
    if (s.feed > 0) o << " feed " << num_text(s.feed) << (s.feed_mode == FeedMode::PerRev ? " /rev" : " /min");
  }
  void operator()(const Groove& g) {
    const GrooveSpec& s = op.grooves.at(g.spec);
    o << (s.face ? "groove G74" : "groove G75") << " from " << vec(g.start) << " to " << vec(g.end) << " retract "
      << num_text(s.retract) << " x " << num_text(s.x_amount) << " z " << num_text(s.z_amount);
    if (s.relief > 0) o << " relief " << num_text(s.relief);
    if (s.feed > 0) o << " feed " << num_text(s.feed);
  }
  void operator()(const GrooveMark& m) { o << (m.begin ? "groove-section" : "groove-section-end"); }
  void operator()(const ThreadMark& m) {
    if (!m.begin) {
      o << "thread-off";
      return;
    }
    o << "thread " << (m.kind == ThreadKind::Turn ? "turn" : m.kind == ThreadKind::Face ? "face" : "taper") << " lead "
      << num_text(m.lead);
  }
  void operator()(const ThreadCycle& t) {
    o << (t.multi ? "thread G76" : "thread G92") << " from " << vec(t.start) << " to " << vec(t.end) << " lead "
      << num_text(t.lead);
    if (t.multi)
      o << " height " << num_text(t.height) << " first " << num_text(t.first_depth) << " min " << num_text(t.min_step)
        << " allowance " << num_text(t.allowance) << " finish " << t.finish_passes;
  }
  void operator()(const RoughMark& m) {
    if (!m.begin) {
      o << "rough-off";
      return;
    }
    o << (m.facing ? "rough G72" : "rough G71") << " from " << vec(m.start) << " depth " << num_text(m.depth) << " retract "
      << num_text(m.retract) << " allow " << num_text(m.allow_x) << " " << num_text(m.allow_z);
    if (m.feed > 0) o << " feed " << num_text(m.feed);
    if (m.finish) o << " finish";
  }
  void operator()(const RotaryIndex& r) {
    o << "rotary-index " << r.axis << " " << num_text(r.angle) << (r.incremental ? " incremental" : " absolute");
    if (r.dir != ArcDir::Unknown) o << " " << dir_name(r.dir);
  }
};

}  // namespace

void print_header(std::ostream& o, const ProgramInfo& info) {
  o << "program";
  if (!info.part_name.empty()) o << " \"" << info.part_name << "\"";
  o << " units " << units_name(info.units);
  if (!info.units_reason.empty()) o << " (" << info.units_reason << ")";
  o << "\n";
  for (const ToolInfo& t : info.tools) {
    o << "tool T" << t.number;
    if (!t.name.empty()) o << " \"" << t.name << "\"";
    if (!t.kind.empty()) o << " " << t.kind;
    o << " d " << num_text(t.diameter) << " r " << num_text(t.corner_radius);
    if (t.length) o << " l " << num_text(t.length);
    if (t.auto_numbered) o << " (numbered by clpc)";
    o << "\n";
  }
}

void print_instr(std::ostream& o, const Operation& op, const Instr& in) {
  o << "  " << in.loc.line << ":" << in.loc.col << "\t";
  std::visit(Printer{o, op}, in.op);
  o << "\n";
}

void print_operation(std::ostream& o, const Operation& op) {
  o << (op.continued ? "operation (continued) " : "operation ") << op.number;
  if (!op.name.empty()) o << " \"" << op.name << "\"";
  if (op.loc.valid()) o << " at " << op.loc.line << ":" << op.loc.col;
  o << "\n";
  for (const Instr& in : op.body) print_instr(o, op, in);
}

}  // namespace clpc::ir
