// Usage errors as a compiler gives them: "clpc: error: ..." with the closest option, command or
// value the user may have meant, and the short help when clpc is run with nothing.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace clpc {

// Writes the diagnostic for a command-line error CLI11 raised (help and version requests are
// printed as they are); returns the exit status.
int report_parse_error(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv, std::ostream& out,
                       std::ostream& err);

// What `clpc` alone prints: the commands, one line each.
void short_help(const CLI::App& app, std::ostream& out);

}  // namespace clpc
