// libFuzzer target: the front end's bytes-to-records path (re2c lexer, Bison parser, the
// lexer's simple-record path and the pre-scan's skipping), on any bytes.
#include <cstdint>
#include <string>
#include <string_view>

#include "grammar/parse.h"

namespace {
struct Count : clpc::RecordSink {
  size_t n = 0;
  void record(const clpc::Record& r) override { n += r.params.size() + 1; }
};
}  // namespace

// An input that starts with 0xFF is the rest of it over and over, past 2.5 MB: several read
// windows, refills inside tokens and continuations.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  std::string big;
  if (size > 1 && data[0] == 0xFF) {
    text.remove_prefix(1);
    while (big.size() < 2560 * 1024) big.append(text);
    text = big;
  }
  for (bool simple : {true, false}) {
    clpc::SourceFile src;
    src.open_memory("fuzz.cls", text);
    clpc::Diagnostics d(nullptr);
    d.set_source(&src);
    Count c;
    try {
      clpc::ParseOptions o;
      o.simple_records = simple;
      clpc::parse_cl(src, d, c, o);
    } catch (const clpc::FatalError&) {
    }
    // A diagnostic's source line, as the real run would fetch it.
    (void)src.line_text(3);
  }
  clpc::SourceFile src;
  src.open_memory("fuzz.cls", text);
  clpc::MajorSet want;
  want.add(clpc::MajorId::Loadtl).add(clpc::MajorId::ToolPath).add(clpc::MajorId::Units).add(clpc::MajorId::Set);
  Count c;
  clpc::prescan_cl(src, c, want);
  return 0;
}
