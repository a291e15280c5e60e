// Random but valid CL programs, for differential fuzzing (fuzz/fuzz_certify.cpp) and its
// deterministic run in the tests (tests/readback/test_differential.cpp): lines, rapids, arcs
// in the three planes with either sense, helices, drilling cycles, five-axis moves with a
// tool axis the UMC-750 reaches, lathe profiles with arcs about Y. Every choice is read from
// a byte source, so libFuzzer's mutations of the bytes are mutations of the program's
// structure. The property checked with them: a compile either fails with a located error or
// writes a program that its certificate accepts.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace clpc::fuzz {

// Bytes in, choices out; zeros once the bytes run out.
class Choices {
 public:
  Choices(const uint8_t* data, size_t size) : p_(data), end_(data + size) {}
  uint8_t byte() { return p_ < end_ ? *p_++ : 0; }
  int pick(int n) { return n <= 1 ? 0 : int((byte() | (byte() << 8)) % unsigned(n)); }
  double in(double lo, double hi) { return lo + (hi - lo) * ((byte() | (byte() << 8)) / 65535.0); }
  bool done() const { return p_ >= end_; }

 private:
  const uint8_t* p_;
  const uint8_t* end_;
};

enum class Family { Mill, FiveAxis, Lathe };

class ClGenerator {
 public:
  explicit ClGenerator(Family f) : family_(f) {}

  std::string program(Choices& c, int max_steps = 40) {
    out_.clear();
    line("UNITS/MM\n");
    line("LOADTL/%d\n", 1 + c.pick(20));
    line("SPINDL/RPM,%d,CLW\n", 500 + 100 * c.pick(family_ == Family::Lathe ? 25 : 40));  // within every built-in's limit
    line("FEDRAT/MMPM,%d\n", 50 + 10 * c.pick(200));
    if (family_ == Family::FiveAxis) line("MULTAX/ON\n");
    // Start clear of the part.
    x_ = c.in(0, 80), y_ = family_ == Family::Lathe ? 0 : c.in(0, 80), z_ = 40;
    if (family_ == Family::Lathe) x_ = c.in(20, 60), z_ = 10;
    line("RAPID\n");
    goto_point(0, 0, 1);
    const int steps = 1 + c.pick(max_steps);
    for (int i = 0; i < steps && !c.done(); ++i) step(c);
    line("RAPID\n");
    if (family_ == Family::Lathe) x_ = 80;
    else z_ = 50;
    goto_point(0, 0, 1);
    line("FINI\n");
    return out_;
  }

 private:
  void step(Choices& c) {
    const int kinds = family_ == Family::Mill ? 5 : 4;
    switch (c.pick(kinds)) {
      case 0: {  // a straight cut, or a rapid
        if (c.pick(4) == 0) line("RAPID\n");
        if (family_ == Family::Lathe) {
          x_ = c.in(5, 60), z_ = c.in(-80, 5);
        } else {
          x_ = c.in(0, 100), y_ = c.in(0, 100), z_ = c.in(-10, 30);
        }
        if (c.pick(3) == 0) line("FEDRAT/MMPM,%d\n", 20 + 10 * c.pick(300));
        tool_axis(c);
        goto_point(i_, j_, k_);
        break;
      }
      case 1: arc(c, false); break;
      case 2:
        if (family_ == Family::FiveAxis) five_axis_run(c);
        else if (family_ == Family::Lathe) arc(c, false);
        else arc(c, true);
        break;
      case 3:
        if (family_ == Family::FiveAxis) arc(c, false);
        else if (family_ == Family::Lathe && c.pick(2) == 0) thread(c);
        else if (family_ == Family::Lathe) rough(c);
        else cycle(c);
        break;
      default: cycle(c); break;
    }
  }

  // An arc from where the tool is: a centre at radius r in a plane, a sweep either way.
  void arc(Choices& c, bool helix) {
    if (family_ == Family::FiveAxis) {  // arcs with the tool along Z
      i_ = 0, j_ = 0, k_ = 1;
      line("GOTO/%.4f,%.4f,%.4f,0.0000000,0.0000000,1.0000000\n", x_, y_, z_);
    }
    int plane = family_ == Family::Lathe ? 1 : c.pick(3);  // 0 XY, 1 XZ (about Y), 2 YZ
    const double r = c.in(2, 30), phi = c.in(0, 2 * M_PI), sweep = c.in(10, 350) * M_PI / 180;
    const double sense = c.pick(2) ? 1 : -1;
    double p[3] = {x_, y_, z_};
    const int u = plane == 0 ? 0 : plane == 1 ? 2 : 1, v = plane == 0 ? 1 : plane == 1 ? 0 : 2, n = 3 - u - v;
    // Right-handed (u, v, n): XY about Z, ZX about Y, YZ about X.
    double centre[3] = {p[0], p[1], p[2]};
    centre[u] -= r * std::cos(phi);
    centre[v] -= r * std::sin(phi);
    double end[3] = {p[0], p[1], p[2]};
    end[u] = centre[u] + r * std::cos(phi + sense * sweep);
    end[v] = centre[v] + r * std::sin(phi + sense * sweep);
    if (helix) end[n] += c.in(-5, 5);
    if (family_ == Family::Lathe && (end[0] < 1 || centre[0] - r < 0.5)) return;  // stays on the positive side
    double axis[3] = {0, 0, 0};
    axis[n] = sense;
    line("CIRCLE/%.4f,%.4f,%.4f,%.7f,%.7f,%.7f,%.4f\n", centre[0], centre[1], centre[2], axis[0], axis[1], axis[2], r);
    x_ = end[0], y_ = end[1], z_ = end[2];
    goto_point(i_, j_, k_);
  }

  // A lathe thread: passes from a start point outside the crest, at Fanuc's G76 depths or at
  // random ones, sometimes along the flank (each pass starting further along Z), sometimes
  // without the return to the start, or across the face.
  void thread(Choices& c) {
    const double crest = c.in(8, 40), start_x = crest + c.in(1, 5), z0 = c.in(-20, 5), z1 = z0 - c.in(5, 40);
    const double lead = 0.25 * (1 + c.pick(12));
    line("RAPID\n");
    x_ = start_x, z_ = z0 + 3;
    goto_point(0, 0, 1);
    const bool face = c.pick(6) == 0;
    line("THREAD/%s,%.4f\n", face ? "FACE" : "TURN", lead);
    const bool fanuc = c.pick(2) == 0, flank = c.pick(4) == 0;
    const double k = c.in(0.3, 2), first = c.in(0.1, 0.5), allowance = c.pick(2) ? c.in(0.01, 0.1) : 0;
    std::vector<double> depths;
    if (fanuc) {
      for (int n = 1; first * std::sqrt(n) < k - allowance && n < 40; ++n) depths.push_back(first * std::sqrt(n));
      depths.push_back(k - allowance);
      for (int m = 1 + c.pick(2); m > 0; --m) depths.push_back(k);
    } else {
      for (int n = 1 + c.pick(6); n > 0; --n) depths.push_back(c.in(0.05, k));
    }
    for (size_t n = 0; n < depths.size(); ++n) {
      const double zs = z0 + 3 - (flank ? 0.3 * double(n) : 0);
      line("RAPID\n");
      if (face) {  // across the face at z0, from start_x in to the bore
        const double inner = std::max(1.0, crest - 6);
        line("GOTO/%.4f,0,%.4f\n", start_x, z0 - depths[n]);
        line("GOTO/%.4f,0,%.4f\n", inner, z0 - depths[n]);
        line("RAPID\n");
        line("GOTO/%.4f,0,%.4f\n", inner, z0 + 3);
        line("RAPID\n");
        line("GOTO/%.4f,0,%.4f\n", start_x, z0 + 3);
        x_ = start_x, z_ = z0 + 3;
        continue;
      }
      if (flank) line("GOTO/%.4f,0,%.4f\n", start_x, zs);
      line("GOTO/%.4f,0,%.4f\n", crest - depths[n], zs);
      line("GOTO/%.4f,0,%.4f\n", crest - depths[n], z1);
      line("RAPID\n");
      line("GOTO/%.4f,0,%.4f\n", start_x, z1);
      x_ = start_x, z_ = z1;
      if (c.pick(8) == 0) continue;
      line("RAPID\n");
      line("GOTO/%.4f,0,%.4f\n", start_x, zs);
      z_ = zs;
    }
    line("THREAD/OFF\n");
  }

  // A lathe stock-removal cycle (CYCLE/ROUGH): turning outside or inside, or facing, over a
  // profile that moves one way along both axes, now and then with a pocket (which the compile
  // must refuse with its location).
  void rough(Choices& c) {
    const bool face = c.pick(3) == 0, inside = !face && c.pick(3) == 0, pocket = c.pick(6) == 0;
    const double depth = c.in(0.5, 3), e = c.in(0.1, 1);
    const double ax = (inside ? -1 : 1) * (c.pick(2) ? c.in(0, 0.3) : 0), az = c.pick(2) ? c.in(0, 0.2) : 0;
    const double xa = face ? c.in(40, 60) : inside ? c.in(3, 8) : c.in(40, 60), za = c.in(1, 5);
    line("RAPID\n");
    x_ = xa, z_ = za;
    goto_point(0, 0, 1);
    line("CYCLE/ROUGH,%s,DEPTH,%.3f,RETRACT,%.3f,ALLOW,%.3f,%.3f%s\n", face ? "FACE" : "TURN", depth, e, ax, az,
         c.pick(2) ? ",FINISH" : "");
    if (c.pick(2)) line("RAPID\n");
    // A': along the level axis alone; then segments towards the stock along it, away along the
    // other axis.
    double x = face ? xa : inside ? xa + c.in(8, 25) : xa - c.in(8, 25), z = face ? za - c.in(3, 10) : za;
    line("GOTO/%.4f,0,%.4f\n", x, z);
    for (int n = 1 + c.pick(4); n > 0; --n) {
      const bool back = pocket && n == 1;
      if (face) {
        x = std::max(0.5, x - c.in(1, 15));
        z = std::min(za - 0.5, z + (back ? -c.in(0.5, 2) : c.in(0, 3)));
      } else {
        z -= c.in(1, 15);
        x += (inside ? -1 : 1) * (back ? -c.in(0.5, 2) : c.in(0, 8));
      }
      line("GOTO/%.4f,0,%.4f\n", x, z);
    }
    line("CYCLE/OFF\n");
    x_ = xa, z_ = za;  // the control is back at the start point
  }

  // Holes: a cycle, a few points at the top, CYCLE/OFF.
  void cycle(Choices& c) {
    if (family_ == Family::Lathe) return;
    static const char* kinds[] = {"DRILL", "DEEP", "BRKCHP", "BORE"};
    const int k = c.pick(4);
    const double depth = c.in(1, 30), clear = c.in(1, 5);
    if (k == 1 || k == 2) line("CYCLE/%s,DEPTH,%.4f,STEP,%.4f,MMPM,%d,CLEAR,%.4f\n", kinds[k], depth, c.in(1, 8), 50 + c.pick(200), clear);
    else line("CYCLE/%s,DEPTH,%.4f,MMPM,%d,CLEAR,%.4f\n", kinds[k], depth, 50 + c.pick(200), clear);
    const int holes = 1 + c.pick(4);
    z_ = c.in(-5, 10);
    i_ = 0, j_ = 0, k_ = 1;
    for (int h = 0; h < holes; ++h) {
      x_ = c.in(0, 100), y_ = c.in(0, 100);
      goto_point(0, 0, 1);
    }
    line("CYCLE/OFF\n");
  }

  // A run of five-axis points, the tool axis turning a little each step.
  void five_axis_run(Choices& c) {
    const int n = 2 + c.pick(30);
    double b = c.in(0, 50) * M_PI / 180, a = c.in(0, 2 * M_PI);
    for (int s = 0; s < n; ++s) {
      x_ = std::clamp(x_ + c.in(-3, 3), 0.0, 100.0), y_ = std::clamp(y_ + c.in(-3, 3), 0.0, 100.0),
      z_ = std::clamp(z_ + c.in(-1, 1), -10.0, 30.0);
      b = std::clamp(b + c.in(-0.05, 0.05), 0.0, 60 * M_PI / 180);
      a += c.in(-0.1, 0.1);
      i_ = std::sin(b) * std::cos(a), j_ = std::sin(b) * std::sin(a), k_ = std::cos(b);
      goto_point(i_, j_, k_);
    }
  }

  void tool_axis(Choices& c) {
    if (family_ != Family::FiveAxis) return;
    const double b = c.in(0, 45) * M_PI / 180, a = c.in(0, 2 * M_PI);
    i_ = std::sin(b) * std::cos(a), j_ = std::sin(b) * std::sin(a), k_ = std::cos(b);
  }

  void goto_point(double i, double j, double k) {
    if (family_ == Family::FiveAxis) line("GOTO/%.4f,%.4f,%.4f,%.7f,%.7f,%.7f\n", x_, y_, z_, i, j, k);
    else line("GOTO/%.4f,%.4f,%.4f\n", x_, y_, z_);
  }

  template <class... A>
  void line(const char* f, A... a) {
    char b[256];
    std::snprintf(b, sizeof b, f, a...);
    out_ += b;
  }

  Family family_;
  std::string out_;
  double x_ = 0, y_ = 0, z_ = 0, i_ = 0, j_ = 0, k_ = 1;
};

}  // namespace clpc::fuzz
