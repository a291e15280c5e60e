// An independent reader: LinuxCNC's rs274 interpreter (Debian linuxcnc-uspace, installed by
// scripts/setup.sh --tests) reads the fanuc-mill output of the corpus milling files and the
// golden tests with a tight arc radius tolerance and must report no error; the arc end points
// and hole bottoms it traces must equal the CL's.
//
// rs274 speaks RS274NGC, close to Fanuc. Words filtered out first (docs/verification.md):
//   G54.1 Pn   Fanuc extended work offsets; LinuxCNC has G59.1-G59.3 instead: n <= 3 is mapped.
//   M29 S..    Fanuc's rigid-tapping mode; LinuxCNC's G84 taps rigidly by itself.
//   G65 P..    macro calls (the offset table's macro); LinuxCNC has no G65.
//   G86        LinuxCNC wants a dwell word (P) with G86; Fanuc's G86 has none: P0 is added.
#include <sys/wait.h>

#include <cmath>
#include <regex>

#include "corpus_cases.h"
#include "helpers.h"
#include "ir/arc_geometry.h"

using namespace clpc;
using namespace clpc::test;

namespace {

constexpr const char* kRs274 = "/usr/bin/rs274";

struct Canon {
  std::string name;
  std::vector<double> args;
  int line = 0;
};

struct Traced {
  int status = -1;
  std::vector<Canon> calls;
  std::vector<std::string> errors;
};

std::string filter_for_rs274(const std::string& program) {
  std::istringstream in(program);
  std::ostringstream out;
  std::string line;
  std::regex g541(R"(G54\.1 P(\d+))");
  while (std::getline(in, line)) {
    if (line.find("M29 ") != std::string::npos || line.find("G65 ") != std::string::npos) {
      out << "(filtered: " << std::regex_replace(line, std::regex("[()]"), "") << ")\n";
      continue;
    }
    if (line.find("G86 ") != std::string::npos) line += " P0";
    std::smatch m;
    if (std::regex_search(line, m, g541)) {
      int n = std::stoi(m[1]);
      if (n <= 3) line = std::regex_replace(line, g541, "G59." + std::to_string(n));
    }
    out << line << "\n";
  }
  return out.str();
}

Traced run_rs274(const std::string& program) {
  Traced t;
  TempDir dir;
  write_file(dir.path("prog.ngc"), filter_for_rs274(program));
  std::string tools;
  for (int i = 1; i <= 99; ++i) tools += "T" + std::to_string(i) + " P" + std::to_string(i) + " D0 Z0\n";
  write_file(dir.path("tools.tbl"), tools);
  // A tight arc check: start and end radius may differ by 1.1 output units (0.001 mm).
  write_file(dir.path("rs274.ini"), "[RS274NGC]\nCENTER_ARC_RADIUS_TOLERANCE_MM = 0.0011\nCENTER_ARC_RADIUS_TOLERANCE_INCH = 0.00011\n");
  // rs274 maps its tool table at $HOME/.tool.mmap, truncating it on start: two runs sharing a
  // HOME (ctest -j) truncate each other's mapping and one dies of SIGBUS. Each run gets its own.
  std::string cmd = "HOME=" + dir.path("") + " " + std::string(kRs274) + " -g -t " + dir.path("tools.tbl") + " -i " + dir.path("rs274.ini") + " " +
                    dir.path("prog.ngc") + " </dev/null >" + dir.path("out.txt") + " 2>&1";
  int st = std::system(cmd.c_str());
  t.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  std::istringstream out(read_file(dir.path("out.txt")));
  std::string line;
  std::regex call(R"(^\s*\d+ N[.\d]+\s+([A-Z0-9_]+)\((.*)\)\s*$)");
  while (std::getline(out, line)) {
    std::smatch m;
    if (std::regex_match(line, m, call)) {
      Canon c;
      c.name = m[1];
      std::string args = m[2];
      std::regex num(R"(-?\d+\.?\d*(e-?\d+)?)");
      if (c.name == "STRAIGHT_TRAVERSE" || c.name == "STRAIGHT_FEED" || c.name == "ARC_FEED")
        for (std::sregex_iterator it(args.begin(), args.end(), num), end; it != end; ++it) c.args.push_back(std::stod(it->str()));
      t.calls.push_back(c);
    } else if (line != "executing" && !line.empty()) {
      t.errors.push_back(line);
    }
  }
  return t;
}

// The CL in the machine's output units: arcs after arc-direction, and hole bottoms.
struct Cl {
  std::vector<ir::Arc> arcs;
  std::vector<ir::Vec3> hole_bottoms;
};

Cl cl_of(const std::string& cl_text, const Machine& m) {
  Lowered l = lower_text(cl_text, {"arc-direction", "drill-cycles"}, &m);
  const double k = ir::mm_per_unit(l.info.units) / ir::mm_per_unit(m.units);
  Cl c;
  for (const auto& op : l.ops)
    for (const auto& in : op.body) {
      if (auto* a = std::get_if<ir::Arc>(&in.op)) {
        ir::Arc s = *a;
        s.start *= k;
        s.end *= k;
        s.center *= k;
        s.radius *= k;
        c.arcs.push_back(s);
      } else if (auto* h = std::get_if<ir::Hole>(&in.op)) {
        c.hole_bottoms.push_back((h->point - h->axis * op.cycles[h->spec].depth) * k);
      }
    }
  return c;
}

void check(const std::string& name, const std::string& cl_text, const Machine& m, int& arcs_checked, int& holes_checked) {
  SCOPED_TRACE(name);
  Compiled c = compile_text(cl_text, m);
  ASSERT_TRUE(c.ok) << c.diags;
  Traced t = run_rs274(c.output);
  EXPECT_EQ(t.status, 0);
  for (const auto& e : t.errors) ADD_FAILURE() << "rs274: " << e;
  Cl cl = cl_of(cl_text, m);
  const double unit = 0.001, tol = unit * std::sqrt(3.0) / 2 + 1e-9;

  // Arc end points, in the order rs274 traced them: each CL arc's end is reached by an arc
  // (or, where legalised into a line, a straight move) lying on that CL arc.
  std::vector<ir::Vec3> arc_ends, all_ends;
  for (const Canon& k : t.calls) {
    if (k.name == "ARC_FEED" && k.args.size() >= 6) {
      // XY plane: first_end = X, second_end = Y, axis_end_point = Z (the planes used here).
      arc_ends.emplace_back(k.args[0], k.args[1], k.args[5]);
      all_ends.push_back(arc_ends.back());
    } else if ((k.name == "STRAIGHT_FEED" || k.name == "STRAIGHT_TRAVERSE") && k.args.size() >= 3) {
      all_ends.emplace_back(k.args[0], k.args[1], k.args[2]);
    }
  }
  size_t next = 0;
  for (const ir::Arc& a : cl.arcs) {
    if (std::abs(a.axis.z()) < 0.5) continue;  // the corpus arcs checked here are in XY
    bool found = false;
    for (size_t i = next; i < all_ends.size(); ++i)
      if ((all_ends[i] - a.end).norm() <= tol) {
        next = i;  // consecutive CL arcs may end at the same rounded point
        found = true;
        break;
      }
    EXPECT_TRUE(found) << "CL arc ending at " << a.end.transpose() << ": rs274 never gets there";
    ++arcs_checked;
  }
  for (const ir::Vec3& e : arc_ends) {
    double best = 1e9;
    for (const ir::Arc& a : cl.arcs) best = std::min(best, arcgeo::distance_to_arc(a, e));
    EXPECT_LE(best, tol) << "rs274 arc end " << e.transpose() << " lies on no CL arc";
  }
  // Hole bottoms: a feed of rs274 ends at each.
  for (const ir::Vec3& b : cl.hole_bottoms) {
    bool found = false;
    for (const Canon& k : t.calls)
      if (k.name == "STRAIGHT_FEED" && (ir::Vec3(k.args[0], k.args[1], k.args[2]) - b).norm() <= tol) found = true;
    EXPECT_TRUE(found) << "hole bottom " << b.transpose() << " not reached";
    ++holes_checked;
  }
}

#define REQUIRE_RS274() \
  if (access(kRs274, X_OK) != 0) FAIL() << kRs274 << " missing: run scripts/setup.sh --tests (installs linuxcnc-uspace)"

}  // namespace

// Every corpus file the sweep posts on the Fanuc mill (tests/corpus_cases.h).
TEST(Rs274, CorpusMillingFiles) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR << ": sweep skipped";
  REQUIRE_RS274();
  Machine m = machine("fanuc-mill");
  int arcs = 0, holes = 0, files = 0;
  for (const CorpusCase& c : corpus_cases()) {
    if (std::string(c.machine) != "fanuc-mill" || *c.error) continue;
    const std::string f = corpus_dir() + "/" + c.file;
    check(f, read_file(f), m, arcs, holes);
    ++files;
  }
  std::printf("rs274 read %d corpus fanuc-mill programs: %d CL arcs and %d holes traced\n", files, arcs, holes);
  EXPECT_GE(files, 16);
  EXPECT_GT(arcs, 1000);
}

TEST(Rs274, GoldenFiles) {
  REQUIRE_RS274();
  Machine m = machine("fanuc-mill");
  int arcs = 0, holes = 0, files = 0;
  for (auto& e : std::filesystem::directory_iterator(std::string(CLPC_SOURCE_DIR) + "/tests/golden")) {
    const std::string f = e.path().string();
    if (e.path().extension() != ".cls" && e.path().extension() != ".ncl") continue;
    if (is_lathe_file(f) || is_five_axis_file(f)) continue;
    check(f, read_file(f), m, arcs, holes);
    ++files;
  }
  std::printf("rs274 read %d golden fanuc-mill programs: %d CL arcs and %d holes traced\n", files, arcs, holes);
  EXPECT_GE(files, 2);
}

TEST(Rs274, EveryCycleKind) {
  REQUIRE_RS274();
  Machine m = machine("fanuc-mill");
  int arcs = 0, holes = 0;
  const char* head = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,800,CLW\nFEDRAT/MMPM,120\nRAPID\nGOTO/0,0,25\n";
  for (const char* cyc : {"CYCLE/DRILL,DEPTH,6,CLEAR,2", "CYCLE/CSINK,DEPTH,1,DWELL,0.5,CLEAR,2",
                          "CYCLE/DEEP,DEPTH,14,STEP,4,CLEAR,2", "CYCLE/BRKCHP,DEPTH,14,STEP,3,CLEAR,2",
                          "CYCLE/TAP,DEPTH,10,PITCH,1.25,CLEAR,3", "CYCLE/BORE,DEPTH,8,CLEAR,2",
                          "CYCLE/BORE,DEPTH,8,DWELL,1,CLEAR,2", "CYCLE/BORE,DRAG,DEPTH,8,CLEAR,2"}) {
    std::string cl = std::string(head) + cyc + "\nGOTO/10,10,0\nGOTO/40,10,-3.5\nGOTO/40,35,0\nCYCLE/OFF\nRAPID\nGOTO/0,0,25\n";
    check(cyc, cl, m, arcs, holes);
  }
  EXPECT_EQ(holes, 24);
}
