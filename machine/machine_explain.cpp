// clpc explain: the resolved machine description as TOML, every key with its value.
#include <sstream>

#include "machine/machine_loader.h"
#include "support/text.h"

namespace clpc {

namespace {

std::string quote(std::string_view s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o.push_back('\\');
    o.push_back(c);
  }
  return o + "\"";
}

std::string list(const std::vector<std::string>& v) {
  std::string o = "[";
  for (size_t i = 0; i < v.size(); ++i) o += (i ? ", " : "") + quote(v[i]);
  return o + "]";
}

std::string list(const std::vector<CodeTemplate>& v) {
  std::vector<std::string> s;
  for (const auto& t : v) s.push_back(t.text);
  return list(s);
}

const char* b(bool x) { return x ? "true" : "false"; }

}  // namespace

std::string explain_machine(const Machine& m) {
  std::ostringstream o;
  o << "# " << m.name << " as clpc resolves it (defaults and inherited values filled in)\n";
  o << "# from " << m.source << "\n";
  o << "[" << m.name << "]\n";
  o << "description = " << quote(m.description) << "\n";
  o << "family = " << quote(m.is_lathe() ? "lathe" : "mill") << "\n";
  o << "units = " << quote(m.units == ir::Units::Inch ? "inch" : "mm") << "\n";
  o << "extension = " << quote(m.extension) << "\n";
  o << "pipeline = " << list(m.pipeline) << "\n";
  o << "rapid_rate = " << num_text(m.rapid_rate) << "\n";
  o << "tool_change_time = " << num_text(m.tool_change_time) << "\n";
  o << "max_feed = " << num_text(m.max_feed) << "\n";
  o << "max_rpm = " << num_text(m.max_rpm) << "\n";

  o << "\n[" << m.name << ".program]\n";
  o << "number = " << m.program_number << "\n";
  o << "start = " << list(m.program_start) << "\n";
  o << "end = " << list(m.program_end) << "\n";
  o << "header = " << b(m.header) << "\n";
  o << "safe_start = " << list(m.safe_start) << "\n";
  o << "finish = " << list(m.finish) << "\n";
  static const char* kInserts[] = {"comment", "raw", "error"};
  o << "inserts = " << quote(kInserts[int(m.inserts)]) << "\n";
  static const char* kStops[] = {"off", "tool-change", "operation"};
  static const char* kSmoothing[] = {"off", "rough", "medium", "finish"};
  o << "number_from_name = " << b(m.number_from_name) << "\n";
  o << "optional_stop = " << quote(kStops[int(m.optional_stop)]) << "\n";
  o << "preselect = " << b(m.preselect) << "\n";
  o << "coolant_around_tool_change = " << b(m.coolant_around_tool_change) << "\n";
  o << "smoothing = " << quote(kSmoothing[m.smoothing]) << "\n";
  o << "smoothing_tolerance = " << num_text(m.smoothing_tolerance) << "\n";
  o << "park = " << b(m.park) << "\n";
  o << "park_blocks = " << list(m.park_blocks) << "\n";
  o << "date = " << quote(m.date) << "\n";
  o << "programmer = " << quote(m.programmer) << "\n";
  o << "stock = " << quote(m.stock) << "\n";

  const SequenceSettings& s = m.sequence;
  o << "\n[" << m.name << ".sequence]\n";
  o << "enabled = " << b(s.enabled) << "\nstart = " << s.start << "\nstep = " << s.step << "\nmax = " << s.max
    << "\nwrap_to = " << s.wrap_to << "\ntool_change_only = " << b(s.tool_change_only) << "\n";

  const CommentSettings& c = m.comments;
  o << "\n[" << m.name << ".comments]\n";
  o << "enabled = " << b(c.enabled) << "\nopen = " << quote(c.open) << "\nclose = " << quote(c.close)
    << "\nmax_length = " << c.max_length << "\nupper_case = " << b(c.upper_case) << "\nreplacement = " << quote(c.replacement)
    << "\n";

  o << "\n[" << m.name << ".words]\n";
  o << "separator = " << quote(m.separator) << "\nblock_end = " << quote(m.block_end) << "\n";

  o << "\n[" << m.name << ".format]\n";
  static const char* points[] = {"always", "never", "if-fraction"};
  for (char l = 'A'; l <= 'Z'; ++l) {
    const AddressFormat& f = m.format(l);
    o << l << " = { decimals = " << f.decimals << ", point = " << quote(points[int(f.point)])
      << ", leading_zero = " << b(f.leading_zero) << ", trailing_zeros = " << b(f.trailing_zeros)
      << ", digits = " << f.digits << ", scale = " << num_text(f.scale) << ", plus = " << b(f.plus) << " }\n";
  }

  o << "\n[" << m.name << ".feeds]\n";
  for (auto [k, f] : {std::pair<const char*, const AddressFormat*>{"per_minute", &m.feeds.per_minute},
                      {"per_rev", &m.feeds.per_rev}, {"inverse_time", &m.feeds.inverse_time}, {"tap", &m.feeds.tap}})
    o << k << " = { decimals = " << f->decimals << ", point = " << quote(points[int(f->point)])
      << ", leading_zero = " << b(f->leading_zero) << ", trailing_zeros = " << b(f->trailing_zeros)
      << ", digits = " << f->digits << ", scale = " << num_text(f->scale) << ", plus = " << b(f->plus) << " }\n";
  o << "max_rounding = " << num_text(m.feeds.max_rounding) << "\n";

  const ArcSettings& a = m.arcs;
  std::vector<std::string> planes;
  if (a.xy) planes.push_back("XY");
  if (a.zx) planes.push_back("ZX");
  if (a.yz) planes.push_back("YZ");
  static const char* centers[] = {"incremental", "absolute", "radius"};
  o << "\n[" << m.name << ".arcs]\n";
  o << "planes = " << list(planes) << "\nhelical = " << b(a.helical) << "\nmax_sweep = " << num_text(a.max_sweep)
    << "\nhelix_max_sweep = " << num_text(a.helix_max_sweep) << "\nmin_radius = " << num_text(a.min_radius)
    << "\nmax_radius = " << num_text(a.max_radius) << "\ncenter = " << quote(centers[int(a.center)])
    << "\ntolerance = " << num_text(a.tolerance) << "\n";

  o << "\n[" << m.name << ".modal]\n";
  o << "motion = " << b(m.modal.motion) << "\ncoordinates = " << b(m.modal.coordinates) << "\nfeed = " << b(m.modal.feed)
    << "\n";

  if (m.is_lathe()) {
    o << "\n[" << m.name << ".lathe]\n";
    o << "arcs_seen_from = " << quote(m.lathe.arcs_from_minus_y ? "-Y" : "+Y") << "\nmax_rpm = " << num_text(m.lathe.max_rpm)
      << "\n";
  }

  static const char* tables[] = {"none", "g10", "g65-macro"};
  o << "\n[" << m.name << ".offsets]\n";
  o << "extended = " << m.offsets.extended_count << "\ndefault = " << m.offsets.default_index
    << "\ntable = " << quote(tables[int(m.offsets.table)]) << "\nper_frame = " << (m.offsets.per_frame ? "true" : "false")
    << "\nreference_height = " << num_text(m.offsets.reference_height) << "\nmacro = " << m.offsets.macro
    << "\nmacro_program = " << (m.offsets.macro_program ? "true" : "false") << "\n";

  const KinematicsSettings& kin = m.kinematics;
  if (kin.has_rotaries()) {
    static const char* sims[] = {"tcp", "transform"};
    static const char* inds[] = {"transform", "dwo", "tcp"};
    o << "\n[" << m.name << ".kinematics]\n";
    o << "simultaneous = " << quote(sims[int(kin.simultaneous)]) << "\nindexed = " << quote(inds[int(kin.indexed)])
      << "\ninverse_time = " << b(kin.inverse_time) << "\nmax_inverse_time = " << num_text(kin.max_inverse_time)
      << "\non_limit = " << quote(kin.retract_on_limit ? "retract" : "error")
      << "\nretract_distance = " << num_text(kin.retract_distance) << "\npivot = " << num_text(kin.pivot) << "\n";
    auto v3 = [](const ir::Vec3& v) { return "[" + num_text(v.x()) + ", " + num_text(v.y()) + ", " + num_text(v.z()) + "]"; };
    if (kin.work_zero_set) o << "work_zero = " << v3(kin.work_zero) << "\n";
    if (kin.travel.set) {
      o << "travel = { ";
      for (int i = 0; i < 3; ++i)
        o << (i ? ", " : "") << "xyz"[i] << " = [" << num_text(kin.travel.min[i]) << ", " << num_text(kin.travel.max[i]) << "]";
      o << " }\n";
    }
    static const char* cycs[] = {"no", "wind", "modulo"};
    for (const RotaryAxis& a : kin.rotaries) {
      o << "\n[[" << m.name << ".kinematics.axes]]\n";
      o << "name = " << quote(a.name) << "\naxis = " << v3(a.axis) << "\nside = " << quote(a.table ? "table" : "head")
        << "\ndirection = " << int(a.direction) << "\ncyclic = " << quote(cycs[int(a.cyclic)]) << "\nmin = " << num_text(a.min)
        << "\nmax = " << num_text(a.max) << "\ncenter = " << v3(a.center) << "\nprefer = " << num_text(a.prefer)
        << "\nrate = " << num_text(a.rate) << "\nclamp = " << quote(a.clamp) << "\nunclamp = " << quote(a.unclamp) << "\n";
    }
  }

  o << "\n[" << m.name << ".cycles]\n";
  o << "return = " << quote(m.cycles.return_initial ? "initial" : "r-plane") << "\ntap_feed = "
    << quote(m.cycles.tap_per_rev ? "per-rev" : "per-minute") << "\npeck_clearance = " << num_text(m.cycles.peck_clearance)
    << "\n";

  const Codes& k = m.codes;
  o << "\n[" << m.name << ".codes]\n";
  auto code = [&](const char* n, const CodeTemplate& t) { o << n << " = " << quote(t.text) << "\n"; };
  code("units_inch", k.units_inch);
  code("units_mm", k.units_mm);
  code("rapid", k.rapid);
  code("linear", k.linear);
  code("arc_cw", k.arc_cw);
  code("arc_ccw", k.arc_ccw);
  code("plane_xy", k.plane_xy);
  code("plane_zx", k.plane_zx);
  code("plane_yz", k.plane_yz);
  code("absolute", k.absolute);
  code("incremental", k.incremental);
  code("feed_per_minute", k.feed_per_minute);
  code("feed_per_rev", k.feed_per_rev);
  code("inverse_time", k.inverse_time);
  code("tool_change", k.tool_change);
  code("tool_preselect", k.tool_preselect);
  code("length_offset", k.length_offset);
  code("length_cancel", k.length_cancel);
  code("spindle_cw", k.spindle_cw);
  code("spindle_ccw", k.spindle_ccw);
  code("spindle_off", k.spindle_off);
  code("spindle_rpm_mode", k.spindle_rpm_mode);
  code("spindle_css_mode", k.spindle_css_mode);
  code("spindle_clamp", k.spindle_clamp);
  code("coolant_flood", k.coolant_flood);
  code("coolant_mist", k.coolant_mist);
  code("coolant_thru", k.coolant_thru);
  code("coolant_air", k.coolant_air);
  code("coolant_tap", k.coolant_tap);
  code("coolant_off", k.coolant_off);
  code("dwell", k.dwell);
  code("optional_stop", k.optional_stop);
  code("stop", k.stop);
  code("comp_left", k.comp_left);
  code("comp_right", k.comp_right);
  code("comp_off", k.comp_off);
  code("work_offset", k.work_offset);
  code("work_offset_extended", k.work_offset_extended);
  code("offset_set", k.offset_set);
  code("offset_set_extended", k.offset_set_extended);
  code("macro_call", k.macro_call);
  code("safe_retract", k.safe_retract);
  code("cycle_drill", k.cycle_drill);
  code("cycle_dwell", k.cycle_dwell);
  code("cycle_peck", k.cycle_peck);
  code("cycle_chip_break", k.cycle_chip_break);
  code("cycle_tap", k.cycle_tap);
  code("cycle_tap_left", k.cycle_tap_left);
  code("cycle_bore", k.cycle_bore);
  code("cycle_bore_dwell", k.cycle_bore_dwell);
  code("cycle_bore_stop", k.cycle_bore_stop);
  code("cycle_fine_bore", k.cycle_fine_bore);
  code("cycle_back_bore", k.cycle_back_bore);
  code("cycle_cancel", k.cycle_cancel);
  code("cycle_return_initial", k.cycle_return_initial);
  code("cycle_return_r", k.cycle_return_r);
  code("cycle_dwell_word", k.cycle_dwell_word);
  code("rigid_tap", k.rigid_tap);
  code("groove_face", k.groove_face);
  code("groove_radial", k.groove_radial);
  code("tcp_on", k.tcp_on);
  code("tcp_off", k.tcp_off);
  code("dwo_on", k.dwo_on);
  code("dwo_off", k.dwo_off);
  code("smoothing_on", k.smoothing_on);
  code("smoothing_off", k.smoothing_off);
  return o.str();
}

}  // namespace clpc
