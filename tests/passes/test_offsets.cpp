// The work-offset table (offset-table pass, G10 / G65 writing): the seed's macro against
// clpc's own G10 offsets, a three-frame part in all three strategies (golden files, registers,
// read back to the CL path), per-frame offsets of the corpus 3+2 files, and the errors.
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <regex>

#include "readback/gcode_interp.h"
#include "machine/kinematics.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ir::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;


// The example A/C trunnion and its g10 / none variants.
std::string ac_toml() { return read_file(source_path("examples/ac_trunnion.toml")) + "\n" + read_file(source_path("tests/offsets/machines.toml")); }

// The words of a block as letter -> value ("G90 G10 L2 P1 X0. Y28.284" -> L 2, P 1, X 0, Y 28.284;
// G codes are not kept).
std::map<char, double> words(const std::string& block) {
  std::map<char, double> w;
  static const std::regex word("([A-Z])(-?[0-9.]+)");
  for (std::sregex_iterator it(block.begin(), block.end(), word), end; it != end; ++it) {
    char l = (*it)[1].str()[0];
    if (l != 'G' && l != 'N') w[l] = std::stod((*it)[2].str());
  }
  return w;
}

std::vector<std::string> lines_with(const std::string& text, const std::string& what) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (l.find(what) != std::string::npos && l[0] != '(') out.push_back(l);  // blocks, not comments
  return out;
}

// The seed paper's macro O2013, as plain arithmetic on its G65 arguments (CL_FORMATS.md).
Vec3 seed_macro(const std::map<char, double>& g65, double n503) {
  const double n1 = g65.at('A') * kPi / 180, n3 = g65.at('C') * kPi / 180;
  const double n24 = g65.at('X'), n25 = g65.at('Y'), n26 = g65.at('Z');
  const double n16 = n26 + n503;
  return {n24 * std::cos(-n3) - n25 * std::sin(-n3),
          n24 * std::cos(-n1) * std::sin(-n3) + n25 * std::cos(-n1) * std::cos(-n3) - n16 * std::sin(-n1),
          n24 * std::sin(-n1) * std::sin(-n3) + n25 * std::sin(-n1) * std::cos(-n3) + n16 * std::cos(-n1)};
}

ir::Mat3 rz(double deg) {
  double c = std::cos(deg * kPi / 180), s = std::sin(deg * kPi / 180);
  ir::Mat3 m;
  m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}
ir::Mat3 rx(double deg) {
  double c = std::cos(deg * kPi / 180), s = std::sin(deg * kPi / 180);
  ir::Mat3 m;
  m << 1, 0, 0, 0, c, -s, 0, s, c;
  return m;
}

std::string camera(const ir::Mat3& r, const Vec3& o) {
  char b[512];
  std::snprintf(b, sizeof b, "CAMERA/%.12f,%.12f,%.12f,%.9f,%.12f,%.12f,%.12f,%.9f, $\n%.12f,%.12f,%.12f,%.9f\n", r(0, 0), r(0, 1),
                r(0, 2), o.x(), r(1, 0), r(1, 1), r(1, 2), o.y(), r(2, 0), r(2, 1), r(2, 2), o.z());
  return b;
}

// The CL GOTO points of a file, outside canned cycles (whose GOTOs are hole tops, not points
// the tool is driven to).
std::vector<Vec3> cl_points(const std::string& path) {
  std::vector<Vec3> out;
  std::istringstream in(read_file(path));
  bool cycle = false;
  for (std::string l; std::getline(in, l);) {
    if (l.rfind("CYCLE/", 0) == 0) cycle = l != "CYCLE/OFF";
    if (l.rfind("GOTO/", 0) != 0 || cycle) continue;
    double x, y, z;
    if (std::sscanf(l.c_str() + 5, "%lf,%lf,%lf", &x, &y, &z) == 3) out.emplace_back(x, y, z);
  }
  return out;
}

// Where each block of a program drives the tool tip in the part (CL) frame, through the
// offsets the program set (or `given`), the rotary positions and the machine's table axes:
// machine = offset + point, part = T(angles)^-1 machine - reference height along Z.
struct Readback {
  std::vector<Vec3> ends;
  std::map<int, Vec3> offsets;
  int problems = 0;
  std::string first_problem;
};
Readback read_back(const std::string& program, const Machine& m, const std::map<int, Vec3>& given = {}) {
  gcode::Result r = gcode::interpret(program, m);
  Readback b;
  b.problems = int(r.problems.size());
  if (!r.problems.empty()) b.first_problem = std::to_string(r.problems[0].line) + ": " + r.problems[0].message;
  b.offsets = given;
  for (const gcode::Event& e : r.events)
    if (e.kind == gcode::Event::Kind::OffsetSet) b.offsets[e.reg] = e.v;
  const KinematicsSettings& k = m.kinematics;
  const double h = m.offsets.reference_height;
  for (const gcode::Segment& s : r.segments) {
    if (std::isnan(s.end.x()) || std::isnan(s.end.z())) continue;
    kin::Angles a{0, 0};
    for (size_t i = 0; i < k.rotaries.size(); ++i) a[i] = s.rotary[size_t(k.rotaries[i].name[0] - 'A')];
    Vec3 machine = b.offsets.count(s.work_offset) ? Vec3(b.offsets[s.work_offset] + s.end) : Vec3(s.end);
    b.ends.push_back(kin::table_rotation(k, a).transpose() * machine - Vec3(0, 0, h));
  }
  return b;
}

// Every CL point is reached, in order, within `tol`.
void expect_follows(const std::vector<Vec3>& cl, const std::vector<Vec3>& ends, double tol) {
  size_t j = 0;
  for (size_t i = 0; i < cl.size(); ++i) {
    while (j < ends.size() && (ends[j] - cl[i]).norm() > tol) ++j;
    ASSERT_LT(j, ends.size()) << "CL point " << i << " (" << cl[i].transpose() << ") is never reached";
  }
}

// The program without sequence numbers (which shift with the head's length).
std::string without_n(const std::string& text) {
  return std::regex_replace(text, std::regex("(^|\n)N[0-9]+ "), "$1");
}

std::string after(const std::string& text, const std::string& marker) {
  size_t at = text.find(marker);
  return at == std::string::npos ? std::string() : text.substr(at);
}

}  // namespace

// --- the seed's macro against clpc's G10 --------------------------------------------------

// 1000 random frames R = Rz(C) Rx(A) (A in [1, 110] on the side the machine prefers), origins
// and registers: the G10 offsets clpc writes equal what the seed's macro computes from the G65
// arguments clpc writes, to 1e-6 (both written with nine decimals, so rounding stays below it).
TEST(SeedMacro, G10EqualsTheMacroForRandomFrames) {
  const std::string fine = ac_toml() +
                           "\n[fine-macro]\ninherits = \"ac-trunnion\"\n[fine-macro.offsets]\nreference_height = 123.456\n"
                           "[fine-macro.format]\nX = { decimals = 9 }\nY = { decimals = 9 }\nZ = { decimals = 9 }\n"
                           "A = { decimals = 9 }\nB = { decimals = 9 }\nC = { decimals = 9 }\n"
                           "[fine-g10]\ninherits = \"fine-macro\"\n[fine-g10.offsets]\ntable = \"g10\"\n";
  const Machine macro = machine("fine-macro", fine), g10 = machine("fine-g10", fine);
  std::mt19937 rng(2013);
  std::uniform_real_distribution<double> ua(1, 110), uc(-179.9, 179.9), uo(-200, 200);
  int frames = 0;
  double worst = 0;
  while (frames < 1000) {
    std::vector<int> regs = {54, 55, 56, 57, 58, 59};
    std::shuffle(regs.begin(), regs.end(), rng);
    const int n = std::min(6, 1000 - frames) - int(rng() % 2);  // 5 or 6 registers a program
    std::string cl = "UNITS/MM\n";
    for (int i = 0; i < n; ++i) {
      const double a = ua(rng), c = uc(rng);
      const ir::Mat3 r = rz(c) * rx(a);
      const Vec3 o(uo(rng), uo(rng), uo(rng));
      const Vec3 z = r.col(2), p = o + 10 * z;
      char go[160];
      std::snprintf(go, sizeof go, "GOTO/%.6f,%.6f,%.6f,%.9f,%.9f,%.9f\n", p.x(), p.y(), p.z(), z.x(), z.y(), z.z());
      cl += "TOOL PATH/OP" + std::to_string(i) + ",TOOL,EM10\nLOAD/TOOL,1\nSET/" + std::to_string(regs[size_t(i)]) + "\n" +
            camera(r, o) + "SPINDL/RPM,1000,CLW\nRAPID\n" + go + "END-OF-PATH\n";
    }
    Compiled cm = compile_text(cl, macro), cg = compile_text(cl, g10);
    ASSERT_TRUE(cm.ok) << cm.diags;
    ASSERT_TRUE(cg.ok) << cg.diags;
    EXPECT_EQ(cm.diags.find("seed macro"), std::string::npos) << cm.diags;  // the angles are the machine's
    auto calls = lines_with(cm.output, "G65 P2013"), sets = lines_with(cg.output, "G10 L2");
    ASSERT_EQ(calls.size(), size_t(n));
    ASSERT_EQ(sets.size(), size_t(n));
    std::map<int, Vec3> by_register;
    for (const std::string& s : sets) {
      auto w = words(s);
      by_register[int(w['P'])] = {w['X'], w['Y'], w['Z']};
    }
    for (const std::string& c : calls) {
      auto w = words(c);
      ASSERT_TRUE(by_register.count(int(w['B']))) << c;
      Vec3 d = seed_macro(w, 123.456) - by_register[int(w['B'])];
      worst = std::max(worst, d.cwiseAbs().maxCoeff());
      EXPECT_LT(d.cwiseAbs().maxCoeff(), 1e-6) << c;
    }
    frames += n;
  }
  std::printf("1000 frames: worst |G10 - macro| = %.3g mm\n", worst);
}

// The reader evaluates the macro from the G65 call and gets the offsets the G10 program sets.
TEST(SeedMacro, ReaderEvaluatesTheMacro) {
  const std::string t = ac_toml();
  const std::string cls = source_path("tests/offsets/three_frames.cls");
  Compiled cm = compile_path(cls, machine("ac-trunnion", t)), cg = compile_path(cls, machine("ac-trunnion-g10", t));
  ASSERT_TRUE(cm.ok && cg.ok) << cm.diags << cg.diags;
  Readback bm = read_back(cm.output, machine("ac-trunnion", t)), bg = read_back(cg.output, machine("ac-trunnion-g10", t));
  EXPECT_EQ(bm.problems, 0) << bm.first_problem;
  EXPECT_EQ(bg.problems, 0) << bg.first_problem;
  ASSERT_EQ(bm.offsets.size(), 3u);
  ASSERT_EQ(bg.offsets.size(), 3u);
  for (auto& [reg, v] : bg.offsets) EXPECT_LT((bm.offsets[reg] - v).norm(), 2e-3) << "register " << reg;
  // G56 (A90 C180, origin 0 40 -20, #503 = 100): Rx(-90) Rz(-180) (0, 40, 80) = (0, 80, 40).
  EXPECT_LT((bg.offsets[3] - Vec3(0, 80, 40)).norm(), 1e-9);
}

// --- a part in three frames, each used more than once --------------------------------------

TEST(OffsetTable, ThreeFramesGolden) {
  const std::string t = ac_toml();
  bool update = std::getenv("CLPC_UPDATE_GOLDEN") != nullptr;
  for (const char* name : {"ac-trunnion", "ac-trunnion-g10", "ac-trunnion-none"}) {
    SCOPED_TRACE(name);
    Compiled c = compile_path(source_path("tests/offsets/three_frames.cls"), machine(name, t));
    ASSERT_TRUE(c.ok) << c.diags;
    EXPECT_EQ(c.diags, "");
    std::string expected = source_path(std::string("tests/offsets/three_frames.") + name + ".nc");
    if (update) write_file(expected, c.output);
    else EXPECT_EQ(c.output, read_file(expected));
  }
}

TEST(OffsetTable, OneOffsetPerRegisterAndTheRightOneInEachOperation) {
  const std::string t = ac_toml();
  Compiled m = compile_path(source_path("tests/offsets/three_frames.cls"), machine("ac-trunnion", t));
  Compiled g = compile_path(source_path("tests/offsets/three_frames.cls"), machine("ac-trunnion-g10", t));
  Compiled n = compile_path(source_path("tests/offsets/three_frames.cls"), machine("ac-trunnion-none", t));
  ASSERT_TRUE(m.ok && g.ok && n.ok);
  // The head: one call / one G10 per register, in order of first use.
  auto calls = lines_with(m.output, "G65 P2013");
  ASSERT_EQ(calls.size(), 3u);
  EXPECT_THAT(calls[0], HasSubstr("G65 P2013 B1. X0. Y0. Z0. A0. C0."));
  EXPECT_THAT(calls[1], HasSubstr("G65 P2013 B2. X50. Y0. Z-10. A45. C90."));
  EXPECT_THAT(calls[2], HasSubstr("G65 P2013 B3. X0. Y40. Z-20. A90. C180."));
  auto sets = lines_with(g.output, "G10 L2");
  ASSERT_EQ(sets.size(), 3u);
  EXPECT_THAT(sets[1], HasSubstr("G90 G10 L2 P2 X0. Y28.284 Z98.995"));  // Rx(-45) Rz(-90) (50, 0, 90)
  EXPECT_TRUE(lines_with(n.output, "G10").empty());
  EXPECT_TRUE(lines_with(n.output, "G65").empty());
  // The macro program follows M30 only where the machine asks for it.
  EXPECT_THAT(after(m.output, "M30"), HasSubstr("O2013\n"));
  EXPECT_THAT(after(m.output, "O2013"), HasSubstr("G90 G10 L2 P#2 X#104 Y#105 Z#106\nM99\n%"));
  EXPECT_EQ(after(g.output, "O2013"), "");
  // The body: each operation selects its frame's register, at the rotary position of its frame.
  const std::vector<std::tuple<std::string, std::string, std::string>> ops = {
      {"(TOP_ROUGH)", "G54", "A0. C0."},      {"(SIDE_A_ROUGH)", "G55", "A45. C90."}, {"(SIDE_B_DRILL)", "G56", "A90. C180."},
      {"(SIDE_A_FINISH)", "G55", "A45. C90."}, {"(TOP_FINISH)", "G54", "A0. C0."}};
  for (auto& [op, reg, rot] : ops) {
    std::string body = after(m.output, op);
    body = body.substr(0, body.find("\n(", 1));
    EXPECT_THAT(body, HasSubstr(rot)) << op;
    EXPECT_THAT(body, HasSubstr(reg + " X")) << op;
    for (const char* other : {"G54", "G55", "G56"})
      if (other != reg) {
        EXPECT_THAT(body, ::testing::Not(HasSubstr(other))) << op;
      }
  }
  // The strategies differ in the head and the macro only.
  std::string body_m = without_n(after(m.output, "(TOP_ROUGH)")), body_g = without_n(after(g.output, "(TOP_ROUGH)")),
              body_n = without_n(after(n.output, "(TOP_ROUGH)"));
  EXPECT_EQ(body_g, body_n);
  EXPECT_EQ(body_m.substr(0, body_m.find("O2013")), body_g.substr(0, body_g.find("%")));
}

// Read back through the offsets the program sets and the table's rotation, the tool follows
// every CL point of the part, whichever strategy set the offsets.
TEST(OffsetTable, ThreeFramesFollowTheClPath) {
  const std::string t = ac_toml();
  const std::string cls = source_path("tests/offsets/three_frames.cls");
  const auto cl = cl_points(cls);
  ASSERT_GT(cl.size(), 30u);
  std::map<int, Vec3> set_by_g10;
  for (const char* name : {"ac-trunnion-g10", "ac-trunnion", "ac-trunnion-none"}) {
    SCOPED_TRACE(name);
    Machine mc = machine(name, t);
    Compiled c = compile_path(cls, mc);
    ASSERT_TRUE(c.ok) << c.diags;
    // "none": the operator set the registers; take the values clpc computed for g10.
    Readback b = read_back(c.output, mc, std::string(name) == "ac-trunnion-none" ? set_by_g10 : std::map<int, Vec3>{});
    EXPECT_EQ(b.problems, 0) << b.first_problem;
    if (set_by_g10.empty()) set_by_g10 = b.offsets;
    expect_follows(cl, b.ends, 2e-3);
  }
}

// The first operation in the part frame with no SET: its register (G54) is never set by the
// program. On the macro and G10 machines the reader took that register's zero at the table
// centre, not on the reference base (#503) where the part zero is, and refused the program
// with "never reached" at every point of the operation.
TEST(OffsetTable, AnUnsetDefaultRegisterHoldsThePartFrameOnTheReferenceBase) {
  const std::string t = ac_toml();
  std::string text = read_file(source_path("tests/offsets/three_frames.cls"));
  const size_t set = text.find("SET/54\n");
  ASSERT_NE(set, std::string::npos);
  text.erase(set, 7);
  for (const char* name : {"ac-trunnion", "ac-trunnion-g10", "ac-trunnion-none"}) {
    Compiled c = compile_text(text, machine(name, t));
    EXPECT_TRUE(c.ok) << name << c.diags;
    EXPECT_THAT(c.output, HasSubstr("G54 X0. Y0.\n")) << name;
  }
}

// --- corpus 3+2 files with one offset per distinct $$-> CSYS --------------------------------

TEST(OffsetTable, CorpusOneOffsetPerDistinctCsys) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR;
  const std::string pf =
      "[umc-per-frame]\ninherits = \"haas-umc750\"\n[umc-per-frame.offsets]\nper_frame = true\ntable = \"g10\"\n"
      "reference_height = 5.0\n";
  const Machine m = machine("umc-per-frame", pf);
  for (const char* f : {"nist/b45_face.ncl", "nist/b270_alldrill.ncl"}) {
    SCOPED_TRACE(f);
    const std::string path = corpus_dir() + "/" + f;
    // The distinct frames, as the file gives them.
    std::vector<std::string> frames;
    {
      std::istringstream in(read_file(path));
      std::string l, rec;
      while (std::getline(in, l)) {
        if (l.rfind("$$-> CSYS", 0) != 0) continue;
        rec = l;
        while (!rec.empty() && rec.back() == '$' && std::getline(in, l)) rec += l;  // continuation lines
        if (std::find(frames.begin(), frames.end(), rec) == frames.end()) frames.push_back(rec);
      }
    }
    ASSERT_FALSE(frames.empty());
    Compiled c = compile_path(path, m);
    ASSERT_TRUE(c.ok) << c.diags;
    EXPECT_EQ(lines_with(c.output, "G10 L2").size(), frames.size()) << c.output;
    // Read back through the offsets and B C: every CL point of the file (in inches).
    Readback b = read_back(c.output, m);
    EXPECT_EQ(b.problems, 0) << b.first_problem;
    expect_follows(cl_points(path), b.ends, 2e-4);
  }
}

// --- errors ---------------------------------------------------------------------------------

TEST(OffsetTable, RegisterGivenTwoFramesIsAnError) {
  const std::string t = ac_toml();
  std::string cl = "UNITS/MM\nTOOL PATH/A,TOOL,T\nLOAD/TOOL,1\nSET/55\n" + camera(rz(0) * rx(30), Vec3(0, 0, 0)) +
                   "GOTO/0,0,10,0,-0.5,0.8660254038\nEND-OF-PATH\nTOOL PATH/B,TOOL,T\nSET/55\n" +
                   camera(rz(90) * rx(30), Vec3(0, 0, 0)) + "GOTO/0,0,10,0.5,0,0.8660254038\nEND-OF-PATH\n";
  Compiled c = compile_text(cl, machine("ac-trunnion-g10", t));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":11:1: error: SET/55 is given a second frame; its register holds the frame of line 5 already"));
}

TEST(OffsetTable, MacroTakesStandardRegistersOnly) {
  const std::string t = ac_toml();
  std::string cl = "UNITS/MM\nTOOL PATH/A,TOOL,T\nLOAD/TOOL,1\nSET/101\n" + camera(rz(0) * rx(30), Vec3(0, 0, 0)) +
                   "SPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10,0,-0.5,0.8660254038\nEND-OF-PATH\n";
  Compiled c = compile_text(cl, machine("ac-trunnion", t));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("error: work-offset table: the seed's macro sets G54-G59 only"));
  // With G10 the extended register is G10 L20 P1 and selected as G54.1 P1.
  Compiled g = compile_text(cl, machine("ac-trunnion-g10", t));
  ASSERT_TRUE(g.ok) << g.diags;
  EXPECT_THAT(g.output, HasSubstr("G90 G10 L20 P1 X0. Y"));
  EXPECT_THAT(g.output, HasSubstr("G54.1 P1 X0. Y5.\n"));
}

TEST(OffsetTable, RunningOutOfRegistersIsAnError) {
  const std::string t = ac_toml() + "\n[tiny]\ninherits = \"ac-trunnion-g10\"\n[tiny.offsets]\nextended = 0\nper_frame = true\n";
  std::string cl = "UNITS/MM\n";
  for (int i = 0; i < 7; ++i)
    cl += "TOOL PATH/OP" + std::to_string(i) + ",TOOL,T\nLOAD/TOOL,1\n" + camera(rz(10 * i) * rx(30), Vec3(0, 0, 0)) +
          "SPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10," + std::to_string(std::sin(10 * i * kPi / 180) * 0.5) + "," +
          std::to_string(-std::cos(10 * i * kPi / 180) * 0.5) + ",0.8660254038\nEND-OF-PATH\n";
  Compiled c = compile_text(cl, machine("tiny", t));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("error: work-offset table: this frame needs a register beyond machine 'tiny''s 6 (6 frames before it)"));
}

TEST(OffsetTable, TiltedFrameOnAThreeAxisMachineNeedsNoTable) {
  std::string cl = "UNITS/MM\nTOOL PATH/A,TOOL,T\nLOAD/TOOL,1\nSET/55\n" + camera(rx(90), Vec3(0, 0, 0)) +
                   "SPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,-10,0,0,-1,0\nEND-OF-PATH\n";
  Compiled c = compile_text(cl, machine("fanuc-mill", "[m]\ninherits = \"fanuc-mill\"\n[m.offsets]\ntable = \"g10\"\n"));
  Machine m = machine("m", "[m]\ninherits = \"fanuc-mill\"\n[m.offsets]\ntable = \"g10\"\n");
  Compiled e = compile_text(cl, m);
  EXPECT_FALSE(e.ok);
  EXPECT_THAT(e.diags, HasSubstr("has no rotary axes to turn this frame up"));
  // Set on the machine (a second setup), the frame's own coordinates are written.
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("(G55 = SET/55 CAMERA LINE 5 ORIGIN X0 Y0 Z0)"));
  EXPECT_THAT(c.output, HasSubstr("G55 G00 X0. Y0.\n"));
  EXPECT_THAT(c.output, HasSubstr("G43 H01 Z10.\n"));
}

// Five-axis motion in a frame only shifted from the program's: the kinematics pass writes it in
// the program frame, so under the frame's register (holding its origin) every point was off by
// the origin, and certified (the read-back under TCPC did not add it). Refused now.
TEST(OffsetTable, FiveAxisMotionUnderAnotherFramesRegisterIsRefused) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nSET/55\n" + camera(rz(0), Vec3(100, 50, -10)) +
                         "MULTAX/ON\nRAPID\nGOTO/110,50,20,0,0,1\nFEDRAT/MMPM,200\nGOTO/110,50,-12,0.5,0,0.8660254\nFINI\n";
  Compiled c = compile_text(cl, machine("haas-umc750"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr(":9:1: error: this operation's tool axis leaves its frame's Z (five-axis motion), and its "
                                 "work offset (register 2, the frame of line 5) is not the program's frame"));
  // In the program's frame it is posted as before.
  std::string base = cl;
  base.replace(base.find("SET/55"), 7, "");
  base.replace(base.find("CAMERA"), base.find("MULTAX") - base.find("CAMERA"), "");
  Compiled b = compile_text(base, machine("haas-umc750"));
  ASSERT_TRUE(b.ok) << b.diags;
  EXPECT_THAT(b.output, HasSubstr("G00 X4.3307 Y1.9685 B0. C0.\n"));
}

// SET/55 with frame A, then a second CAMERA with no SET: its points are in the part frame,
// which the default register holds. G55 stayed in force on the control, holding A's origin,
// and verify refused the program with a "never reached" at every point. The default register
// is selected again; with a SET of its own the frame gets its register.
TEST(OffsetTable, AFrameWithoutSetAfterASetsFrameSelectsTheDefaultRegisterAgain) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nFEDRAT/200\nSET/55\n" + camera(rz(0), Vec3(100, 50, -10)) +
                           "RAPID\nGOTO/110,50,20\nGOTO/110,60,-2\n";
  const std::string b = camera(rz(0), Vec3(200, 0, 0)) + "RAPID\nGOTO/210,0,20\nGOTO/210,10,-2\nFINI\n";
  Compiled c = compile_text(head + b, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N50 G55 G00 X10. Y0.\n"));
  // Another register: the post's retract in the old one first (helper-70), then the rapid to
  // the next frame, which rises first (rapid-split), then crosses.
  EXPECT_THAT(c.output, HasSubstr("N80 G91 G28 Z0.\nN90 G90 G54 G00 X110. Y60.\nN100 Z20.\nN110 X210. Y0.\n"));
  for (const char* m : {"fanuc-mill", "haas-umc750"}) {
    Compiled v = verify_text(head + b, machine(m));
    EXPECT_TRUE(v.ok) << m << v.diags;
    Compiled set = verify_text(head + "SET/56\n" + b, machine(m));
    EXPECT_TRUE(set.ok) << m << set.diags;
  }
}

// On a machine without rotaries, frames with Z up are one setup: the part is set with the first
// one's axes along the machine's. A second frame turned about Z from it was written in its own
// turned coordinates under a register that holds only its origin (the tool 14 mm off). Refused;
// one turned frame alone is still the part's setup.
TEST(OffsetTable, FramesTurnedAboutZInOneSetupAreRefusedWithoutRotaries) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nFEDRAT/200\n";
  const std::string second = "SET/56\n" + camera(rz(90), Vec3(200, 0, 0)) + "RAPID\nGOTO/210,0,20\nGOTO/210,10,-2\n";
  Compiled one = compile_text(head + second + "FINI\n", machine("fanuc-mill"));
  ASSERT_TRUE(one.ok) << one.diags;
  EXPECT_THAT(one.output, HasSubstr("G56 G00 X0. Y-10.\n"));
  Compiled two = compile_text(head + "SET/55\n" + camera(rz(0), Vec3(100, 50, 0)) + "RAPID\nGOTO/110,50,20\n" + second + "FINI\n",
                              machine("fanuc-mill"));
  EXPECT_FALSE(two.ok);
  EXPECT_THAT(two.diags, HasSubstr(":14:1: error: this operation's frame (line 11) is turned about Z from the frame of line 6, in "
                                   "the same setup: work offset register 3 holds its origin, not its turn"));
  // The same in a later setup (the part turned over: both frames' Z down), where it was missed.
  const std::string under = "SET/55\n" + camera(rx(180) * rz(90), Vec3(100, 0, 0)) + "RAPID\nGOTO/100,0,-20\nSET/56\n" +
                            camera(rx(180), Vec3(100, 0, 0)) + "RAPID\nGOTO/110,0,-20\nFINI\n";
  Compiled turned_over = compile_text(head + under, machine("fanuc-mill"));
  EXPECT_FALSE(turned_over.ok);
  EXPECT_THAT(turned_over.diags, HasSubstr(":14:1: error: this operation's frame (line 11) is turned about Z from the frame of line "
                                           "6, in the same setup"));
}

// SET with no frame record names the register of the frame in force; the table lists every
// register the program uses, for the operator.
TEST(OffsetTable, SetWithoutFrameSelectsItsRegister) {
  Compiled c = compile_text(
      "UNITS/MM\nLOADTL/1\nSET/56\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/1,2,3\nFEDRAT/MMPM,100\nGOTO/5,2,3\nSET/101\nGOTO/6,2,3\nFINI\n",
      machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("(WORK OFFSETS - SET ON THE MACHINE)\n(G56 = SET/56 BASE FRAME LINE 3 ORIGIN X0 Y0 Z0)\n"
                                  "(G54.1 P1 = SET/101 BASE FRAME LINE 9 ORIGIN X0 Y0 Z0)\n"));
  EXPECT_THAT(c.output, HasSubstr("N50 G56 G00 X1. Y2.\n"));
  // Another offset: up in the old one, over the point and down in the new one.
  EXPECT_THAT(c.output, HasSubstr("N80 G91 G28 Z0.\nN90 G90 G54.1 P1 G00 X6. Y2.\nN100 G94 G01 Z3. F100.\n"));
}

// The first rapid in another frame (NX's MSYS of the next operation, 100 across and 50 down)
// was one non-linear G00: Z could reach the bottom before X crossed. The tool stands where the
// last cut left it, and another frame or register moves no axis: split, across and then down.
TEST(OffsetTable, TheFirstRapidInAnotherFrameIsSplitToo) {
  const std::string op = "TOOL PATH/OP,TOOL,EM\nTLDATA/MILL,10,0,50,0,0\nLOAD/TOOL,1,ADJUST,1\n";
  const std::string moves = "SPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,20,0,0,1\nFEDRAT/MMPM,100\nGOTO/0,0,0\nRAPID\nGOTO/0,0,20\nEND-OF-PATH\n";
  const std::string cl = "UNITS/MM\n" + op + "MSYS/0,0,0,1,0,0,0,1,0\n" + moves + op + "MSYS/100,0,-50,1,0,0,0,1,0\n" + moves;
  Compiled one = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(one.ok) << one.diags;
  EXPECT_THAT(one.output, HasSubstr("(OP)\nN90 S3000 M03\nN100 X100.\nN110 Z-30.\nN120 G01 Z-50.\n"));
  Compiled per_frame = compile_text(cl, machine("my-mill", "[my-mill]\ninherits = \"fanuc-mill\"\n[my-mill.offsets]\nper_frame = true\n"),
                                    {.certify = true});
  ASSERT_TRUE(per_frame.ok) << per_frame.diags;
  // Another register: up in the old one first (helper-70), then across and down in the new one.
  EXPECT_THAT(per_frame.output, HasSubstr("N90 G91 G28 Z0.\nN100 S3000 M03\nN110 G90 G55 G00 X0. Y0.\nN120 Z70.\nN130 Z20.\n"
                                          "N140 G94 G01 Z0. F100.\n"));
}

// SET pairs with the frame record next to it, with no motion between. In an APT file with no
// operation records (CAMERA, its cuts, SET/55, CAMERA) the SET after the first frame's cuts
// named the first frame: its part was cut in G55, the second in G54, while the shop's G55
// held the second fixture as the CL means.
TEST(OffsetTable, ASetAfterAFramesCutsIsTheNextFrames) {
  const std::string cl = "UNITS/MM\nLOADTL/1\n" + camera(rz(0), Vec3(0, 0, 0)) +
                         "SPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,0,20\nFEDRAT/MMPM,100\nGOTO/10,0,0\nGOTO/20,0,0\nRAPID\n"
                         "GOTO/20,0,20\nSET/55\n" + camera(rz(0), Vec3(100, 0, 0)) +
                         "RAPID\nGOTO/110,0,20\nGOTO/110,0,0\nGOTO/120,0,0\nRAPID\nGOTO/120,0,20\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("(G55 = SET/55 CAMERA LINE 14 ORIGIN X100 Y0 Z0)\n"));
  EXPECT_THAT(c.output, HasSubstr("N50 G54 G00 X10. Y0.\n"));
  EXPECT_THAT(c.output, HasSubstr("N100 G91 G28 Z0.\nN110 G90 G55 G00 X10. Y0.\nN120 Z20.\nN130 G94 G01 Z0. F100.\n"));
  // Right after its frame record, before the cuts, it is that frame's.
  std::string before = cl;
  before.erase(before.find("SET/55\n"), 7);
  before.insert(before.find("SPINDL"), "SET/55\n");
  Compiled b = compile_text(before, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(b.ok) << b.diags;
  EXPECT_THAT(b.output, HasSubstr("(G55 = SET/55 CAMERA LINE 3 ORIGIN X0 Y0 Z0)\n"));
}

// A cut that runs on from one frame into a 3+2 frame with an entry of the table: the program
// retracts (G53 Z0) and turns the table between the two points, and the CL's cut (10,0,0) to
// (50,0,-20) was replaced by a feed down from the retract height, certified. Refused; as
// simultaneous five-axis (no register for the frame) it is the CL's move.
TEST(OffsetTable, ACutIntoAThreePlusTwoFrameIsRefused) {
  const std::string cl =
      "UNITS/MM\nTOOL PATH/OP1,TOOL,EM\nTLDATA/MILL,10,0,50,0,0\nLOAD/TOOL,1,ADJUST,1\nMSYS/0,0,0,1,0,0,0,1,0\n"
      "SPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,20,0,0,1\nFEDRAT/MMPM,100\nGOTO/0,0,0\nGOTO/10,0,0\n"
      "MSYS/50,0,-20,0,1,0,0,0,1\nGOTO/0,0,0,0,0,1\nGOTO/10,0,0\nRAPID\nGOTO/10,0,20\nEND-OF-PATH\n";
  Compiled per_frame = compile_text(cl, machine("my-umc", "[my-umc]\ninherits = \"haas-umc750\"\n[my-umc.offsets]\nper_frame = true\n"));
  EXPECT_FALSE(per_frame.ok);
  EXPECT_THAT(per_frame.diags, HasSubstr("part.cls:13:1: error: this cut runs on from the last point of the frame before into "
                                         "the frame of line 12, a 3+2 position of its own (work offset 2): the program retracts "
                                         "and turns the rotaries between the two points"));
  Compiled simultaneous = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(simultaneous.ok) << simultaneous.diags;
  EXPECT_THAT(simultaneous.output, HasSubstr("X1.9685 Z-0.7874 B90."));
}

// The travel check in a SET register's frame: the offset table puts the points in the frame,
// and the limits pass took them as from the program zero (a fixture 400 mm across on 300 mm of
// travel passed, certified). With work_zero, the frame's points are placed from it; without,
// the span counts the frames' origins.
TEST(OffsetTable, TravelIsCheckedInEachRegistersFrame) {
  const std::string toml = "[lim]\ninherits = \"fanuc-mill\"\npipeline = [\"arc-direction\", \"helix\", \"arc-legalise\", "
                           "\"drill-cycles\", \"rapid-split\", \"offset-table\", \"limits\"]\n[lim.kinematics]\ntravel = { x = [0.0, 300.0], y = [0.0, 200.0], "
                           "z = [-300.0, 0.0] }\n";
  auto fixtures = [](double apart) {
    const std::string x = std::to_string(int(apart) + 10);
    return "UNITS/MM\nLOADTL/1\nSET/54\n" + camera(rz(0), Vec3(0, 0, 0)) +
           "SPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,0,20\nFEDRAT/MMPM,100\nGOTO/10,0,0\nRAPID\nGOTO/10,0,20\nSET/55\n" +
           camera(rz(0), Vec3(apart, 0, 0)) + "RAPID\nGOTO/" + x + ",0,20\nGOTO/" + x + ",0,0\nRAPID\nGOTO/" + x + ",0,20\nFINI\n";
  };
  Compiled at = compile_text(fixtures(400), machine("lim", toml + "work_zero = [100.0, 100.0, -200.0]\n"));
  EXPECT_FALSE(at.ok);
  EXPECT_THAT(at.diags, HasSubstr("part.cls:17:1: error: X reaches 510 mm in machine coordinates, beyond the travel (0 to 300)"));
  Compiled span = compile_text(fixtures(400), machine("lim", toml));
  EXPECT_FALSE(span.ok);
  EXPECT_THAT(span.diags, HasSubstr("part.cls:17:1: error: the program's X positions now span 400 mm, more than the machine's "
                                    "300 mm of travel"));
  // 200 mm apart, from X50: 60 to 260, it fits.
  Compiled fits = compile_text(fixtures(200), machine("lim", toml + "work_zero = [50.0, 100.0, -200.0]\n"), {.certify = true});
  EXPECT_TRUE(fits.ok) << fits.diags;
}

// Motion in the part frame (the default register) and a SET/54 frame elsewhere: one register
// for two origins. verify refused every point of the first with "never reached" and no word
// on why; refused at the first such motion, naming the SET.
TEST(OffsetTable, ASetThatTakesTheDefaultRegisterFromThePartFrameIsRefused) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,0,20\nFEDRAT/MMPM,100\nGOTO/10,0,0\nRAPID\n"
                         "GOTO/10,0,20\nSET/54\n" + camera(rz(0), Vec3(100, 0, 0)) + "RAPID\nGOTO/110,0,20\nGOTO/110,0,0\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("part.cls:5:1: error: this motion is in the part frame, whose register is the default one, "
                                 "but SET/54 (line 11) gives that register to another frame"));
  std::string other = cl;
  other.replace(other.find("SET/54"), 6, "SET/55");
  Compiled ok = compile_text(other, machine("fanuc-mill"), {.certify = true});
  EXPECT_TRUE(ok.ok) << ok.diags;
}

// Another work offset (the next fixture) between holes of a cycle: the holes after it were
// written as the cycle's modal X Y, in the old offset, so fixture 1's holes were drilled twice
// and fixture 2 got none (helper-70: certified, both origins alike in the CL). And a rapid to
// the next fixture crossed in one dog-leg at the old Z. Now: the cycle ends, the tool goes up
// in the old offset, then over the point and down to the cycle's start in the new one.
TEST(OffsetTable, AnotherFixtureIsReachedFromTheRetractAndItsHolesInItsOffset) {
  const std::string cl = "UNITS/MM\nSET/54\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,50\n"
                         "CYCLE/DRILL,DEPTH,10,MMPM,100,CLEAR,3\nGOTO/0,0,0\nGOTO/10,0,0\nSET/55\nGOTO/0,0,0\nGOTO/10,0,0\n"
                         "CYCLE/OFF\nRAPID\nGOTO/10,0,50\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N70 G94 G98 G81 X0. Y0. Z-10. R3. F100.\nN80 X10.\nN90 G80\nN100 G91 G28 Z0.\n"
                                  "N110 G90 G55 G00 X0. Y0.\nN120 Z50.\nN130 G94 G98 G81 X0. Y0. Z-10. R3. F100.\nN140 X10.\n"
                                  "N150 G80\nN160 M05\n"));
  Compiled h = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(h.ok) << h.diags;
  EXPECT_THAT(h.output, HasSubstr("N60 G80\nN65 G53 G00 Z0.\nN70 G55 G00 X0. Y0.\nN75 Z1.9685\n"
                                  "N80 G94 G98 G81 X0. Y0. Z-0.3937 R0.1181 F3.94\n"));
  const std::string moves = "UNITS/MM\nSET/54\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,50\nFEDRAT/MMPM,300\n"
                            "GOTO/0,0,-2\nGOTO/50,0,-2\nRAPID\nGOTO/50,0,50\nSET/55\nRAPID\nGOTO/10,10,50\nFEDRAT/MMPM,300\n"
                            "GOTO/10,10,-2\nFINI\n";
  Compiled m = compile_text(moves, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(m.ok) << m.diags;
  EXPECT_THAT(m.output, HasSubstr("N90 G00 Z50.\nN100 G91 G28 Z0.\nN110 G90 G55 G00 X10. Y10.\nN120 Z50.\n"));
}
