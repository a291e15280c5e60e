// Sweeps the real CL files in ../shared/corpus (tests/corpus_cases.h): each is posted on the
// machine it fits and its program passes `clpc verify`, or it is refused with the located error
// the table gives. Skips (and says why) when the corpus is absent.
#include <set>

#include "driver/readback_commands.h"
#include "corpus_cases.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;

namespace {

#define REQUIRE_CORPUS()                                                                       \
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR << ": sweep skipped"

// The built-in machines, and the test machines of tests/machines/.
Machine corpus_machine(const std::string& name) {
  std::string extra;
  for (auto& e : std::filesystem::directory_iterator(std::string(CLPC_SOURCE_DIR) + "/tests/machines"))
    if (e.path().extension() == ".toml" && e.path().filename() != "shop_mill.toml") extra += read_file(e.path().string()) + "\n";
  return machine(name, extra);
}

CompileOptions options_for(const CorpusCase& c) {
  CompileOptions o;
  if (std::string(c.input_units) == "mm") o.input_units = ir::Units::Mm;
  if (std::string(c.input_units) == "inch") o.input_units = ir::Units::Inch;
  return o;
}

}  // namespace

TEST(Corpus, Found) {
  REQUIRE_CORPUS();
  EXPECT_GE(corpus_files().size(), 38u);
}

// Every corpus file has its line in the table, and every line its file.
TEST(Corpus, EveryFileHasItsCase) {
  REQUIRE_CORPUS();
  std::set<std::string> files, cases;
  for (const std::string& f : corpus_files()) files.insert(f.substr(corpus_dir().size() + 1));
  for (const CorpusCase& c : corpus_cases()) cases.insert(c.file);
  EXPECT_EQ(files, cases);
}

// The front end and lowering (clpc check without a machine) read every file; the refused files
// give their error there already when it is the CL's own.
TEST(Corpus, CheckReadsEveryFile) {
  REQUIRE_CORPUS();
  for (const CorpusCase& c : corpus_cases()) {
    SCOPED_TRACE(c.file);
    Machine m = default_machine(Family::Mill, ir::Units::Mm);
    m.pipeline = {"arc-direction"};
    CompileOptions opt = options_for(c);
    opt.emit = Emit::Nothing;
    std::ostringstream err;
    CompileResult r = compile_file(corpus_dir() + "/" + c.file, "-", m, opt, err);
    if (*c.error && !c.machine_error) EXPECT_NE(err.str().find(c.error), std::string::npos) << err.str();
    else EXPECT_TRUE(r.ok) << err.str();  // (a machine's refusal needs the machine: compile's, below)
  }
}

// Posted and certified (clpc compile's own check, the certificate line on its standard error),
// or refused as the table says.
TEST(Corpus, EveryFilePostedAndCertifiedOrRefusedWithItsError) {
  REQUIRE_CORPUS();
  int posted = 0, refused = 0;
  long points = 0, arcs = 0, holes = 0, ambiguous = 0;
  double worst_mm = 0;
  TempDir t;
  for (const CorpusCase& c : corpus_cases()) {
    const std::string path = corpus_dir() + "/" + c.file;
    const Machine m = corpus_machine(c.machine);
    SCOPED_TRACE(std::string(c.file) + " on " + c.machine);
    if (*c.error) {
      Compiled r = compile_path(path, m, options_for(c));
      EXPECT_FALSE(r.ok);
      EXPECT_NE(r.diags.find(path + c.error), std::string::npos) << r.diags;
      ++refused;
      continue;
    }
    CompileOptions o = options_for(c);
    o.certify = true;
    std::ostringstream err;
    const std::string out = t.path("program.nc");
    CompileResult r = compile_file(path, out, m, o, err);
    EXPECT_TRUE(r.ok) << err.str();
    ASSERT_TRUE(r.certificate.has_value()) << err.str();
    const VerifyReport& rep = *r.certificate;
    EXPECT_TRUE(rep.ok) << err.str();
    EXPECT_NE(err.str().find("clpc: certified " + out + ": " + std::to_string(rep.cl_points) + " points, "), std::string::npos)
        << err.str();
    EXPECT_GT(rep.cl_points + rep.cl_arcs + rep.cl_holes, 0);
    worst_mm = std::max(worst_mm, rep.max_deviation * ir::mm_per_unit(m.units));
    points += rep.cl_points;
    arcs += rep.cl_arcs;
    holes += rep.cl_holes;
    ambiguous += rep.ambiguous_arcs;
    ++posted;
  }
  std::printf("corpus: %d files posted and certified (%ld points, %ld arcs, %ld holes; %ld arcs where convention and "
              "geometry disagree), %d refused with their located error; worst deviation %.4f mm\n",
              posted, points, arcs, holes, ambiguous, refused, worst_mm);
  EXPECT_EQ(posted + refused, int(corpus_cases().size()));
}

// helical.ncl.1 says UNITS/INCHES, but its numbers are millimetres: read as inches it spans more
// than the UMC-750 travels, and the diagnostic says why and names --input-units.
TEST(Corpus, UnitsThatContradictTheDataAreNamed) {
  REQUIRE_CORPUS();
  const std::string path = corpus_dir() + "/nist/helical.ncl.1";
  Compiled c = compile_path(path, machine("haas-umc750"));
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.diags.find(path + ": warning: the file says its units are inches, but tool T1 would be 10 in across (254 mm): "
                                "if its numbers are millimetres, --input-units mm reads them so"),
            std::string::npos)
      << c.diags;
  EXPECT_NE(c.diags.find(path + ":35:1: error: the program's Y positions now span 22.6636 in, more than the machine's 20 in of "
                                "travel: it cannot fit wherever the part is set up (are the CL's units right? tool T1 would be "
                                "10 in across (254 mm); see --input-units)"),
            std::string::npos)
      << c.diags;
}
