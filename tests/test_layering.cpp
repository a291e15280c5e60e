// The layering rule of docs/design.md, held against the code: every #include of a project
// folder must be one the including folder's row of the table allows.
#include <regex>

#include "helpers.h"

using namespace clpc::test;

namespace {

namespace fs = std::filesystem;

// docs/design.md's "| `folder/` | `a/`, `b/` |" rows: folder -> the folders it may include.
std::map<std::string, std::set<std::string>> allowed_includes() {
  std::map<std::string, std::set<std::string>> out;
  std::istringstream doc(read_file(std::string(CLPC_SOURCE_DIR) + "/docs/design.md"));
  const std::regex row(R"(^\| `([a-z]+)/` \| (.*) \|$)");
  const std::regex folder("`([a-z]+)/`");
  std::string line;
  while (std::getline(doc, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    std::set<std::string>& may = out[m[1]];
    const std::string rest = m[2];
    for (std::sregex_iterator it(rest.begin(), rest.end(), folder), end; it != end; ++it) may.insert((*it)[1]);
  }
  return out;
}

}  // namespace

TEST(Layering, TheTableNamesEveryLayer) {
  const auto allowed = allowed_includes();
  for (const char* layer : {"support", "grammar", "ir", "lower", "machine", "passes", "backends", "readback", "driver", "cli"})
    EXPECT_TRUE(allowed.count(layer)) << layer << " has no row in docs/design.md";
  // Every source folder of the house is a layer of the table.
  for (const auto& e : fs::directory_iterator(CLPC_SOURCE_DIR)) {
    if (!e.is_directory()) continue;
    const std::string name = e.path().filename().string();
    bool has_sources = false;
    for (const auto& f : fs::directory_iterator(e.path()))
      has_sources = has_sources || f.path().extension() == ".cpp" || f.path().extension() == ".h";
    const bool outside = name == "tests" || name == "bench" || name == "fuzz" || name == "build" || name[0] == '.';
    if (has_sources && !outside) {
      EXPECT_TRUE(allowed.count(name)) << name << "/ holds sources but is no layer of docs/design.md";
    }
  }
}

TEST(Layering, NoIncludeRunsUpTheLayers) {
  const auto allowed = allowed_includes();
  ASSERT_FALSE(allowed.empty()) << "no layer table in docs/design.md";
  const std::regex include(R"(^\s*#\s*include\s*"([a-z]+)/)");
  int files = 0;
  for (const auto& [layer, may] : allowed) {
    const fs::path dir = fs::path(CLPC_SOURCE_DIR) / layer;
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".cpp" && ext != ".h" && ext != ".re" && ext != ".y") continue;
      ++files;
      std::istringstream text(read_file(e.path().string()));
      std::string line;
      for (int n = 1; std::getline(text, line); ++n) {
        std::smatch m;
        if (!std::regex_search(line, m, include)) continue;
        const std::string to = m[1];
        if (to != layer && !may.count(to))
          ADD_FAILURE() << layer << "/" << e.path().filename().string() << ":" << n << ": includes " << to
                        << "/, which docs/design.md does not let " << layer << "/ use: " << line;
      }
    }
  }
  EXPECT_GT(files, 100);
}
