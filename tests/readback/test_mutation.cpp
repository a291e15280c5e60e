// The verifier tested by mutation: compiled programs (mill, five-axis, lathe, offsets, drilling;
// the corpus's too when it is there) changed one edit at a time — an arc flipped, a block
// dropped, a coordinate moved by 10 increments, a rotary turned 0.1 degree, a feed made rapid,
// another work offset register, another length offset, a cycle's depth — and certified
// against their CL. The unchanged program must pass; every mutant that moves the tool off the
// original path beyond the tolerance (judged by reading both programs back and comparing their
// paths, segment by segment), and every mutant that is wrong on any control whatever its
// registers hold (a feed made rapid, another work offset, another length offset), must fail.
// Mutants that leave the path as it was (a dropped block on a straight line) may pass: they
// are counted as equivalent.
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>

#include "driver/certify.h"
#include "driver/driver.h"
#include "helpers.h"
#include "support/text.h"
#include "thread_cl.h"
#include "ir/arc_geometry.h"
#include "machine/format.h"
#include "readback/program_reader.h"

using namespace clpc;
using namespace clpc::test;
using ir::Vec3;

namespace {


enum class Kind { FlipArc, DropBlock, Coordinate, Rotary, FeedToRapid, WorkOffset, LengthOffset, CycleDepth };
constexpr Kind kKinds[] = {Kind::FlipArc,     Kind::DropBlock,  Kind::Coordinate,   Kind::Rotary,
                           Kind::FeedToRapid, Kind::WorkOffset, Kind::LengthOffset, Kind::CycleDepth};
const char* kind_name(Kind k) {
  switch (k) {
    case Kind::FlipArc: return "flip G02/G03";
    case Kind::DropBlock: return "drop a block";
    case Kind::Coordinate: return "coordinate +10 increments";
    case Kind::Rotary: return "rotary +0.1 deg";
    case Kind::FeedToRapid: return "feed block made G00";
    case Kind::WorkOffset: return "another work offset";
    case Kind::LengthOffset: return "another length offset";
    case Kind::CycleDepth: return "cycle depth +10 increments";
  }
  return "";
}
// Wrong on a real control whatever the path as read says: always to be caught. (A feed made
// rapid is judged by the path: a rapid shorter than the tolerance cuts nothing.)
bool always_wrong(Kind k) { return k == Kind::WorkOffset || k == Kind::LengthOffset; }

// --- the words of a block, outside comments ----------------------------------------------

struct WordAt {
  char letter;
  size_t at, len;  // of the number
  double value;
};

std::vector<WordAt> words(const std::string& line) {
  std::vector<WordAt> w;
  int depth = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '(') ++depth;
    else if (c == ')') depth = std::max(0, depth - 1);
    if (depth || c < 'A' || c > 'Z') continue;
    size_t j = i + 1;
    while (j < line.size() && (std::isdigit(static_cast<unsigned char>(line[j])) || line[j] == '.' || line[j] == '-' || line[j] == '+'))
      ++j;
    if (j == i + 1) continue;
    w.push_back({c, i + 1, j - i - 1, std::atof(line.substr(i + 1, j - i - 1).c_str())});
    i = j - 1;
  }
  return w;
}

bool has_g(const std::vector<WordAt>& w, double g) {
  for (const WordAt& x : w)
    if (x.letter == 'G' && std::abs(x.value - g) < 1e-6) return true;
  return false;
}
const WordAt* word(const std::vector<WordAt>& w, char c) {
  for (const WordAt& x : w)
    if (x.letter == c) return &x;
  return nullptr;
}
bool special(const std::vector<WordAt>& w) {  // blocks that set things, not motion
  return has_g(w, 10) || has_g(w, 65) || has_g(w, 28) || has_g(w, 53) || has_g(w, 4) || has_g(w, 50) || word(w, 'O');
}
bool motion(const std::vector<WordAt>& w) {
  if (special(w)) return false;
  for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'W'})
    if (word(w, c)) return true;
  return false;
}
bool cycle(const std::vector<WordAt>& w) {
  for (double g : {73.0, 74.0, 75.0, 81.0, 82.0, 83.0, 84.0, 85.0, 86.0, 87.0, 88.0, 89.0})
    if (has_g(w, g)) return true;
  return false;
}

std::string with_number(const std::string& line, const WordAt& w, const std::string& number) {
  return line.substr(0, w.at) + number + line.substr(w.at + w.len);
}
std::string num(double v, int decimals) { return fixed_text(v, decimals); }

// --- the program read back, as samples along each segment --------------------------------

struct Sampled {
  std::vector<std::array<Vec3, 4>> at;  // end, and 1/4, 1/2, 3/4 along
  std::vector<Vec3> axis;
  std::vector<bool> rapid, arc;
};

Sampled read_back(const std::string& path, const Machine& m, const ir::ProgramInfo& info) {
  Sampled out;
  ProgramReader rd(m, info);
  std::string why;
  EXPECT_TRUE(rd.open(path, why)) << why;
  TipSegment s;
  const double nan = std::nan("");
  while (rd.next(s)) {
    std::array<Vec3, 4> p;
    p[0] = s.end;
    const bool known = std::isfinite(s.start.x()) && std::isfinite(s.end.x());
    for (int k = 1; k < 4; ++k) {
      if (!known) p[k] = Vec3(nan, nan, nan);
      else if (s.raw.kind == gcode::Segment::Kind::Arc) p[k] = arcgeo::point_at(arc_of(s), k / 4.0);
      else p[k] = rd.tip_at(s, k / 4.0);
    }
    out.at.push_back(p);
    out.axis.push_back(s.axis);
    out.rapid.push_back(s.raw.kind == gcode::Segment::Kind::Rapid);
    out.arc.push_back(s.raw.kind == gcode::Segment::Kind::Arc);
  }
  return out;
}

double far(const Vec3& a, const Vec3& b) {
  const bool fa = std::isfinite(a.x()), fb = std::isfinite(b.x());
  if (fa != fb) return INFINITY;
  return fa ? (a - b).norm() : 0;
}

// The CL's rapid points (output units, the program's part frame): a rapid of the program that
// ends at one is on the CL path; the post's own positioning rapids are not.
std::vector<Vec3> cl_rapid_points(const std::string& cl, const Machine& m) {
  Lowered l = lower_text(read_file(cl), {}, &m);
  const double k = ir::mm_per_unit(l.info.units) / ir::mm_per_unit(m.units);
  std::vector<Vec3> out;
  for (const ir::Operation& op : l.ops)
    for (const ir::Instr& in : op.body)
      if (auto* mv = std::get_if<ir::Move>(&in.op); mv && mv->kind == ir::MoveKind::Rapid) out.push_back(mv->point * k);
  return out;
}

struct Oracle {
  std::vector<Vec3> rapid_points;
  double tol;
  bool on_cl(const Vec3& p) const {
    for (const Vec3& q : rapid_points)
      if ((p - q).norm() <= tol) return true;
    return false;
  }
};

bool same_segment(const Sampled& a, size_t i, const Sampled& b, size_t j, const Oracle& o) {
  const double tol = o.tol;
  if (a.rapid[i] != b.rapid[j] && 2 * far(a.at[i][3], a.at[i][1]) > tol) return false;  // a cut made at rapid
  if (a.rapid[i] && b.rapid[j]) {  // the way a rapid goes is the post's business, where it ends may be the CL's
    return !o.on_cl(a.at[i][0]) || far(a.at[i][0], b.at[j][0]) <= tol;
  }
  for (int k = 0; k < 4; ++k)
    if (far(a.at[i][k], b.at[j][k]) > tol) return false;
  return std::acos(std::clamp(a.axis[i].normalized().dot(b.axis[j].normalized()), -1.0, 1.0)) * 180 / M_PI <= 0.01;
}

double point_line(const Vec3& p, const Vec3& a, const Vec3& b) {
  Vec3 ab = b - a;
  double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0;
  return (a + t * ab - p).norm();
}

// Does the mutant take the tool off the original's path by more than the tolerance: a cut
// (or a rapid to a CL point) that is not where it was?
bool moves_the_tool(const Sampled& a, const Sampled& b, const Oracle& o) {
  const double tol = o.tol;
  if (a.at.size() == b.at.size()) {
    for (size_t i = 0; i < a.at.size(); ++i) {
      if (same_segment(a, i, b, i, o)) continue;
      // A rapid to a CL point that ends elsewhere, the tool still at that point within the
      // next few rapids (a canned cycle's positioning): the CL point is reached.
      bool later = false;
      if (a.rapid[i] && b.rapid[i])
        for (size_t j = i + 1; j < b.at.size() && j <= i + 3 && b.rapid[j] && !later; ++j)
          later = far(b.at[j][0], a.at[i][0]) <= tol;
      if (!later) return true;
    }
    return false;
  }
  if (a.at.size() != b.at.size() + 1) return true;
  // A block dropped: the path is the same if the dropped straight move's end lies on the
  // straight move that now replaces both.
  size_t i = 0;
  while (i < b.at.size() && same_segment(a, i, b, i, o)) ++i;
  if (i == b.at.size()) return !a.rapid[i] || o.on_cl(a.at[i][0]);  // the last move dropped
  for (size_t k = i; k < b.at.size(); ++k)
    if (!same_segment(a, k + 1, b, k, o)) return true;
  if (a.rapid[i] && !o.on_cl(a.at[i][0])) return false;  // a positioning rapid dropped
  if (a.arc[i] || a.rapid[i] != b.rapid[i]) return true;
  const Vec3 from = i > 0 ? a.at[i - 1][0] : a.at[i][0];
  if (!std::isfinite(from.x())) return true;
  // A straight move dropped before an arc: the arc now starts where the move did (and matched
  // the original's within the tolerance above); every point of the dropped move is within its
  // length of that start.
  if (a.arc[i + 1] || b.arc[i]) return far(from, a.at[i][0]) > tol;
  return point_line(a.at[i][0], from, b.at[i][0]) > tol;
}

// --- one program and its mutants -----------------------------------------------------------

struct Tally {
  int tried = 0, moved = 0, caught = 0, equivalent = 0, equivalent_caught = 0;
};

struct Subject {
  std::string cl, what;
  Machine m;
  CompileOptions opt;
};

std::vector<Subject> subjects(const std::string& scratch) {
  std::vector<Subject> s;
  const std::string ac = read_file(source_path("examples/ac_trunnion.toml")) + "\n" + read_file(source_path("tests/offsets/machines.toml"));
  s.push_back({source_path("tests/golden/nx_mill.cls"), "mill, arcs, cutter compensation", machine("fanuc-mill"), {}});
  s.push_back({source_path("tests/golden/creo_mill.ncl"), "mill on the five-axis UMC-750", machine("haas-umc750"), {}});
  s.push_back({source_path("tests/golden/creo_lathe.ncl"), "lathe", machine("fanuc-lathe"), {}});
  s.push_back({source_path("tests/offsets/three_frames.cls"), "3+2, offsets by the G65 macro", machine("ac-trunnion", ac), {}});
  s.push_back({source_path("tests/offsets/three_frames.cls"), "3+2, offsets by G10", machine("ac-trunnion-g10", ac), {}});
  // Drilling (G81, G83, G82 with a dwell) and a five-axis sweep, made here.
  const std::string drill = "UNITS/MM\nLOADTL/3\nSPINDL/RPM,2000,CLW\nRAPID\nGOTO/0,0,50\nFEDRAT/MMPM,120\n"
                            "CYCLE/DRILL,DEPTH,12,MMPM,120,CLEAR,2\nGOTO/10,10,0\nGOTO/30,10,0\nGOTO/30,25,-1\nCYCLE/OFF\n"
                            "CYCLE/DEEP,DEPTH,30,STEP,5,MMPM,100,CLEAR,3\nGOTO/50,10,0\nGOTO/70,10,0\nCYCLE/OFF\n"
                            "CYCLE/DRILL,DEPTH,3,MMPM,80,CLEAR,2,DWELL,0.5\nGOTO/50,40,0\nCYCLE/OFF\nRAPID\nGOTO/50,40,50\nFINI\n";
  write_file(scratch + "/drill.cls", drill);
  s.push_back({scratch + "/drill.cls", "drilling cycles", machine("fanuc-mill"), {}});
  std::string five = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,6000,CLW\nMULTAX/ON\nRAPID\nGOTO/0,0,60,0,0,1\nFEDRAT/MMPM,800\n";
  char line[160];
  for (int i = 0; i <= 40; ++i) {
    const double t = i / 40.0, b = 30 * t * M_PI / 180, c = 120 * t * M_PI / 180;
    const Vec3 axis(std::sin(b) * std::cos(c), std::sin(b) * std::sin(c), std::cos(b));
    std::snprintf(line, sizeof line, "GOTO/%.4f,%.4f,%.4f,%.7f,%.7f,%.7f\n", 40 * t, 10 * std::sin(3 * t), 5 - 3 * t, axis.x(),
                  axis.y(), axis.z());
    five += line;
  }
  five += "RAPID\nGOTO/40,0,60,0,0,1\nFINI\n";
  write_file(scratch + "/five.cls", five);
  s.push_back({scratch + "/five.cls", "five-axis sweep", machine("haas-umc750"), {}});
  // A thread, as one G76, as G92 per pass, and as G32 moves.
  write_file(scratch + "/thread.cls", thread_cl(g76_depths()));
  const std::string lathes = "[g92-lathe]\ninherits = \"fanuc-lathe\"\n[g92-lathe.codes]\nthread_multi = \"\"\n"
                             "[g32-lathe]\ninherits = \"fanuc-lathe\"\n[g32-lathe.codes]\nthread_multi = \"\"\nthread_box = \"\"\n";
  s.push_back({scratch + "/thread.cls", "thread, G76", machine("fanuc-lathe"), {}});
  s.push_back({scratch + "/thread.cls", "thread, G92", machine("g92-lathe", lathes), {}});
  s.push_back({scratch + "/thread.cls", "thread, G32", machine("g32-lathe", lathes), {}});
  if (!corpus_dir().empty()) {
    const std::string extra = read_file(source_path("tests/machines/a_rotary_5x.toml"));
    for (auto [file, name, what] : std::vector<std::array<const char*, 3>>{
             {"nist/multi_axis1.ncl.2", "haas-umc750", "five-axis (Creo)"},
             {"nx-course/APT_Variable_Axis.cls", "haas-umc750", "five-axis (NX)"},
             {"catia/peening.aptsource", "haas-umc750", "five-axis (CATIA)"},
             {"catia/karlo_DEMO4.aptsource", "fanuc-mill", "peck drilling (CATIA)"},
             {"nist/casting_drill_tap.ncl.1", "haas-umc750", "3+2 drilling and tapping"},
             {"nist/turn_op10.ncl.4", "fanuc-lathe", "lathe"},
             {"nist/b_turn_groove2.ncl.1", "fanuc-lathe", "lathe grooves"},
             {"stepnode/simple_block.cls", "fanuc-mill", "mill (NX)"}})
      s.push_back({corpus_dir() + "/" + file, std::string(what) + ", corpus", machine(name, extra), {}});
  }
  return s;
}

// Up to `n` lines of `lines` where `fits` holds, spread over the program.
template <class Fits>
std::vector<size_t> sites(const std::vector<std::string>& lines, Fits fits, size_t n = 5) {
  std::vector<size_t> all;
  for (size_t i = 0; i < lines.size(); ++i)
    if (fits(words(lines[i]))) all.push_back(i);
  if (all.size() <= n) return all;
  std::vector<size_t> out;
  for (size_t k = 0; k < n; ++k) out.push_back(all[k * (all.size() - 1) / (n - 1)]);
  return out;
}

// The mutants of one kind: what was changed, and the whole program text.
struct Mutant {
  std::string change, text;
};
std::vector<Mutant> mutants(Kind kind, const std::vector<std::string>& lines, const Machine& m) {
  auto join = [&](const std::vector<std::string>& l) {
    std::string t;
    for (const std::string& x : l) t += x + "\n";
    return t;
  };
  auto increment = [&](char c) { return std::abs(dequantize(1, m.format(c))); };
  const int dec = m.units == ir::Units::Inch ? 5 : 4;
  std::vector<Mutant> out;
  auto each = [&](auto fits, auto change) {
    for (size_t i : sites(lines, fits)) {
      std::vector<std::string> l = lines;
      change(l, i);
      if (l == lines) continue;
      const std::string after = l.size() == lines.size() ? "'" + l[i] + "'" : std::string("nothing");
      out.push_back({"line " + std::to_string(i + 1) + ": '" + lines[i] + "' -> " + after, join(l)});
    }
  };
  switch (kind) {
    case Kind::FlipArc:
      each([](const auto& w) { return has_g(w, 2) || has_g(w, 3); },
           [&](std::vector<std::string>& l, size_t i) {
             for (const WordAt& w : words(l[i]))
               if (w.letter == 'G' && (std::abs(w.value - 2) < 1e-6 || std::abs(w.value - 3) < 1e-6)) {
                 const bool two = std::abs(w.value - 2) < 1e-6;
                 std::string digits = l[i].substr(w.at, w.len);
                 digits.back() = two ? '3' : '2';
                 l[i] = with_number(l[i], w, digits);
                 return;
               }
           });
      break;
    case Kind::DropBlock:
      each([](const auto& w) { return motion(w) && !cycle(w); }, [](std::vector<std::string>& l, size_t i) { l.erase(l.begin() + long(i)); });
      break;
    case Kind::Coordinate: {
      int turn = 0;
      each([](const auto& w) { return motion(w) && !cycle(w) && (word(w, 'X') || word(w, 'Y') || word(w, 'Z')); },
           [&](std::vector<std::string>& l, size_t i) {
             const auto w = words(l[i]);
             for (int k = 0; k < 3; ++k) {
               const char c = "XYZ"[(turn + k) % 3];
               if (const WordAt* x = word(w, c)) {
                 l[i] = with_number(l[i], *x, num(x->value + 10 * increment(c), dec + 1));
                 ++turn;
                 return;
               }
             }
           });
      break;
    }
    case Kind::Rotary:
      each([](const auto& w) { return !special(w) && (word(w, 'A') || word(w, 'B') || word(w, 'C')); },
           [&](std::vector<std::string>& l, size_t i) {
             const auto w = words(l[i]);
             for (char c : {'A', 'B', 'C'})
               if (const WordAt* x = word(w, c)) {
                 l[i] = with_number(l[i], *x, num(x->value + 0.1, 4));
                 return;
               }
           });
      break;
    case Kind::FeedToRapid:
      each([](const auto& w) { return has_g(w, 1) && motion(w); },
           [&](std::vector<std::string>& l, size_t i) {
             for (const WordAt& w : words(l[i]))
               if (w.letter == 'G' && std::abs(w.value - 1) < 1e-6) {
                 std::string digits = l[i].substr(w.at, w.len);
                 digits.back() = '0';
                 l[i] = with_number(l[i], w, digits);
                 return;
               }
           });
      break;
    case Kind::WorkOffset:
      each([](const auto& w) { return has_g(w, 54) || has_g(w, 55) || has_g(w, 56) || has_g(w, 57) || has_g(w, 58) ||
                                      ((has_g(w, 154) || has_g(w, 54.1)) && word(w, 'P')); },
           [&](std::vector<std::string>& l, size_t i) {
             const auto w = words(l[i]);
             if ((has_g(w, 154) || has_g(w, 54.1)) && word(w, 'P')) {
               const WordAt* p = word(w, 'P');
               l[i] = with_number(l[i], *p, std::to_string(int(std::round(p->value)) + 1));
               return;
             }
             for (const WordAt& x : w)
               if (x.letter == 'G' && x.value > 53.5 && x.value < 58.5 && std::abs(x.value - std::round(x.value)) < 1e-6) {
                 l[i] = with_number(l[i], x, std::to_string(int(std::round(x.value)) + 1));
                 return;
               }
           });
      break;
    case Kind::LengthOffset:
      each([&](const auto& w) { return m.is_lathe() ? word(w, 'T') != nullptr && !has_g(w, 4) : word(w, 'H') != nullptr; },
           [&](std::vector<std::string>& l, size_t i) {
             const auto w = words(l[i]);
             const WordAt* x = word(w, m.is_lathe() ? 'T' : 'H');
             const int v = int(std::round(x->value));
             char b[16];
             if (m.is_lathe()) std::snprintf(b, sizeof b, "%04d", v / 100 * 100 + (v % 100 + 1) % 100);
             else std::snprintf(b, sizeof b, "%02d", v + 1);
             l[i] = with_number(l[i], *x, b);
           });
      break;
    case Kind::CycleDepth:
      each([](const auto& w) { return cycle(w) && !has_g(w, 76) && (word(w, 'Z') || word(w, 'X')); },
           [&](std::vector<std::string>& l, size_t i) {
             const auto w = words(l[i]);
             const bool face = has_g(w, 75) && m.is_lathe();  // G75 plunges along X
             const char c = face && word(w, 'X') ? 'X' : word(w, 'Z') ? 'Z' : 'X';
             const WordAt* x = word(w, c);
             l[i] = with_number(l[i], *x, num(x->value + 10 * increment(c), dec + 1));
           });
      break;
  }
  return out;
}

std::vector<std::string> split_lines(const std::string& t) {
  std::vector<std::string> l;
  size_t at = 0;
  while (at < t.size()) {
    size_t nl = t.find('\n', at);
    if (nl == std::string::npos) nl = t.size();
    l.push_back(t.substr(at, nl - at));
    at = nl + 1;
  }
  return l;
}

}  // namespace

TEST(Mutation, EveryMutantThatMovesTheToolIsCaught) {
  TempDir t;
  std::map<Kind, Tally> tally;
  int programs = 0;
  for (const Subject& s : subjects(t.path(""))) {
    SCOPED_TRACE(s.cl + " on " + s.m.name + " (" + s.what + ")");
    const std::string original = t.path("original.nc");
    std::ostringstream err;
    CompileResult c = compile_file(s.cl, original, s.m, s.opt, err);
    ASSERT_TRUE(c.ok) << err.str();
    ++programs;
    SourceFile cl;
    std::string why;
    ASSERT_TRUE(cl.open(s.cl, why)) << why;
    const Oracle oracle{cl_rapid_points(s.cl, s.m), default_tolerance(s.m)};
    auto certify_text = [&](const std::string& path) {
      Diagnostics quiet(nullptr);
      quiet.set_source(&cl);
      return certify(cl, path, s.m, c.info, {}, quiet);
    };
    ASSERT_TRUE(certify_text(original).ok) << "the program as compiled must certify";
    const Sampled before = read_back(original, s.m, c.info);
    const std::vector<std::string> lines = split_lines(read_file(original));
    for (Kind k : kKinds) {
      for (const Mutant& mu : mutants(k, lines, s.m)) {
        const std::string path = t.path("mutant.nc");
        write_file(path, mu.text);
        Tally& n = tally[k];
        ++n.tried;
        const bool moved = always_wrong(k) || moves_the_tool(before, read_back(path, s.m, c.info), oracle);
        const bool caught = !certify_text(path).ok;
        if (moved) {
          ++n.moved;
          n.caught += caught;
          EXPECT_TRUE(caught) << kind_name(k) << ": a mutant that moves the tool passed: " << mu.change;
        } else {
          ++n.equivalent;
          n.equivalent_caught += caught;
        }
      }
    }
  }
  std::printf("mutation: %d programs\n  %-28s %6s %6s %6s %11s\n", programs, "kind", "tried", "moved", "caught",
              "equivalent");
  int tried = 0, moved = 0, caught = 0;
  for (Kind k : kKinds) {
    const Tally& n = tally[k];
    std::printf("  %-28s %6d %6d %6d %6d (%d caught)\n", kind_name(k), n.tried, n.moved, n.caught, n.equivalent,
                n.equivalent_caught);
    tried += n.tried;
    moved += n.moved;
    caught += n.caught;
  }
  std::printf("  %-28s %6d %6d %6d\n", "all", tried, moved, caught);
  // Every kind was tried on something.
  for (Kind k : kKinds) EXPECT_GT(tally[k].tried, 0) << kind_name(k);
  EXPECT_EQ(caught, moved);
}
