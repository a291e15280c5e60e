// Bad input, run through the real binary: every case gets a compiler-style diagnostic with its
// location, exit status 1, and no output file — never a crash, a hang or a half-written
// program. And the output is safe: a compile killed while it writes leaves the old program
// intact, its temporary file removed at once (SIGTERM, SIGPIPE) or by the next run (SIGKILL).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <random>
#include <regex>
#include <thread>
#include <vector>

#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

struct Outcome {
  int status = -1;
  std::string err;
  bool output_written = false;
  bool temp_left = false;
};

// Compiles `name` (written with `bytes`) for fanuc-mill in a fresh directory, with a time
// limit: a hang fails the test instead of stalling the suite.
Outcome compile_bytes(const std::string& name, const std::string& bytes, const std::string& extra = {}) {
  TempDir t;
  write_file(t.path(name), bytes);
  std::string out = t.path("out.nc");
  RunResult r = run_clpc("compile " + t.path(name) + " -t fanuc-mill -o " + out + " " + extra);
  Outcome o;
  o.status = r.status;
  o.err = r.err;
  o.output_written = std::filesystem::exists(out);
  for (auto& e : std::filesystem::directory_iterator(t.path("")))
    if (e.path().filename().string().find(".clpc-") != std::string::npos) o.temp_left = true;
  return o;
}

// The common verdict: refused with a located error, nothing written.
void expect_refused(const Outcome& o, const std::string& located_error) {
  EXPECT_EQ(o.status, 1) << o.err;
  EXPECT_THAT(o.err, HasSubstr(located_error));
  EXPECT_FALSE(o.output_written);
  EXPECT_FALSE(o.temp_left);
  EXPECT_EQ(o.err.find("Sanitizer"), std::string::npos) << o.err;
}

const std::string kHead = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\n";

}  // namespace

TEST(BadInput, EmptyFile) { expect_refused(compile_bytes("empty.cls", ""), "empty.cls:1:1: error: the file is empty"); }

// A G-code program where the CL is due: one error at its first block that says what the file is
// (not one for the '%' and a warning per block); a CL file whose first lines look like blocks is
// still CL data once a record shows.
TEST(BadInput, AGcodeProgramIsNamedForWhatItIs) {
  Outcome o = compile_bytes("part.nc", "%\nO1234 (PART)\n! ISO comment\nN10 G21 G17 G40 G80 G90\nN20 T1 M06\nN30 G00 X0. Y0.\n"
                                       "N40 G43 H1 Z5.\nN50 G01 Z-1. F100.\nM30\n%\n");
  expect_refused(o, "part.nc:2:1: error: this is a G-code program ('O1234 (PART)'), not CL data: clpc reads the "
                    "cutter-location file a CAM system writes (APT, CLSF) and makes the program; to check a program "
                    "against its CL: clpc verify PART.cls --program ");
  EXPECT_THAT(o.err, HasSubstr("clpc: 1 error, 0 warnings"));
  Outcome cl = compile_bytes("blocks_then_cl.cls", "X1 Y2\nG1 X3\nM3 S100\n" + kHead + "GOTO/0,0,5\nGOTO/10,0,5\nFINI\n");
  EXPECT_THAT(cl.err, ::testing::Not(HasSubstr("G-code program"))) << cl.err;
}

// Windows editors write a UTF-8 byte-order mark: read past, columns counted after it (and the
// source line shown without it). UTF-16 text is refused at 1:1 with what to do.
TEST(BadInput, ByteOrderMarks) {
  Outcome utf8 = compile_bytes("bom.cls", "\xEF\xBB\xBF" + kHead + "FROM/0,0,5\nGOTO/1.2.3,0,5\nFINI\n");
  expect_refused(utf8, "bom.cls:6:6: error: GOTO: expected a number, found '1.2.3'\n 6 | GOTO/1.2.3,0,5\n");
  EXPECT_THAT(utf8.err, HasSubstr("clpc: 1 error, 0 warnings"));  // UNITS/MM on the first line was read
  Outcome first = compile_bytes("bom1.cls", "\xEF\xBB\xBFQUUX/1\n" + kHead);
  EXPECT_THAT(first.err, HasSubstr("bom1.cls:1:1: warning: unknown record 'QUUX' (passed through as a comment) "
                                   "[-Wunknown-record]\n 1 | QUUX/1\n"));
  std::string wide = "\xFF\xFE";
  for (char c : kHead) wide += std::string{c, '\0'};
  expect_refused(compile_bytes("wide.cls", wide),
                 "wide.cls:1:1: error: the file is UTF-16 text (it starts with the byte-order mark FF FE): clpc reads "
                 "CL data as ASCII or UTF-8; save the file as UTF-8 or ASCII");
}

// DOS's end-of-file mark (Ctrl-Z) at the very end is no text; anywhere else it is a byte no
// record may hold.
TEST(BadInput, DosEndOfFileMark) {
  Outcome end = compile_bytes("dos.cls", kHead + "GOTO/0,0,5\r\nGOTO/10,0,5\r\nFINI\r\n\x1A\x1A");
  EXPECT_EQ(end.status, 0) << end.err;
  EXPECT_TRUE(end.output_written);
  EXPECT_THAT(end.err, HasSubstr("clpc: certified "));
  expect_refused(compile_bytes("mid.cls", kHead + "GOTO/0,0,5\n\x1A\nGOTO/10,0,5\nFINI\n"),
                 "mid.cls:6:1: error: expected a major word at the start of a record, found byte 0x1A");
}

// Lines that end in CR alone (classic Mac OS) are lines: the program is the one the LF file
// makes, a free-text record ends at its CR, and an error is located on its own line.
TEST(BadInput, ClassicMacLineEnds) {
  const std::string lf = kHead + "PPRINT/ROUGH, THEN FINISH\nGOTO/0,0,5\nGOTO/10,0,5\nGOTO/10,10,5\nFINI\n";
  std::string cr = lf;
  std::replace(cr.begin(), cr.end(), '\n', '\r');
  TempDir lf_dir, cr_dir;  // the same file name: the programs name their source
  write_file(lf_dir.path("part.cls"), lf);
  write_file(cr_dir.path("part.cls"), cr);
  for (TempDir* d : {&lf_dir, &cr_dir}) {
    RunResult r = run_clpc("compile " + d->path("part.cls") + " -t fanuc-mill -o " + d->path("part.nc"));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const std::string program = read_file(cr_dir.path("part.nc"));
  EXPECT_EQ(program, read_file(lf_dir.path("part.nc")));
  EXPECT_THAT(program, HasSubstr("(ROUGH, THEN FINISH)\nN50 G54 G00 X0. Y0.\nN60 G43 H01 G94 G01 Z5. F100.\nN70 X10.\nN80 Y10.\n"));

  std::string bad = kHead + "GOTO/0,0,5\nGOTO/1.2.3,0,5\nFINI\n";
  std::replace(bad.begin(), bad.end(), '\n', '\r');
  Outcome o = compile_bytes("bad.cls", bad);
  expect_refused(o, "bad.cls:6:6: error: GOTO: expected a number, found '1.2.3'");
  EXPECT_THAT(o.err, HasSubstr(" 6 | GOTO/1.2.3,0,5\n"));
  // In a file with LF line ends a lone CR stays a blank, as before.
  Outcome mixed = compile_bytes("mixed.cls", kHead + "GOTO/0,0,5\r\nGOTO/10,\r0,5\nFINI\n");
  EXPECT_EQ(mixed.status, 0) << mixed.err;
}

TEST(BadInput, BinaryGarbage) {
  std::mt19937 rng(11);
  std::string bytes(64 * 1024, '\0');
  for (char& c : bytes) c = char(rng() & 0xFF);
  const size_t first_nul = bytes.find('\0');
  const std::string first_line = bytes.substr(0, first_nul);
  const size_t line = size_t(std::count(first_line.begin(), first_line.end(), '\n')) + 1;
  const size_t col = first_nul - (first_line.rfind('\n') == std::string::npos ? size_t(-1) : first_line.rfind('\n'));
  Outcome o = compile_bytes("garbage.cls", bytes);
  expect_refused(o, "garbage.cls:" + std::to_string(line) + ":" + std::to_string(col) +
                        ": error: a binary file (NUL bytes from here on), not CL data: clpc reads CL data as text");
  EXPECT_THAT(o.err, HasSubstr("clpc: 1 error, 0 warnings"));
  // Without NUL bytes it is text, read as such: an error per bad line, up to the limit.
  for (char& c : bytes)
    if (c == '\0') c = 'x';
  Outcome text = compile_bytes("garbage.cls", bytes);
  expect_refused(text, "garbage.cls:1:1: error:");
  EXPECT_TRUE(std::regex_search(text.err, std::regex("garbage\\.cls:[0-9]+:[0-9]+: error: ")));
  EXPECT_THAT(text.err, HasSubstr("fatal: too many errors (50), stopping"));
}

TEST(BadInput, TenMegabyteLine) {
  expect_refused(compile_bytes("word.cls", std::string(10 << 20, 'A') + "\n"),
                 "word.cls:1:1: error: line too long: a word, number or text of more than 65536 characters");
  std::string numbers = "GOTO/1.5";
  while (numbers.size() < size_t(10 << 20)) numbers += ",1.5";
  expect_refused(compile_bytes("numbers.cls", kHead + numbers + "\n"), "numbers.cls:5:16390: error: record has more than 4096 parameters");
}

TEST(BadInput, NulBytes) {
  expect_refused(compile_bytes("nul.cls", kHead + std::string("GOTO/1,2\0,3\n", 12)), "nul.cls:5:9: error: unexpected NUL byte in a record");
}

// Comments and text are UTF-8; a byte of a one-byte code page (CAMWorks writes Windows code
// pages) is a warning at its place, which names the way to say so: text carries no motion.
TEST(BadInput, InvalidUtf8InComments) {
  const std::string cl = kHead + "$$ caf\xE9 cr\xE8me\nPPRINT bad \xFF text\nRAPID\nGOTO/1,2,3\nGOTO/4,5,6\n";
  Outcome o = compile_bytes("utf8.cls", cl);
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_THAT(o.err, HasSubstr("utf8.cls:5:7: warning: invalid UTF-8 in a comment: byte 0xE9, read as a one-byte code page "
                               "(--input-encoding latin1 says so for the file)"));
  EXPECT_THAT(o.err, HasSubstr("utf8.cls:6:12: warning: invalid UTF-8 in a text: byte 0xFF"));
  EXPECT_THAT(compile_bytes("utf8.cls", cl, "--Werror").status, 1);
  Outcome ok = compile_bytes("utf8.cls", cl, "--input-encoding latin1");
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_EQ(ok.err.find("invalid UTF-8"), std::string::npos);
  EXPECT_TRUE(ok.output_written);
  // Valid UTF-8 is fine as it is.
  EXPECT_EQ(compile_bytes("ok.cls", kHead + "$$ caf\xC3\xA9\nRAPID\nGOTO/1,2,3\n").status, 0);
}

TEST(BadInput, NumbersThatAreNot) {
  expect_refused(compile_bytes("a.cls", kHead + "GOTO/1e999,0,0\n"), "a.cls:5:6: error: number out of range: '1e999'");
  expect_refused(compile_bytes("b.cls", kHead + "GOTO/nan,0,0\n"), "b.cls:5:6: error: GOTO: expected a number, found 'nan'");
  expect_refused(compile_bytes("c.cls", kHead + "GOTO/--1,0,0\n"), "c.cls:5:6: error: GOTO: expected a number, found '--1'");
  expect_refused(compile_bytes("d.cls", kHead + "GOTO/1.2.3,0,0\n"), "d.cls:5:6: error: GOTO: expected a number, found '1.2.3'");
  expect_refused(compile_bytes("e.cls", kHead + "GOTO/inf,0,0\n"), "e.cls:5:6: error: GOTO: expected a number, found 'inf'");
}

TEST(BadInput, CircleWithoutGoto) {
  expect_refused(compile_bytes("circle.cls", kHead + "GOTO/0,0,0\nCIRCLE/0,0,0,0,0,1,5,0.01,0.5,10,0\nFINI\n"),
                 "circle.cls:6:1: error: CIRCLE is not followed by a GOTO giving its end point");
}

// Motion before the first tool in a file that loads tools later; a file that loads none is
// refused at its first cut (a rapid alone positions the spindle, cutting needs the length
// offset of a loaded tool).
TEST(BadInput, GotoBeforeAnyToolIsLoaded) {
  expect_refused(compile_bytes("notool.cls", "UNITS/MM\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nGOTO/1,0,0\nLOADTL/1\nSPINDL/RPM,100,CLW\nGOTO/2,0,0\n"),
                 "notool.cls:5:1: error: motion before any tool is loaded; the file loads T1 at line 6 later");
  // A rapid there is where the tool starts (CATIA writes its start point before the first tool).
  Outcome start = compile_bytes("start.cls", "UNITS/MM\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nLOADTL/1\nSPINDL/RPM,100,CLW\nGOTO/2,0,0\n");
  EXPECT_EQ(start.status, 0) << start.err;
  EXPECT_THAT(start.err, HasSubstr("start.cls:4:1: warning: rapid motion before the first tool change (T1 at line 5) is taken as "
                                   "the start point (as FROM): no motion is written for it"));
  expect_refused(compile_bytes("none.cls", "UNITS/MM\nSPINDL/RPM,100,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nGOTO/1,0,0\n"),
                 "none.cls:6:1: error: cutting with no tool loaded: the CL loads none before this move (LOADTL, LOAD/TOOL, "
                 "TURRET), so no tool length offset is in force; add LOADTL/n before it, or have the CAM system write its "
                 "tool change");
  // An arc or a drilled hole is a cut too.
  expect_refused(compile_bytes("arc.cls", "UNITS/MM\nSPINDL/RPM,100,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/10,0,0\n"
                                          "CIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\n"),
                 "arc.cls:6:1: error: cutting with no tool loaded");
  expect_refused(compile_bytes("hole.cls", "UNITS/MM\nSPINDL/RPM,100,CLW\nRAPID\nGOTO/10,0,5\nCYCLE/DRILL,DEPTH,5,CLEAR,2,MMPM,50\n"
                                           "GOTO/10,0,0\nCYCLE/OFF\n"),
                 "hole.cls:6:1: error: cutting with no tool loaded");
}

TEST(BadInput, ContinuationAtEndOfFile) {
  expect_refused(compile_bytes("dollar.cls", kHead + "GOTO/1,2,$"), "dollar.cls:5:10: error: unterminated continuation: '$' at the end of the file");
}

TEST(BadInput, UnterminatedOperation) {
  expect_refused(compile_bytes("cut.cls", "UNITS/MM\nTOOL PATH/ROUGH,TOOL,EM10\nLOAD/TOOL,1\nSPINDL/RPM,100,CLW\nRAPID\nGOTO/0,0,5\n"),
                 "cut.cls:2:1: error: TOOL PATH/ROUGH has no END-OF-PATH: the file ends inside the operation (was it cut short?)");
  expect_refused(compile_bytes("sub.cls", kHead + "DEFSUB/1\nGOTO/1,2,3\n"), "sub.cls:5:1: error: DEFSUB/1 has no ENDSUB");
}

TEST(BadInput, NestedSubroutineDefinitions) {
  expect_refused(compile_bytes("nested.cls", kHead + "DEFSUB/1\nGOTO/1,2,3\nDEFSUB/2\nGOTO/1,2,3\nENDSUB\nENDSUB\nCALSUB/1\n"),
                 "nested.cls:7:1: error: DEFSUB inside DEFSUB/1: subroutine definitions cannot nest");
}

// Machine descriptions: an inheritance cycle and absurd values, each at its line and column.
TEST(BadInput, MachineDescriptions) {
  TempDir t;
  write_file(t.path("part.cls"), kHead + "RAPID\nGOTO/1,2,3\n");
  auto run = [&](const std::string& name, const std::string& toml, const std::string& target) {
    write_file(t.path(name), toml);
    return run_clpc("compile " + t.path("part.cls") + " -t " + target + " --machines " + t.path(name) + " -o " + t.path("out.nc"));
  };
  RunResult cycle = run("cycle.toml", "[a]\ninherits = \"b\"\n[b]\ninherits = \"a\"\n", "a");
  EXPECT_EQ(cycle.status, 1);
  EXPECT_THAT(cycle.err, HasSubstr("cycle.toml:4:12: error: b.inherits: inheritance cycle: a -> b -> a"));
  RunResult neg = run("neg.toml", "[m]\ninherits = \"fanuc-mill\"\n[m.format]\nX = { decimals = -2 }\n", "m");
  EXPECT_EQ(neg.status, 1);
  EXPECT_THAT(neg.err, HasSubstr("neg.toml:4:18: error: m.format.X.decimals: expected an integer from 0 to 9, found -2"));
  RunResult minmax = run("minmax.toml",
                         "[m]\ninherits = \"haas-umc750\"\n[[m.kinematics.axes]]\nname = \"A\"\naxis = [1.0, 0.0, 0.0]\nmin = 90.0\nmax = -90.0\n", "m");
  EXPECT_EQ(minmax.status, 1);
  EXPECT_THAT(minmax.err, HasSubstr("minmax.toml:7:7: error: m.kinematics.axes[0].max: must be more than min (90)"));
  RunResult huge = run("huge.toml", "[m]\ninherits = \"fanuc-mill\"\n[m.arcs]\ntolerance = 1e300\n", "m");
  EXPECT_EQ(huge.status, 1);
  EXPECT_THAT(huge.err, HasSubstr("huge.toml:4:13: error: m.arcs.tolerance: expected a number at least 1e-06 and at most 1000, found 1e+300"));
  EXPECT_FALSE(std::filesystem::exists(t.path("out.nc")));
}

// More mistakes than the error limit (found by fuzz_machine: clpc used to abort). Refused like
// one mistake, the first ones reported with their places, then the stop.
TEST(BadInput, MachineDescriptionWithMoreErrorsThanTheLimit) {
  TempDir t;
  std::string toml = "[m]\ninherits = \"fanuc-mill\"\n";
  for (int i = 0; i < 60; ++i) toml += "typo" + std::to_string(i) + " = 1\n";
  write_file(t.path("typos.toml"), toml);
  write_file(t.path("part.cls"), kHead + "GOTO/0,0,0\n");
  for (const std::string& command : std::vector<std::string>{"explain m", "compile " + t.path("part.cls") + " -t m -o " + t.path("out.nc")}) {
    SCOPED_TRACE(command);
    RunResult r = run_clpc(command + " --machines " + t.path("typos.toml"));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr("typos.toml:3:1: error: unknown key 'typo0' in m"));
    EXPECT_THAT(r.err, HasSubstr("typos.toml: fatal: too many errors (50), stopping\n"));
    EXPECT_EQ(r.err.find("terminate"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  EXPECT_FALSE(std::filesystem::exists(t.path("out.nc")));
}

// --- output safety ---------------------------------------------------------------------------

namespace {

// A CL file big enough that writing its program takes a while (about 60 MB in).
std::string big_cl() {
  std::string s = kHead + "RAPID\nGOTO/0,0,10\n";
  char b[64];
  for (int i = 0; s.size() < size_t(60) << 20; ++i) {
    std::snprintf(b, sizeof b, "GOTO/%.4f,%.4f,-1.0000\n", (i % 1000) * 0.1, (i / 1000 % 1000) * 0.1);
    s += b;
  }
  return s;
}

bool temp_beside(const std::string& dir) {
  for (auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string().find(".clpc-") != std::string::npos) return true;
  return false;
}

// Starts clpc on `in` -> `out`, waits until its temporary output exists, kills it with `sig`.
void kill_while_writing(const std::string& in, const std::string& out, const std::string& dir, int sig) {
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    int devnull = open("/dev/null", O_WRONLY);
    dup2(devnull, 2);
    execl(CLPC_BINARY, "clpc", "compile", in.c_str(), "-t", "fanuc-mill", "-o", out.c_str(), nullptr);
    _exit(127);
  }
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!temp_beside(dir) && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // well into the writing
  kill(pid, sig);
  int st = 0;
  waitpid(pid, &st, 0);
  EXPECT_TRUE(WIFSIGNALED(st)) << "clpc finished before it could be killed";
}

}  // namespace

TEST(OutputSafety, KilledMidWriteLeavesTheOldProgram) {
  TempDir t;
  const std::string dir = t.path(""), in = t.path("big.cls"), out = t.path("part.nc");
  write_file(in, big_cl());
  const std::string old_program = "%\nO0001 (THE PROGRAM FROM YESTERDAY)\nM30\n%\n";
  write_file(out, old_program);

  // SIGTERM: the handler removes the temporary file before clpc dies.
  kill_while_writing(in, out, dir, SIGTERM);
  EXPECT_EQ(read_file(out), old_program);
  EXPECT_FALSE(temp_beside(dir));

  // SIGKILL cannot be caught: the temporary file stays, the old program is intact, and the
  // next run writing beside it removes the dead run's leftovers.
  kill_while_writing(in, out, dir, SIGKILL);
  EXPECT_EQ(read_file(out), old_program);
  EXPECT_TRUE(temp_beside(dir));
  write_file(t.path("small.cls"), kHead + "RAPID\nGOTO/1,2,3\n");
  RunResult next = run_clpc("compile " + t.path("small.cls") + " -t fanuc-mill -o " + out);
  EXPECT_EQ(next.status, 0) << next.err;
  EXPECT_FALSE(temp_beside(dir));
  EXPECT_THAT(read_file(out), HasSubstr("X1. Y2."));
}

TEST(OutputSafety, RefusesToOverwriteItsInput) {
  TempDir t;
  write_file(t.path("part.cls"), kHead + "RAPID\nGOTO/1,2,3\n");
  RunResult r = run_clpc("compile " + t.path("part.cls") + " -t fanuc-mill -o " + t.path("part.cls"));
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("is the input file; refusing to overwrite it"));
  EXPECT_EQ(read_file(t.path("part.cls")), kHead + "RAPID\nGOTO/1,2,3\n");
}

// A file truncated, appended to or rewritten while it is read is not posted: the program
// would be what was read of it (a 10-million-GOTO file cut to 40% mid-compile was certified).
TEST(OutputSafety, AFileThatChangesWhileItIsReadIsNotPosted) {
  TempDir t;
  const std::string cl = t.path("part.cls");
  write_file(cl, kHead + "RAPID\nGOTO/1,2,3\n");
  SourceFile src;
  std::string why;
  ASSERT_TRUE(src.open(cl, why)) << why;
  EXPECT_FALSE(src.changed_since_open());
  write_file(cl, kHead + "RAPID\nGOTO/1,2,3\nGOTO/1,2,4\n");
  EXPECT_TRUE(src.changed_since_open());
  std::ostringstream err;
  CompileResult r = compile_source(src, t.path("part.nc"), machine("fanuc-mill"), CompileOptions{}, err);
  EXPECT_FALSE(r.ok);
  EXPECT_THAT(err.str(), HasSubstr("error: the file changed while it was read (its size or modification time is not what "
                                   "it was when the compile began)"));
  EXPECT_FALSE(std::filesystem::exists(t.path("part.nc")));
}

// The file at the output path: a read-only one (a proven program a shop protected) is not
// replaced; one replaced keeps its permissions; a symbolic link is written through, to the
// file it names (renamed over, the link became a file and the target kept the old program).
TEST(OutputSafety, TheFileThereKeepsItsProtectionItsModeAndItsLinks) {
  TempDir t;
  const std::string cl = t.path("part.cls");
  write_file(cl, kHead + "RAPID\nGOTO/1,2,3\nFEDRAT/100\nGOTO/10,2,3\n");
  write_file(t.path("proven.nc"), "OLD\n");
  chmod(t.path("proven.nc").c_str(), 0444);
  RunResult ro = run_clpc("compile " + cl + " -t fanuc-mill -o " + t.path("proven.nc"));
  EXPECT_EQ(ro.status, 1);
  EXPECT_THAT(ro.err, HasSubstr("error: cannot write '" + t.path("proven.nc") + "': it is read-only (write-protected); "
                                "refusing to replace it"));
  EXPECT_EQ(read_file(t.path("proven.nc")), "OLD\n");
  write_file(t.path("shared.nc"), "OLD\n");
  chmod(t.path("shared.nc").c_str(), 0640);
  ASSERT_EQ(run_clpc("compile " + cl + " -t fanuc-mill -o " + t.path("shared.nc")).status, 0);
  struct stat st {};
  ASSERT_EQ(stat(t.path("shared.nc").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  write_file(t.path("target.nc"), "OLD\n");
  ASSERT_EQ(symlink("target.nc", t.path("link.nc").c_str()), 0);
  ASSERT_EQ(run_clpc("compile " + cl + " -t fanuc-mill -o " + t.path("link.nc")).status, 0);
  ASSERT_EQ(lstat(t.path("link.nc").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_THAT(read_file(t.path("target.nc")), HasSubstr("G01 X10."));
  ASSERT_EQ(symlink("nowhere.nc", t.path("dangling.nc").c_str()), 0);
  RunResult dangling = run_clpc("compile " + cl + " -t fanuc-mill -o " + t.path("dangling.nc"));
  EXPECT_EQ(dangling.status, 1);
  EXPECT_THAT(dangling.err, HasSubstr("it is a symbolic link to 'nowhere.nc', which does not exist"));
}

// Every command refuses to replace a file the run reads: plot's -o (or its default name, for
// an input called part.svg), verify's --report and -o onto the CL or onto the program it
// checks (each destroyed its input, exit 0).
TEST(OutputSafety, NoCommandOverwritesAFileItReads) {
  TempDir t;
  const std::string cl = t.path("part.cls"), text = kHead + "RAPID\nGOTO/1,2,3\nFEDRAT/100\nGOTO/10,2,3\n";
  write_file(cl, text);
  const std::string refuses = "is a file this run reads (the CL, or the program checked or drawn); refusing to overwrite it";
  for (const std::string& args : {"plot -t fanuc-mill " + cl + " -o " + cl, "verify -t fanuc-mill " + cl + " --report " + cl,
                                  "verify -t fanuc-mill " + cl + " -o " + cl}) {
    RunResult r = run_clpc(args);
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_THAT(r.err, HasSubstr(refuses)) << args;
    EXPECT_EQ(read_file(cl), text) << args;
  }
  // Standard input redirected from the file, and the machine file the run reads.
  RunResult stdin_cl = run_clpc("compile -t fanuc-mill - -o " + cl + " < " + cl);
  EXPECT_EQ(stdin_cl.status, 1);
  EXPECT_THAT(stdin_cl.err, HasSubstr(refuses));
  EXPECT_EQ(read_file(cl), text);
  write_file(t.path("shop.toml"), "[my-mill]\ninherits = \"fanuc-mill\"\n");
  RunResult toml = run_clpc("compile " + cl + " --machines " + t.path("shop.toml") + " -t my-mill -o " + t.path("shop.toml"));
  EXPECT_EQ(toml.status, 1);
  EXPECT_EQ(read_file(t.path("shop.toml")), "[my-mill]\ninherits = \"fanuc-mill\"\n");
  write_file(t.path("drawn.svg"), text);
  RunResult svg = run_clpc("plot -t fanuc-mill " + t.path("drawn.svg"));
  EXPECT_EQ(svg.status, 1);
  EXPECT_EQ(read_file(t.path("drawn.svg")), text);
  ASSERT_EQ(run_clpc("compile " + cl + " -t fanuc-mill -o " + t.path("hand.nc")).status, 0);
  const std::string hand = read_file(t.path("hand.nc"));
  for (const std::string& args : {"verify -t fanuc-mill " + cl + " --program " + t.path("hand.nc") + " -o " + t.path("hand.nc"),
                                  "verify -t fanuc-mill " + cl + " --program " + t.path("hand.nc") + " --report " + t.path("hand.nc"),
                                  "plot -t fanuc-mill " + cl + " --program " + t.path("hand.nc") + " -o " + t.path("hand.nc")}) {
    RunResult r = run_clpc(args);
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_THAT(r.err, HasSubstr(refuses)) << args;
    EXPECT_EQ(read_file(t.path("hand.nc")), hand) << args;
  }
}

// verify's files: a report that cannot be written fails the run (it exited 0); -o gets the
// program only once it passes (a failing one replaced the file there), and `-o -` writes it
// to standard output with the report on standard error (it failed, reading back '-').
TEST(OutputSafety, VerifyWritesItsFilesOnlyWhenAllIsWell) {
  TempDir t;
  const std::string cl = t.path("part.cls");
  write_file(cl, kHead + "RAPID\nGOTO/1,2,3\nFEDRAT/100\nGOTO/10,2,3\n");
  RunResult report = run_clpc("verify -t fanuc-mill " + cl + " --report " + t.path("nodir/r.html"));
  EXPECT_EQ(report.status, 1);
  EXPECT_THAT(report.err, HasSubstr("error: cannot create the output in '" + t.path("nodir") + "'"));
  // Said before any work: no report that says PASS above an output that cannot be written.
  RunResult keep = run_clpc("verify -t fanuc-mill " + cl + " -o " + t.path("nodir/p.nc"));
  EXPECT_EQ(keep.status, 1);
  EXPECT_THAT(keep.out + keep.err, Not(HasSubstr("PASS")));
  EXPECT_THAT(keep.err, HasSubstr("error: cannot create the output in '" + t.path("nodir") + "'"));
  RunResult onto_cl = run_clpc("verify -t fanuc-mill - --report " + cl + " < " + cl);
  EXPECT_EQ(onto_cl.status, 1);
  EXPECT_THAT(onto_cl.err, HasSubstr("is a file this run reads"));
  ASSERT_EQ(run_clpc("compile " + cl + " -t fanuc-mill -o " + t.path("hand.nc")).status, 0);
  std::string wrong = read_file(t.path("hand.nc"));
  wrong.replace(wrong.find("X10."), 4, "X11.");
  write_file(t.path("wrong.nc"), wrong);
  write_file(t.path("keep.nc"), "OLD\n");
  RunResult fails = run_clpc("verify -t fanuc-mill " + cl + " --program " + t.path("wrong.nc") + " -o " + t.path("keep.nc"));
  EXPECT_EQ(fails.status, 1);
  EXPECT_THAT(fails.err, HasSubstr("error: the program does not pass: it is not written to '" + t.path("keep.nc") + "'"));
  EXPECT_EQ(read_file(t.path("keep.nc")), "OLD\n");
  RunResult out = run_clpc("verify -t fanuc-mill " + cl + " -o -");
  EXPECT_EQ(out.status, 0) << out.err;
  EXPECT_EQ(out.out, read_file(t.path("hand.nc")));
  EXPECT_THAT(out.err, HasSubstr("result: PASS"));
}

// Diagnostics piped into a reader that goes away (clpc compile ... 2>&1 | head -1): the run
// dies of SIGPIPE as any program would, and leaves no temporary file beside the target; an
// older program there stays as it was.
TEST(OutputSafety, ASigpipeOnTheDiagnosticsLeavesNoTemporaryFile) {
  TempDir t;
  std::string cl = kHead;
  for (int i = 0; i < 20000; ++i) cl += "FOOBAR/" + std::to_string(i) + "\nGOTO/" + std::to_string(i % 50) + ",0,0\n";
  write_file(t.path("big.cls"), cl + "FINI\n");
  write_file(t.path("big.nc"), "the older program\n");
  RunResult r = run_shell("bash -c '" + std::string(CLPC_BINARY) + " compile " + t.path("big.cls") + " -t fanuc-mill -o " +
                          t.path("big.nc") + " 2>&1 | head -1 >/dev/null; echo ${PIPESTATUS[0]}'");
  EXPECT_EQ(r.out, "141\n") << r.err;  // 128 + SIGPIPE
  EXPECT_EQ(read_file(t.path("big.nc")), "the older program\n");
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::directory_iterator(t.path("")))
    left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"big.cls", "big.nc"}));
}

// A pipe or a device (-o /dev/null) is written to, never renamed over: a rename would put a
// regular file where the device was.
TEST(OutputSafety, APipeIsWrittenToNotReplaced) {
  TempDir t;
  write_file(t.path("part.cls"), kHead + "RAPID\nGOTO/1,2,3\n");
  ASSERT_EQ(mkfifo(t.path("pipe").c_str(), 0600), 0);
  const std::string cmd = "cat '" + t.path("pipe") + "' > '" + t.path("got") + "' & " + CLPC_BINARY + " compile '" +
                          t.path("part.cls") + "' -t fanuc-mill -o '" + t.path("pipe") + "' 2>'" + t.path("err") + "'; s=$?; wait; exit $s";
  const int st = std::system(("sh -c \"" + std::regex_replace(cmd, std::regex("\""), "\\\"") + "\"").c_str());
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << read_file(t.path("err"));
  // The certificate, and no "replaced" note: nothing was replaced.
  EXPECT_EQ(read_file(t.path("err")), "clpc: certified " + t.path("pipe") +
                                          ": 1 points, 0 arcs, 0 holes checked; max deviation 0.0000 mm; tolerance 0.0060 mm\n");
  struct stat s {};
  ASSERT_EQ(stat(t.path("pipe").c_str(), &s), 0);
  EXPECT_TRUE(S_ISFIFO(s.st_mode));
  EXPECT_THAT(read_file(t.path("got")), HasSubstr("X1. Y2."));
  RunResult dir = run_clpc("compile " + t.path("part.cls") + " -t fanuc-mill -o " + t.path(""));
  EXPECT_EQ(dir.status, 1);
  EXPECT_THAT(dir.err, HasSubstr("it is a directory"));
}
