// The command line, run as a program: exit codes, stdin/stdout, default output names,
// atomic output, diagnostics format.
#include <sys/stat.h>

#include <filesystem>

#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {
const char* kSmall = "UNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10\nFEDRAT/MMPM,100\nGOTO/0,0,0\nGOTO/10,0,0\nFINI\n";
}

TEST(Cli, VersionAndHelp) {
  RunResult v = run_clpc("--version");
  EXPECT_EQ(v.status, 0);
  EXPECT_THAT(v.out, StartsWith("clpc "));
  RunResult h = run_clpc("--help");
  EXPECT_EQ(h.status, 0);
  EXPECT_THAT(h.out, HasSubstr("compile"));
  EXPECT_THAT(h.out, HasSubstr("machines"));
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run_clpc("").status, 2);
  EXPECT_EQ(run_clpc("compile").status, 2);
  EXPECT_EQ(run_clpc("compile x.cls").status, 2);  // no -t
  EXPECT_EQ(run_clpc("frobnicate").status, 2);
  EXPECT_EQ(run_clpc("compile - -t fanuc-mill --emit=pdf").status, 2);
  EXPECT_EQ(run_clpc("compile - -t fanuc-mill --print-after=nosuch").status, 2);
}

TEST(Cli, Machines) {
  RunResult r = run_clpc("machines");
  EXPECT_EQ(r.status, 0);
  EXPECT_THAT(r.out, HasSubstr("haas-umc750\tHaas UMC-750"));
  EXPECT_THAT(r.out, HasSubstr("fanuc-mill\t"));
  EXPECT_THAT(r.out, HasSubstr("fanuc-lathe\t"));
}

TEST(Cli, StdinToStdout) {
  RunResult r = run_clpc("compile - -t fanuc-mill -o -", kSmall);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, StartsWith("%\nO1000\n"));
  EXPECT_THAT(r.out, HasSubstr("N70 G94 G01 Z0. F100.\nN80 X10.\n"));
}

TEST(Cli, DefaultOutputNameAndRefusingTheInput) {
  TempDir t;
  write_file(t.path("part.cls"), kSmall);
  RunResult r = run_clpc("compile " + t.path("part.cls") + " -t haas-umc750");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(read_file(t.path("part.nc")), HasSubstr("M30"));
  RunResult same = run_clpc("compile " + t.path("part.cls") + " -t haas-umc750 -o " + t.path("part.cls"));
  EXPECT_EQ(same.status, 1);
  EXPECT_THAT(same.err, HasSubstr("is the input file; refusing to overwrite it"));
  EXPECT_EQ(read_file(t.path("part.cls")), kSmall);
}

// Options that may be given again take one value each: --machines, --set, --job and -W took
// every word after them, so the CL files after --machines were read as TOML. An empty -t is
// a usage error (it compiled for an empty machine).
TEST(Cli, RepeatableOptionsTakeOneValueEach) {
  TempDir t;
  write_file(t.path("a.cls"), kSmall);
  write_file(t.path("b.cls"), kSmall);
  write_file(t.path("shop.toml"), "[my-mill]\ninherits = \"fanuc-mill\"\n");
  RunResult two = run_clpc("compile -t my-mill --machines " + t.path("shop.toml") + " " + t.path("a.cls") + " " + t.path("b.cls"));
  EXPECT_EQ(two.status, 0) << two.err;
  EXPECT_TRUE(std::filesystem::exists(t.path("a.nc")));
  EXPECT_TRUE(std::filesystem::exists(t.path("b.nc")));
  RunResult set = run_clpc("compile --set units=inch " + t.path("a.cls") + " -t fanuc-mill -o " + t.path("inch.nc"));
  EXPECT_EQ(set.status, 0) << set.err;
  EXPECT_THAT(read_file(t.path("inch.nc")), HasSubstr("G20"));
  RunResult w = run_clpc("compile -W no-units " + t.path("a.cls") + " -t fanuc-mill -o " + t.path("w.nc"));
  EXPECT_EQ(w.status, 0) << w.err;
  RunResult empty = run_clpc("compile -t '' " + t.path("a.cls"));
  EXPECT_EQ(empty.status, 2);
  EXPECT_THAT(empty.err, HasSubstr("the machine name is empty"));
}

TEST(Cli, ErrorKeepsTheOldOutputAndLeavesNoTemporary) {
  TempDir t;
  write_file(t.path("bad.cls"), "UNITS/MM\nGOTO/1,2,3,4\n");
  write_file(t.path("bad.nc"), "old program\n");
  RunResult r = run_clpc("compile " + t.path("bad.cls") + " -t fanuc-mill");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, t.path("bad.cls") + ":2:12: error: GOTO needs 3 or 6 values (x,y,z[,i,j,k]), found 4\n 2 | GOTO/1,2,3,4\n   |            ^\n"
                   "clpc: 1 error, 0 warnings\n");
  EXPECT_EQ(read_file(t.path("bad.nc")), "old program\n");
  int files = 0;
  for (auto& e : std::filesystem::directory_iterator(std::filesystem::path(t.path("")))) files += e.is_regular_file();
  EXPECT_EQ(files, 2);  // bad.cls and bad.nc: no temporary left
}

TEST(Cli, NoOutputOnErrorToStdout) {
  RunResult r = run_clpc("compile - -t fanuc-mill -o -", "GOTO/1,2,3\nFOO/1\nGOTO/1,2\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_THAT(r.err, HasSubstr("<stdin>:2:1: warning: unknown record 'FOO'"));
  EXPECT_THAT(r.err, HasSubstr("<stdin>:3:9: error: GOTO needs 3 or 6 values"));
}

TEST(Cli, WerrorTurnsWarningsIntoErrors) {
  RunResult r = run_clpc("compile - -t fanuc-mill -o - --Werror", std::string(kSmall) + "FOO/1\n");
  EXPECT_EQ(r.status, 1);
  RunResult ok = run_clpc("compile - -t fanuc-mill -o -", std::string("FOO/1\n") + kSmall);
  EXPECT_EQ(ok.status, 0) << ok.err;
}

TEST(Cli, CheckWritesNothing) {
  TempDir t;
  write_file(t.path("p.cls"), kSmall);
  RunResult r = run_clpc("check " + t.path("p.cls"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_FALSE(std::filesystem::exists(t.path("p.nc")));
  RunResult bad = run_clpc("check -", "GOTO/1,2,3,4\n");
  EXPECT_EQ(bad.status, 1);
}

TEST(Cli, EmitIr) {
  RunResult r = run_clpc("compile - -t fanuc-mill --emit=ir", kSmall);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("program units mm\ntool T1 d 0 r 0\noperation 1 at 2:1\n  2:1\ttool-change T1\n"));
}

TEST(Cli, PrintAfterPass) {
  RunResult r = run_clpc("compile - -t fanuc-mill -o - --print-after=arc-direction",
                   "UNITS/MM\nLOAD/TOOL,1\nFEDRAT/100\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\n");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("; after arc-direction\n"));
  EXPECT_THAT(r.err, HasSubstr("arc ccw to (0, 10, 0)"));
}

TEST(Cli, MissingInputFile) {
  RunResult r = run_clpc("compile /nonexistent/x.cls -t fanuc-mill");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("cannot open '/nonexistent/x.cls'"));
}

TEST(Cli, UnknownMachine) {
  RunResult r = run_clpc("compile - -t nosuch", kSmall);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("no machine named 'nosuch'"));
  RunResult caps = run_clpc("compile - -t FANUC-MILL", kSmall);
  EXPECT_THAT(caps.err, HasSubstr("no machine named 'FANUC-MILL'; did you mean 'fanuc-mill'?"));
}

// A tolerance is a finite number above zero ("nan" passed CLI11's check and certified with
// the default); an unknown option is named even when INPUT is missing too.
TEST(Cli, OptionValuesAndUnknownOptionsAreSaidPlainly) {
  for (const char* v : {"nan", "-1", "0", "inf", "1e400", "2mm"}) {
    RunResult r = run_clpc(std::string("compile - -t fanuc-mill -o - --tolerance ") + v, kSmall);
    EXPECT_EQ(r.status, 2) << v;
    EXPECT_EQ(r.err, std::string("clpc: error: --tolerance: '") + v +
                         "' is not a number above zero\nRun 'clpc compile --help' for the options.\n");
  }
  EXPECT_EQ(run_clpc("compile - -t fanuc-mill -o - --axis-tolerance 0.02", kSmall).status, 0);
  RunResult bogus = run_clpc("compile --bogus");
  EXPECT_EQ(bogus.status, 2);
  EXPECT_EQ(bogus.err, "clpc: error: unknown option '--bogus'\nRun 'clpc compile --help' for the options.\n");
  RunResult slip = run_clpc("verify --tolerence=0.01");
  EXPECT_EQ(slip.err, "clpc: error: unknown option '--tolerence'; did you mean '--tolerance'?\nRun 'clpc verify --help' for the options.\n");
  RunResult missing = run_clpc("compile -t fanuc-mill");
  EXPECT_THAT(missing.err, HasSubstr("INPUT is required"));
  // An option's value that starts with '-' is its value, not an unknown option; as a file to
  // write it is refused (`-o --bogus part.cls` wrote a program named --bogus), ./-x.nc is taken.
  RunResult value = run_clpc("compile -t fanuc-mill -o -x.nc");
  EXPECT_EQ(value.status, 2);
  EXPECT_EQ(value.err, "clpc: error: --output: '-x.nc' looks like an option, not a file name (write ./-x.nc if it is "
                       "the file's name)\nRun 'clpc compile --help' for the options.\n");
  for (const char* args : {"compile - -t fanuc-mill -o --bogus", "verify - -t fanuc-mill --report -r.html",
                           "verify - -t fanuc-mill -o -p.nc", "plot - -t fanuc-mill -o -p.svg"})
    EXPECT_THAT(run_clpc(args, kSmall).err, HasSubstr("looks like an option, not a file name")) << args;
  TempDir dir;
  const std::string dashed = dir.path("-x.nc");
  EXPECT_EQ(run_clpc("compile - -t fanuc-mill -o " + dashed, kSmall).status, 0);
  EXPECT_THAT(read_file(dashed), HasSubstr("M30"));
  EXPECT_EQ(run_clpc("compile - -t fanuc-mill -o - --tolerance +0.01", kSmall).status, 0);
}

TEST(Cli, ExampleCompiles) {
  RunResult r = run_clpc(std::string("compile ") + CLPC_SOURCE_DIR + "/examples/bracket.cls -t haas-umc750 -o -");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("T2 M06"));
}

// A progress bar for large inputs, on a terminal only: under `script` (a pseudo-terminal) the
// compile shows its phases; with standard error a file, nothing but diagnostics.
TEST(Cli, ProgressBarOnlyOnATerminal) {
  TempDir t;
  std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,500\nRAPID\nGOTO/0,0,10\n";
  char line[64];
  for (int i = 0; i < 170000; ++i) {
    std::snprintf(line, sizeof line, "GOTO/%.4f,%.4f,-1.0000\n", (i % 100) * 0.5, (i / 100 % 100) * 0.5);
    cl += line;
  }
  cl += "FINI\n";
  ASSERT_GT(cl.size(), size_t(4) << 20);
  write_file(t.path("big.cls"), cl);
  const std::string args = "compile " + t.path("big.cls") + " -t fanuc-mill -o " + t.path("big.nc");
  RunResult quiet = run_clpc(args);
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.err, "clpc: certified " + t.path("big.nc") +
                           ": 170001 points, 0 arcs, 0 holes checked; max deviation 0.0000 mm; tolerance 0.0060 mm\n");
  const std::string typed = t.path("typescript");
  std::string cmd = "script -qfec '" + std::string(CLPC_BINARY) + " " + args + "' " + typed + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::string tty = read_file(typed);
  EXPECT_THAT(tty, HasSubstr("big.cls: pre-scan "));
  EXPECT_THAT(tty, HasSubstr("big.cls: compile  [==============================] 100%"));
  EXPECT_THAT(tty, HasSubstr("\r\033[K"));
}

// -j N: files compiled at once, each file's diagnostics whole and in input order, the status
// failing if any file fails, the good files written all the same.
TEST(Cli, ParallelCompileKeepsDiagnosticsInInputOrder) {
  TempDir t;
  const std::string good = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/MMPM,100\nGOTO/1,0,0\n";
  write_file(t.path("a.cls"), good + "PPRINT A\n");
  write_file(t.path("b.cls"), good + "GOTO/1,2,x\n");
  write_file(t.path("c.cls"), good + "SPINDL/RPM,1000,SIDEWAYS\n");
  write_file(t.path("d.cls"), good);
  RunResult r = run_clpc("compile " + t.path("a.cls") + " " + t.path("b.cls") + " " + t.path("c.cls") + " " + t.path("d.cls") +
                         " -t fanuc-mill -j 3");
  EXPECT_EQ(r.status, 1);
  const size_t b = r.err.find("b.cls:8:"), c = r.err.find("c.cls:8:");
  ASSERT_NE(b, std::string::npos) << r.err;
  ASSERT_NE(c, std::string::npos) << r.err;
  EXPECT_LT(b, c);
  EXPECT_TRUE(std::filesystem::exists(t.path("a.nc")));
  EXPECT_FALSE(std::filesystem::exists(t.path("b.nc")));
  EXPECT_TRUE(std::filesystem::exists(t.path("d.nc")));
  // The same programs as one at a time.
  TempDir u;
  write_file(u.path("a.cls"), good + "PPRINT A\n");
  ASSERT_EQ(run_clpc("compile " + u.path("a.cls") + " -t fanuc-mill").status, 0);
  EXPECT_EQ(read_file(t.path("a.nc")), read_file(u.path("a.nc")));
}
