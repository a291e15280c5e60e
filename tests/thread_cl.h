// CL threads for the tests (threading, mutation): an M20 x 1.5 outside thread cut in passes.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace clpc::test {

// A CL thread: M20 x 1.5 outside (crest radius 10) from Z5 to Z-20, the tool waiting at X15,
// one pass per depth (radius below the crest), each a G92-shaped box.
inline std::string thread_cl(const std::vector<double>& depths, const std::string& spindle = "SPINDL/RPM,800,CLW",
                      const std::vector<double>& start_z = {}) {
  std::string s = "UNITS/MM\nMACHIN/TURN\nLOAD/TOOL,3\n" + spindle + "\nFEDRAT/MMPR,0.2\nRAPID\nGOTO/15,0,5\nTHREAD/TURN,1.5\n";
  char b[200];
  for (size_t n = 0; n < depths.size(); ++n) {
    const double x = 10 - depths[n], z0 = start_z.empty() ? 5 : start_z[n];
    if (!start_z.empty()) {
      std::snprintf(b, sizeof b, "RAPID\nGOTO/15,0,%.4f\n", z0);
      s += b;
    }
    std::snprintf(b, sizeof b, "RAPID\nGOTO/%.4f,0,%.4f\nGOTO/%.4f,0,-20\nRAPID\nGOTO/15,0,-20\nRAPID\nGOTO/15,0,%.4f\n", x, z0, x, z0);
    s += b;
  }
  return s + "THREAD/OFF\nRAPID\nGOTO/30,0,30\nFINI\n";
}

// Fanuc's depths for k = 0.92, first 0.3, d = 0.05, m = 2, rounded as a CAM system writes them.
inline std::vector<double> g76_depths() {
  std::vector<double> d;
  for (int n = 1; n <= 8; ++n) d.push_back(std::round(0.3 * std::sqrt(n) * 1e4) / 1e4);
  d.insert(d.end(), {0.87, 0.92, 0.92});
  return d;
}

}  // namespace clpc::test
