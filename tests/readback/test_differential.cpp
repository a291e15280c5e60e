// Differential fuzzing, its deterministic part: random but valid CL programs
// (fuzz/cl_generator.h: lines, arcs in the three planes either way, helices, drilling cycles,
// five-axis runs, lathe profiles) compiled with the certificate on. Each must either fail with
// a located error or be written and certified; a compile that writes a program its own
// certificate rejects, or that fails without saying where, is a finding. fuzz/fuzz_certify.cpp
// is the same property under libFuzzer; what it finds becomes a seed here.
#include <random>
#include <regex>

#include "driver/driver.h"
#include "fuzz/cl_generator.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;

namespace {

struct Case {
  fuzz::Family family;
  const char* machine;
  const char* toml = nullptr;  // an example machine's description (examples/), or a built-in
};


}  // namespace

TEST(Differential, RandomProgramsAreCertifiedOrRefusedWithALocatedError) {
  const Case cases[] = {{fuzz::Family::Mill, "fanuc-mill"},
                        {fuzz::Family::Mill, "haas-umc750"},
                        {fuzz::Family::FiveAxis, "haas-umc750"},
                        {fuzz::Family::Lathe, "fanuc-lathe"},
                        {fuzz::Family::FiveAxis, "fanuc-ac-plane", "examples/fanuc_ac_plane.toml"},
                        {fuzz::Family::FiveAxis, "gantry-ac-head", "examples/gantry_ac_head.toml"},
                        {fuzz::Family::FiveAxis, "head-table-bc", "examples/head_table_bc.toml"}};
  const std::regex located(":[0-9]+:[0-9]+: error: ");
  TempDir t;
  int certified = 0, refused = 0;
  int grepped = 0;  // certified programs with CLPC_DIFF_GREP's text in them (what a sweep exercised)
  // CLPC_DIFF_SEEDS=N runs N programs per machine (a longer sweep by hand; ctest runs 60).
  const unsigned seeds = std::getenv("CLPC_DIFF_SEEDS") ? unsigned(std::atoi(std::getenv("CLPC_DIFF_SEEDS"))) : 60;
  const char* only = std::getenv("CLPC_DIFF_MACHINE");  // one machine of the list
  for (const Case& k : cases) {
    if (only && std::string(only) != k.machine) continue;
    const Machine m = k.toml ? machine(k.machine, read_file(source_path(k.toml))) : machine(k.machine);
    for (unsigned seed = 1; seed <= seeds; ++seed) {
      std::mt19937 rng(seed * 7919 + unsigned(k.family));
      std::vector<uint8_t> bytes(600);
      for (uint8_t& b : bytes) b = uint8_t(rng());
      fuzz::Choices c(bytes.data(), bytes.size());
      const std::string cl = fuzz::ClGenerator(k.family).program(c);
      const std::string in = t.path("fuzz.cls"), out = t.path("fuzz.nc");
      write_file(in, cl);
      std::remove(out.c_str());
      CompileOptions o;
      o.certify = true;
      std::ostringstream err;
      CompileResult r = compile_file(in, out, m, o, err);
      SCOPED_TRACE(std::string(k.machine) + ", seed " + std::to_string(seed) + ":\n" + cl);
      if (r.ok) {
        ++certified;
        ASSERT_TRUE(r.certificate && r.certificate->ok) << err.str();
        if (const char* g = std::getenv("CLPC_DIFF_GREP"); g && read_file(out).find(g) != std::string::npos) ++grepped;
        EXPECT_TRUE(std::filesystem::exists(out));
      } else {
        ++refused;
        if (std::getenv("CLPC_SHOW_REFUSALS")) std::printf("%s\n", err.str().c_str());
        EXPECT_TRUE(std::regex_search(err.str(), located)) << "refused without a located error:\n" << err.str();
        EXPECT_EQ(err.str().find("the program does not follow the CL"), std::string::npos)
            << "written wrong, caught only by the certificate:\n"
            << err.str();
        EXPECT_FALSE(std::filesystem::exists(out));
      }
    }
  }
  std::printf("differential: %d programs certified, %d refused with a located error\n", certified, refused);
  if (std::getenv("CLPC_DIFF_GREP")) std::printf("differential: %d certified programs contain '%s'\n", grepped, std::getenv("CLPC_DIFF_GREP"));
  EXPECT_GT(certified, 100);
}
