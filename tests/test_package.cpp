// The Debian package (CPack, scripts/package.sh): built from this build tree, it declares its
// runtime Depends (which apt can satisfy here), installs with dpkg into a scratch root, and
// the installed clpc prints its version, compiles the bundled example byte for byte as the
// build's clpc does, has a manual page that man renders and a bash completion that completes.
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {


// What is missing here to build or install the package ("" when nothing).
std::string tools_missing() {
  for (const char* tool : {"cpack", "dpkg", "dpkg-deb", "dpkg-shlibdeps", "man", "bash"})
    if (run_shell(std::string("command -v ") + tool).status != 0)
      return std::string(tool) + " is not here (scripts/setup.sh installs it)";
  if (!std::filesystem::exists(std::string(CLPC_BUILD_DIR) + "/man/clpc.1.gz"))
    return "the build made no manual page (help2man missing when it was configured; scripts/setup.sh installs it)";
  return "";
}

}  // namespace

TEST(Package, DebInstallsIntoAScratchRootAndWorks) {
  if (std::string why = tools_missing(); !why.empty()) GTEST_SKIP() << why;
  TempDir t;
  RunResult pack = run_shell("cpack -G DEB --config " + std::string(CLPC_BUILD_DIR) + "/CPackConfig.cmake -B " + t.path("pkg"));
  ASSERT_EQ(pack.status, 0) << pack.out << pack.err;
  RunResult found = run_shell("ls " + t.path("pkg") + "/clpc_*.deb");
  ASSERT_EQ(found.status, 0) << found.err;
  const std::string deb = found.out.substr(0, found.out.find('\n'));

  // Its runtime dependencies are declared (from the libraries clpc links), and apt can
  // satisfy them on this Debian machine.
  RunResult depends = run_shell("dpkg-deb -f " + deb + " Depends");
  ASSERT_EQ(depends.status, 0) << depends.err;
  EXPECT_THAT(depends.out, HasSubstr("libc6 (>="));
  EXPECT_THAT(depends.out, HasSubstr("libstdc++6 (>="));
  EXPECT_THAT(depends.out, HasSubstr("libtomlplusplus3 (>="));
  if (run_shell("command -v apt-get").status == 0) {
    RunResult apt = run_shell("apt-get install -s " + deb);
    EXPECT_EQ(apt.status, 0) << apt.out << apt.err;
    EXPECT_THAT(apt.out, HasSubstr("Inst clpc ("));
  }

  // dpkg installs it into a scratch root (its own package database there).
  const std::string root = t.path("root");
  RunResult admin = run_shell("mkdir -p " + root + "/var/lib/dpkg/updates " + root + "/var/lib/dpkg/info && touch " + root +
                              "/var/lib/dpkg/status");
  ASSERT_EQ(admin.status, 0) << admin.err;
  RunResult inst = run_shell("dpkg --root=" + root + " --admindir=" + root +
                             "/var/lib/dpkg --force-not-root --force-depends --force-script-chrootless -i " + deb);
  ASSERT_EQ(inst.status, 0) << inst.out << inst.err;
  EXPECT_THAT(inst.out, HasSubstr("Setting up clpc ("));
  const std::string clpc = root + "/usr/bin/clpc";

  RunResult version = run_shell(clpc + " --version");
  EXPECT_EQ(version.status, 0);
  EXPECT_THAT(version.out, ::testing::MatchesRegex("clpc [0-9]+\\.[0-9]+\\.[0-9]+\n"));

  // The installed program compiles the bundled example as the build's does, byte for byte.
  RunResult mine = run_shell(clpc + " compile " + source_path("examples/bracket.cls") + " -t fanuc-mill -o " + t.path("installed.nc"));
  ASSERT_EQ(mine.status, 0) << mine.err;
  EXPECT_THAT(mine.err, HasSubstr("clpc: certified "));
  RunResult built = run_clpc("compile " + source_path("examples/bracket.cls") + " -t fanuc-mill -o " + t.path("built.nc"));
  ASSERT_EQ(built.status, 0) << built.err;
  EXPECT_EQ(read_file(t.path("installed.nc")), read_file(t.path("built.nc")));

  // The manual page renders, with every subcommand's help.
  RunResult man = run_shell("MANWIDTH=100 man -l " + root + "/usr/share/man/man1/clpc.1.gz | col -b");
  ASSERT_EQ(man.status, 0) << man.err;
  EXPECT_THAT(man.out, HasSubstr("clpc - CNC postprocessor built as a compiler"));
  EXPECT_THAT(man.out, HasSubstr("COMMANDS"));
  EXPECT_THAT(man.out, HasSubstr("Usage: clpc compile [OPTIONS] INPUT..."));
  EXPECT_THAT(man.out, HasSubstr("EXAMPLES"));

  // Bash completes subcommands, options from each subcommand's help, and machine names.
  auto complete = [&](const std::string& words, int cword) {
    return run_shell("PATH=" + root + "/usr/bin:$PATH bash -c 'source " + root +
                     "/usr/share/bash-completion/completions/clpc; COMP_WORDS=(" + words + "); COMP_CWORD=" +
                     std::to_string(cword) + "; _clpc; echo \"${COMPREPLY[*]}\"'")
        .out;
  };
  EXPECT_EQ(complete("clpc com", 1), "compile\n");
  EXPECT_EQ(complete("clpc compile --no-v", 2), "--no-verify\n");
  EXPECT_EQ(complete("clpc compile part.cls -t haas", 4), "haas-umc750\n");
  EXPECT_EQ(complete("clpc explain fanuc-l", 2), "fanuc-lathe\n");
  EXPECT_EQ(complete("clpc compile --input-units i", 3), "inch\n");
}
