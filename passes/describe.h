// The passes described from their PassInfo (passes/pass.h): as `clpc passes` prints them, and
// as the generated section of docs/passes.md (tests/passes/test_pass_docs.cpp keeps the two
// equal).
#pragma once

#include <string>

namespace clpc {

// Plain text, one block per pass.
std::string describe_passes();
// Markdown: the facts table and one section per pass.
std::string passes_markdown();

}  // namespace clpc
