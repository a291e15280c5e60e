// Golden files: each tests/golden/NAME.{cls,ncl} names the machines it is compiled for on its
// first line ("$$ golden: m1 m2 ..."); the whole output must equal NAME.MACHINE.nc.
// CLPC_UPDATE_GOLDEN=1 rewrites the expected files (then review the diff before committing).
#include <cstdlib>

#include "helpers.h"

using namespace clpc;
using namespace clpc::test;

namespace {

struct Case {
  std::string input, machine, expected;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  std::string dir = std::string(CLPC_SOURCE_DIR) + "/tests/golden";
  std::vector<std::string> inputs;
  for (auto& e : std::filesystem::directory_iterator(dir)) {
    auto ext = e.path().extension();
    if (ext == ".cls" || ext == ".ncl") inputs.push_back(e.path().string());
  }
  std::sort(inputs.begin(), inputs.end());
  for (const std::string& in : inputs) {
    std::string first = read_file(in).substr(0, read_file(in).find('\n'));
    const std::string tag = "$$ golden:";
    if (first.rfind(tag, 0) != 0) continue;
    std::istringstream names(first.substr(tag.size()));
    std::string m;
    std::string stem = in.substr(0, in.rfind('.'));
    while (names >> m) out.push_back({in, m, stem + "." + m + ".nc"});
  }
  return out;
}

}  // namespace

TEST(Golden, EveryCaseMatches) {
  auto all = cases();
  ASSERT_GE(all.size(), 1u);
  bool update = std::getenv("CLPC_UPDATE_GOLDEN") != nullptr;
  for (const Case& c : all) {
    SCOPED_TRACE(c.input + " for " + c.machine);
    Machine m = machine(c.machine);
    Compiled out = compile_path(c.input, m);
    ASSERT_TRUE(out.ok) << out.diags;
    // The source line names the file: make it independent of where the tree is.
    std::string text = out.output;
    if (update) {
      write_file(c.expected, text);
      continue;
    }
    ASSERT_TRUE(std::filesystem::exists(c.expected)) << "missing " << c.expected << " (CLPC_UPDATE_GOLDEN=1 makes it)";
    EXPECT_EQ(text, read_file(c.expected));
  }
}

// Whole programs from the corpus files the issues name (not copied here: read from
// ../shared/corpus, with the expected output in tests/golden/corpus).
TEST(Golden, CorpusPrograms) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"nist/turn_op10.ncl.4", "fanuc-lathe"},       {"nist/b_turn_1.ncl.1", "fanuc-lathe"},
      {"nist/b_turn_innr.ncl.4", "fanuc-lathe"},     {"nist/b_turn_groove2.ncl.1", "fanuc-lathe"},
      {"creopost/bohren_1.ncl.8", "fanuc-mill"},     {"creopost/bohren_1.ncl.8", "haas-umc750"},
  };
  bool update = std::getenv("CLPC_UPDATE_GOLDEN") != nullptr;
  for (const auto& [file, name] : cases) {
    SCOPED_TRACE(file + " for " + name);
    std::string base = file.substr(file.rfind('/') + 1);
    std::string expected = std::string(CLPC_SOURCE_DIR) + "/tests/golden/corpus/" + base + "." + name + ".nc";
    Machine m = machine(name);
    // bohren_1 drills at 9000 rpm: a UMC-750 with its 12,000 rpm spindle option.
    if (name == "haas-umc750") m.max_rpm = 12000;
    Compiled out = compile_path(corpus_dir() + "/" + file, m);
    ASSERT_TRUE(out.ok) << out.diags;
    if (update) {
      write_file(expected, out.output);
      continue;
    }
    ASSERT_TRUE(std::filesystem::exists(expected)) << "missing " << expected << " (CLPC_UPDATE_GOLDEN=1 makes it)";
    EXPECT_EQ(out.output, read_file(expected));
  }
}

// The schedule is how the pipeline runs, never what it writes: every golden case posted on one
// thread and on three, whole and with operations cut into chunks of 64 instructions (so the
// passes' state crosses chunks), gives the same program and the same diagnostics.
TEST(Golden, EverySchedulePostsTheSameProgram) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.input + " for " + c.machine);
    Machine m = machine(c.machine);
    CompileOptions threaded;
    threaded.schedule = Schedule::Threaded;
    Compiled reference = compile_path(c.input, m, threaded);
    ASSERT_TRUE(reference.ok) << reference.diags;
    for (Schedule s : {Schedule::Single, Schedule::Threaded}) {
      CompileOptions o;
      o.schedule = s;
      o.lower.chunk_size = 64;
      Compiled chunked = compile_path(c.input, m, o);
      EXPECT_EQ(chunked.output, reference.output) << (s == Schedule::Single ? "single" : "threaded") << ", chunks of 64";
      EXPECT_EQ(chunked.diags, reference.diags);
    }
    CompileOptions single;
    single.schedule = Schedule::Single;
    Compiled one = compile_path(c.input, m, single);
    EXPECT_EQ(one.output, reference.output) << "single, whole";
    EXPECT_EQ(one.diags, reference.diags);
  }
}
