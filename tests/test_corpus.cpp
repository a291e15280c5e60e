// Sweeps the real CL files in ../shared/corpus: the front end reads them all, and every
// machine compiles the files it applies to. Skips (and says why) when the corpus is absent.
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;

namespace {

#define REQUIRE_CORPUS()                                                                       \
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR << ": sweep skipped"

}  // namespace

TEST(Corpus, Found) {
  REQUIRE_CORPUS();
  EXPECT_GE(corpus_files().size(), 20u);
}

TEST(Corpus, CheckAcceptsEveryFile) {
  REQUIRE_CORPUS();
  for (const std::string& f : corpus_files()) {
    Machine m = default_machine(Family::Mill, ir::Units::Mm);
    m.pipeline = {"arc-direction"};
    CompileOptions opt;
    opt.emit = Emit::Nothing;
    std::ostringstream err;
    CompileResult r = compile_file(f, "-", m, opt, err);
    EXPECT_TRUE(r.ok) << f << "\n" << err.str();
    EXPECT_EQ(r.errors, 0u) << f;
  }
}

// Every milling file becomes a complete Haas program, but two the UMC-750 cannot run, which
// clpc refuses with the reason:
//   helical.ncl.1 says UNITS/INCHES, but its numbers are millimetres (a 10-inch cutter at
//     5 rpm): read as inches it spans more Y than the machine has. With --input-units mm it
//     compiles.
//   dwnhole.ncl.3 indexes an A axis between subroutine calls (ROTATE/AAXIS); the UMC has none.
TEST(Corpus, HaasCompilesEveryMillingFile) {
  REQUIRE_CORPUS();
  Machine haas = machine("haas-umc750");
  int compiled = 0;
  for (const std::string& f : corpus_files()) {
    if (is_lathe_file(f)) continue;
    Compiled c = compile_path(f, haas);
    if (f.find("helical.ncl.1") != std::string::npos) {
      EXPECT_FALSE(c.ok);
      EXPECT_NE(c.diags.find("error: the program's Y positions now span 22.6636 in, more than the machine's 20 in of travel"),
                std::string::npos)
          << c.diags;
      CompileOptions mm;
      mm.input_units = ir::Units::Mm;
      Compiled again = compile_path(f, haas, mm);
      EXPECT_TRUE(again.ok) << again.diags;
      continue;
    }
    if (f.find("dwnhole.ncl.3") != std::string::npos) {
      EXPECT_FALSE(c.ok);
      EXPECT_NE(c.diags.find(":215:1: error: ROTATE (rotary indexing between subroutine calls) is not supported"),
                std::string::npos)
          << c.diags;
      continue;
    }
    EXPECT_TRUE(c.ok) << f << "\n" << c.diags;
    EXPECT_NE(c.output.find("M30\n%\n"), std::string::npos) << f;
    ++compiled;
  }
  EXPECT_EQ(compiled, 14);
}
