// Arcs as emitted, read back with the G-code interpreter (not the IR): for every arc of every
// corpus milling file and every mill machine, the start and end radii agree within one output
// unit and the emitted arc's midpoint lies within the machine's tolerance (or one unit,
// whichever is larger) of the CL arc.
#include <cmath>

#include "machine/format.h"
#include "readback/gcode_interp.h"
#include "corpus_cases.h"
#include "helpers.h"
#include "ir/arc_geometry.h"

using namespace clpc;
using namespace clpc::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

using arcgeo::distance_to_arc;

ir::Vec3 emitted_midpoint(const gcode::Segment& s) {
  int u = s.normal.z() != 0 ? 0 : s.normal.y() != 0 ? 2 : 1;
  int v = s.normal.z() != 0 ? 1 : s.normal.y() != 0 ? 0 : 2;
  int w = 3 - u - v;
  double a0 = std::atan2(s.start[v] - s.center[v], s.start[u] - s.center[u]);
  double half = s.sweep / 2 * kPi / 180 * (s.ccw ? 1 : -1);
  ir::Vec3 m;
  m[u] = s.center[u] + s.start_radius * std::cos(a0 + half);
  m[v] = s.center[v] + s.start_radius * std::sin(a0 + half);
  m[w] = (s.start[w] + s.end[w]) / 2;
  return m;
}

struct ArcStats {
  int cl_arcs = 0, emitted = 0;
  double worst_radius = 0, worst_mid = 0;
};

void check_file(const std::string& file, const Machine& m, ArcStats& st) {
  SCOPED_TRACE(file + " on " + m.name);
  CompileOptions opt;
  // helical.ncl.1's numbers are millimetres (see test_corpus.cpp): the Haas cannot hold them
  // as the inches the file claims.
  bool mm = m.name == "haas-umc750" && file.find("helical.ncl.1") != std::string::npos;
  if (mm) opt.input_units = ir::Units::Mm;
  Compiled c = compile_path(file, m, opt);
  ASSERT_TRUE(c.ok) << c.diags;
  gcode::Result g = gcode::interpret(c.output, m);
  for (const auto& p : g.problems) ADD_FAILURE() << "line " << p.line << ": " << p.message;

  Lowered l = lower_text(read_file(file), {"arc-direction"}, &m, mm ? std::optional<ir::Units>(ir::Units::Mm) : std::nullopt);
  std::vector<ir::Arc> arcs;
  for (const auto& op : l.ops)
    for (const auto& in : op.body)
      if (auto* a = std::get_if<ir::Arc>(&in.op)) arcs.push_back(*a);
  const double k = ir::mm_per_unit(l.info.units) / ir::mm_per_unit(m.units);
  for (auto& a : arcs) {
    a.start *= k;
    a.end *= k;
    a.center *= k;
    a.radius *= k;
  }
  st.cl_arcs += int(arcs.size());
  const double unit = std::abs(dequantize(1, m.format('X')));
  const double tol = std::max(m.arcs.tolerance, unit) + 1e-9;
  size_t next = 0;
  for (const gcode::Segment& s : g.segments) {
    if (s.kind != gcode::Segment::Kind::Arc) continue;
    ++st.emitted;
    double dr = std::abs(s.start_radius - s.end_radius);
    st.worst_radius = std::max(st.worst_radius, dr);
    EXPECT_LE(dr, unit * (1 + 1e-6)) << "G-code line " << s.line;
    // The CL arc this piece belongs to: the next one (in order) holding its ends; of those, the
    // first whose path its midpoint is on (consecutive arcs may share a circle and its ends).
    ir::Vec3 mid = emitted_midpoint(s);
    bool found = false;
    double nearest = 1e300;
    for (size_t i = next; i < arcs.size() && !found; ++i) {
      if (distance_to_arc(arcs[i], s.start) > tol || distance_to_arc(arcs[i], s.end) > tol) continue;
      double d = distance_to_arc(arcs[i], mid);
      nearest = std::min(nearest, d);
      if (d <= tol) {
        st.worst_mid = std::max(st.worst_mid, d);
        next = i;
        found = true;
      }
    }
    if (!found && nearest < 1e300) st.worst_mid = std::max(st.worst_mid, nearest);
    EXPECT_TRUE(found) << "G-code line " << s.line << ": arc matches no CL arc (nearest midpoint " << nearest << ")";
  }
}

}  // namespace

// The three-axis milling files of the corpus (tests/corpus_cases.h), on both mills.
TEST(ArcOutput, CorpusArcsReadBackWithinTolerance) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR;
  for (const char* name : {"haas-umc750", "fanuc-mill"}) {
    Machine m = machine(name);
    m.max_rpm = 0;  // the Creo files spin small cutters at 15,915 rpm; this test is about arcs
    ArcStats st;
    for (const CorpusCase& c : corpus_cases()) {
      if (std::string(c.machine) != "fanuc-mill" || *c.error) continue;
      const std::string f = corpus_dir() + "/" + c.file;
      if (f.find("bohren") != std::string::npos) continue;  // canned cycles: see the drilling tests
      check_file(f, m, st);
    }
    std::printf("%s: %d CL arcs, %d arcs emitted; worst radius mismatch %.3g, worst midpoint %.3g (%s units)\n",
                name, st.cl_arcs, st.emitted, st.worst_radius, st.worst_mid, m.units == ir::Units::Inch ? "inch" : "mm");
    EXPECT_GT(st.emitted, 1000);
  }
}
