// One schema of the machine keys (machine/schema.cpp): the reader takes kinds and ranges from
// it and refuses to read a key outside it, `clpc explain` lists exactly its keys, and the key
// reference of docs/machines.md names exactly its keys, with its types and placeholders.
#include <cstdlib>
#include <map>
#include <regex>
#include <set>

#include "helpers.h"
#include "machine/schema.h"

using namespace clpc;
using namespace clpc::test;

namespace {

using Keys = std::set<std::string>;  // "section.key" ("" section: ".key")

std::string id(std::string_view section, std::string_view key) { return std::string(section) + "." + std::string(key); }

// The keys explain prints: "key = value" lines under their section headers, the keys of the
// inline tables (address formats, travel), and each section header as its section's key.
Keys explained(const std::string& text, const std::string& name) {
  Keys keys;
  std::string section;
  std::istringstream in(text);
  std::regex header(R"(^\[\[?)" + name + R"(\.?([a-z._]*)\]\]?$)"), line(R"(^([A-Za-z_]+) = (.*)$)"), inline_key(R"(([a-z_]+) = )");
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_match(l, m, header)) {
      section = m[1];
      if (!section.empty()) keys.insert(id(section.substr(0, section.rfind('.') == std::string::npos ? 0 : section.rfind('.')),
                                           section.substr(section.rfind('.') == std::string::npos ? 0 : section.rfind('.') + 1)));
    } else if (std::regex_match(l, m, line)) {
      keys.insert(id(section, m[1].str()));
      const std::string value = m[2];
      if (value.rfind("{ ", 0) == 0) {
        const std::string inner = section == "format" || section == "feeds" ? "address" : section + "." + m[1].str();
        for (std::sregex_iterator it(value.begin(), value.end(), inline_key), end; it != end; ++it) keys.insert(id(inner, (*it)[1].str()));
      }
    }
  }
  return keys;
}

// The cells of a markdown table row ("\\|" inside a cell is no separator); empty if no row.
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  if (line.rfind("| ", 0) != 0) return out;
  std::string cell;
  for (size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '|' && line[i - 1] != '\\') {
      cell.erase(0, cell.find_first_not_of(' '));
      cell.erase(cell.find_last_not_of(' ') + 1);
      out.push_back(cell);
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return out;
}

Keys schema_keys(const Machine& m) {
  Keys keys;
  for (const KeySpec& k : machine_keys()) {
    const std::string top = std::string(k.section.substr(0, k.section.find('.')));
    const KeySpec* sec = k.section.empty() ? &k : find_key("", top);
    auto shown = [&](const KeySpec& s) {
      return s.shown == Shown::Always || (s.shown == Shown::Lathe && m.is_lathe()) ||
             (s.shown == Shown::Rotaries && m.kinematics.has_rotaries()) ||
             (s.shown == Shown::WhenGiven && s.value && !s.value(m, 0).empty());
    };
    if (!shown(k) || (sec && !shown(*sec))) continue;
    if (k.section == "kinematics.travel" && !m.kinematics.travel.set) continue;
    if (k.section == "address" && m.formats.empty()) continue;
    keys.insert(id(k.section, k.key));
  }
  return keys;
}

}  // namespace

TEST(Schema, ExplainListsExactlyTheKeysOfTheTable) {
  for (const char* name : {"haas-umc750", "fanuc-mill", "fanuc-lathe"}) {
    SCOPED_TRACE(name);
    const Machine m = machine(name);
    const Keys shown = explained(explain_machine(m), name), table = schema_keys(m);
    for (const std::string& k : table) EXPECT_TRUE(shown.count(k)) << k << " is in the table but explain does not show it";
    for (const std::string& k : shown) EXPECT_TRUE(table.count(k)) << k << " is shown by explain but not in the table";
  }
}

// What explain prints loads back as the same machine: every key it shows is one the reader
// reads, with the value it shows.
TEST(Schema, ExplainRoundTrips) {
  for (const char* name : {"haas-umc750", "fanuc-mill", "fanuc-lathe"}) {
    SCOPED_TRACE(name);
    const std::string once = explain_machine(machine(name));
    const Machine again = machine(name, once);  // the same name: replaces the built-in
    std::string twice = explain_machine(again);
    twice.replace(twice.find("# from "), twice.find('\n', twice.find("# from ")) - twice.find("# from "), "# from machines.toml (built-in)");
    EXPECT_EQ(twice, once);
  }
}

TEST(Schema, AKeyOutsideTheTableIsUnknownWithASuggestion) {
  EXPECT_THAT(machine_errors("[m]\nfamily = \"mill\"\n[m.arcs]\ntolerence = 0.01\n"),
              testing::HasSubstr("shop.toml:4:1: error: unknown key 'tolerence' in m.arcs; did you mean 'tolerance'?"));
}

TEST(Schema, RangesComeFromTheTable) {
  const KeySpec* step = find_key("sequence", "step");
  ASSERT_NE(step, nullptr);
  EXPECT_EQ(step->type_text(), "integer 1 to 100000");
  EXPECT_THAT(machine_errors("[m]\nfamily = \"mill\"\n[m.sequence]\nstep = 0\n"),
              testing::HasSubstr("m.sequence.step: expected an integer from 1 to 100000, found 0"));
  EXPECT_EQ(find_key("program", "optional_stop")->type_text(), "`\"off\"` \\| `\"tool-change\"` \\| `\"operation\"`");
}

// docs/machines.md: each "### `[NAME.section]`" key table names exactly the table's keys, with
// the type the table gives (the codes: the placeholders it allows). CLPC_UPDATE_DOCS=1 rewrites
// the type cells from the table (then review the diff).
TEST(Schema, TheDocsKeyReferenceMatchesTheTable) {
  const std::string doc = read_file(std::string(CLPC_SOURCE_DIR) + "/docs/machines.md");
  std::map<std::string, std::string> section_of = {
      {"Top level", ""}, {"`[NAME.format.L]`", "address"}, {"`[[NAME.kinematics.axes]]`", "kinematics.axes"}};
  std::string section = "-";
  Keys documented;
  const bool update = std::getenv("CLPC_UPDATE_DOCS") != nullptr;
  std::string rewritten;
  std::istringstream in(doc);
  std::regex heading(R"(^#+ (.*?)( — .*)?$)"), sect(R"(`\[NAME\.([a-z._]+)\]`)"),
      quoted_key("`([a-z_]+)`");
  for (std::string l; std::getline(in, l); rewritten += l + "\n") {
    std::smatch m;
    if (std::regex_match(l, m, heading)) {
      std::smatch s;
      const std::string title = m[1];
      section = section_of.count(title) ? section_of[title] : std::regex_search(title, s, sect) ? s[1].str() : "-";
      continue;
    }
    if (l.rfind("`[[NAME.kinematics.axes]]`", 0) == 0) section = "kinematics.axes";
    const std::vector<std::string> row = cells(l);
    if (section == "-" || row.size() < 2 || row[0].empty() || row[0][0] != '`') continue;
    std::vector<std::string> keys;
    const std::string& cell = row[0];
    for (std::sregex_iterator it(cell.begin(), cell.end(), quoted_key), end; it != end; ++it) keys.push_back((*it)[1]);
    std::vector<std::string> placeholders;  // the codes' second column: one part per key, or one for all
    const std::string second = row[1];
    if (update && section != "codes" && !keys.empty())
      if (const KeySpec* spec = find_key(section, keys[0]); spec && second != spec->type_text()) {
        const size_t at = l.find(" " + second + " |", row[0].size() + 2);
        if (at != std::string::npos) l.replace(at + 1, second.size(), spec->type_text());
      }
    if (section == "codes") {
      std::istringstream parts(second);
      for (std::string part; std::getline(parts, part, '/');) placeholders.push_back(part);
    }
    for (size_t k = 0; k < keys.size(); ++k) {
      const KeySpec* spec = find_key(section, keys[k]);
      if (!spec) {
        ADD_FAILURE() << "docs/machines.md documents " << section << "." << keys[k] << ", which is not in machine/schema.cpp";
        continue;
      }
      documented.insert(id(section, keys[k]));
      if (section == "codes") {
        std::set<std::string> want, got;
        for (int v = 0; v < int(Var::Count); ++v)
          if (spec->vars >> v & 1) want.insert(std::string(var_name(Var(v))));
        const std::string part = placeholders.size() == keys.size() ? placeholders[k] : placeholders.empty() ? "" : placeholders[0];
        for (std::sregex_iterator it(part.begin(), part.end(), quoted_key), end; it != end; ++it) got.insert((*it)[1]);
        EXPECT_EQ(got, want) << "placeholders of codes." << keys[k];
      } else {
        EXPECT_EQ(second, spec->type_text()) << "type of " << section << "." << keys[k];
      }
    }
  }
  if (update) write_file(std::string(CLPC_SOURCE_DIR) + "/docs/machines.md", rewritten);
  for (const KeySpec& k : machine_keys()) {
    if (k.kind == KeyKind::Table || k.section == "format") continue;  // sections: their headings
    EXPECT_TRUE(documented.count(id(k.section, k.key))) << k.section << "." << k.key << " has no row in docs/machines.md";
  }
}
