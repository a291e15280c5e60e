#include "machine/machine_loader.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "machine/block_check.h"
#include "machine/pipeline_check.h"
#include "machine/schema.h"
#include "support/suggest.h"
#include "support/text.h"

namespace clpc {

struct MachineRegistry::Source {
  std::string path;
  std::string text;
  toml::table table;
};

namespace {

constexpr const char* kBuiltinName = "machines.toml (built-in)";

std::string line_of(std::string_view text, uint32_t line) {
  size_t at = 0;
  for (uint32_t l = 1; l < line && at != std::string_view::npos; ++l) {
    at = text.find('\n', at);
    if (at != std::string_view::npos) ++at;
  }
  if (at == std::string_view::npos || at > text.size()) return {};
  size_t end = text.find('\n', at);
  std::string s(text.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at));
  if (!s.empty() && s.back() == '\r') s.pop_back();
  return s;
}

struct Ctx {
  Diagnostics& d;
  const std::vector<std::unique_ptr<MachineRegistry::Source>>* sources;
  bool ok = true;

  void error(const toml::source_region& at, const std::string& msg) {
    ok = false;
    std::string file = at.path ? *at.path : std::string("<machine>");
    std::string text;
    if (sources)
      for (const auto& s : *sources)
        if (s->path == file) text = line_of(s->text, at.begin.line);
    d.report_in(Severity::Error, file, SourceLoc{at.begin.line, at.begin.column}, msg, text);
  }
};

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "true or false";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date or time";
  }
}

// `abstract = true`: a base to inherit from, never posted for.
bool is_abstract(const toml::table& t) {
  const toml::node* n = t.get("abstract");
  return n && n->value<bool>().value_or(false) && n->is_boolean();
}

// Reads one machine table with validation. A machine that inherits is a stack of tables,
// parent first: a key is looked up from the top, so every value keeps its own file and line.
// Keys never read are reported by finish(), in whichever file they are.
class Reader {
 public:
  using Layers = std::vector<const toml::table*>;
  // `units`: the units each layer's machine is in (a layer without "units" has its parent's);
  // `target`: the machine's. A length or rate a layer in other units gives is converted, so a
  // machine can inherit from one in the other units (docs/machines.md, "Inheritance").
  // `section`: which of the schema's sections (machine/schema.h) the table is; every key read
  // must be one of its keys, and takes its range or choices from there.
  Reader(Ctx& c, Layers layers, std::string path, std::string section, std::vector<ir::Units> units = {},
         ir::Units target = ir::Units::Mm)
      : c_(c), layers_(std::move(layers)), path_(std::move(path)), section_(std::move(section)), units_(std::move(units)),
        target_(target) {
    units_.resize(layers_.size(), target_);
  }
  // The schema's row for `k`: a key read that is not there is a bug in clpc, not in the file.
  const KeySpec& spec(std::string_view k) const {
    if (const KeySpec* s = find_key(section_, k)) return *s;
    throw std::logic_error("internal: machine key '" + section_ + (section_.empty() ? "" : ".") + std::string(k) +
                           "' is read but not in machine/schema.cpp");
  }
  // The factor from the units of the layer that gives `k` to the machine's (1 when it is not given).
  double to_target(std::string_view k) const {
    for (size_t i = layers_.size(); i-- > 0;)
      if (layers_[i]->get(k)) return ir::mm_per_unit(units_[i]) / ir::mm_per_unit(target_);
    return 1;
  }
  // A length or a rate (per minute): a number, converted to the machine's units.
  void length(std::string_view k, double& out) {
    const double f = to_target(k);
    double v = std::numeric_limits<double>::quiet_NaN();
    number(k, v);
    if (!std::isnan(v)) out = v * f;
  }
  bool length3(std::string_view k, ir::Vec3& out) {
    const double f = to_target(k);
    if (!vec3(k, out)) return false;
    out *= f;
    return true;
  }
  ir::Units target() const { return target_; }

  const std::string& path() const { return path_; }
  bool has(std::string_view k) const { return find(k) != nullptr; }
  const toml::node* find(std::string_view k) const {
    for (auto it = layers_.rbegin(); it != layers_.rend(); ++it)
      if (const toml::node* n = (*it)->get(k)) return n;
    return nullptr;
  }
  // The top table (for "missing key" messages) and all keys of all layers.
  const toml::table& top() const { return *layers_.back(); }
  std::vector<std::pair<std::string, const toml::key*>> keys() const {
    std::vector<std::pair<std::string, const toml::key*>> out;
    std::set<std::string> seen;
    // The topmost layer's key first: a mistake is said where the file that made it gives it.
    for (auto it = layers_.rbegin(); it != layers_.rend(); ++it)
      for (auto&& [key, n] : **it)
        if (seen.insert(std::string(key.str())).second) out.emplace_back(std::string(key.str()), &key);
    return out;
  }

  // A key already reported as wrong: finish() need not call it unknown.
  void reported(std::string_view k) { used_.insert(std::string(k)); }
  const toml::node* node(std::string_view k) {
    spec(k);
    used_.insert(std::string(k));
    return find(k);
  }
  void error(const toml::node& n, std::string_view key, const std::string& msg) {
    c_.error(n.source(), key_path(key) + ": " + msg);
  }
  // A problem with what this table inherits: said at the table itself, in the user's file.
  void at_table(const std::string& msg) { c_.error(top().source(), path_ + ": " + msg); }
  void missing(std::string_view key, const std::string& what) {
    c_.error(top().source(), path_ + ": missing required key '" + std::string(key) + "' (" + what + ")");
  }
  std::string key_path(std::string_view key) const { return path_.empty() ? std::string(key) : path_ + "." + std::string(key); }

  void boolean(std::string_view k, bool& out) {
    const toml::node* n = node(k);
    if (!n) return;
    if (auto v = n->value<bool>(); v && n->is_boolean()) out = *v;
    else error(*n, k, "expected true or false, found " + type_name(*n));
  }
  template <class Int>
  void integer(std::string_view k, Int& out) {
    const long long lo = (long long)spec(k).lo, hi = (long long)spec(k).hi;
    const toml::node* n = node(k);
    if (!n) return;
    if (!n->is_integer()) {
      error(*n, k, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", found " + type_name(*n));
      return;
    }
    long long v = *n->value<int64_t>();
    if (v < lo || v > hi) {
      error(*n, k, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", found " + std::to_string(v));
      return;
    }
    out = Int(v);
  }
  // A number in the schema's [lo, hi].
  void number(std::string_view k, double& out) {
    const double lo = spec(k).lo, hi = spec(k).hi;
    const toml::node* n = node(k);
    if (!n) return;
    if (!n->is_number()) {
      error(*n, k, "expected a number, found " + type_name(*n));
      return;
    }
    double v = *n->value<double>();
    if (!(v >= lo) || !(v <= hi)) {
      std::string range = "at least " + num_text(lo);
      if (hi < 1e300) range += " and at most " + num_text(hi);
      error(*n, k, "expected a number " + range + ", found " + num_text(v));
      return;
    }
    out = v;
  }
  void string(std::string_view k, std::string& out) {
    const toml::node* n = node(k);
    if (!n) return;
    if (!n->is_string()) {
      error(*n, k, "expected a string, found " + type_name(*n));
      return;
    }
    out = **n->as_string();
  }
  // One of the schema's choices; returns the index or -1.
  int choice(std::string_view k) {
    const std::vector<std::string> options = spec(k).choice_list();
    const toml::node* n = node(k);
    if (!n) return -1;
    std::string all;
    for (const std::string& o : options) all += (all.empty() ? "\"" : ", \"") + o + "\"";
    if (!n->is_string()) {
      error(*n, k, "expected one of " + all + ", found " + type_name(*n));
      return -1;
    }
    const std::string& v = **n->as_string();
    for (size_t i = 0; i < options.size(); ++i)
      if (v == options[i]) return int(i);
    error(*n, k, "expected one of " + all + ", found \"" + v + "\"");
    return -1;
  }
  bool strings(std::string_view k, std::vector<std::string>& out) {
    const toml::node* n = node(k);
    if (!n) return false;
    const toml::array* a = n->as_array();
    if (!a) {
      error(*n, k, "expected an array of strings, found " + type_name(*n));
      return false;
    }
    std::vector<std::string> v;
    for (const toml::node& e : *a) {
      if (!e.is_string()) {
        error(e, k, "expected an array of strings; this element is " + type_name(e));
        return false;
      }
      v.push_back(**e.as_string());
    }
    out = std::move(v);
    return true;
  }
  bool vec3(std::string_view k, ir::Vec3& out) {
    const toml::node* n = node(k);
    if (!n) return false;
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3 || !(*a)[0].is_number() || !(*a)[1].is_number() || !(*a)[2].is_number()) {
      error(*n, k, "expected an array of three numbers [x, y, z]");
      return false;
    }
    out = {*(*a)[0].value<double>(), *(*a)[1].value<double>(), *(*a)[2].value<double>()};
    return true;
  }
  // An array of tables (not merged across layers: the top one wins).
  std::optional<std::vector<Reader>> table_array(std::string_view k) {
    const toml::node* n = node(k);
    if (!n) return std::nullopt;
    const toml::array* a = n->as_array();
    if (a && a->empty()) return std::vector<Reader>{};  // "axes = []": none, whatever a parent had
    if (!a || !a->is_array_of_tables()) {
      error(*n, k, "expected an array of tables ([[" + key_path(k) + "]])");
      return std::nullopt;
    }
    ir::Units u = target_;
    for (size_t i = layers_.size(); i-- > 0;)
      if (layers_[i]->get(k)) {
        u = units_[i];
        break;
      }
    std::vector<Reader> out;
    for (size_t i = 0; i < a->size(); ++i)
      out.emplace_back(c_, Layers{(*a)[i].as_table()}, key_path(k) + "[" + std::to_string(i) + "]", sub_section(section_, k),
                       std::vector<ir::Units>{u}, target_);
    return out;
  }
  // The sub-table `k`, merged over the layers (a layer that sets `k` to something else
  // hides the tables below it).
  std::optional<Reader> sub(std::string_view k) {
    const toml::node* top = node(k);
    if (!top) return std::nullopt;
    if (!top->is_table()) {
      error(*top, k, "expected a table, found " + type_name(*top));
      return std::nullopt;
    }
    Layers sub;
    std::vector<ir::Units> units;
    for (size_t i = 0; i < layers_.size(); ++i) {
      const toml::node* n = layers_[i]->get(k);
      if (!n) continue;
      if (!n->is_table()) {
        sub.clear();
        units.clear();
      } else {
        sub.push_back(n->as_table());
        units.push_back(units_[i]);
      }
    }
    return Reader(c_, std::move(sub), key_path(k), sub_section(section_, k), std::move(units), target_);
  }
  // Reports every key that was not read.
  void finish() {
    const std::vector<std::string> known(used_.begin(), used_.end());
    for (const auto& [name, key] : keys())
      if (!used_.count(name)) {
        const std::string near = closest(name, known);
        c_.error(key->source(), "unknown key '" + name + "' in " + (path_.empty() ? "the machine" : path_) +
                                    (near.empty() ? std::string() : "; did you mean '" + near + "'?"));
      }
  }

 private:
  Ctx& c_;
  Layers layers_;
  std::string path_;
  std::string section_;
  std::vector<ir::Units> units_;
  ir::Units target_;
  std::set<std::string> used_;
};

// A register, a tool, a speed or any number that is no position, written in an axis address
// (G43 Z{offset} H{tool}: the offset number became a Z to move to, certified; helper-52). An
// axis word may hold a position (a tilted plane's origin), a winding axis's angle, or a
// dwell's time (G04 X{seconds}). "" when there is none.
std::string number_in_an_axis_word(const CodeTemplate& t) {
  for (const CodeTemplate::Word& w : t.words) {
    const char letter = CodeTemplate::letter(w);
    if (letter == 0 || std::string_view("XYZABCUVW").find(letter) == std::string_view::npos) continue;
    for (const CodeTemplate::Piece& p : w) {
      if (p.var < 0) continue;
      switch (Var(p.var)) {
        case Var::X: case Var::Y: case Var::Z: case Var::I: case Var::J: case Var::K: case Var::Angle:
        case Var::Seconds: case Var::Milliseconds:
          continue;
        default:
          return "placeholder {" + std::string(var_name(Var(p.var))) + "} in the axis address " + letter +
                 ": the control would move the axis to it; give it its own address (H{offset}, D{register})";
      }
    }
  }
  return "";
}

void read_template(Reader& r, std::string_view key, CodeTemplate& out, uint32_t allowed) {
  const toml::node* n = r.node(key);
  if (!n) return;
  if (!n->is_string()) {
    r.error(*n, key, "expected a code template string, found " + type_name(*n));
    return;
  }
  CodeTemplate t;
  std::string err;
  if (!parse_template(**n->as_string(), t, err)) {
    r.error(*n, key, "bad code template: " + err);
    return;
  }
  uint32_t extra = t.vars_used() & ~allowed;
  if (extra) {
    std::string names, ok;
    for (int v = 0; v < int(Var::Count); ++v) {
      if (extra >> v & 1) names += (names.empty() ? "{" : ", {") + std::string(var_name(Var(v))) + "}";
      if (allowed >> v & 1) ok += (ok.empty() ? "{" : ", {") + std::string(var_name(Var(v))) + "}";
    }
    r.error(*n, key, "placeholder " + names + " cannot be used here" + (ok.empty() ? " (this code takes none)" : " (allowed: " + ok + ")"));
    return;
  }
  if (const std::string why = number_in_an_axis_word(t); !why.empty()) {
    r.error(*n, key, why);
    return;
  }
  out = std::move(t);
}

bool read_templates(Reader& r, std::string_view key, std::vector<CodeTemplate>& out) {
  const toml::node* n = r.node(key);
  if (!n) return false;
  const toml::array* a = n->as_array();
  if (!a) {
    r.error(*n, key, "expected an array of code templates, found " + type_name(*n));
    return false;
  }
  std::vector<CodeTemplate> v;
  for (const toml::node& e : *a) {
    if (!e.is_string()) {
      r.error(e, key, "expected an array of strings; this element is " + type_name(e));
      return false;
    }
    CodeTemplate t;
    std::string err;
    if (!parse_template(**e.as_string(), t, err) || t.vars_used() != 0) {
      r.error(e, key, err.empty() ? "placeholders cannot be used here" : "bad code template: " + err);
      return false;
    }
    v.push_back(std::move(t));
  }
  out = std::move(v);
  return true;
}

// The defaults that depend on the output units. Everything else a family has by default (its
// codes, pipeline, program start and end, a lathe's diameter X and ZX arcs) is in the
// abstract bases `mill` and `lathe` of machines.toml, which a machine without `inherits`
// starts from.
void set_defaults(Machine& m) {
  const bool inch = m.units == ir::Units::Inch;
  for (char c = 'A'; c <= 'Z'; ++c) {
    AddressFormat f;
    switch (c) {
      case 'X': case 'Y': case 'Z': case 'I': case 'J': case 'K': case 'R': case 'U': case 'V': case 'W': case 'Q': case 'E':
        f.decimals = inch ? 4 : 3;
        break;
      case 'A': case 'B': case 'C':
        f.decimals = 3;
        break;
      case 'F':
        f.decimals = inch ? 2 : 1;
        break;
      default:  // G M N O P S T H D L: whole numbers
        f.decimals = 0;
        f.point = AddressFormat::Point::Never;
        break;
    }
    m.formats[size_t(c - 'A')] = f;
  }
  m.cycles.peck_clearance = inch ? 0.02 : 0.5;
  if (m.is_lathe()) {
    // P and Q of G74/G75: least input increments, no point.
    for (char c : {'P', 'Q'}) {
      m.formats[size_t(c - 'A')].decimals = inch ? 4 : 3;
      m.formats[size_t(c - 'A')].point = AddressFormat::Point::Never;
    }
  }
  m.arcs.tolerance = inch ? 0.0002 : 0.005;
}

// `length_like`: the address holds a length or a rate, so one written for a machine in the other
// units has a decimal more (mm -> inch) or fewer.
void read_format(Reader r, AddressFormat& f, bool length_like) {
  r.integer("decimals", f.decimals);
  if (length_like && r.has("decimals")) {
    const double to = r.to_target("decimals");
    if (to > 1.5) f.decimals = std::max(0, f.decimals - 1);  // given in inches, for a machine in mm
    else if (to < 0.5) f.decimals = std::min(9, f.decimals + 1);
  }
  int p = r.choice("point");
  if (p >= 0) f.point = AddressFormat::Point(p);
  r.boolean("leading_zero", f.leading_zero);
  r.boolean("trailing_zeros", f.trailing_zeros);
  r.integer("digits", f.digits);
  // A scale is a diameter's 2 or a sign change, not a way to lose every digit.
  if (const toml::node* n = r.find("scale"); n && n->is_number() &&
                                             !(std::abs(*n->value<double>()) >= 1e-3 && std::abs(*n->value<double>()) <= 1e3))
    r.error(*n, "scale", "expected a number from 0.001 to 1000 (or -1000 to -0.001), found " + num_text(*n->value<double>()));
  else
    r.number("scale", f.scale);
  r.boolean("plus", f.plus);
  r.finish();
}

// A pipeline that does not make a legal program for the machine (machine/pipeline_check.h):
// one located error at its `pipeline` key.
void report_pipeline(Reader& r, const Machine& m, const ir::PassContracts& passes) {
  const std::string problem = check_pipeline(m, passes);
  if (problem.empty()) return;
  // An inherited pipeline that does not fit what this machine adds (travel limits, rotaries) is
  // said here, where the machine is written, not at its parent's key in another file.
  if (const toml::node* n = r.top().get("pipeline")) r.error(*n, "pipeline", problem);
  else if (r.find("pipeline")) r.at_table(problem + " (its pipeline is inherited: give the machine its own)");
  else r.missing("pipeline", problem);
}

// Per-job options that ask for what the machine cannot do (docs/machines.md, "Per-job
// options"): one located error at the option.
void check_job_options(Reader& p, const Machine& m) {
  if (const toml::node* n = p.find("park"); n && m.park && m.park_blocks.empty())
    p.error(*n, "park", "machine '" + m.name + "' has no park_blocks to park with (say, park_blocks = [\"G53 G00 Y0.\"])");
  if (const toml::node* n = p.find("preselect"); n && m.preselect && m.is_lathe())
    p.error(*n, "preselect", "a lathe's turret indexes the tool it cuts with: there is no next tool to preselect");
}

// A dwell's time written so the control reads another: without a point P, X and U are in
// milliseconds (least increments), with one in seconds. G04 X{milliseconds} wrote X1250. for
// 1.25 s, G04 P{seconds} P1 for 1 s (helper-52). "" when the word reads as written.
std::string dwell_word_problem(const CodeTemplate& t, const Machine& m) {
  for (const CodeTemplate::Word& w : t.words) {
    const char letter = CodeTemplate::letter(w);
    if (letter == 0 || w.size() < 2 || w[0].literal.size() != 1 || w[1].var < 0) continue;
    const Var v = Var(w[1].var);
    if ((letter != 'P' && letter != 'X' && letter != 'U') || (v != Var::Seconds && v != Var::Milliseconds)) continue;
    const AddressFormat& f = m.format(letter);
    const bool whole = w[1].width > 0;  // {milliseconds:1}: a whole number, no point
    const std::string word = std::string(1, letter) + "{" + std::string(var_name(v)) + (whole ? ":" + std::to_string(w[1].width) : "") + "}";
    const std::string fmt = "format." + std::string(1, letter);
    if (v == Var::Milliseconds && !whole && (f.decimals != 0 || f.point == AddressFormat::Point::Always))
      return word + " is written " + (f.point == AddressFormat::Point::Always ? "with a point" : "with decimals") +
             " (" + fmt + "), and the control reads a dwell's " + letter + " with a point in seconds, without one in " +
             "milliseconds: 1.25 s would be read as 1250 s or 1.25 ms; write " + letter + "{milliseconds:1}, or " +
             letter + "{seconds} with a point";
    if (v == Var::Seconds && (whole || !(f.point == AddressFormat::Point::Always ||
                                          (f.point == AddressFormat::Point::Never && f.decimals == 3))))
      return word + " may be written without a point (" + (whole ? "a whole number" : fmt) + "), and the control " +
             "reads a dwell's " + letter + " without a point in milliseconds: 1 s would be read as 1 ms; write " +
             letter + "{milliseconds:1}" + (letter == 'P' ? " or X{seconds} (a Fanuc's P takes no point)" : "") +
             ", or give " + fmt + " point = \"always\" where the control takes one (Haas)";
  }
  return "";
}

// The addresses that hold whole numbers only: a speed, a tool, a register, a program number, a
// count, a code.
constexpr std::string_view kWholeNumberLetters = "STHDOLMG";

// A whole number (a tool, a register, a work offset's number, a speed) in a word whose address
// is written without a point in decimals: G54.1 P{number} with format.P = { decimals = 1,
// point = "never" } wrote P10 for P1, another fixture's offset, certified (verify read it back
// through the same format; helper-67). "" when there is none.
std::string whole_number_problem(const CodeTemplate& t, const Machine& m) {
  for (const CodeTemplate::Word& w : t.words) {
    const char letter = CodeTemplate::letter(w);
    // S, T, H, D, ... themselves are refused at their format (the same mistake, said once).
    if (letter == 0 || kWholeNumberLetters.find(letter) != std::string_view::npos) continue;
    const AddressFormat& f = m.format(letter);
    if (f.point != AddressFormat::Point::Never || f.decimals == 0) continue;
    for (const CodeTemplate::Piece& p : w) {
      if (p.var < 0 || p.width > 0) continue;
      switch (Var(p.var)) {
        case Var::Tool: case Var::Offset: case Var::Register: case Var::Number: case Var::Level: case Var::Tip:
        case Var::Speed: case Var::Max:
          return std::string(1, letter) + "{" + std::string(var_name(Var(p.var))) + "} is a whole number, and format." +
                 letter + " writes it without a point in " + std::to_string(f.decimals) + " decimals: 1 would be " +
                 letter + "1" + std::string(size_t(f.decimals), '0') + ", which the control reads as " +
                 "1" + std::string(size_t(f.decimals), '0') + "; write " + letter + "{" +
                 std::string(var_name(Var(p.var))) + ":1} (a plain whole number)";
        default: break;
      }
    }
  }
  return "";
}

// The axes a run of blocks sends home (G91 G28 Z0., G53 Z0.; a lathe's G28 U0. W0.): X, Y, Z.
std::string homed_axes(const std::vector<CodeTemplate>& blocks, size_t count) {
  std::string homed;
  for (size_t i = 0; i < count && i < blocks.size(); ++i) {
    const CodeTemplate& b = blocks[i];
    const std::string t = control_words(b.text);
    bool home = false;
    for (double g : code_numbers(t, 'G'))
      if (g == 28 || g == 30 || g == 53) home = true;
    if (!home) continue;
    for (char a : axis_words(t)) {
      const char axis = a == 'U' ? 'X' : a == 'V' ? 'Y' : a == 'W' ? 'Z' : a;
      if (homed.find(axis) == std::string::npos) homed += axis;
    }
  }
  return homed;
}

// A machine's fixed blocks run wherever the CL has left the tool, so they may move it only in
// ways that clear the part whatever it is: G53, or G91 G28 Z0. "G28 Z0." as safe_retract
// rapided from Z100 down to the part's Z0 on the way home, and "G00 X0. Y0. Z-30." in finish
// went into the part; both certified (helper-67).
// A mill's block that runs where the tool may still be down in the part moves Z alone, up,
// before anything else: "G91 G28 X0. Y0. Z0." and "G53 G00 X0. Y0. Z0." start every axis at
// once (a Fanuc's rapids are not interpolated), and "G53 G00 Y0." before Z went across at the
// depth the tool stood; all certified (helper-74). `z_home`: Z has gone home in the list.
std::string across_before_z_home(std::string_view block, bool& z_home) {
  const std::string t = control_words(block);
  if (z_home) return "";
  for (double g : code_numbers(t, 'G'))
    if (g == 65 || g == 66 || g == 66.1) return "";  // a macro's words are its arguments
  std::string axes = axis_words(t);
  std::replace(axes.begin(), axes.end(), 'W', 'Z');  // (a Mazak's W is its Z)
  if (axes.empty()) return "";
  if (axes.find_first_not_of('Z') == std::string::npos) {
    z_home = true;
    return "";
  }
  std::string others;
  for (char a : axes)
    if (a != 'Z') others += a;
  return "'" + std::string(block) + "' moves " + others + (axes.find('Z') != std::string::npos ? " with Z" : " before Z") +
         " while the tool may still be down in the part: it would cross at the depth it stands; send Z home in a block "
         "of its own first (G91 G28 Z0., G53 G00 Z0.)";
}

void check_fixed_blocks(Reader& r, const Machine& m) {
  const bool lathe = m.is_lathe();
  // The park blocks come before the finish's last block (the program end), from where the ones
  // before it sent the tool: Z at home leaves X, Y and the rotaries free to go anywhere (a
  // mill's table to the front, a lathe's turret out in X); a Z move is judged, back towards a
  // lathe's chuck or down a mill's column (helper-69: G00 X0. Z-40. after G28 U0. W0.).
  const std::string homed = homed_axes(m.finish, m.finish.empty() ? 0 : m.finish.size() - 1);
  const bool z_home = homed.find('Z') != std::string::npos;
  const std::string_view park_free = !z_home ? "" : lathe ? "XUC" : "XYABCUV";
  const std::string advice = "move in machine coordinates (G53 G00 Z0.) or straight home (G91 G28 Z0.)";
  if (auto p = r.sub("program"))
    for (const char* key : {"start", "safe_start", "finish", "park_blocks"}) {
      const toml::node* n = p->find(key);
      const toml::array* a = n ? n->as_array() : nullptr;
      if (!a) continue;
      bool incremental = false;
      // (Z first in the finish and the park; a program's start finds the tool up.)
      // (Park blocks run only with program.park.)
      bool z_up = lathe || std::string_view(key) == "start" || std::string_view(key) == "safe_start" ||
                  (std::string_view(key) == "park_blocks" && (z_home || !m.park));
      for (const toml::node& e : *a)
        if (const auto* text = e.as_string()) {
          std::string free(std::string_view(key) == "park_blocks" ? park_free : "");
          // A lathe parked in front of the face (Z above 0, where lathes put the part's face):
          // G00 X200. Z100. after G28 U0. W0.
          if (lathe && !free.empty()) {
            const std::vector<double> z = code_numbers(control_words(**text), 'Z');
            if (!z.empty() && std::all_of(z.begin(), z.end(), [](double v) { return v > 0; }) &&
                control_words(**text).find("Z-") == std::string::npos)
              free += 'Z';
          }
          if (const std::string why = part_position_in(**text, lathe, incremental, free); !why.empty())
            p->error(e, key, why + ": a fixed block must clear the part wherever the tool stands; " + advice);
          else if (const std::string across = across_before_z_home(**text, z_up); !across.empty())
            p->error(e, key, across);
        }
    }
  // (A lathe's tool change at a position in the part's coordinates, G00 X250. Z200. T0101, is
  // refused too: clpc cannot know it is clear of the part, G00 X0. Z-40. was certified
  // (helper-69); G30 U0. W0., the control's second reference point, is the tool change
  // position made for it.)
  if (auto codes = r.sub("codes"))
    for (auto [code, key] : {std::pair{&m.codes.safe_retract, "safe_retract"}, std::pair{&m.codes.tool_change, "tool_change"},
                             std::pair{&m.codes.tool_preselect, "tool_preselect"}}) {
      bool incremental = false;
      bool z_up = lathe || std::string_view(key) != "safe_retract";  // (the tool change comes after it)
      if (const std::string why = part_position_in(code->text, lathe, incremental); !why.empty()) {
        if (const toml::node* n = codes->find(key))
          codes->error(*n, key, why + ": it runs wherever the tool stands, so it must clear the part whatever it is; " +
                                    advice);
      } else if (const std::string across = across_before_z_home(code->text, z_up); !across.empty()) {
        if (const toml::node* n = codes->find(key)) codes->error(*n, key, across);
      }
    }
}

// On a mill M03 turns the spindle clockwise and M04 counter-clockwise (ISO 6983), whichever way
// a builder wires it: swapped, every right-hand cutter ran backwards, certified, as verify holds
// the program to the machine's own codes (helper-67). (A lathe's M03 is "forward", which APT's
// CLW means as seen from where the turret is: not judged.)
void check_spindle_codes(Reader& r, const Machine& m) {
  auto codes = r.sub("codes");
  if (!codes || m.is_lathe()) return;
  for (auto [code, key, wrong] : {std::tuple{&m.codes.spindle_cw, "spindle_cw", 4}, std::tuple{&m.codes.spindle_ccw, "spindle_ccw", 3}})
    for (double mc : code_numbers(control_words(code->text), 'M'))
      if (mc == wrong)
        if (const toml::node* n = codes->find(key))
          codes->error(*n, key, "M0" + std::to_string(wrong) + " turns a mill's spindle " +
                                    (wrong == 4 ? "counter-clockwise" : "clockwise") + " (ISO 6983), the other way than " +
                                    key + " says: every cutter would run backwards");
}

// A mill's G41/G42 takes the cutter's radius from the D it names: with none the control uses
// the D in force, D00 (radius 0) after a reset or power-up, and the contour was cut on the
// tool's centre, the radius into the wall (helper-71: certified). (A lathe's T word selects its
// nose radius.)
void check_comp_codes(Reader& r, const Machine& m) {
  auto codes = r.sub("codes");
  if (!codes || m.is_lathe()) return;
  // (Siemens selects the edge, its length and radius, with the tool: T{tool} M06 D{offset}.)
  // (Its words as the control reads them: a D in a comment is none; helper-72.)
  const std::string change = control_words(m.codes.tool_change.text);
  for (size_t d = change.find_first_of("Dd"); d != std::string::npos; d = change.find_first_of("Dd", d + 1))
    if (d + 1 < change.size() && (change[d + 1] == '{' || std::isdigit(static_cast<unsigned char>(change[d + 1])))) return;
  for (auto [code, key] : {std::pair{&m.codes.comp_left, "comp_left"}, std::pair{&m.codes.comp_right, "comp_right"}})
    if (!code->empty() && !code->uses(Var::Register))
      if (const toml::node* n = codes->find(key))
        codes->error(*n, key, "'" + code->text + "' " +
                                  (control_words(code->text).find('D') != std::string::npos
                                       ? "names one radius register for every tool, not the tool's ({register})"
                                       : "names no radius register: a mill's control takes the one in force, D00 "
                                         "(radius 0) after a reset, and cuts on the tool's centre") +
                                  "; write " +
                                  (std::string(key) == "comp_left" ? "\"G41 D{register}\"" : "\"G42 D{register}\"") +
                                  " (or select it with the tool: tool_change = \"T{tool} M06 D{offset}\")");
}

// The same, for options that need a code (read after [NAME.codes]).
void check_job_codes(Reader& r, const Machine& m) {
  // Inverse time with no G93 to write it: every move that turns a rotary would be an error,
  // several per record; said once, where the machine asks for it.
  if (auto k = r.sub("kinematics"); k && m.kinematics.inverse_time && m.codes.inverse_time.empty())
    if (const toml::node* n = k->find("inverse_time"))
      k->error(*n, "inverse_time", "machine '" + m.name + "' has no codes.inverse_time (say, \"G93\") to write it with");
  if (auto k = r.sub("kinematics"); k && m.kinematics.indexed == Indexed::Plane) {
    if (const toml::node* n = k->find("indexed"); n && (m.codes.plane_on.empty() || m.codes.plane_off.empty()))
      k->error(*n, "indexed",
               "\"plane\" needs codes.plane_on and codes.plane_off (say, \"G68.2 X{x} Y{y} Z{z} I{i} J{j} K{k}\" and "
               "\"G69\")");
  }
  // A mode switched on with no code to switch it off stays on through G28, M06 and the next
  // tool (G43.4 H01 kept for T2).
  if (auto codes = r.sub("codes")) {
    const bool tcp_used = m.kinematics.has_rotaries() &&
                          (m.kinematics.simultaneous == Simultaneous::Tcp || m.kinematics.indexed == Indexed::Tcp);
    const bool dwo_used = m.kinematics.has_rotaries() && m.kinematics.indexed == Indexed::Dwo;
    for (auto [on, off, used, name] : {std::tuple{&m.codes.tcp_on, &m.codes.tcp_off, tcp_used, "tcp"},
                                       std::tuple{&m.codes.dwo_on, &m.codes.dwo_off, dwo_used, "dwo"}})
      if (used && !on->empty() && off->empty())
        if (const toml::node* n = codes->find(std::string(name) + "_off") ? codes->find(std::string(name) + "_off")
                                                                           : codes->find(std::string(name) + "_on"))
          codes->error(*n, std::string(name) + (codes->find(std::string(name) + "_off") ? "_off" : "_on"),
                       "machine '" + m.name + "' switches " + (std::string(name) == "tcp" ? "tool centre point control" : "its dynamic work offset") +
                           " on with \"" + on->text + "\" and has no code to switch it off: it would stay on through the "
                           "tool change and the retract; give the control's cancel (say, \"" +
                           (std::string(name) == "tcp" ? "G49" : "G255") + "\")");
  }
  if (auto codes = r.sub("codes"))
    for (auto [code, key] : {std::pair{&m.codes.dwell, "dwell"}, std::pair{&m.codes.cycle_dwell_word, "cycle_dwell_word"}})
      if (const toml::node* n = codes->find(key))
        if (const std::string why = dwell_word_problem(*code, m); !why.empty()) {
          // Said where this machine's file made it so: its own code, else its own format of the
          // word (an inherited code made wrong by a format given here), else the code.
          const toml::node* at = r.top().at_path(std::string("codes.") + key).node();
          if (!at) at = r.top().at_path(std::string("format.") + why[0]).node();  // (the message starts with the word)
          codes->error(at ? *at : *n, key, why);
        }
  if (auto codes = r.sub("codes"))
    for (const KeySpec& k : machine_keys()) {
      if (k.section != "codes" || !k.code) continue;
      if (const std::string why = whole_number_problem(m.codes.*k.code, m); !why.empty()) {
        // Said where this machine's file made it so, as for the dwell.
        const toml::node* at = r.top().at_path("codes." + k.key).node();
        if (!at) at = r.top().at_path(std::string("format.") + why[0]).node();
        if (at) codes->error(*at, k.key, why);
        else if (const toml::node* n = codes->find(k.key)) codes->error(*n, k.key, why);
      }
    }
  auto p = r.sub("program");
  if (!p) return;
  if (const toml::node* n = p->find("smoothing"); n && m.smoothing > 0 && m.codes.smoothing_on.empty())
    p->error(*n, "smoothing", "machine '" + m.name + "' has no codes.smoothing_on to switch its smoothing on with");
  if (const toml::node* n = p->find("smoothing_tolerance");
      n && m.smoothing_tolerance > 0 && !(m.codes.smoothing_on.vars_used() & (1u << unsigned(Var::Tolerance))))
    p->error(*n, "smoothing_tolerance",
             "machine '" + m.name + "''s codes.smoothing_on (\"" + m.codes.smoothing_on.text +
                 "\") has no {tolerance}: the control takes its tolerance from its parameters");
  if (const toml::node* n = p->find("preselect"); n && m.preselect && !m.is_lathe() && m.codes.tool_preselect.empty())
    p->error(*n, "preselect", "machine '" + m.name + "' has no codes.tool_preselect");
}

Machine build_machine(Ctx& c, const std::string& name, Reader::Layers layers, const ir::PassContracts& passes,
                      const std::string& source) {
  Machine m;
  m.name = name;
  m.source = source;
  // The units each layer is in: its own "units", else its parent's.
  std::vector<ir::Units> layer_units;
  ir::Units in_force = ir::Units::Mm;
  for (const toml::table* t : layers) {
    if (const toml::node* n = t->get("units"); n && n->is_string())
      in_force = **n->as_string() == "inch" ? ir::Units::Inch : ir::Units::Mm;
    layer_units.push_back(in_force);
  }
  Reader r(c, std::move(layers), name, "", layer_units, in_force);
  r.node("inherits");  // used while flattening
  bool abstract_base = false;  // only the named machine's own counts (resolve)
  r.boolean("abstract", abstract_base);
  int fam = r.choice("family");
  if (!r.has("family")) r.missing("family", "\"mill\" or \"lathe\"");
  if (fam >= 0) m.family = Family(fam);
  int u = r.choice("units");
  if (u >= 0) m.units = ir::Units(u);
  set_defaults(m);
  r.string("description", m.description);
  if (const toml::node* n = r.find("extension"); n && n->is_string() && (**n->as_string()).empty())
    r.error(*n, "extension", "expected a file extension such as \".nc\", found \"\"");
  else
    r.string("extension", m.extension);
  if (!m.extension.empty() && m.extension[0] != '.') m.extension = "." + m.extension;
  std::vector<std::string> pipeline;
  if (r.strings("pipeline", pipeline) && !passes.empty()) {
    const toml::node* n = r.find("pipeline");
    for (size_t i = 0; i < pipeline.size(); ++i) {
      if (std::none_of(passes.begin(), passes.end(), [&](const ir::PassContract& p) { return p.name == pipeline[i]; })) {
        std::string all;
        for (const auto& k : passes) all += (all.empty() ? "" : ", ") + k.name;
        r.error((*n->as_array())[i], "pipeline", "unknown pass '" + pipeline[i] + "' (passes: " + all + ")");
      }
    }
    m.pipeline = pipeline;
  }
  r.length("rapid_rate", m.rapid_rate);
  r.number("tool_change_time", m.tool_change_time);
  r.length("max_feed", m.max_feed);
  r.number("max_rpm", m.max_rpm);

  if (auto p = r.sub("program")) {
    p->integer("number", m.program_number);
    p->strings("start", m.program_start);
    p->strings("end", m.program_end);
    p->boolean("header", m.header);
    read_templates(*p, "safe_start", m.safe_start);
    read_templates(*p, "finish", m.finish);
    p->boolean("number_from_name", m.number_from_name);
    int os = p->choice("optional_stop");
    if (os >= 0) m.optional_stop = Machine::OptionalStop(os);
    p->boolean("preselect", m.preselect);
    p->boolean("coolant_around_tool_change", m.coolant_around_tool_change);
    int sm = p->choice("smoothing");
    if (sm >= 0) m.smoothing = sm;
    p->length("smoothing_tolerance", m.smoothing_tolerance);
    p->boolean("park", m.park);
    read_templates(*p, "park_blocks", m.park_blocks);
    p->string("date", m.date);
    p->string("programmer", m.programmer);
    p->string("stock", m.stock);
    check_job_options(*p, m);
    int ins = p->choice("inserts");
    if (ins >= 0) m.inserts = Machine::Inserts(ins);
    p->finish();
  }
  if (auto s = r.sub("sequence")) {
    SequenceSettings& q = m.sequence;
    s->boolean("enabled", q.enabled);
    s->integer("start", q.start);
    s->integer("step", q.step);
    s->integer("max", q.max);
    s->integer("wrap_to", q.wrap_to);
    s->boolean("tool_change_only", q.tool_change_only);
    if (q.max < q.start) {
      if (const toml::node* n = s->find("max")) s->error(*n, "max", "must not be less than start (" + std::to_string(q.start) + ")");
      else if (const toml::node* n2 = s->find("start")) s->error(*n2, "start", "must not be more than max (" + std::to_string(q.max) + ")");
    }
    s->finish();
  }
  // A '%' inside the program is the tape's end to a Fanuc or Haas loading it, and a '(' or ')'
  // opens or closes a comment: from these keys they reached the program (helper-67).
  auto no_tape_marks = [](Reader& s, const char* key, const std::string& value, std::string_view bad) {
    if (value.find_first_of(bad) == std::string::npos) return;
    if (const toml::node* n = s.find(key))
      s.error(*n, key, "'" + std::string(1, value[value.find_first_of(bad)]) + "' would stand in the program's blocks, "
                           "where a control reads '%' as the end of the tape and '(' ')' as a comment's ends");
  };
  if (auto s = r.sub("comments")) {
    CommentSettings& q = m.comments;
    s->boolean("enabled", q.enabled);
    s->string("open", q.open);
    s->string("close", q.close);
    s->integer("max_length", q.max_length);
    s->boolean("upper_case", q.upper_case);
    s->string("replacement", q.replacement);
    no_tape_marks(*s, "replacement", q.replacement, "%()");
    s->finish();
  }
  if (auto s = r.sub("words")) {
    s->string("separator", m.separator);
    s->string("block_end", m.block_end);
    no_tape_marks(*s, "separator", m.separator, "%()");
    no_tape_marks(*s, "block_end", m.block_end, "%()");
    s->finish();
  }
  if (auto s = r.sub("format")) {
    for (const auto& [k, key] : s->keys()) {
      if (k.size() != 1 || k[0] < 'A' || k[0] > 'Z') {
        c.error(key->source(), s->key_path(k) + ": expected an address letter A-Z");
        s->reported(k);
        continue;
      }
      // A lathe's P is G74/G75's peck in least input increments, a length like Q (a mill's P
      // is a dwell): given for a metric lathe and inherited by an inch one, it kept 3 decimals
      // and the peck was written 10 times too small.
      const bool length_like = std::string_view("XYZUVWIJKRQF").find(k[0]) != std::string_view::npos ||
                               (k[0] == 'P' && m.is_lathe());
      if (auto f = s->sub(k)) read_format(*f, m.formats[size_t(k[0] - 'A')], length_like);
      // A block number is a whole number: only its zero-padding (digits) is the user's to choose.
      if (k[0] == 'N') {
        const AddressFormat& nf = m.formats[size_t('N' - 'A')];
        if (nf.decimals != 0 || nf.scale != 1 || nf.plus)
          c.error(key->source(), s->key_path(k) + ": a block number is a whole number, written as counted "
                                     "([sequence] start and step): only digits (zero-padding) applies");
      }
      // A scale on an axis of the arcs' plane stretches or mirrors X while I, J, K and the
      // arcs' directions stay the CL's: scale = -1 on a mill's X wrote a 90 degree G03 that a
      // control cuts as 270 (verify divided by the same scale, and certified it).
      const double scale = m.formats[size_t(k[0] - 'A')].scale;
      const bool diameter_x = m.is_lathe() && k[0] == 'X';
      if (std::string_view("XYZIJK").find(k[0]) != std::string_view::npos &&
          !(scale == 1 || (diameter_x && scale == 2)))
        c.error(key->source(), s->key_path(k) + ".scale: " + num_text(scale) + " would stretch or mirror " + k +
                                   " while the arcs' centres and directions stay the CL's; a lathe's X is 1 (radius) or "
                                   "2 (diameter), every other axis 1 (a lathe that views its arcs from -Y says "
                                   "lathe.arcs_seen_from)");
      // A feed, a speed, a dwell or a register is no length to scale: F with scale 2 fed twice
      // as fast, and verify caught it only as a failed certificate (helper-52).
      if (std::string_view("FSPTHDMGOLE").find(k[0]) != std::string_view::npos && scale != 1)
        if (auto f = s->sub(k))
          if (const toml::node* n = f->find("scale"))
            f->error(*n, "scale", num_text(scale) + " on " + k + ", which is no length: the control would read another "
                                  "feed, speed, time or number than the one meant; a scale is for a lathe's diameter X");
      // A position or angle written without its point when it is whole (X50) is read by a
      // Fanuc or Haas in least input increments (0.050 mm) unless the control is set for
      // calculator-type input: every whole position a thousand times short, certified (the
      // reader took it as written; helper-62). point = "always" reads right on every control.
      if (std::string_view("XYZUVWIJKRABC").find(k[0]) != std::string_view::npos &&
          m.formats[size_t(k[0] - 'A')].point == AddressFormat::Point::Never &&
          m.formats[size_t(k[0] - 'A')].decimals == 0)
        c.error(key->source(), s->key_path(k) + ": written without a point in whole units (" + k + "20), which a control "
                                   "reads in least input increments (0.020 mm): give the decimals of its increment "
                                   "(3 in mm, 4 in inches) or point = \"always\"");
      // A speed, a tool, a register, a program number or a repeat count is a whole number the
      // control reads as written: without a point in decimals, S3000 was written S30000 (past
      // max_rpm, which holds the CL's speed) and H1 as H10, certified (helper-67).
      if (const AddressFormat& f = m.formats[size_t(k[0] - 'A')];
          kWholeNumberLetters.find(k[0]) != std::string_view::npos && f.point == AddressFormat::Point::Never &&
          f.decimals > 0)
        c.error(key->source(), s->key_path(k) + ": " + k + " is a whole number (a speed, a tool, a register, a "
                                   "program number, a count), and without a point in " + std::to_string(f.decimals) +
                                   " decimals " + k + "1 would be written " + k + "1" +
                                   std::string(size_t(f.decimals), '0') + ", which the control reads as that number: "
                                   "say decimals = 0");
      // (Q too: a peck, a bore's shift; and a lathe's P, a groove's peck: G83 Q5 pecked 0.005 mm,
      // helper-71.)
      if ((std::string_view("XYZUVWIJKRABCQ").find(k[0]) != std::string_view::npos || (k[0] == 'P' && m.is_lathe())) &&
          m.formats[size_t(k[0] - 'A')].point == AddressFormat::Point::IfFraction)
        c.error(key->source(), s->key_path(k) + ".point: \"if-fraction\" writes a whole " + k + " without its point (" +
                                   k + "50), which a control reads in least input increments (0.050 mm, 0.0050 in) "
                                   "unless it is set for calculator-type input: say " +
                                   (m.is_lathe() && (k[0] == 'P' || k[0] == 'Q')
                                        ? std::string("point = \"never\" in the axes' decimals (a lathe's cycles take P "
                                                      "and Q without a point)")
                                        : std::string("point = \"always\"")));
      // Numbers without a point are counted in the control's one least input increment: two
      // axes written so with other decimals (X in 0.001, Y in 0.0001) put one 10 times off.
      const AddressFormat& mine = m.formats[size_t(k[0] - 'A')];
      if (std::string_view("XYZIJKUVW").find(k[0]) != std::string_view::npos && mine.point == AddressFormat::Point::Never)
        for (char o : std::string_view("XYZIJKUVW")) {
          const AddressFormat& other = m.formats[size_t(o - 'A')];
          if (o != k[0] && other.point == AddressFormat::Point::Never && other.decimals != mine.decimals) {
            c.error(key->source(), s->key_path(k) + ": written without a point in " + std::to_string(mine.decimals) +
                                       " decimals, while " + o + " is in " + std::to_string(other.decimals) +
                                       ": a control counts both in its one least input increment, so one would be off "
                                       "by a power of ten");
            break;
          }
        }
    }
    // R (an arc's radius, a cycle's R plane), Q (a peck, a bore's shift) and a lathe's P (a
    // groove's peck) written without a point are counted in the same least input increment as
    // the axes: format.R = { decimals = 2, point = "never" } wrote R3.2 as R320, a 0.32 mm
    // R plane, certified (helper-67). The increment is that of an axis written without a point,
    // else the usual one (0.001 mm, 0.0001 in).
    {
      int increment = m.units == ir::Units::Inch ? 4 : 3;
      char axis = 0;  // the axis that says the increment, if any
      for (char a : {'X', 'Y', 'Z'})
        if (m.format(a).point == AddressFormat::Point::Never) {
          increment = m.format(a).decimals;
          axis = a;
          break;
        }
      for (char k : std::string_view(m.is_lathe() ? "PQR" : "QR")) {
        const AddressFormat& f = m.format(k);
        if (f.point != AddressFormat::Point::Never || f.decimals == increment) continue;
        // Said where this machine's file made it so: its own R, Q or P, else the axis whose
        // decimals it gave (an inherited P made wrong by an X given here).
        const toml::node* n = r.top().at_path(std::string("format.") + k).node();
        if (!n && axis) n = r.top().at_path(std::string("format.") + axis).node();
        if (!n) n = s->find(std::string(1, k));
        if (n)
          s->error(*n, std::string(1, k),
                   std::string(1, k) + " is a length written without a point in " + std::to_string(f.decimals) +
                       " decimals, and the control counts it in its least input increment (" +
                       std::to_string(increment) + " decimals" +
                       (axis ? std::string(", as format.") + axis + " says"
                             : std::string(", the usual ") + (increment == 4 ? "0.0001 in" : "0.001 mm") +
                                   "; a control in finer increments says so by writing its axes without a point") +
                       "): every " + k + " would be off by a power of ten; give it " + std::to_string(increment) +
                       " decimals" + (k == 'P' ? "" : ", or point = \"always\" where the control takes one"));
      }
    }
    s->finish();
  }
  if (auto s = r.sub("arcs")) {
    ArcSettings& a = m.arcs;
    std::vector<std::string> planes;
    if (s->strings("planes", planes)) {
      a.xy = a.zx = a.yz = false;
      const toml::node* n = s->find("planes");
      for (size_t i = 0; i < planes.size(); ++i) {
        if (planes[i] == "XY") a.xy = true;
        else if (planes[i] == "ZX") a.zx = true;
        else if (planes[i] == "YZ") a.yz = true;
        else s->error((*n->as_array())[i], "planes", "expected \"XY\", \"ZX\" or \"YZ\", found \"" + planes[i] + "\"");
      }
    }
    s->boolean("helical", a.helical);
    s->number("max_sweep", a.max_sweep);
    s->number("helix_max_sweep", a.helix_max_sweep);
    s->length("min_radius", a.min_radius);
    s->length("max_radius", a.max_radius);
    if (a.max_radius > 0 && a.max_radius < a.min_radius)
      s->error(*s->find("max_radius"), "max_radius", "must not be less than min_radius (" + num_text(a.min_radius) + ")");
    int ctr = s->choice("center");
    if (ctr >= 0) a.center = ArcCenter(ctr);
    s->length("tolerance", a.tolerance);
    s->finish();
  }
  if (auto s = r.sub("modal")) {
    s->boolean("motion", m.modal.motion);
    s->boolean("coordinates", m.modal.coordinates);
    s->boolean("feed", m.modal.feed);
    s->finish();
  }
  if (auto s = r.sub("lathe")) {
    int v = s->choice("arcs_seen_from");
    if (v >= 0) m.lathe.arcs_from_minus_y = v == 1;
    s->number("max_rpm", m.lathe.max_rpm);
    s->integer("tip", m.lathe.tip);
    s->finish();
  }
  if (auto s = r.sub("motion")) {
    MotionSettings& mo = m.motion;
    s->length3("velocity", mo.velocity);
    s->length3("acceleration", mo.acceleration);
    s->vec3("rotary_velocity", mo.rotary_velocity);
    s->length("junction_deviation", mo.junction_deviation);
    s->boolean("rapids_linear", mo.rapids_linear);
    if (const toml::node* n = s->find("rapids_linear"); n && !mo.rapids_linear && m.is_lathe())
      s->error(*n, "rapids_linear", "false is for mills: clpc does not split a lathe's rapids (which of X and Z "
                                    "must go first depends on the side the tool comes from)");
    for (const char* k : {"velocity", "acceleration", "rotary_velocity"})
      if (const toml::node* n = s->find(k); n && (k[0] == 'v' ? mo.velocity : k[0] == 'a' ? mo.acceleration : mo.rotary_velocity).minCoeff() < 0)
        s->error(*n, k, "expected numbers of at least 0 (0: unknown)");
    s->finish();
  }
  if (auto s = r.sub("offsets")) {
    OffsetSettings& o = m.offsets;
    s->integer("extended", o.extended_count);
    s->integer("default", o.default_index);
    int tb = s->choice("table");
    if (tb >= 0) o.table = OffsetTable(tb);
    s->boolean("per_frame", o.per_frame);
    s->length("reference_height", o.reference_height);
    s->integer("macro", o.macro);
    s->boolean("macro_program", o.macro_program);
    s->finish();
  }
  if (auto s = r.sub("kinematics")) {
    KinematicsSettings& k = m.kinematics;
    if (auto axes = s->table_array("axes")) {
      if (axes->size() > 2) {
        s->error(*s->find("axes"), "axes", "clpc handles at most two rotary axes, found " + std::to_string(axes->size()));
      }
      for (Reader& a : *axes) {
        RotaryAxis ax;
        a.string("name", ax.name);
        if (!a.has("name")) a.missing("name", "the axis word: A, B or C");
        else if (ax.name != "A" && ax.name != "B" && ax.name != "C")
          a.error(*a.find("name"), "name", "expected \"A\", \"B\" or \"C\", found \"" + ax.name + "\"");
        else
          for (const RotaryAxis& before : k.rotaries)
            if (before.name == ax.name)
              a.error(*a.find("name"), "name", "a second axis named \"" + ax.name +
                                                   "\": each rotary is written with a word of its own (the other is the first [[axes]])");
        if (a.vec3("axis", ax.axis)) {
          if (ax.axis.norm() < 1e-9) a.error(*a.find("axis"), "axis", "must not be zero");
          else ax.axis.normalize();
        } else if (!a.has("axis")) {
          a.missing("axis", "the direction the axis turns about, [x, y, z]");
        }
        int side = a.choice("side");
        if (side >= 0) ax.table = side == 0;
        int dir = 0;
        a.integer("direction", dir);
        if (dir == 0 && a.has("direction")) a.error(*a.find("direction"), "direction", "expected 1 or -1, found 0");
        if (dir != 0) ax.direction = dir;
        int cyc = a.choice("cyclic");
        if (cyc >= 0) ax.cyclic = Cyclic(cyc);
        a.number("min", ax.min);
        a.number("max", ax.max);
        ax.wind_range = ax.cyclic == Cyclic::Wind && (a.has("min") || a.has("max"));
        if (ax.wind_range && ax.max - ax.min < 720)
          a.error(*(a.find("max") ? a.find("max") : a.find("min")), "max",
                  "a winding axis needs a range of at least two turns (max - min >= 720), found " + num_text(ax.max - ax.min));
        if (ax.max <= ax.min && ax.cyclic == Cyclic::No)
          a.error(*(a.find("max") ? a.find("max") : a.find("name")), "max", "must be more than min (" + num_text(ax.min) + ")");
        // A modulo axis goes the short way to any angle: limits narrower than a turn were dropped
        // without a word, and C270 certified on an axis declared 0 to 90 (helper-52).
        if (ax.cyclic == Cyclic::Modulo && (a.has("min") || a.has("max")) && ax.max - ax.min < 359.99)  // (0 to 359.99 is a turn; 0 to 359 let C359.6 through, helper-55)
          a.error(*(a.find("max") ? a.find("max") : a.find("min")), a.find("max") ? "max" : "min",
                  "a modulo axis (cyclic = \"modulo\") turns to any angle the short way: limits narrower than a turn "
                  "cannot be kept; an axis that stops within a range is cyclic = \"no\"");
        for (const RotaryAxis& before : k.rotaries)
          if (ax.axis.norm() > 0.5 && std::abs(ax.axis.dot(before.axis)) > 1 - 1e-9)
            a.error(*a.find("axis"), "axis",
                    "parallel to " + before.name + "'s axis: two rotaries about one direction cannot turn the tool to "
                    "another; a five-axis machine's two axes are square to each other (or tilted, never parallel)");
        a.length3("center", ax.center);
        double prefer = 0;
        a.number("prefer", prefer);
        ax.prefer = prefer;
        a.number("rate", ax.rate);
        a.string("clamp", ax.clamp);
        a.string("unclamp", ax.unclamp);
        a.finish();
        k.rotaries.push_back(ax);
      }
    }
    int sim = s->choice("simultaneous");
    if (sim >= 0) k.simultaneous = Simultaneous(sim);
    int ind = s->choice("indexed");
    if (ind >= 0) k.indexed = Indexed(ind);
    int euler = s->choice("plane_euler");
    if (euler >= 0) k.plane_euler = EulerOrder(euler);
    s->boolean("inverse_time", k.inverse_time);
    s->boolean("degrees_per_minute", k.degrees_per_minute);
    if (k.inverse_time && k.degrees_per_minute)
      s->error(*s->find("degrees_per_minute"), "degrees_per_minute", "a control feeds rotary moves one way: inverse_time or degrees_per_minute, not both");
    s->number("max_inverse_time", k.max_inverse_time);
    int lim = s->choice("on_limit");
    if (lim >= 0) k.retract_on_limit = lim == 1;
    s->length("retract_distance", k.retract_distance);
    s->length("pivot", k.pivot);
    // The pivot is the head's: on a machine whose rotaries all turn the table it changed nothing,
    // without a word (helper-52).
    if (const toml::node* n = s->find("pivot"); n && k.pivot != 0 &&
        std::none_of(k.rotaries.begin(), k.rotaries.end(), [](const RotaryAxis& a) { return !a.table; }))
      s->error(*n, "pivot", "a pivot is the distance from a tilting head's axes to the tool: this machine has no head "
                            "axis (side = \"head\"), so it would change nothing");
    if (auto t = s->sub("travel")) {
      for (int i = 0; i < 3; ++i) {
        const char* key = i == 0 ? "x" : i == 1 ? "y" : "z";
        const toml::node* n = t->node(key);
        if (!n) continue;
        const toml::array* arr = n->as_array();
        if (!arr || arr->size() != 2 || !(*arr)[0].is_number() || !(*arr)[1].is_number() ||
            *(*arr)[0].value<double>() >= *(*arr)[1].value<double>()) {
          t->error(*n, key, "expected [min, max] with min < max");
          continue;
        }
        k.travel.min[i] = *(*arr)[0].value<double>() * t->to_target(key);
        k.travel.max[i] = *(*arr)[1].value<double>() * t->to_target(key);
        k.travel.set = true;
      }
      t->finish();
    }
    k.work_zero_set = s->length3("work_zero", k.work_zero);
    if (k.retract_on_limit && !(k.retract_distance > 0))
      s->error(*s->find("on_limit"), "on_limit", "\"retract\" needs retract_distance greater than zero");
    s->finish();
  }
  if (auto s = r.sub("cycles")) {
    int ret = s->choice("return");
    if (ret >= 0) m.cycles.return_initial = ret == 0;
    int tf = s->choice("tap_feed");
    if (tf >= 0) m.cycles.tap_per_rev = tf == 1;
    s->length("peck_clearance", m.cycles.peck_clearance);
    s->finish();
  }
  if (auto s = r.sub("codes")) {
    for (const KeySpec& k : machine_keys())
      if (k.section == "codes") read_template(*s, k.key, m.codes.*k.code, k.vars);
    s->finish();
  }
  // With no family there is no default pipeline to judge: the missing family is the error.
  if (!passes.empty() && fam >= 0) report_pipeline(r, m, passes);
  check_job_codes(r, m);
  check_fixed_blocks(r, m);
  check_spindle_codes(r, m);
  check_comp_codes(r, m);
  // O12345 where format.O has 4 digits: another program's number to a control, or an alarm.
  if (auto p = r.sub("program"))
    if (const toml::node* n = p->find("number"); n && m.format('O').digits > 0 && m.format('O').digits < 9) {
      long most = 1;
      for (int i = 0; i < m.format('O').digits; ++i) most *= 10;
      if (m.program_number >= most)
        p->error(*n, "number", std::to_string(m.program_number) + " has more digits than format.O's " +
                                   std::to_string(m.format('O').digits) + ": the control would read another program "
                                   "number, or refuse it (give format.O more digits where the control takes them)");
    }
  // Feeds: each kind in its own format. Defaults from format.F, with at least the decimals a
  // feed per revolution (4 in inches, 3 in mm) and a tap's feed (per revolution 6 and 4, per
  // minute 4 and 3) need to keep their meaning.
  {
    const bool inch = m.units == ir::Units::Inch;
    const AddressFormat& f = m.format('F');
    auto at_least = [&](int decimals) {
      AddressFormat g = f;
      g.decimals = std::max(g.decimals, decimals);
      g.point = AddressFormat::Point::Always;
      return g;
    };
    m.feeds.per_minute = f;
    m.feeds.per_rev = at_least(inch ? 4 : 3);
    m.feeds.inverse_time = f;
    m.feeds.tap = m.cycles.tap_per_rev ? at_least(inch ? 6 : 4) : at_least(inch ? 4 : 3);
    m.feeds.lead = at_least(inch ? 6 : 4);  // Fanuc takes a lead to 6 decimals in inches, 4 in mm
    if (auto s = r.sub("feeds")) {
      for (const char* k : {"per_minute", "per_rev", "inverse_time", "tap", "lead"}) {
        AddressFormat& g = std::string(k) == "per_minute" ? m.feeds.per_minute
                           : std::string(k) == "per_rev"  ? m.feeds.per_rev
                           : std::string(k) == "tap"      ? m.feeds.tap
                           : std::string(k) == "lead"     ? m.feeds.lead
                                                          : m.feeds.inverse_time;
        if (auto t = s->sub(k)) read_format(*t, g, std::string(k) != "inverse_time");
      }
      s->number("max_rounding", m.feeds.max_rounding);
      s->finish();
    }
    // A control reads a feed per minute without a point as whole units (mm/min, in/min): with
    // decimals it was written F5000 for 500 mm/min, and read back in clpc's own increments,
    // certified.
    auto no_point_with_decimals = [](const AddressFormat& g) { return g.point == AddressFormat::Point::Never && g.decimals > 0; };
    auto why = [](const AddressFormat& g) {
      return " is written without a point in " + std::to_string(g.decimals) +
             " decimals: a control reads a feed per minute without a point in whole units, so every feed would be read " +
             (g.decimals == 1 ? std::string("10") : "1" + std::string(size_t(g.decimals), '0')) +
             " times too fast; say point = \"always\" (or decimals = 0)";
    };
    bool said = false;
    if (auto s = r.sub("format"); s && no_point_with_decimals(m.format('F')))
      if (const toml::node* n = s->find("F")) {
        s->error(*n, "F", "F" + why(m.format('F')));
        said = true;
      }
    // Per minute (and inverse time, 1/min) only: a feed per revolution or a lead without a
    // point is read by the control's own increment (Fanuc lathes: 0.0001 mm/rev), as clpc
    // writes and reads it back.
    if (auto s = r.sub("feeds"); s && !said)
      for (const char* k : {"per_minute", "inverse_time", "tap"}) {
        if (std::string(k) == "tap" && m.cycles.tap_per_rev) continue;
        const AddressFormat& g = std::string(k) == "per_minute" ? m.feeds.per_minute
                                 : std::string(k) == "tap"      ? m.feeds.tap
                                                                : m.feeds.inverse_time;
        if (const toml::node* n = s->find(k); n && no_point_with_decimals(g)) s->error(*n, k, "the feed" + why(g));
      }
    // A feed per revolution or a lead written whole without its point (F1 for 1 mm/rev) is read
    // in the control's increments, 0.0001 mm/rev: a tap fed so breaks (helper-71: certified).
    if (auto s = r.sub("feeds"))
      for (const char* k : {"per_rev", "lead", "tap"}) {
        if (std::string(k) == "tap" && !m.cycles.tap_per_rev) continue;
        const AddressFormat& g = std::string(k) == "per_rev" ? m.feeds.per_rev
                                 : std::string(k) == "lead"  ? m.feeds.lead
                                                             : m.feeds.tap;
        if (const toml::node* n = s->find(k); n && g.point == AddressFormat::Point::IfFraction)
          s->error(*n, k, "\"if-fraction\" writes a whole feed per revolution or lead without its point (F1 for 1 a "
                          "turn), which the control reads in its least increments (0.0001 a turn): say point = \"always\"");
      }
  }
  r.finish();
  return m;
}

// Past the error limit Diagnostics stops the run (FatalError). The registry's entry points turn
// that into a refusal like any other: the errors and the stop have been reported.
template <class T, class Body>
T refusing_past_error_limit(T refusal, Body&& body) {
  try {
    return body();
  } catch (const FatalError&) {
    return refusal;
  }
}

// A machine description file read whole, or null (reported).
std::unique_ptr<MachineRegistry::Source> read_source(const std::string& path, Diagnostics& d) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    d.report_in(Severity::Error, path, {}, "cannot read machine description");
    return nullptr;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  auto s = std::make_unique<MachineRegistry::Source>();
  s->path = path;
  s->text = ss.str();
  return s;
}

}  // namespace

Machine default_machine(Family family, ir::Units units) {
  const bool lathe = family == Family::Lathe;
  const std::string name = lathe ? "generic-lathe" : "generic-mill";
  std::ostringstream err;
  Diagnostics d(&err);
  MachineRegistry reg({});  // no passes: the base's pipeline is taken as it is
  reg.load_builtin(d);
  reg.load_text("<generic>", "[" + name + "]\nfamily = \"" + (lathe ? "lathe" : "mill") + "\"\nunits = \"" +
                                 (units == ir::Units::Inch ? "inch" : "mm") + "\"\n",
                d);
  std::optional<Machine> m = reg.resolve(name, d);
  if (!m) throw std::logic_error("internal: the built-in base machines do not load: " + err.str());
  return *m;
}

MachineRegistry::MachineRegistry(ir::PassContracts passes) : passes_(std::move(passes)) {
  // The abstract bases, always at hand: every machine without a parent starts from one.
  auto s = std::make_unique<Source>();
  s->path = kBuiltinName;
  s->text = std::string(builtin_machines_toml());
  s->table = toml::parse(s->text, s->path);  // the built-in text: a parse error fails every test
  for (auto&& [key, n] : s->table)
    if (n.is_table() && is_abstract(*n.as_table())) bases_[std::string(key.str())] = Entry{s.get(), n.as_table()};
  sources_.push_back(std::move(s));
}
MachineRegistry::~MachineRegistry() = default;

bool MachineRegistry::add_source(std::unique_ptr<Source> src, Diagnostics& d, std::vector<std::string>* names) {
  try {
    src->table = toml::parse(src->text, src->path);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source();
    d.report_in(Severity::Error, src->path, SourceLoc{at.begin.line, at.begin.column},
                "invalid TOML: " + std::string(e.description()), line_of(src->text, at.begin.line));
    return false;
  }
  bool ok = true;
  for (auto&& [key, n] : src->table) {
    if (!n.is_table()) {
      Ctx c{d, &sources_};
      sources_.push_back(std::move(src));
      c.error(key.source(), "'" + std::string(key.str()) + "' is not a machine table ([name] with its keys)");
      return false;
    }
  }
  const Source* s = src.get();
  sources_.push_back(std::move(src));
  for (auto&& [key, n] : s->table) {
    // A machine of the same name is replaced whole, none of its keys kept: a shop's [fanuc-mill]
    // with max_rpm = 8000 lost the built-in's M29 rigid tap. Said, with the way to keep them.
    if (auto before = machines_.find(std::string(key.str())); before != machines_.end()) {
      const std::string was = before->second.source->path == kBuiltinName ? std::string("the built-in one")
                                                                               : "the one in " + before->second.source->path;
      d.report_in(Severity::Note, s->path, SourceLoc{key.source().begin.line, key.source().begin.column},
                  "machine '" + std::string(key.str()) + "' replaces " + was +
                      " whole, keeping none of its keys; to change only some, give it a name of its own with inherits = \"" +
                      std::string(key.str()) + "\"",
                  line_of(s->text, key.source().begin.line));
    }
    machines_[std::string(key.str())] = Entry{s, n.as_table()};
    if (names) names->push_back(std::string(key.str()));
  }
  return ok;
}

bool MachineRegistry::load_builtin_and(const std::vector<std::string>& files, Diagnostics& d) {
  bool ok = load_builtin(d);
  for (const std::string& f : files) ok = load_file(f, d) && ok;
  return ok;
}

bool MachineRegistry::load_builtin(Diagnostics& d) {
  auto s = std::make_unique<Source>();
  s->path = kBuiltinName;
  s->text = std::string(builtin_machines_toml());
  return refusing_past_error_limit(false, [&] { return add_source(std::move(s), d, nullptr); });
}

bool MachineRegistry::load_text(const std::string& name, std::string text, Diagnostics& d) {
  auto s = std::make_unique<Source>();
  s->path = name;
  s->text = std::move(text);
  return refusing_past_error_limit(false, [&] { return add_source(std::move(s), d, nullptr); });
}

bool MachineRegistry::load_file(const std::string& path, Diagnostics& d) {
  return refusing_past_error_limit(false, [&] {
    auto s = read_source(path, d);
    return s && add_source(std::move(s), d, nullptr);
  });
}

std::optional<Machine> MachineRegistry::resolve(const std::string& name_or_path, Diagnostics& d, const Job& job) {
  return refusing_past_error_limit(std::optional<Machine>{}, [&] { return resolve_unguarded(name_or_path, d, job); });
}

namespace {

bool is_key_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
}

std::string toml_string(std::string_view v) {
  std::string out = "\"";
  for (char c : v) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// One --set KEY=VALUE as a TOML line: VALUE as TOML when it is a TOML value (1, true,
// "text", [..]), else as a string (--set program.smoothing=finish). "" and a message when
// the option is malformed.
std::string set_line(const std::string& set, std::string& error) {
  const size_t eq = set.find('=');
  std::string key = eq == std::string::npos ? set : set.substr(0, eq);
  while (!key.empty() && key.back() == ' ') key.pop_back();
  if (eq == std::string::npos || key.empty() || key.front() == '.' || key.back() == '.' ||
      !std::all_of(key.begin(), key.end(), is_key_char) || key.find("..") != std::string::npos) {
    error = "--set " + set + ": expected KEY=VALUE, KEY a machine key such as program.optional_stop or units";
    return {};
  }
  std::string value = set.substr(eq + 1);
  while (!value.empty() && value.front() == ' ') value.erase(value.begin());
  const std::string as_toml = key + " = " + value;
  try {
    (void)toml::parse(as_toml);
    return as_toml;
  } catch (const toml::parse_error&) {
    return key + " = " + toml_string(value);
  }
}

}  // namespace

bool MachineRegistry::job_layers(const Job& job, std::vector<const toml::table*>& layers, Diagnostics& d) {
  Ctx c{d, &sources_};
  auto parse = [&](std::unique_ptr<Source> s) -> const Source* {
    try {
      s->table = toml::parse(s->text, s->path);
    } catch (const toml::parse_error& e) {
      const auto& at = e.source();
      d.report_in(Severity::Error, s->path, SourceLoc{at.begin.line, at.begin.column},
                  "invalid TOML: " + std::string(e.description()), line_of(s->text, at.begin.line));
      return nullptr;
    }
    sources_.push_back(std::move(s));
    return sources_.back().get();
  };
  // A job changes how a machine's programs are written, never which machine it is.
  auto machine_keys_only = [&](const toml::table& t) {
    for (const char* k : {"inherits", "family"})
      if (const toml::node* n = t.get(k)) {
        c.error(n->source(), std::string(k) + ": a job cannot change the machine's " +
                                 (std::string(k) == "family" ? "family" : "parent") + "; name another machine with -t");
        return false;
      }
    return true;
  };
  for (const std::string& path : job.files) {
    auto src = read_source(path, d);
    if (!src) return false;
    const Source* s = parse(std::move(src));
    if (!s) return false;
    const toml::node* jt = s->table.get("job");
    for (auto&& [key, n] : s->table)
      if (key.str() != "job" || !n.is_table()) {
        c.error(key.source(), "'" + std::string(key.str()) + "': a job file holds one [job] table of machine keys (docs/machines.md, \"Per-job options\")");
        return false;
      }
    if (!jt) {
      d.report_in(Severity::Error, path, SourceLoc{1, 1}, "no [job] table: a job file holds one [job] table of machine keys");
      return false;
    }
    if (!machine_keys_only(*jt->as_table())) return false;
    layers.push_back(jt->as_table());
  }
  if (!job.sets.empty()) {
    // Each --set is one line of a TOML text named "--set", so an error points at the option;
    // a later --set of the same key replaces an earlier one.
    std::vector<std::pair<std::string, std::string>> lines;  // key, line
    for (const std::string& set : job.sets) {
      std::string error;
      std::string line = set_line(set, error);
      if (line.empty()) {
        d.report_in(Severity::Error, "clpc", {}, error);
        return false;
      }
      std::string key = line.substr(0, line.find(" = "));
      std::erase_if(lines, [&](const auto& l) { return l.first == key; });
      lines.emplace_back(key, line);
    }
    auto s = std::make_unique<Source>();
    s->path = "--set";
    for (const auto& [key, line] : lines) s->text += line + "\n";
    const Source* src = parse(std::move(s));
    if (!src || !machine_keys_only(src->table)) return false;
    layers.push_back(&src->table);
  }
  return true;
}

bool MachineRegistry::flatten(const std::string& name, std::vector<const toml::table*>& layers, std::vector<std::string>& chain,
                              Diagnostics& d) {
  auto it = machines_.find(name);
  if (it == machines_.end()) return false;
  Ctx c{d, &sources_};
  const toml::table& t = *it->second.table;
  chain.push_back(name);
  if (const toml::node* inh = t.get("inherits")) {
    if (!inh->is_string()) {
      c.error(inh->source(), name + ".inherits: expected the name of another machine, found " + type_name(*inh));
      return false;
    }
    std::string parent = **inh->as_string();
    if (std::find(chain.begin(), chain.end(), parent) != chain.end()) {
      std::string cycle;
      for (const auto& n : chain) cycle += n + " -> ";
      c.error(inh->source(), name + ".inherits: inheritance cycle: " + cycle + parent +
                                 (parent == name ? " (a machine that replaces '" + name +
                                                       "' cannot inherit from it: give yours a name of its own)"
                                                 : std::string()));
      return false;
    }
    if (!machines_.count(parent)) {
      std::vector<std::string> names;
      for (const auto& [n, e] : machines_) names.push_back(n);
      const std::string near = closest(parent, names);
      c.error(inh->source(), name + ".inherits: no machine named '" + parent + "'" +
                                 (near.empty() ? std::string() : "; did you mean '" + near + "'?"));
      return false;
    }
    if (!flatten(parent, layers, chain, d)) return false;
  } else if (const toml::node* fam = t.get("family"); fam && fam->is_string() && !is_abstract(t)) {
    // No parent named: the abstract base of its family (machines.toml): the registry's own
    // (loaded, or a user's replacement), else the built-in one, which is always there.
    const std::string base = **fam->as_string();
    if (auto b = machines_.find(base); b != machines_.end() && is_abstract(*b->second.table)) {
      if (!flatten(base, layers, chain, d)) return false;
    } else if (auto k = bases_.find(base); k != bases_.end()) {
      layers.push_back(k->second.table);
    }
  }
  layers.push_back(&t);
  return true;
}

std::optional<Machine> MachineRegistry::resolve_unguarded(const std::string& name_or_path, Diagnostics& d, const Job& job) {
  std::string name = name_or_path;
  bool is_path = name.find('/') != std::string::npos || (name.size() > 5 && name.substr(name.size() - 5) == ".toml");
  if (is_path) {
    std::vector<std::string> names;
    auto s = read_source(name, d);
    if (!s || !add_source(std::move(s), d, &names)) return std::nullopt;
    if (names.size() != 1) {
      d.report_in(Severity::Error, name, {}, "-t with a file needs exactly one machine in it; it has " + std::to_string(names.size()));
      return std::nullopt;
    }
    name = names[0];
  }
  auto it = machines_.find(name);
  if (it == machines_.end()) {
    std::string all;
    std::vector<std::string> names;
    for (const auto& [n, e] : machines_)
      if (!is_abstract(*e.table)) {
        all += (all.empty() ? "" : ", ") + n;
        names.push_back(n);
      }
    const std::string near = closest(name, names);
    d.report_in(Severity::Error, "clpc", {},
                "no machine named '" + name + "'" + (near.empty() ? std::string() : "; did you mean '" + near + "'?") +
                    " (known: " + all + "; see 'clpc machines')");
    return std::nullopt;
  }
  if (is_abstract(*it->second.table)) {
    d.report_in(Severity::Error, "clpc", {},
                "machine '" + name + "' is an abstract base (the defaults of its family): post for a machine that inherits " +
                    "from it, or write one with inherits = \"" + name + "\" (docs/machines.md)");
    return std::nullopt;
  }
  std::vector<const toml::table*> layers;
  std::vector<std::string> chain;
  if (!flatten(name, layers, chain, d)) return std::nullopt;
  const size_t machine_layers = layers.size();
  if (!job_layers(job, layers, d)) return std::nullopt;
  // A job that states the program number means that number, whatever the file is called.
  bool number_given = false, from_name_given = false;
  for (size_t i = machine_layers; i < layers.size(); ++i) {
    number_given = number_given || layers[i]->at_path("program.number");
    from_name_given = from_name_given || layers[i]->at_path("program.number_from_name");
  }
  Ctx c{d, &sources_};
  Machine m = build_machine(c, name, std::move(layers), passes_, it->second.source->path);
  if (!c.ok) return std::nullopt;
  if (number_given && !from_name_given) m.number_from_name = false;
  return m;
}

std::vector<std::pair<std::string, std::string>> MachineRegistry::list() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [n, e] : machines_) {
    if (is_abstract(*e.table)) continue;
    std::string desc;
    if (const toml::node* dn = e.table->get("description"); dn && dn->is_string()) desc = **dn->as_string();
    out.emplace_back(n, desc);
  }
  return out;
}

}  // namespace clpc
