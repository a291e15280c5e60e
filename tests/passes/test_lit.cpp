// IR-in / IR-out pass tests in the style of LLVM's lit and FileCheck: each
// tests/passes/lit/*.cls is a small CL file whose `$$` directive lines say what to run and
// what the IR must then look like, so one pass can be changed and checked alone:
//
//   $$ MACHINE: fanuc-mill              the machine (default fanuc-mill)
//   $$ PASSES: arc-direction, helix     the passes run after lowering, in order (none: lowering)
//   $$ CHECK: text                      a later line of the printed IR holds `text`
//   $$ CHECK-NEXT: text                 the line right after the last match holds it
//   $$ CHECK-NOT: text                  no line between the last match and the next holds it
//
// As in FileCheck, {{regex}} in a text matches a regular expression (e.g. a coordinate that
// is -1.2e-15 rather than 0); the rest matches as written.
// The printed IR is ir/printer.cpp's (what --print-after shows). Directive lines are blanked
// before lowering, so line numbers in the IR are the file's own.
#include <cstring>
#include <filesystem>
#include <regex>

#include "helpers.h"

using namespace clpc;
using namespace clpc::test;

namespace {

struct Check {
  enum Kind { Plain, Next, Not } kind;
  std::string text;
  int line;  // in the .cls file
};

// `text` as a regular expression: literal but for its {{regex}} parts.
std::regex pattern(const std::string& text) {
  std::string re;
  for (size_t at = 0; at < text.size();) {
    const size_t open = text.find("{{", at);
    const size_t close = open == std::string::npos ? open : text.find("}}", open + 2);
    const size_t literal_end = close == std::string::npos ? text.size() : open;
    for (size_t i = at; i < literal_end; ++i) {
      if (std::strchr("\\^$.|?*+()[]{}", text[i])) re += '\\';
      re += text[i];
    }
    if (close == std::string::npos) break;
    re += "(?:" + text.substr(open + 2, close - open - 2) + ")";
    at = close + 2;
  }
  return std::regex(re);
}

bool holds(const std::string& line, const Check& c) { return std::regex_search(line, pattern(c.text)); }

struct LitFile {
  std::string machine = "fanuc-mill";
  std::vector<std::string> passes;
  std::vector<Check> checks;
  std::string cl;  // directives blanked
};

std::string trim(std::string s) {
  s.erase(0, s.find_first_not_of(" \t"));
  s.erase(s.find_last_not_of(" \t\r") + 1);
  return s;
}

LitFile parse_lit(const std::string& text) {
  LitFile f;
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    auto directive = [&](const std::string& name) {
      const std::string key = "$$ " + name + ":";
      return line.rfind(key, 0) == 0 ? std::optional<std::string>(trim(line.substr(key.size()))) : std::nullopt;
    };
    if (auto v = directive("MACHINE")) {
      f.machine = *v;
    } else if (auto p = directive("PASSES")) {
      std::istringstream names(*p);
      for (std::string name; std::getline(names, name, ',');)
        if (!trim(name).empty()) f.passes.push_back(trim(name));
    } else if (auto c = directive("CHECK")) {
      f.checks.push_back({Check::Plain, *c, n});
    } else if (auto c = directive("CHECK-NEXT")) {
      f.checks.push_back({Check::Next, *c, n});
    } else if (auto c = directive("CHECK-NOT")) {
      f.checks.push_back({Check::Not, *c, n});
    } else {
      f.cl += line;
    }
    f.cl += "\n";
  }
  return f;
}

// FileCheck's rules, for substrings: failures as "file:line: message".
std::vector<std::string> file_check(const std::vector<Check>& checks, const std::string& output, const std::string& file) {
  std::vector<std::string> lines, failures;
  std::istringstream in(output);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  size_t at = 0;  // the next line a CHECK may match
  bool matched = false;
  std::vector<const Check*> nots;
  auto where = [&](const Check& c) { return file + ":" + std::to_string(c.line) + ": "; };
  for (const Check& c : checks) {
    if (c.kind == Check::Not) {
      nots.push_back(&c);
      continue;
    }
    size_t found = lines.size();
    if (c.kind == Check::Next) {
      if (!matched) failures.push_back(where(c) + "CHECK-NEXT with no CHECK before it");
      else if (at < lines.size() && holds(lines[at], c)) found = at;
      else failures.push_back(where(c) + "CHECK-NEXT: '" + c.text + "' is not on the next line: '" + (at < lines.size() ? lines[at] : "<end>") + "'");
    } else {
      for (size_t i = at; i < lines.size(); ++i)
        if (holds(lines[i], c)) {
          found = i;
          break;
        }
      if (found == lines.size()) failures.push_back(where(c) + "CHECK: '" + c.text + "' not found after IR line " + std::to_string(at + 1));
    }
    if (found == lines.size()) return failures;
    for (const Check* k : nots)
      for (size_t i = at; i < found; ++i)
        if (holds(lines[i], *k)) failures.push_back(where(*k) + "CHECK-NOT: '" + k->text + "' found: '" + lines[i] + "'");
    nots.clear();
    at = found + 1;
    matched = true;
  }
  for (const Check* k : nots)
    for (size_t i = at; i < lines.size(); ++i)
      if (holds(lines[i], *k)) failures.push_back(where(*k) + "CHECK-NOT: '" + k->text + "' found: '" + lines[i] + "'");
  return failures;
}

std::vector<std::string> lit_files() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(CLPC_SOURCE_DIR) + "/tests/passes/lit"))
    if (e.path().extension() == ".cls") files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  return files;
}

class Lit : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(Lit, IrAfterThePasses) {
  const std::string file = "tests/passes/lit/" + GetParam();
  const LitFile f = parse_lit(read_file(std::string(CLPC_SOURCE_DIR) + "/" + file));
  ASSERT_FALSE(f.checks.empty()) << file << ": no CHECK lines";
  for (const std::string& p : f.passes) ASSERT_NE(find_pass(p), nullptr) << file << ": no pass named '" << p << "'";
  const Machine m = machine(f.machine);
  const Lowered l = lower_text(f.cl, f.passes, &m);
  for (const std::string& failure : file_check(f.checks, l.ir, file)) ADD_FAILURE() << failure << "\nIR:\n" << l.ir;
}

INSTANTIATE_TEST_SUITE_P(Passes, Lit, ::testing::ValuesIn(lit_files()), [](const auto& info) {
  std::string name = info.param.substr(0, info.param.find('.'));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

// The checker itself: a check that does not hold fails, with the line of the check.
TEST(LitChecker, FailsWhereTheIrDiffers) {
  const std::string ir = "a 1\nb 2\nc 3\n";
  EXPECT_TRUE(file_check({{Check::Plain, "a", 1}, {Check::Next, "b", 2}, {Check::Not, "x", 3}, {Check::Plain, "c", 4}}, ir, "f").empty());
  EXPECT_EQ(file_check({{Check::Plain, "a", 1}, {Check::Next, "c", 2}}, ir, "f"),
            std::vector<std::string>{"f:2: CHECK-NEXT: 'c' is not on the next line: 'b 2'"});
  EXPECT_EQ(file_check({{Check::Plain, "c", 1}, {Check::Plain, "a", 2}}, ir, "f"),
            std::vector<std::string>{"f:2: CHECK: 'a' not found after IR line 4"});
  EXPECT_EQ(file_check({{Check::Plain, "a", 1}, {Check::Not, "b", 2}, {Check::Plain, "c", 3}}, ir, "f"),
            std::vector<std::string>{"f:2: CHECK-NOT: 'b' found: 'b 2'"});
  EXPECT_EQ(file_check({{Check::Plain, "b", 1}, {Check::Not, "c", 2}}, ir, "f"),
            std::vector<std::string>{"f:2: CHECK-NOT: 'c' found: 'c 3'"});
  EXPECT_TRUE(file_check({{Check::Plain, "b {{[0-9]}}", 1}, {Check::Next, "c (3)", 2}}, "b 2\nc (3)\n", "f").empty());
  EXPECT_FALSE(file_check({{Check::Plain, "b {{[a-z]}}", 1}}, ir, "f").empty());
}
