// gen_cl: writes a large, realistic NX-style CL file (CLSF), deterministic for a seed.
//
//   gen_cl --size-mb 200 [--kind mixed|contour|fiveaxis|drill] [--op-mb 8] [--seed 1] > big.cls
//
// Operations, each its own TOOL PATH with a tool change, in turn (kind "mixed"):
//   contour   3-axis z-level roughing of a rounded pocket: lines and NX CIRCLE corners;
//   fiveaxis  variable-axis finishing of a wavy surface: a GOTO with its tool axis on every
//             line, the axis tilted 12-28 degrees and turning slowly (never vertical, so a
//             B/C trunnion has no singularity to cross);
//   drill     CYCLE/DRILL and CYCLE/DEEP over a grid of holes.
// The part stays inside 300 x 200 x 60 mm, within every built-in mill's travel. Operations
// stop at about --op-mb megabytes; the file at about --size-mb.
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

constexpr double kPi = 3.14159265358979323846;

// splitmix64: small, fast and the same everywhere.
struct Rng {
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) / double(1ULL << 53); }
};

class Writer {
 public:
  Writer() : buf_(new char[kCap]) {}
  ~Writer() {
    flush();
    delete[] buf_;
  }
  void line(const char* fmt, ...) __attribute__((format(printf, 2, 3))) {
    if (len_ + 512 > kCap) flush();
    va_list ap;
    va_start(ap, fmt);
    int n = std::vsnprintf(buf_ + len_, 512, fmt, ap);
    va_end(ap);
    len_ += size_t(n);
    written_ += uint64_t(n);
  }
  uint64_t written() const { return written_; }

 private:
  void flush() {
    std::fwrite(buf_, 1, len_, stdout);
    len_ = 0;
  }
  static constexpr size_t kCap = 1 << 20;
  char* buf_;
  size_t len_ = 0;
  uint64_t written_ = 0;
};

struct Options {
  double size_mb = 10;
  double op_mb = 8;
  std::string kind = "mixed";
  uint64_t seed = 1;
};

void header(Writer& w, int op, const char* name, const char* tool, int number, double dia, double cr) {
  w.line("TOOL PATH/%s_%05d,TOOL,%s\n", name, op, tool);
  w.line("TLDATA/MILL,%.4f,%.4f,75.0000,0.0000,0.0000\n", dia, cr);
  w.line("MSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000\n");
  w.line("$$ centerline data\n");
  w.line("PAINT/PATH\n");
  w.line("LOAD/TOOL,%d,ADJUST,%d\n", number, number);
  w.line("SPINDL/RPM,%d,CLW\n", 4500 + 500 * (number % 8));  // within the UMC-750's 8100 rpm
  w.line("COOLNT/FLOOD\n");
}

void footer(Writer& w) {
  w.line("PAINT/SPEED,10\n");
  w.line("END-OF-PATH\n");
}

// A rounded rectangle pocket, level by level, counter-clockwise (NX: the CIRCLE axis is the
// one clockwise rotation is about, so -Z).
void contour(Writer& w, Rng& r, int op, uint64_t budget) {
  header(w, op, "ZLEVEL_ROUGH", "EM12", 1 + op % 4, 12, 0.8);
  const uint64_t stop = w.written() + budget;
  const double x0 = r.uniform(20, 60), y0 = r.uniform(20, 50);
  double level = 0;
  w.line("RAPID\nGOTO/%.4f,%.4f,%.4f,0.0000000,0.0000000,1.0000000\n", x0 + 15, y0, 50.0);
  w.line("RAPID\nGOTO/%.4f,%.4f,%.4f\n", x0 + 15, y0, 3.0);
  w.line("FEDRAT/MMPM,%.4f\n", r.uniform(800, 2400));
  while (w.written() < stop) {
    // Offsets inwards make many loops per level; each loop is 4 lines and 4 arcs.
    for (double off = 0; off < 40 && w.written() < stop; off += 2.5) {
      const double xa = x0 + off, ya = y0 + off, xb = x0 + 200 - off, yb = y0 + 120 - off, rad = 15;
      const double z = level > 0 ? -level : 0.0;
      w.line("GOTO/%.4f,%.4f,%.4f\n", xa + rad, ya, z);
      w.line("GOTO/%.4f,%.4f,%.4f\n", xb - rad, ya, z);
      w.line("CIRCLE/%.4f,%.4f,%.4f,0.0000000,0.0000000,-1.0000000,%.4f,0.0600,0.5000,12.0000,0.8000\n", xb - rad, ya + rad, z, rad);
      w.line("GOTO/%.4f,%.4f,%.4f\n", xb, ya + rad, z);
      w.line("GOTO/%.4f,%.4f,%.4f\n", xb, yb - rad, z);
      w.line("CIRCLE/%.4f,%.4f,%.4f,0.0000000,0.0000000,-1.0000000,%.4f,0.0600,0.5000,12.0000,0.8000\n", xb - rad, yb - rad, z, rad);
      w.line("GOTO/%.4f,%.4f,%.4f\n", xb - rad, yb, z);
      w.line("GOTO/%.4f,%.4f,%.4f\n", xa + rad, yb, z);
      w.line("CIRCLE/%.4f,%.4f,%.4f,0.0000000,0.0000000,-1.0000000,%.4f,0.0600,0.5000,12.0000,0.8000\n", xa + rad, yb - rad, z, rad);
      w.line("GOTO/%.4f,%.4f,%.4f\n", xa, yb - rad, z);
      w.line("GOTO/%.4f,%.4f,%.4f\n", xa, ya + rad, z);
      w.line("CIRCLE/%.4f,%.4f,%.4f,0.0000000,0.0000000,-1.0000000,%.4f,0.0600,0.5000,12.0000,0.8000\n", xa + rad, ya + rad, z, rad);
      w.line("GOTO/%.4f,%.4f,%.4f\n", xa + rad, ya, z);
    }
    level = std::fmod(level + 0.5, 40.0);
  }
  w.line("RAPID\nGOTO/%.4f,%.4f,%.4f\n", x0 + 15, y0, 50.0);
  footer(w);
}

// Variable-axis finishing: zig-zag over z = 6 sin(x/23) sin(y/31), the tool tilted.
void fiveaxis(Writer& w, Rng& r, int op, uint64_t budget) {
  header(w, op, "VARIABLE_CONTOUR", "BALL6", 5 + op % 3, 6, 3);
  const uint64_t stop = w.written() + budget;
  const double phase = r.uniform(0, 2 * kPi), step = r.uniform(0.15, 0.35);
  auto point = [&](double x, double y) {
    double z = 6 * std::sin(x / 23 + phase) * std::sin(y / 31);
    double tilt = (20 + 8 * std::sin(x / 41 + y / 37)) * kPi / 180;
    double az = (30 + 25 * std::sin(x / 53 - phase)) * kPi / 180;
    w.line("GOTO/%.4f,%.4f,%.4f,%.7f,%.7f,%.7f\n", x, y, z, std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az),
           std::cos(tilt));
  };
  w.line("RAPID\n");
  point(40, 30);
  w.line("FEDRAT/MMPM,%.4f\n", r.uniform(1500, 4000));
  double y = 30;
  bool forward = true;
  while (w.written() < stop) {
    for (double x = 40; x <= 240 && w.written() < stop; x += step) point(forward ? x : 280 - x, y);
    y += 1.2;
    if (y > 170) y = 30;
    forward = !forward;
  }
  w.line("RAPID\nGOTO/%.4f,%.4f,%.4f,0.0000000,0.0000000,1.0000000\n", 40.0, 30.0, 60.0);
  footer(w);
}

void drill(Writer& w, Rng& r, int op, uint64_t budget) {
  header(w, op, "DRILLING", "DRILL8", 9 + op % 2, 8, 0);
  const uint64_t stop = w.written() + budget;
  const bool deep = r.next() % 2;
  w.line("RAPID\nGOTO/%.4f,%.4f,%.4f,0.0000000,0.0000000,1.0000000\n", 30.0, 30.0, 50.0);
  if (deep) w.line("CYCLE/DEEP,FEDTO,-%.4f,STEP,2.0000,MMPM,120.0000,RAPTO,3.0000\n", r.uniform(8, 20));
  else w.line("CYCLE/DRILL,RAPTO,3.0000,FEDTO,-%.4f,MMPM,150.0000\n", r.uniform(5, 15));
  for (int i = 0; w.written() < stop; ++i) {
    double x = 30 + (i % 40) * 6, y = 30 + (i / 40 % 25) * 6;
    w.line("GOTO/%.4f,%.4f,0.0000,0.0000000,0.0000000,1.0000000\n", x, y);
  }
  w.line("CYCLE/OFF\n");
  w.line("RAPID\nGOTO/%.4f,%.4f,%.4f\n", 30.0, 30.0, 50.0);
  footer(w);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "gen_cl: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--size-mb") o.size_mb = std::atof(value().c_str());
    else if (a == "--op-mb") o.op_mb = std::atof(value().c_str());
    else if (a == "--kind") o.kind = value();
    else if (a == "--seed") o.seed = std::strtoull(value().c_str(), nullptr, 10);
    else {
      std::fprintf(stderr, "usage: gen_cl --size-mb N [--kind mixed|contour|fiveaxis|drill] [--op-mb N] [--seed N]\n");
      return 2;
    }
  }
  if (o.kind != "mixed" && o.kind != "contour" && o.kind != "fiveaxis" && o.kind != "drill") {
    std::fprintf(stderr, "gen_cl: unknown kind '%s'\n", o.kind.c_str());
    return 2;
  }
  Rng r{o.seed};
  Writer w;
  const uint64_t total = uint64_t(o.size_mb * 1e6), per_op = uint64_t(o.op_mb * 1e6);
  w.line("$$ generated by clpc bench/gen_cl --size-mb %g --kind %s --op-mb %g --seed %llu\n", o.size_mb, o.kind.c_str(), o.op_mb,
         static_cast<unsigned long long>(o.seed));
  w.line("UNITS/MM\n");
  for (int op = 0; w.written() < total; ++op) {
    uint64_t budget = std::min<uint64_t>(per_op, total - w.written());
    int k = o.kind == "contour" ? 0 : o.kind == "fiveaxis" ? 1 : o.kind == "drill" ? 2 : op % 5 == 4 ? 2 : op % 2;
    // Drilling writes short lines: a fifth of the budget is plenty.
    if (k == 0) contour(w, r, op, budget);
    else if (k == 1) fiveaxis(w, r, op, budget);
    else drill(w, r, op, std::max<uint64_t>(budget / 5, 20000));
  }
  w.line("FINI\n");
  return 0;
}
