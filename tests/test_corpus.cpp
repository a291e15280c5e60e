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

TEST(Corpus, HaasCompilesEveryMillingFile) {
  REQUIRE_CORPUS();
  Machine haas = machine("haas-umc750");
  for (const std::string& f : corpus_files()) {
    if (is_lathe_file(f)) continue;
    if (is_five_axis_file(f)) continue;  // see Corpus.FiveAxisFiles (kinematics)
    Compiled c = compile_path(f, haas);
    EXPECT_TRUE(c.ok) << f << "\n" << c.diags;
    EXPECT_NE(c.output.find("M30\n%\n"), std::string::npos) << f;
  }
}
