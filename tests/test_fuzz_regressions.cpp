// Inputs that once crashed, hung or exhausted memory (or were built to try): every file in
// tests/fuzz_regressions goes through the compiler for each built-in machine (*.cls), the
// machine loader (*.toml) or the G-code reader (*.nc). They must end, under the sanitizers
// too, with a program or diagnostics — whichever, but nothing else. fuzz/run.sh says how a
// finding becomes one of these files.
#include "readback/gcode_interp.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;

TEST(FuzzRegressions, EveryInputEnds) {
  const std::string dir = std::string(CLPC_SOURCE_DIR) + "/tests/fuzz_regressions";
  int files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string path = e.path().string(), ext = e.path().extension().string();
    SCOPED_TRACE(path);
    ++files;
    if (ext == ".cls") {
      for (const char* m : {"fanuc-mill", "haas-umc750", "fanuc-lathe"}) {
        Compiled c = compile_path(path, machine(m));
        EXPECT_TRUE(c.ok || c.diags.find(": error: ") != std::string::npos) << m << ": failed without saying why\n" << c.diags;
      }
    } else if (ext == ".toml") {
      Diagnostics d(nullptr);
      MachineRegistry reg(pass_contracts());
      reg.load_builtin(d);
      if (reg.load_text(path, read_file(path), d))
        for (const auto& [name, desc] : reg.list()) (void)reg.resolve(name, d);
    } else if (ext == ".nc") {
      for (const char* m : {"fanuc-mill", "fanuc-lathe"}) {
        gcode::Result r = gcode::interpret(read_file(path), machine(m));
        EXPECT_LT(r.segments.size(), 2000000u) << m;
      }
    }
  }
  EXPECT_GE(files, 8);
}

// The bounds these inputs hit, by their messages.
TEST(FuzzRegressions, AbsurdAmountsAreRefusedNotObeyed) {
  const std::string dir = std::string(CLPC_SOURCE_DIR) + "/tests/fuzz_regressions/";
  Compiled peck = compile_path(dir + "peck_step_tiny.cls", machine("fanuc-mill"));
  EXPECT_THAT(peck.diags, ::testing::HasSubstr(":7:1: error: CYCLE/DEEP: a peck depth of 1e-06 makes more than 10000 pecks per hole of depth 1000"));
  Compiled q0 = compile_path(dir + "peck_rounds_to_zero.cls", machine("fanuc-mill"));
  EXPECT_THAT(q0.diags, ::testing::HasSubstr(":8:1: error: the peck depth 4e-04 rounds to Q0 at machine 'fanuc-mill''s resolution"));
  gcode::Result g83 = gcode::interpret(read_file(dir + "g83_q_tiny.nc"), machine("fanuc-mill"));
  ASSERT_FALSE(g83.problems.empty());
  EXPECT_EQ(g83.problems[0].message, "peck cycle with Q so small it would peck more than 100000 times");
  gcode::Result g75 = gcode::interpret(read_file(dir + "g75_pq_tiny.nc"), machine("fanuc-lathe"));
  ASSERT_FALSE(g75.problems.empty());
  EXPECT_EQ(g75.problems[0].message, "G75: P and Q so small the cycle would make more than a million moves");
}
