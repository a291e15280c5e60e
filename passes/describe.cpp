#include "passes/describe.h"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "passes/pass.h"

namespace clpc {

namespace {

// "  label:     text", the text wrapped at 100 columns under itself.
void field(std::ostringstream& o, std::string_view label, std::string_view text) {
  const size_t indent = 14, width = 100;
  std::string line = "  " + std::string(label) + ":";
  line.resize(indent, ' ');
  size_t col = indent;
  bool first = true;
  for (size_t at = 0; at < text.size();) {
    size_t end = text.find(' ', at);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view word = text.substr(at, end - at);
    if (!first && col + 1 + word.size() > width) {
      o << line << "\n";
      line.assign(indent, ' ');
      col = indent;
      first = true;
    }
    if (!first) {
      line += ' ';
      ++col;
    }
    line += word;
    col += word.size();
    first = false;
    at = end + 1;
  }
  o << line << "\n";
}

}  // namespace

std::string describe_passes() {
  std::ostringstream o;
  for (const PassInfo& p : all_passes()) {
    o << p.name << ": " << p.summary << "\n";
    field(o, "expects", p.expects);
    field(o, "guarantees", p.guarantees);
    field(o, "reads", p.settings);
    field(o, "requires", ir::fact_names(p.needs));
    field(o, "provides", ir::fact_names(p.provides));
    if (p.breaks) field(o, "breaks", ir::fact_names(p.breaks));
  }
  return o.str();
}

std::string passes_markdown() {
  std::ostringstream o;
  o << "### Facts\n\n| fact | made by | a machine needs it | --verify-ir checks |\n|---|---|---|---|\n";
  for (const ir::FactInfo& f : ir::all_facts()) {
    std::string provided;
    for (const PassInfo& p : all_passes())
      if (p.provides & f.fact) provided += (provided.empty() ? "" : ", ") + std::string("`") + std::string(p.name) + "`";
    o << "| `" << f.name << "` | " << provided << " | " << f.why << " | "
      << (f.checked.empty() ? "(only the pass can tell)" : f.checked) << " |\n";
  }
  for (const PassInfo& p : all_passes()) {
    std::string summary(p.summary), file(p.name);
    if (!summary.empty()) summary[0] = char(std::toupper(static_cast<unsigned char>(summary[0])));
    std::replace(file.begin(), file.end(), '-', '_');
    o << "\n### " << p.name << "\n\n*" << summary << ".* (`passes/" << file << ".cpp`)\n\n";
    o << "- Expects: " << p.expects << ".\n";
    o << "- Guarantees: " << p.guarantees << ".\n";
    o << "- Reads: " << p.settings << ".\n";
    o << "- Requires " << ir::fact_names(p.needs) << "; provides " << ir::fact_names(p.provides);
    if (p.breaks) o << "; breaks " << ir::fact_names(p.breaks);
    o << ".";
    if (p.costly) o << " The threaded schedule splits the pipeline after it.";
    o << "\n";
  }
  return o.str();
}

}  // namespace clpc
