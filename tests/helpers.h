// Helpers shared by the test files.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "machine/machine_loader.h"
#include "driver/driver.h"
#include "grammar/parse.h"
#include "support/diagnostics.h"
#include "lower/lower.h"
#include "lower/prescan.h"
#include "passes/pass.h"

namespace clpc::test {

// A file of the source tree, by its path from the top ("tests/tools/svg_check.py").
std::string source_path(const std::string& rel);
std::string read_file(const std::string& path);
void write_file(const std::string& path, const std::string& text);

// A fresh directory under the build tree's temp area, removed at exit of the test.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  std::filesystem::path dir_;
};

// Records of a CL text, as "line:col MAJOR/params" strings, and the diagnostics.
struct Parsed {
  std::vector<std::string> records;
  std::vector<Diagnostic> diags;
};
Parsed parse_text(const std::string& text);

// The IR of a CL text after lowering (and the given passes), printed; plus diagnostics.
struct Lowered {
  std::string ir;
  std::vector<Diagnostic> diags;
  std::vector<ir::Operation> ops;
  ir::ProgramInfo info;
};
Lowered lower_text(const std::string& text, const std::vector<std::string>& passes = {},
                   const Machine* machine = nullptr, std::optional<ir::Units> units = std::nullopt);

// A built-in machine (or one from extra TOML text).
Machine machine(const std::string& name, const std::string& extra_toml = {});
// Loads `toml` as the file "shop.toml" beside the built-ins and resolves `name` (the first
// table's name when empty): the diagnostics printed.
std::string machine_errors(const std::string& toml, std::string name = {});

// Compiles a CL text for a machine; output text and diagnostics (as printed).
struct Compiled {
  bool ok = false;
  std::string output;
  std::string diags;
};
Compiled compile_text(const std::string& cl, const Machine& m, CompileOptions opt = {});
Compiled compile_path(const std::string& path, const Machine& m, CompileOptions opt = {});
// Verifies a CL text (written as part.cl in a temporary directory) for `m`: clpc's own
// program, or `program` (G-code text) when given. ok, and the diagnostics as printed.
Compiled verify_text(const std::string& cl, const Machine& m, const std::string& program = {});

// Runs the clpc binary with arguments (shell-quoted by the caller); captures both streams.
struct RunResult {
  int status = -1;
  std::string out, err;
};
RunResult run_clpc(const std::string& args, const std::string& stdin_text = {});
// Runs a shell command line the same way.
RunResult run_shell(const std::string& command, const std::string& stdin_text = {});

// The corpus folder, or "" (tests then say so and skip).
std::string corpus_dir();
std::vector<std::string> corpus_files();          // every CL file
bool is_lathe_file(const std::string& path);      // turning data (MACHIN/TURN or XZ-only)
bool is_five_axis_file(const std::string& path);  // tool axis other than +Z somewhere

std::string first_error(const std::vector<Diagnostic>& d);
size_t count(const std::vector<Diagnostic>& d, Severity s);

}  // namespace clpc::test
