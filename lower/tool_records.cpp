#include "lower/tool_records.h"

#include "support/text.h"

#include <cmath>

#include "lower/params.h"

namespace clpc {

namespace {

bool whole(double v, int lo, int hi) { return v == std::floor(v) && v >= lo && v <= hi; }

}  // namespace

// Names are names: a tool named 12 is named "12" (as written), not no name; its operations were
// cut with no tool loaded (helper-61).
std::string tool_name_of_tool_path(const Record& r) {
  for (size_t i = 0; i + 1 < r.params.size(); ++i)
    if (r.params[i].is("TOOL")) {
      const Param& p = r.params[i + 1];
      if (p.is_number()) return p.text.empty() ? num_text(p.number) : std::string(p.text);
      return std::string(p.text);
    }
  return {};
}

ToolRecord read_tool_record(const Record& r, Diagnostics* d) {
  ToolRecord t;
  auto fail = [&](SourceLoc loc, const std::string& msg) {
    if (d) d->error(loc, std::string(r.major) + ": " + msg);
  };
  size_t i = 0;
  if (r.id == MajorId::Load || r.id == MajorId::Select) {
    if (r.params.empty() || !r.params[0].is("TOOL")) {
      fail(r.params.empty() ? r.end : r.params[0].loc, "expected TOOL,n");
      return t;
    }
    i = 1;
    t.preselect = r.id == MajorId::Select;
  }
  if (i >= r.params.size() || !r.params[i].is_number()) {
    fail(i < r.params.size() ? r.params[i].loc : r.end, "expected a tool number");
    return t;
  }
  double n = r.params[i].number;
  if (!whole(n, 0, 99999)) {
    fail(r.params[i].loc, "tool number must be a whole number from 0 to 99999, found " + num_text(n));
    return t;
  }
  t.number = int(n);
  for (size_t k = i + 1; k < r.params.size(); ++k) {
    const Param& p = r.params[k];
    if (p.is("LENGTH")) {
      // APT's LOADTL/n,LENGTH,l: the tool's gauge length, not an offset register.
      if (k + 1 >= r.params.size() || !r.params[k + 1].is_number() || !(r.params[k + 1].number > 0)) {
        fail(k + 1 < r.params.size() ? r.params[k + 1].loc : r.end, "LENGTH needs the tool's length, a number above 0");
        continue;
      }
      t.length = r.params[k + 1].number;
      ++k;
      continue;
    }
    if (p.is("OSETNO") || p.is("ADJUST")) {
      if (k + 1 >= r.params.size() || !r.params[k + 1].is_number() ||
          !whole(r.params[k + 1].number, 0, 9999)) {
        fail(k + 1 < r.params.size() ? r.params[k + 1].loc : r.end,
             std::string(p.text) + " needs an offset register number from 0 to 9999");
        continue;
      }
      t.length_offset = int(r.params[k + 1].number);
      ++k;
    }
    if (p.is_number() && k == i + 1 && d && p.number != 1 && p.number != t.number) {
      // A bare number after the tool's is CATIA's corrector (LOADTL/2,1; docs/cl-input.md), no
      // register. Where it is neither 1 nor the tool's own number (TURRET/5,12) it may be meant
      // as the offset register, and the offset would be another: say which one is used.
      d->warning(p.loc, std::string(r.major) + ": " + num_text(p.number) + " after the tool number is read as the tool's "
                        "corrector, not an offset register: the offset is the tool's number, " + std::to_string(t.number) +
                        " (write OSETNO," + num_text(p.number) + " for register " + num_text(p.number) + ")",
                 "tool-offset");
    }
    // CATIA's SETOOL,x,y,z (the tip from the turret's reference point: the control's offset
    // holds it, as clpc writes tip positions) and Fusion's IN,n say nothing clpc needs. Other
    // words (MANUAL, SIZE, REAR, ...) are said, not dropped silently.
    if (p.is("SETOOL") || p.is("IN")) {
      const size_t numbers = p.is("SETOOL") ? 3 : 1;
      for (size_t j = 0; j < numbers && k + 1 < r.params.size() && r.params[k + 1].is_number(); ++j) ++k;
      continue;
    }
    // LOADTL/2,NEXT: the tool to get ready (a preselection) or the one to load now; loaded now,
    // the cuts the CL gives the tool in the spindle were made with it (certified).
    if (!t.preselect && (p.is("NEXT") || p.is("PRESEL") || p.is("PRESELECT"))) {
      fail(p.loc, std::string(p.text) + ": the tool to get ready or the one to load now? Which is meant is not known; "
                  "have the CAM system write SELECT/TOOL," + std::to_string(t.number) + " for a tool to get ready");
      continue;
    }
    if (p.is_word() && !p.is("OSETNO") && !p.is("ADJUST") && d)
      d->warning(p.loc, std::string(r.major) + ": the word '" + std::string(p.text) + "' is not read (the tool is loaded " +
                            "with its number and offset register only)",
                 "ignored-word");
  }
  return t;
}

ToolGeometry read_tool_geometry(const Record& r, Diagnostics* d) {
  ToolGeometry g;
  g.loc = r.loc;
  size_t i = 0;
  if (r.id == MajorId::Tldata) {
    if (r.params.empty() || !r.params[0].is_word()) {
      if (d) d->error(r.params.empty() ? r.end : r.params[0].loc, "TLDATA: expected the tool kind (MILL, DRILL, TURN, ...)");
      return g;
    }
    g.kind = std::string(r.params[0].text);
    for (char& c : g.kind) c = char(std::toupper(static_cast<unsigned char>(c)));
    i = 1;
  }
  double v[3] = {0, 0, 0};
  int n = 0;
  for (size_t k = i; k < r.params.size() && n < 3; ++k) {
    if (!r.params[k].is_number()) break;
    v[n++] = r.params[k].number;
  }
  if (n == 0) {
    // A record without motion: what it says is not read, and said (CUTTER/DIAMTR,10,RADIUS,2
    // stopped the post with a caret past the line's end; helper-51). A surface speed that needs
    // the diameter says so where it does.
    if (d && r.id == MajorId::Cutter)
      d->warning(r.params.empty() ? r.end : r.params[0].loc,
                 "CUTTER: expected the tool diameter first, found " +
                     (r.params.empty() ? std::string("nothing") : "'" + std::string(r.params[0].name()) + "'") +
                     ": the tool's geometry is not read",
                 "tool-geometry");
    g.any = !g.kind.empty();
    return g;
  }
  bool milling = r.id == MajorId::Cutter || g.kind == "MILL" || g.kind == "DRILL";
  if (milling) {
    if (v[0] < 0 || v[1] < 0 || v[2] < 0) {
      if (d) d->error(r.loc, std::string(r.major) + ": tool dimensions must not be negative");
      return g;
    }
    g.diameter = v[0];
    if (g.kind != "DRILL") g.corner_radius = n > 1 ? v[1] : 0;
    if (r.id == MajorId::Tldata && n > 2) g.length = v[2];
    // A corner radius beyond the tool's radius is no milling cutter (CUTTER/10,30): the numbers
    // are in another order than read, or mistyped. Only the tool list shows them: said. (CATIA's
    // seven-number CUTTER also describes turning tools, where it is no such radius: not judged.)
    const bool plain_mill = (r.id == MajorId::Cutter && r.params.size() == 2) || g.kind == "MILL";
    if (d && plain_mill && g.corner_radius > g.diameter / 2 + 1e-9)
      d->warning(r.params[i + 1].loc, std::string(r.major) + ": a corner radius of " + num_text(g.corner_radius) +
                                          " is more than the tool's radius (" + num_text(g.diameter / 2) +
                                          "): are the numbers in the order " + (r.id == MajorId::Cutter ? "CUTTER/d,r" : "TLDATA/MILL,d,r,...") + "?",
                 "tool-geometry");
  }
  g.any = true;
  return g;
}

std::optional<ir::Units> units_word(std::string_view w) {
  for (const char* m : {"MM", "MILLIMETERS", "MILLIMETRES", "MILLIMETER", "METRIC"})
    if (iequals(w, m)) return ir::Units::Mm;
  for (const char* m : {"INCHES", "INCH", "IN"})
    if (iequals(w, m)) return ir::Units::Inch;
  return std::nullopt;
}

}  // namespace clpc
