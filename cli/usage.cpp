#include "cli/usage.h"

#include <algorithm>

#include "support/suggest.h"

namespace clpc {

namespace {

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best = closest(word, candidates);
  return best.empty() ? std::string() : "; did you mean '" + best + "'?";
}

// The options of a (sub)command, as a user types them.
std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* s : app.get_subcommands({})) names.push_back(s->get_name());
  return names;
}

// The words of `s` after `marker` (CLI11's "... not expected: a b").
std::vector<std::string> words_after(const std::string& s, const std::string& marker) {
  std::vector<std::string> out;
  size_t at = s.find(marker);
  if (at == std::string::npos) return out;
  std::string rest = s.substr(at + marker.size());
  size_t i = 0;
  while (i < rest.size()) {
    while (i < rest.size() && rest[i] == ' ') ++i;
    size_t j = rest.find(' ', i);
    if (j == std::string::npos) j = rest.size();
    if (j > i) out.push_back(rest.substr(i, j - i));
    i = j;
  }
  return out;
}

// The words of argv after the command that look like options (`-x`, `--xyz`, `--xyz=v`) and
// name none of its options. "-" alone is standard input. An option's value that starts with a
// '-' (`--tolerance -1`) is taken for an option only if it names none; CLI11 reports such
// values itself, so this list is used only when CLI11's error says nothing more precise.
std::vector<std::string> unknown_options(const CLI::App& sub, int argc, char** argv) {
  const std::vector<std::string> known = option_names(sub);
  // The options that take a value: the word after them is that value (`-o -x.nc`).
  std::vector<std::string> with_value;
  for (const CLI::Option* o : sub.get_options())
    if (o->get_type_size() != 0) {
      for (const std::string& l : o->get_lnames()) with_value.push_back("--" + l);
      for (const std::string& n : o->get_snames()) with_value.push_back("-" + n);
    }
  std::vector<std::string> out;
  for (int i = 2; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--") break;
    if (a.size() < 2 || a[0] != '-' || (a[1] >= '0' && a[1] <= '9') || a[1] == '.') continue;
    const bool glued = a.find('=') != std::string::npos || (a[1] != '-' && a.size() > 2);
    if (size_t eq = a.find('='); eq != std::string::npos) a.resize(eq);
    // Short options take their value glued on (-tfanuc-mill, -Wno-approach): the first two
    // characters name the option.
    const std::string name = a[1] == '-' ? a : a.substr(0, 2);
    if (std::find(known.begin(), known.end(), name) == known.end()) out.push_back(a);
    else if (!glued && std::find(with_value.begin(), with_value.end(), name) != with_value.end()) ++i;
  }
  return out;
}

}  // namespace

void short_help(const CLI::App& app, std::ostream& out) {
  out << "clpc - a CNC postprocessor: CL data (APT/CLSF) in, G-code out\n\nusage: clpc COMMAND [OPTIONS]\n\n";
  for (const CLI::App* s : app.get_subcommands({})) {
    std::string name = s->get_name();
    out << "  " << name << std::string(name.size() < 10 ? 10 - name.size() : 1, ' ') << s->get_description() << "\n";
  }
  out << "\n  clpc compile part.cls -t haas-umc750     the main job\n"
         "  clpc COMMAND --help                      a command's options\n";
}

int report_parse_error(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv, std::ostream& out,
                       std::ostream& err) {
  if (e.get_exit_code() == 0) return app.exit(e, out, err);  // --help, --version
  if (argc <= 1) {
    short_help(app, out);
    return 2;
  }
  // The command the user meant to run, if argv names one.
  const CLI::App* sub = nullptr;
  const std::string first = argv[1];
  for (const CLI::App* s : app.get_subcommands({}))
    if (s->get_name() == first) sub = s;
  const std::string what = e.what();
  std::string msg;
  if (!sub && !first.empty() && first[0] != '-') {
    msg = "unknown command '" + first + "'" + did_you_mean(first, command_names(app));
  } else if (dynamic_cast<const CLI::RequiredError*>(&e) && sub && !unknown_options(*sub, argc, argv).empty()) {
    // CLI11 checks what is required before what is unknown: `compile --bogus` said "INPUT is
    // required". The unknown option is the mistake to name.
    for (const std::string& x : unknown_options(*sub, argc, argv)) {
      if (!msg.empty()) msg += "\nclpc: error: ";
      msg += "unknown option '" + x + "'" + did_you_mean(x, option_names(*sub));
    }
  } else if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    const CLI::App& in = sub ? *sub : app;
    for (const std::string& x : words_after(what, "expected: ")) {
      if (!msg.empty()) msg += "\nclpc: error: ";
      if (x.size() > 1 && x[0] == '-') msg += "unknown option '" + x + "'" + did_you_mean(x, option_names(in));
      else msg += "unexpected argument '" + x + "'";
    }
    if (msg.empty()) msg = what;
  } else if (size_t at = what.find(" not in {"); at != std::string::npos && what.back() == '}') {
    // "--emit: gcdoe not in {gcode,ir}"
    size_t colon = what.find(": ");
    std::string opt = colon == std::string::npos ? std::string() : what.substr(0, colon);
    std::string value = what.substr(colon == std::string::npos ? 0 : colon + 2, at - (colon == std::string::npos ? 0 : colon + 2));
    std::vector<std::string> allowed;
    std::string list = what.substr(at + 9, what.size() - at - 10);
    for (size_t i = 0; i <= list.size();) {
      size_t j = list.find(',', i);
      if (j == std::string::npos) j = list.size();
      allowed.push_back(list.substr(i, j - i));
      i = j + 1;
    }
    std::string joined;
    for (const std::string& a : allowed) joined += (joined.empty() ? "" : ", ") + a;
    msg = opt + ": '" + value + "' is not one of " + joined + did_you_mean(value, allowed);
  } else {
    msg = what;
  }
  err << "clpc: error: " << msg << "\n";
  err << "Run 'clpc " << (sub ? sub->get_name() + " " : std::string()) << "--help' for the options.\n";
  return 2;
}

}  // namespace clpc
