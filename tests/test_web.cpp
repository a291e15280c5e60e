// clpc in the browser (web/): the WebAssembly build's page, served by a plain static server on
// 127.0.0.1, driven by headless Chromium through a scripted case (tests/tools/web_case.py):
// the G-code it shows is the native build's byte for byte, with the same certificate, and a
// bad file shows its located diagnostic, linked to its CL line. Skipped with a message where
// Emscripten was absent at configure time (scripts/setup.sh --tests installs it).
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

struct Page {
  std::string state, gcode, log, certificate, diagnostics;
};

std::string why_not() {
  if (std::string(CLPC_WEB_SITE).empty())
    return "Emscripten was not found when this build was configured: the browser page is not built "
           "(scripts/setup.sh --tests installs emscripten)";
  if (run_shell("command -v chromium").status != 0) return "chromium is not installed (scripts/setup.sh --tests installs it)";
  return "";
}

// The page posts `cl` (copied as `name`) for `machine`.
Page in_browser(const TempDir& t, const std::string& cl, const std::string& machine) {
  const std::string out = t.path("page");
  RunResult r = run_shell("python3 " + std::string(CLPC_SOURCE_DIR) + "/tests/tools/web_case.py " + CLPC_WEB_SITE + " " + cl + " " +
                          machine + " " + out);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  return {read_file(out + "/state.txt"), read_file(out + "/gcode.nc"), read_file(out + "/log.txt"),
          read_file(out + "/certificate.txt"), read_file(out + "/diagnostics.txt")};
}

// The native clpc on the same file, run where it lies so the names match the page's.
RunResult native(const std::string& dir, const std::string& name, const std::string& machine) {
  return run_shell("cd " + dir + " && " + CLPC_BINARY + " compile " + name + " -t " + machine + " -o out.nc");
}

void same_as_native(const std::string& cl, const std::string& machine) {
  TempDir t;
  const std::string name = std::filesystem::path(cl).filename().string();
  std::filesystem::copy_file(cl, t.path(name));
  RunResult n = native(t.path(""), name, machine);
  ASSERT_EQ(n.status, 0) << n.err;
  Page p = in_browser(t, t.path(name), machine);
  EXPECT_EQ(p.state, "done");
  ASSERT_FALSE(p.gcode.empty()) << p.log;
  EXPECT_EQ(p.gcode, read_file(t.path("out.nc"))) << cl;  // byte for byte
  // The same diagnostics and certificate, word for word; only the program's name differs
  // (out.nc here, NAME.nc there).
  std::string log = n.err;
  const std::string base = name.substr(0, name.rfind('.'));
  const size_t at = log.find("clpc: certified out.nc: ");
  ASSERT_NE(at, std::string::npos) << log;
  log.replace(at + 16, 6, base + ".nc");
  EXPECT_EQ(p.log, log);
  EXPECT_EQ(p.certificate, log.substr(at, log.find('\n', at) - at));
}

}  // namespace

TEST(Web, ThePageWritesTheNativeProgramByteForByte) {
  if (std::string why = why_not(); !why.empty()) GTEST_SKIP() << why;
  same_as_native(std::string(CLPC_SOURCE_DIR) + "/tests/golden/nx_mill.cls", "haas-umc750");
  same_as_native(std::string(CLPC_SOURCE_DIR) + "/tests/golden/creo_lathe.ncl", "fanuc-lathe");
}

// NX's variable-axis finishing (nx-course/APT_Variable_Axis.cls): a tool axis on every GOTO.
TEST(Web, ACorpusFiveAxisFile) {
  if (std::string why = why_not(); !why.empty()) GTEST_SKIP() << why;
  if (corpus_dir().empty()) GTEST_SKIP() << "the corpus (../shared/corpus) is not here";
  same_as_native(corpus_dir() + "/nx-course/APT_Variable_Axis.cls", "haas-umc750");
}

TEST(Web, ABadFileShowsItsLocatedDiagnostic) {
  if (std::string why = why_not(); !why.empty()) GTEST_SKIP() << why;
  TempDir t;
  write_file(t.path("bad.cls"), "UNITS/MM\nLOADTL/1\nSPINDL/RPM,2000,CLW\nGOTO/0,0,X\nFINI\n");
  RunResult n = native(t.path(""), "bad.cls", "fanuc-mill");
  ASSERT_EQ(n.status, 1);
  const std::string first = n.err.substr(0, n.err.find('\n'));
  EXPECT_THAT(first, HasSubstr("bad.cls:4:"));
  Page p = in_browser(t, t.path("bad.cls"), "fanuc-mill");
  EXPECT_EQ(p.state, "done");
  EXPECT_EQ(p.gcode, "");
  EXPECT_EQ(p.log, n.err);                          // what clpc compile says, word for word
  EXPECT_EQ(p.diagnostics, "4\t" + first + "\n");  // a link to CL line 4
  EXPECT_FALSE(std::filesystem::exists(t.path("out.nc")));
}
