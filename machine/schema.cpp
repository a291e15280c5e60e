#include "machine/schema.h"

#include <sstream>

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
std::string b(bool x) { return x ? "true" : "false"; }
std::string n(double x) { return num_text(x); }
std::string i(long x) { return std::to_string(x); }
std::string v3(const ir::Vec3& v) { return "[" + n(v.x()) + ", " + n(v.y()) + ", " + n(v.z()) + "]"; }
// The `index`th of the choices "a|b|c", quoted.
std::string pick(std::string_view choices, int index) {
  for (int k = 0; k < index; ++k) choices.remove_prefix(choices.find('|') + 1);
  return quote(choices.substr(0, choices.find('|')));
}
std::string format_table(const AddressFormat& f) {
  return "{ decimals = " + i(f.decimals) + ", point = " + pick("always|never|if-fraction", int(f.point)) +
         ", leading_zero = " + b(f.leading_zero) + ", trailing_zeros = " + b(f.trailing_zeros) + ", digits = " + i(f.digits) +
         ", scale = " + n(f.scale) + ", plus = " + b(f.plus) + " }";
}
const RotaryAxis& axis(const Machine& m, size_t k) { return m.kinematics.rotaries[k]; }

constexpr uint32_t bit(Var v) { return 1u << unsigned(v); }

using K = KeyKind;
using V = std::string (*)(const Machine&, size_t);

std::vector<KeySpec> build() {
  std::vector<KeySpec> t;
  auto key = [&](std::string_view section, std::string name, K kind, std::string_view doc, V value) -> KeySpec& {
    KeySpec s;
    s.section = section;
    s.key = std::move(name);
    s.kind = kind;
    s.doc = doc;
    s.value = value;
    t.push_back(s);
    return t.back();
  };
  auto ranged = [&](std::string_view section, std::string name, K kind, double lo, double hi, std::string_view doc, V value) {
    KeySpec& s = key(section, std::move(name), kind, doc, value);
    s.lo = lo;
    s.hi = hi;
  };
  auto choice = [&](std::string_view section, std::string name, std::string_view choices, std::string_view doc, V value) {
    key(section, std::move(name), K::Choice, doc, value).choices = choices;
  };
  auto section = [&](std::string_view parent, std::string name, std::string_view doc, Shown shown = Shown::Always) {
    key(parent, std::move(name), K::Table, doc, nullptr).shown = shown;
  };

  // --- the machine's own keys ---------------------------------------------------------------
  key("", "inherits", K::String, "a machine to start from", nullptr).shown = Shown::Never;
  key("", "abstract", K::Bool, "a base to inherit from, never posted for", nullptr).shown = Shown::Never;
  key("", "description", K::String, "shown by clpc machines and in the program header",
      [](const Machine& m, size_t) { return quote(m.description); });
  choice("", "family", "mill|lathe", "which backend writes the program (required)",
         [](const Machine& m, size_t) { return pick("mill|lathe", int(m.family)); });
  choice("", "units", "mm|inch", "output units; the CL's are converted",
         [](const Machine& m, size_t) { return pick("mm|inch", int(m.units)); });
  key("", "extension", K::String, "the output file's extension", [](const Machine& m, size_t) { return quote(m.extension); });
  key("", "pipeline", K::Strings, "the passes, in order (docs/passes.md)", [](const Machine& m, size_t) { return list(m.pipeline); });
  ranged("", "rapid_rate", K::Length, 0, 1e9, "output units per minute, for cycle-time estimates (0: unknown)",
         [](const Machine& m, size_t) { return n(m.rapid_rate); });
  ranged("", "tool_change_time", K::Number, 0, 3600, "seconds per tool change, for cycle-time estimates (0: unknown)",
         [](const Machine& m, size_t) { return n(m.tool_change_time); });
  ranged("", "max_feed", K::Length, 0, 1e9, "output units per minute; higher feeds are capped (0: no cap)",
         [](const Machine& m, size_t) { return n(m.max_feed); });
  ranged("", "max_rpm", K::Number, 0, 1e6, "the spindle's limit; a SPINDL above it is an error (0: none)",
         [](const Machine& m, size_t) { return n(m.max_rpm); });
  section("", "program", "program start and end, header, per-job options");
  section("", "sequence", "block numbers");
  section("", "comments", "how comments are written");
  section("", "words", "word separator and block end");
  section("", "format", "one address format per letter");
  section("", "feeds", "each kind of feed in its own format");
  section("", "arcs", "the arcs the control can cut");
  section("", "modal", "which words are dropped when unchanged");
  section("", "lathe", "lathe settings", Shown::Lathe);
  section("", "offsets", "work offsets");
  section("", "kinematics", "rotary axes (five-axis, 3+2)", Shown::Rotaries);
  section("", "cycles", "canned drilling cycles");
  section("", "motion", "axis velocities and accelerations, for cycle times (verify's dynamic estimate); how G00 moves");
  section("", "codes", "code templates");

  // --- [program] ------------------------------------------------------------------------------
  const std::string_view p = "program";
  ranged(p, "number", K::Integer, 0, 99999999, "program number line (0: none)", [](const Machine& m, size_t) { return i(m.program_number); });
  key(p, "start", K::Strings, "lines written first", [](const Machine& m, size_t) { return list(m.program_start); });
  key(p, "end", K::Strings, "lines written last", [](const Machine& m, size_t) { return list(m.program_end); });
  key(p, "header", K::Bool, "comment lines: machine, source, units, tool table", [](const Machine& m, size_t) { return b(m.header); });
  key(p, "safe_start", K::Templates, "blocks after the header", [](const Machine& m, size_t) { return list(m.safe_start); });
  key(p, "finish", K::Templates, "blocks at the end", [](const Machine& m, size_t) { return list(m.finish); });
  choice(p, "inserts", "comment|raw|error", "an INSERT that is no block the control reads",
         [](const Machine& m, size_t) { return pick("comment|raw|error", int(m.inserts)); });
  key(p, "number_from_name", K::Bool, "the CL file's leading number is the program number",
      [](const Machine& m, size_t) { return b(m.number_from_name); });
  choice(p, "optional_stop", "off|tool-change|operation", "M01 before each tool change or operation",
         [](const Machine& m, size_t) { return pick("off|tool-change|operation", int(m.optional_stop)); });
  key(p, "preselect", K::Bool, "the next tool's T after each tool change", [](const Machine& m, size_t) { return b(m.preselect); });
  key(p, "coolant_around_tool_change", K::Bool, "coolant off before each tool change, on after",
      [](const Machine& m, size_t) { return b(m.coolant_around_tool_change); });
  choice(p, "smoothing", "off|rough|medium|finish", "the control's smoothing mode",
         [](const Machine& m, size_t) { return pick("off|rough|medium|finish", m.smoothing); });
  ranged(p, "smoothing_tolerance", K::Length, 0, 1e3, "the {tolerance} of codes.smoothing_on (0: left out)",
         [](const Machine& m, size_t) { return n(m.smoothing_tolerance); });
  key(p, "park", K::Bool, "park_blocks before the program end", [](const Machine& m, size_t) { return b(m.park); });
  key(p, "park_blocks", K::Templates, "how the machine parks", [](const Machine& m, size_t) { return list(m.park_blocks); });
  key(p, "date", K::String, "a DATE header line: \"today\" or the text", [](const Machine& m, size_t) { return quote(m.date); });
  key(p, "programmer", K::String, "a PROGRAMMER header line", [](const Machine& m, size_t) { return quote(m.programmer); });
  key(p, "stock", K::String, "a STOCK header line", [](const Machine& m, size_t) { return quote(m.stock); });

  // --- [sequence], [comments], [words] ----------------------------------------------------------
  const std::string_view q = "sequence";
  key(q, "enabled", K::Bool, "write N numbers", [](const Machine& m, size_t) { return b(m.sequence.enabled); });
  ranged(q, "start", K::Integer, 0, 999999999, "first number", [](const Machine& m, size_t) { return i(m.sequence.start); });
  ranged(q, "step", K::Integer, 1, 100000, "increment", [](const Machine& m, size_t) { return i(m.sequence.step); });
  ranged(q, "max", K::Integer, 1, 999999999, "largest number (not less than start)", [](const Machine& m, size_t) { return i(m.sequence.max); });
  ranged(q, "wrap_to", K::Integer, 0, 999999999, "after max, continue from this (0: from start)",
         [](const Machine& m, size_t) { return i(m.sequence.wrap_to); });
  key(q, "tool_change_only", K::Bool, "number only the tool-change blocks", [](const Machine& m, size_t) { return b(m.sequence.tool_change_only); });
  const std::string_view c = "comments";
  key(c, "enabled", K::Bool, "write comments", [](const Machine& m, size_t) { return b(m.comments.enabled); });
  key(c, "open", K::String, "opening delimiter", [](const Machine& m, size_t) { return quote(m.comments.open); });
  key(c, "close", K::String, "closing delimiter", [](const Machine& m, size_t) { return quote(m.comments.close); });
  ranged(c, "max_length", K::Integer, 0, 100000, "cut comments to this length (0: no limit)",
         [](const Machine& m, size_t) { return i(m.comments.max_length); });
  key(c, "upper_case", K::Bool, "comments in capitals", [](const Machine& m, size_t) { return b(m.comments.upper_case); });
  key(c, "replacement", K::String, "what stands in for characters the control cannot take",
      [](const Machine& m, size_t) { return quote(m.comments.replacement); });
  key("words", "separator", K::String, "between words", [](const Machine& m, size_t) { return quote(m.separator); });
  key("words", "block_end", K::String, "at the end of every block", [](const Machine& m, size_t) { return quote(m.block_end); });

  // --- [format], an address format, [feeds] ----------------------------------------------------
  static const char* kLetters[26] = {"A", "B", "C", "D", "E", "F", "G", "H", "I", "J", "K", "L", "M",
                                     "N", "O", "P", "Q", "R", "S", "T", "U", "V", "W", "X", "Y", "Z"};
  // One function per letter: captureless lambdas cannot hold the letter.
  static const V kLetterValues[26] = {
#define CLPC_LETTER(L) [](const Machine& m, size_t) { return format_table(m.format(L)); }
        CLPC_LETTER('A'), CLPC_LETTER('B'), CLPC_LETTER('C'), CLPC_LETTER('D'), CLPC_LETTER('E'), CLPC_LETTER('F'),
        CLPC_LETTER('G'), CLPC_LETTER('H'), CLPC_LETTER('I'), CLPC_LETTER('J'), CLPC_LETTER('K'), CLPC_LETTER('L'),
        CLPC_LETTER('M'), CLPC_LETTER('N'), CLPC_LETTER('O'), CLPC_LETTER('P'), CLPC_LETTER('Q'), CLPC_LETTER('R'),
        CLPC_LETTER('S'), CLPC_LETTER('T'), CLPC_LETTER('U'), CLPC_LETTER('V'), CLPC_LETTER('W'), CLPC_LETTER('X'),
        CLPC_LETTER('Y'), CLPC_LETTER('Z'),
#undef CLPC_LETTER
  };
  for (int l = 0; l < 26; ++l) key("format", kLetters[l], K::Format, "how the address writes its value", kLetterValues[l]);
  const std::string_view a = "address";
  ranged(a, "decimals", K::Integer, 0, 9, "digits after the point", nullptr);
  choice(a, "point", "always|never|if-fraction", "never: least-input increments without a point", nullptr);
  key(a, "leading_zero", K::Bool, "0.5 (true) or .5", nullptr);
  key(a, "trailing_zeros", K::Bool, "1.500 (true) or 1.5", nullptr);
  ranged(a, "digits", K::Integer, 0, 12, "zero-pad the whole part to this many digits", nullptr);
  ranged(a, "scale", K::Number, -1e3, 1e3, "multiply before writing (at least 0.001 in size)", nullptr);
  key(a, "plus", K::Bool, "write + on positive values", nullptr);
  const std::string_view f = "feeds";
  key(f, "per_minute", K::Format, "G94 feeds", [](const Machine& m, size_t) { return format_table(m.feeds.per_minute); });
  key(f, "per_rev", K::Format, "G95 feeds", [](const Machine& m, size_t) { return format_table(m.feeds.per_rev); });
  key(f, "inverse_time", K::Format, "G93 feeds", [](const Machine& m, size_t) { return format_table(m.feeds.inverse_time); });
  key(f, "tap", K::Format, "the F of G84/G74", [](const Machine& m, size_t) { return format_table(m.feeds.tap); });
  key(f, "lead", K::Format, "the F of a thread (G32/G92/G76): its lead", [](const Machine& m, size_t) { return format_table(m.feeds.lead); });
  ranged(f, "max_rounding", K::Number, 0, 0.5, "the largest fraction a feed may change by in rounding",
         [](const Machine& m, size_t) { return n(m.feeds.max_rounding); });

  // --- [arcs], [modal], [lathe] -------------------------------------------------------------------
  const std::string_view r = "arcs";
  key(r, "planes", K::Strings, "planes the control has arcs in", [](const Machine& m, size_t) {
    std::vector<std::string> planes;
    if (m.arcs.xy) planes.push_back("XY");
    if (m.arcs.zx) planes.push_back("ZX");
    if (m.arcs.yz) planes.push_back("YZ");
    return list(planes);
  }).choices = "XY|ZX|YZ";
  key(r, "helical", K::Bool, "helical arcs", [](const Machine& m, size_t) { return b(m.arcs.helical); });
  ranged(r, "max_sweep", K::Number, 1, 360, "most degrees in one arc block", [](const Machine& m, size_t) { return n(m.arcs.max_sweep); });
  ranged(r, "helix_max_sweep", K::Number, 1, 360, "most degrees in one helical block",
         [](const Machine& m, size_t) { return n(m.arcs.helix_max_sweep); });
  ranged(r, "min_radius", K::Length, 0, 1e9, "smallest radius (0: none)", [](const Machine& m, size_t) { return n(m.arcs.min_radius); });
  ranged(r, "max_radius", K::Length, 0, 1e9, "largest radius (0: none)", [](const Machine& m, size_t) { return n(m.arcs.max_radius); });
  choice(r, "center", "incremental|absolute|radius", "I/J/K from the start, absolute, or R",
         [](const Machine& m, size_t) { return pick("incremental|absolute|radius", int(m.arcs.center)); });
  ranged(r, "tolerance", K::Length, 1e-6, 1e3, "chord error allowed when linearising", [](const Machine& m, size_t) { return n(m.arcs.tolerance); });
  key("modal", "motion", K::Bool, "G00/G01/G02/G03", [](const Machine& m, size_t) { return b(m.modal.motion); });
  key("modal", "coordinates", K::Bool, "unchanged axis words", [](const Machine& m, size_t) { return b(m.modal.coordinates); });
  key("modal", "feed", K::Bool, "an unchanged F", [](const Machine& m, size_t) { return b(m.modal.feed); });
  choice("lathe", "arcs_seen_from", "+Y|-Y", "G02/G03 as seen from +Y (ISO, Fanuc) or -Y",
         [](const Machine& m, size_t) { return pick("+Y|-Y", m.lathe.arcs_from_minus_y); });
  ranged("lathe", "max_rpm", K::Number, 0, 1e6, "caps the G50 S clamp", [](const Machine& m, size_t) { return n(m.lathe.max_rpm); });
  ranged("lathe", "tip", K::Integer, 0, 9, "the imaginary tool tip for nose radius compensation ({tip})",
         [](const Machine& m, size_t) { return n(m.lathe.tip); });
  key("motion", "velocity", K::Length3, "X Y Z: each axis's fastest, output units per minute (0: unknown)",
      [](const Machine& m, size_t) { return v3(m.motion.velocity); });
  key("motion", "acceleration", K::Length3, "X Y Z: each axis's acceleration, output units per second squared (0: unknown)",
      [](const Machine& m, size_t) { return v3(m.motion.acceleration); });
  key("motion", "rotary_velocity", K::Vec3, "A B C: each rotary's fastest, degrees per second (0: unknown)",
      [](const Machine& m, size_t) { return v3(m.motion.rotary_velocity); });
  ranged("motion", "junction_deviation", K::Length, 0, 1e3,
         "how far the control may round a corner at speed (the corner slowdown), output units",
         [](const Machine& m, size_t) { return n(m.motion.junction_deviation); });
  key("motion", "rapids_linear", K::Bool,
      "G00 along a straight line; false: each axis at its own rate (non-linear positioning), rapids down and across are split by rapid-split (mills)",
      [](const Machine& m, size_t) { return b(m.motion.rapids_linear); });

  // --- [offsets] ------------------------------------------------------------------------------------
  const std::string_view o = "offsets";
  ranged(o, "extended", K::Integer, 0, 300, "extended registers beyond G54-G59", [](const Machine& m, size_t) { return i(m.offsets.extended_count); });
  ranged(o, "default", K::Integer, 1, 306, "register used when the CL selects none", [](const Machine& m, size_t) { return i(m.offsets.default_index); });
  choice(o, "table", "none|g10|g65-macro", "how the program sets the registers",
         [](const Machine& m, size_t) { return pick("none|g10|g65-macro", int(m.offsets.table)); });
  key(o, "per_frame", K::Bool, "one register per distinct frame", [](const Machine& m, size_t) { return b(m.offsets.per_frame); });
  ranged(o, "reference_height", K::Length, -1e5, 1e5, "the reference base above the table centre",
         [](const Machine& m, size_t) { return n(m.offsets.reference_height); });
  ranged(o, "macro", K::Integer, 1, 99999999, "g65-macro: the macro's program number", [](const Machine& m, size_t) { return i(m.offsets.macro); });
  key(o, "macro_program", K::Bool, "g65-macro: append the macro program", [](const Machine& m, size_t) { return b(m.offsets.macro_program); });

  // --- [kinematics] ---------------------------------------------------------------------------------
  const std::string_view k = "kinematics";
  choice(k, "simultaneous", "tcp|transform", "moves whose tool axis changes: TCPC or transformed",
         [](const Machine& m, size_t) { return pick("tcp|transform", int(m.kinematics.simultaneous)); });
  choice(k, "indexed", "transform|dwo|tcp|plane", "3+2 operations: transformed, dynamic work offset, TCPC or tilted plane",
         [](const Machine& m, size_t) { return pick("transform|dwo|tcp|plane", int(m.kinematics.indexed)); });
  choice(k, "plane_euler", "zxz|xyz", "indexed = \"plane\": the order of codes.plane_on's angles",
         [](const Machine& m, size_t) { return pick("zxz|xyz", int(m.kinematics.plane_euler)); });
  key(k, "inverse_time", K::Bool, "G93 for feed moves that turn a rotary", [](const Machine& m, size_t) { return b(m.kinematics.inverse_time); });
  key(k, "degrees_per_minute", K::Bool, "F of feed moves that turn a rotary over the linear and rotary axes together",
      [](const Machine& m, size_t) { return b(m.kinematics.degrees_per_minute); });
  ranged(k, "max_inverse_time", K::Number, 0, 1e9, "cap on F in G93 (0: none)", [](const Machine& m, size_t) { return n(m.kinematics.max_inverse_time); });
  choice(k, "on_limit", "error|retract", "where only a jump can follow the path",
         [](const Machine& m, size_t) { return pick("error|retract", m.kinematics.retract_on_limit); });
  ranged(k, "retract_distance", K::Length, 0, 1e6, "along the tool axis, for on_limit = \"retract\"",
         [](const Machine& m, size_t) { return n(m.kinematics.retract_distance); });
  ranged(k, "pivot", K::Length, 0, 1e6, "head machines: gauge line to the head axes", [](const Machine& m, size_t) { return n(m.kinematics.pivot); });
  key(k, "work_zero", K::Length3, "the program zero's machine position at all rotaries zero",
      [](const Machine& m, size_t) { return m.kinematics.work_zero_set ? v3(m.kinematics.work_zero) : std::string(); })
      .shown = Shown::WhenGiven;
  key(k, "travel", K::Table, "machine travel, checked by the limits pass", [](const Machine& m, size_t) {
    if (!m.kinematics.travel.set) return std::string();
    std::string s = "{ ";
    for (int a = 0; a < 3; ++a)
      s += std::string(a ? ", " : "") + "xyz"[a] + " = [" + n(m.kinematics.travel.min[a]) + ", " + n(m.kinematics.travel.max[a]) + "]";
    return s + " }";
  }).shown = Shown::WhenGiven;
  key(k, "axes", K::Tables, "one table per rotary axis, from the base outwards (at most two)", nullptr);
  for (const char* xyz : {"x", "y", "z"}) key("kinematics.travel", xyz, K::Range, "[min, max], output units", nullptr);
  const std::string_view x = "kinematics.axes";
  choice(x, "name", "A|B|C", "the word it is written with (required)", [](const Machine& m, size_t a) { return quote(axis(m, a).name); });
  key(x, "axis", K::Vec3, "the direction it turns about, at all rotaries zero (required)",
      [](const Machine& m, size_t a) { return v3(axis(m, a).axis); });
  choice(x, "side", "table|head", "turns the part or the tool", [](const Machine& m, size_t a) { return pick("table|head", !axis(m, a).table); });
  ranged(x, "direction", K::Integer, -1, 1, "-1: a positive angle turns the negative way (not 0)",
         [](const Machine& m, size_t a) { return i(long(axis(m, a).direction)); });
  choice(x, "cyclic", "no|wind|modulo", "continuous axes: wind on, or modulo 360",
         [](const Machine& m, size_t a) { return pick("no|wind|modulo", int(axis(m, a).cyclic)); });
  // A continuous axis has no limits unless a winding one was given its range: explain leaves
  // them out (written out, -360 and 360 would be a range the machine has not).
  ranged(x, "min", K::Number, -1e6, 1e6, "lower limit, degrees", [](const Machine& m, size_t a) {
    return axis(m, a).cyclic == Cyclic::No || axis(m, a).wind_range ? n(axis(m, a).min) : std::string();
  });
  ranged(x, "max", K::Number, -1e6, 1e6, "upper limit, degrees", [](const Machine& m, size_t a) {
    return axis(m, a).cyclic == Cyclic::No || axis(m, a).wind_range ? n(axis(m, a).max) : std::string();
  });
  key(x, "center", K::Length3, "a point on the axis", [](const Machine& m, size_t a) { return v3(axis(m, a).center); });
  ranged(x, "prefer", K::Number, -1, 1, "the sign preferred where solutions tie", [](const Machine& m, size_t a) { return n(axis(m, a).prefer); });
  ranged(x, "rate", K::Number, 0, 1e9, "degrees per minute (0: unknown)", [](const Machine& m, size_t a) { return n(axis(m, a).rate); });
  key(x, "clamp", K::String, "brake on", [](const Machine& m, size_t a) { return quote(axis(m, a).clamp); });
  key(x, "unclamp", K::String, "brake off", [](const Machine& m, size_t a) { return quote(axis(m, a).unclamp); });

  // --- [cycles] -------------------------------------------------------------------------------------
  choice("cycles", "return", "initial|r-plane", "G98 or G99 between holes",
         [](const Machine& m, size_t) { return pick("initial|r-plane", !m.cycles.return_initial); });
  choice("cycles", "tap_feed", "per-minute|per-rev", "tapping feed: pitch x S in G94, or pitch in G95",
         [](const Machine& m, size_t) { return pick("per-minute|per-rev", m.cycles.tap_per_rev); });
  ranged("cycles", "peck_clearance", K::Length, 0, 1e6, "re-entry above the last depth, pecking written as moves",
         [](const Machine& m, size_t) { return n(m.cycles.peck_clearance); });

  // --- [codes] ---------------------------------------------------------------------------------------
  struct Code {
    const char* name;
    CodeTemplate Codes::*member;
    uint32_t vars;
  };
  const uint32_t none = 0;
  static const Code codes[] = {
      {"units_inch", &Codes::units_inch, none}, {"units_mm", &Codes::units_mm, none},
      {"rapid", &Codes::rapid, none}, {"linear", &Codes::linear, none},
      {"arc_cw", &Codes::arc_cw, none}, {"arc_ccw", &Codes::arc_ccw, none},
      {"plane_xy", &Codes::plane_xy, none}, {"plane_zx", &Codes::plane_zx, none}, {"plane_yz", &Codes::plane_yz, none},
      {"absolute", &Codes::absolute, none}, {"incremental", &Codes::incremental, none},
      {"feed_per_minute", &Codes::feed_per_minute, none}, {"feed_per_rev", &Codes::feed_per_rev, none},
      {"inverse_time", &Codes::inverse_time, none},
      {"tool_change", &Codes::tool_change, bit(Var::Tool) | bit(Var::Offset)},
      {"tool_preselect", &Codes::tool_preselect, bit(Var::Tool)},
      {"length_offset", &Codes::length_offset, bit(Var::Offset) | bit(Var::Tool)},
      {"length_cancel", &Codes::length_cancel, none},
      {"spindle_cw", &Codes::spindle_cw, none}, {"spindle_ccw", &Codes::spindle_ccw, none},
      {"spindle_off", &Codes::spindle_off, none},
      {"spindle_rpm_mode", &Codes::spindle_rpm_mode, none}, {"spindle_css_mode", &Codes::spindle_css_mode, none},
      {"spindle_clamp", &Codes::spindle_clamp, bit(Var::Max)},
      {"coolant_flood", &Codes::coolant_flood, none}, {"coolant_mist", &Codes::coolant_mist, none},
      {"coolant_thru", &Codes::coolant_thru, none}, {"coolant_air", &Codes::coolant_air, none},
      {"coolant_tap", &Codes::coolant_tap, none}, {"coolant_off", &Codes::coolant_off, none},
      {"coolant_thru_off", &Codes::coolant_thru_off, none}, {"coolant_air_off", &Codes::coolant_air_off, none},
      {"dwell", &Codes::dwell, bit(Var::Seconds) | bit(Var::Milliseconds)},
      {"optional_stop", &Codes::optional_stop, none}, {"stop", &Codes::stop, none},
      {"comp_left", &Codes::comp_left, bit(Var::Register) | bit(Var::Tip)},
      {"comp_right", &Codes::comp_right, bit(Var::Register) | bit(Var::Tip)},
      {"comp_off", &Codes::comp_off, none},
      {"work_offset", &Codes::work_offset, bit(Var::Number)},
      {"work_offset_extended", &Codes::work_offset_extended, bit(Var::Number)},
      {"offset_set", &Codes::offset_set, bit(Var::Number)},
      {"offset_set_extended", &Codes::offset_set_extended, bit(Var::Number)},
      {"macro_call", &Codes::macro_call, bit(Var::Number)},
      {"safe_retract", &Codes::safe_retract, none},
      {"cycle_drill", &Codes::cycle_drill, none}, {"cycle_dwell", &Codes::cycle_dwell, none},
      {"cycle_peck", &Codes::cycle_peck, none}, {"cycle_chip_break", &Codes::cycle_chip_break, none},
      {"cycle_tap", &Codes::cycle_tap, none}, {"cycle_tap_left", &Codes::cycle_tap_left, none},
      {"cycle_bore", &Codes::cycle_bore, none}, {"cycle_bore_dwell", &Codes::cycle_bore_dwell, none},
      {"cycle_bore_stop", &Codes::cycle_bore_stop, none}, {"cycle_fine_bore", &Codes::cycle_fine_bore, none},
      {"cycle_back_bore", &Codes::cycle_back_bore, none}, {"cycle_cancel", &Codes::cycle_cancel, none},
      {"cycle_return_initial", &Codes::cycle_return_initial, none}, {"cycle_return_r", &Codes::cycle_return_r, none},
      {"cycle_dwell_word", &Codes::cycle_dwell_word, bit(Var::Seconds) | bit(Var::Milliseconds)},
      {"rigid_tap", &Codes::rigid_tap, bit(Var::Speed)},
      {"groove_face", &Codes::groove_face, none}, {"groove_radial", &Codes::groove_radial, none},
      {"thread", &Codes::thread, none}, {"thread_box", &Codes::thread_box, none}, {"thread_multi", &Codes::thread_multi, none},
      {"rough_turn", &Codes::rough_turn, none}, {"rough_face", &Codes::rough_face, none},
      {"rough_finish", &Codes::rough_finish, none},
      {"tcp_on", &Codes::tcp_on, bit(Var::Offset) | bit(Var::Tool)}, {"tcp_off", &Codes::tcp_off, none},
      {"dwo_on", &Codes::dwo_on, none}, {"dwo_off", &Codes::dwo_off, none},
      {"plane_on", &Codes::plane_on, bit(Var::X) | bit(Var::Y) | bit(Var::Z) | bit(Var::I) | bit(Var::J) | bit(Var::K)},
      {"plane_orient", &Codes::plane_orient, none}, {"plane_off", &Codes::plane_off, none},
      {"unwind", &Codes::unwind, bit(Var::Angle)},
      {"smoothing_on", &Codes::smoothing_on, bit(Var::Level) | bit(Var::Tolerance)},
      {"smoothing_off", &Codes::smoothing_off, none},
  };
  for (const Code& code : codes) {
    KeySpec& s = key("codes", code.name, K::Template, "a code template (docs/machines.md, [NAME.codes])", nullptr);
    s.vars = code.vars;
    s.code = code.member;
  }
  return t;
}

}  // namespace

std::vector<std::string> KeySpec::choice_list() const {
  std::vector<std::string> out;
  std::string_view c = choices;
  while (!c.empty()) {
    const size_t bar = c.find('|');
    out.emplace_back(c.substr(0, bar));
    c = bar == std::string_view::npos ? std::string_view() : c.substr(bar + 1);
  }
  return out;
}

std::string KeySpec::type_text() const {
  auto range = [&](const char* what) {
    if (hi >= 1e9 - 1) return std::string(what) + " ≥ " + num_text(lo);
    return std::string(what) + " " + num_text(lo) + " to " + num_text(hi);
  };
  auto choices_text = [&] {
    std::string s;
    for (const std::string& c : choice_list()) s += (s.empty() ? "" : " \\| ") + std::string("`\"") + c + "\"`";
    return s;
  };
  switch (kind) {
    case K::Bool: return "bool";
    case K::Integer: return range("integer");
    case K::Number: return range("number");
    case K::Length: return range("length");
    case K::String: return "string";
    case K::Choice: return choices_text();
    case K::Strings: return choices.empty() ? "array of strings" : "array of " + choices_text();
    case K::Template: return "code template";
    case K::Templates: return "array of code templates";
    case K::Vec3:
    case K::Length3: return "`[x, y, z]`";
    case K::Range: return "`[min, max]`";
    case K::Format: return "address format";
    case K::Table: return "table";
    case K::Tables: return "array of tables";
  }
  return "";
}

const std::vector<KeySpec>& machine_keys() {
  static const std::vector<KeySpec> keys = build();
  return keys;
}

const KeySpec* find_key(std::string_view section, std::string_view key) {
  for (const KeySpec& k : machine_keys())
    if (k.section == section && k.key == key) return &k;
  return nullptr;
}

std::string sub_section(std::string_view section, std::string_view key) {
  if (section == "format" || section == "feeds") return "address";
  return section.empty() ? std::string(key) : std::string(section) + "." + std::string(key);
}

std::string explain_machine(const Machine& m) {
  std::ostringstream o;
  o << "# " << m.name << " as clpc resolves it (defaults and inherited values filled in)\n";
  o << "# from " << m.source << "\n";
  auto shown = [&](const KeySpec& k) {
    switch (k.shown) {
      case Shown::Always: return true;
      case Shown::Lathe: return m.is_lathe();
      case Shown::Rotaries: return m.kinematics.has_rotaries();
      case Shown::WhenGiven: return true;  // the value is empty when not given
      case Shown::Never: return false;
    }
    return false;
  };
  auto keys_of = [&](std::string_view section, size_t item) {
    for (const KeySpec& k : machine_keys()) {
      if (k.section != section || !(k.value || k.code) || !shown(k)) continue;
      const std::string v = k.code ? quote((m.codes.*k.code).text) : k.value(m, item);
      if (!v.empty()) o << k.key << " = " << v << "\n";
    }
  };
  o << "[" << m.name << "]\n";
  keys_of("", 0);
  for (const KeySpec& s : machine_keys()) {
    if (!s.section.empty() || s.kind != K::Table || !shown(s)) continue;
    o << "\n[" << m.name << "." << s.key << "]\n";
    keys_of(s.key, 0);
    if (s.key == "kinematics")
      for (size_t a = 0; a < m.kinematics.rotaries.size(); ++a) {
        o << "\n[[" << m.name << ".kinematics.axes]]\n";
        keys_of("kinematics.axes", a);
      }
  }
  return o.str();
}

}  // namespace clpc
