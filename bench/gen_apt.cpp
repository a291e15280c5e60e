// gen_apt: writes a large CL file as PTC Creo writes it (Pro/CLfile: APT records with spaces
// around the slash, `$` continuations, `$$->` operation marks), deterministic for a seed. The
// second input shape of the benchmarks, written apart from bench/gen_cl so the two do not share
// one file's habits (docs/performance.md):
//
//   gen_apt --size-mb 200 [--kind mixed|pocket|fiveaxis|drill] [--op-mb 8] [--seed 1] > big.ncl
//
// Operations, each a `$$-> FEATNO` with its LOADTL and `$$-> CUTTER`, in turn (kind "mixed"):
//   pocket    3-axis spiral pocketing of a round boss: full turns split into four CIRCLE
//             records (7 values, right-hand rule) each with a GOTO on the circle before its
//             end (Creo's intermediate points), stepping down and over;
//   fiveaxis  swarf-like finishing around a ring: every GOTO continued with `$` onto a second
//             line carrying the tool axis, tilted 10-22 degrees outwards (no singularity);
//   drill     CYCLE / DRILL and CYCLE / DEEP (Creo's keyword form) over a bolt circle.
// The part stays inside 220 x 220 x 60 mm around the part zero, which five-axis machines with a
// rotary table have on its centre: the ring turns the table whole turns and stays in travel.
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

constexpr double kPi = 3.14159265358979323846;

// xorshift64*: a different generator from gen_cl's, small and the same everywhere.
struct Random {
  uint64_t state;
  double between(double lo, double hi) {
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return lo + (hi - lo) * double((state * 0x2545F4914F6CDD1DULL) >> 11) / double(1ULL << 53);
  }
};

class Out {
 public:
  Out() : buf_(size_t(1) << 20, '\0') {}
  ~Out() { flush(); }
  void put(const char* fmt, ...) __attribute__((format(printf, 2, 3))) {
    if (len_ + 1024 > buf_.size()) flush();
    va_list ap;
    va_start(ap, fmt);
    const int n = std::vsnprintf(buf_.data() + len_, 1024, fmt, ap);
    va_end(ap);
    len_ += size_t(n);
    total_ += uint64_t(n);
  }
  uint64_t total() const { return total_; }

 private:
  void flush() {
    std::fwrite(buf_.data(), 1, len_, stdout);
    len_ = 0;
  }
  std::string buf_;
  size_t len_ = 0;
  uint64_t total_ = 0;
};

constexpr double kCx = 0, kCy = 0;  // the part's centre: the part zero, on the rotary table's centre

void feature(Out& o, int featno, int tool, double diameter, int rpm) {
  o.put("$$-> FEATNO / %d\n", featno);
  o.put("LOADTL / %d\n", tool);
  o.put("$$-> CUTTER / %.6f\n", diameter);
  o.put("$$-> CSYS / 1.0000000000, 0.0000000000, 0.0000000000, 0.0000000000,  $\n"
        "            0.0000000000, 1.0000000000, 0.0000000000, 0.0000000000,  $\n"
        "            0.0000000000, 0.0000000000, 1.0000000000, 0.0000000000\n");
  o.put("SPINDL / RPM, %d.000000,  CLW\n", rpm);
  o.put("COOLNT / ON\n");
}

void goto3(Out& o, double x, double y, double z) { o.put("GOTO / %.10f, %.10f, %.10f\n", x, y, z); }

void end_feature(Out& o) {
  o.put("COOLNT / OFF\n");
  o.put("$$-> END /\n");
}

// Round spiral pocketing, counter-clockwise seen from +Z: each turn is four quarter arcs with
// a point on the circle half way along each.
void pocket(Out& o, Random& rnd, int featno, uint64_t budget) {
  feature(o, featno, 1 + featno % 3, 16, 3500 + 250 * (featno % 5));
  const uint64_t stop = o.total() + budget;
  const double depth_step = rnd.between(0.8, 1.6);
  o.put("RAPID\n");
  goto3(o, kCx + 20, kCy, 20);
  o.put("FEDRAT / %.6f,  MMPM\n", rnd.between(600, 1800));
  double z = 0;
  while (o.total() < stop) {
    goto3(o, kCx + 20, kCy, z);
    for (double r = 20; r <= 100 && o.total() < stop; r += rnd.between(4, 7)) {
      goto3(o, kCx + r, kCy, z);
      for (int q = 0; q < 4; ++q) {
        const double a0 = q * kPi / 2, am = a0 + kPi / 4, a1 = a0 + kPi / 2;
        o.put("CIRCLE / %.10f, %.10f, %.10f,  $\n0.0000000000, 0.0000000000, 1.0000000000,  %.10f\n", kCx, kCy, z, r);
        goto3(o, kCx + r * std::cos(am), kCy + r * std::sin(am), z);
        goto3(o, kCx + r * std::cos(a1), kCy + r * std::sin(a1), z);
      }
    }
    goto3(o, kCx + 20, kCy, z + 2);
    z -= depth_step;
    if (z < -40) z = 0;
  }
  o.put("RAPID\n");
  goto3(o, kCx + 20, kCy, 20);
  end_feature(o);
}

// Finishing round a ring wall in small steps, the tool leaning outwards and rising slowly.
void fiveaxis(Out& o, Random& rnd, int featno, uint64_t budget) {
  feature(o, featno, 5 + featno % 2, 10, 6000);
  o.put("MULTAX / ON\n");
  const uint64_t stop = o.total() + budget;
  const double step = rnd.between(0.4, 0.9) * kPi / 180, wave = rnd.between(2, 6);
  auto point = [&](double a, double z) {
    const double r = 70 + wave * std::sin(5 * a);
    const double tilt = (16 + 6 * std::sin(3 * a + z / 7)) * kPi / 180;
    o.put("GOTO / %.8f, %.8f, %.8f,  $\n%.8f, %.8f, %.8f\n", kCx + r * std::cos(a), kCy + r * std::sin(a), z,
          std::sin(tilt) * std::cos(a), std::sin(tilt) * std::sin(a), std::cos(tilt));
  };
  o.put("RAPID\n");
  point(0, 25);
  o.put("FEDRAT / %.6f,  MMPM\n", rnd.between(1200, 3000));
  double a = 0, z = -30;
  while (o.total() < stop) {
    point(a, z);
    a += step;
    z += 0.002;
    if (z > 0) z = -30;
  }
  o.put("RAPID\n");
  o.put("GOTO / %.8f, %.8f, %.8f,  $\n0.00000000, 0.00000000, 1.00000000\n", kCx, kCy, 40.0);
  o.put("MULTAX / OFF\n");
  end_feature(o);
}

// Holes on bolt circles, Creo's CYCLE keyword form.
void drill(Out& o, Random& rnd, int featno, uint64_t budget) {
  feature(o, featno, 8 + featno % 2, 6.8, 2200);
  const uint64_t stop = o.total() + budget;
  o.put("RAPID\n");
  goto3(o, kCx, kCy, 30);
  if (featno % 2)
    o.put("CYCLE / DEEP, DEPTH, %.6f, STEP, 2.500000, MMPM, 140.000000, CLEAR, 2.000000\n", rnd.between(10, 25));
  else
    o.put("CYCLE / DRILL, DEPTH, %.6f, MMPM, 160.000000, CLEAR, 2.000000\n", rnd.between(6, 15));
  for (int i = 0; o.total() < stop; ++i) {
    const double r = 20 + 8 * (i / 36 % 10), a = (i % 36) * 10 * kPi / 180;
    goto3(o, kCx + r * std::cos(a), kCy + r * std::sin(a), 0);
  }
  o.put("CYCLE / OFF\n");
  o.put("RAPID\n");
  goto3(o, kCx, kCy, 30);
  end_feature(o);
}

}  // namespace

int main(int argc, char** argv) {
  double size_mb = 10, op_mb = 8;
  std::string kind = "mixed";
  uint64_t seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "usage: gen_apt --size-mb N [--kind mixed|pocket|fiveaxis|drill] [--op-mb N] [--seed N]\n");
      return 2;
    }
    const char* v = argv[++i];
    if (a == "--size-mb") size_mb = std::atof(v);
    else if (a == "--op-mb") op_mb = std::atof(v);
    else if (a == "--kind") kind = v;
    else if (a == "--seed") seed = std::strtoull(v, nullptr, 10);
    else {
      std::fprintf(stderr, "gen_apt: unknown option '%s'\n", a.c_str());
      return 2;
    }
  }
  if (kind != "mixed" && kind != "pocket" && kind != "fiveaxis" && kind != "drill") {
    std::fprintf(stderr, "gen_apt: unknown kind '%s'\n", kind.c_str());
    return 2;
  }
  Random rnd{seed * 0x9E3779B97F4A7C15ULL + 1};
  Out o;
  const uint64_t total = uint64_t(size_mb * 1e6), per_op = uint64_t(op_mb * 1e6);
  o.put("$$*          Pro/CLfile  Version Wildfire 5.0 - M030\n");
  o.put("$$-> MFGNO / BENCH_%llu\n", static_cast<unsigned long long>(seed));
  o.put("PARTNO / BENCH\n");
  o.put("MACHIN / UNCX01, 1\n");
  o.put("UNITS / MM\n");
  for (int featno = 1; o.total() < total; ++featno) {
    const uint64_t budget = std::min<uint64_t>(per_op, total - o.total());
    const int k = kind == "pocket" ? 0 : kind == "fiveaxis" ? 1 : kind == "drill" ? 2 : featno % 5 == 0 ? 2 : featno % 2;
    if (k == 0) pocket(o, rnd, featno, budget);
    else if (k == 1) fiveaxis(o, rnd, featno, budget);
    else drill(o, rnd, featno, std::max<uint64_t>(budget / 5, 20000));
  }
  o.put("FINI\n");
  return 0;
}
