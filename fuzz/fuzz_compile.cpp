// libFuzzer target: the whole compile after the parser — pre-scan tables, lowering, every pass
// of each built-in machine's pipeline and its backend (output dropped) — on any bytes.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "backends/backend.h"
#include "machine/machine_loader.h"
#include "support/output.h"
#include "driver/pipeline.h"
#include "lower/prescan.h"

namespace {

const std::vector<clpc::Machine>& machines() {
  static const std::vector<clpc::Machine> m = [] {
    clpc::Diagnostics d(nullptr);
    clpc::MachineRegistry reg(clpc::pass_contracts());
    reg.load_builtin(d);
    std::vector<clpc::Machine> out;
    for (const char* n : {"haas-umc750", "fanuc-mill", "fanuc-lathe"}) out.push_back(*reg.resolve(n, d));
    return out;
  }();
  return m;
}

}  // namespace

// An input that starts with 0xFF is the rest of it over and over, past 1.5 MB: a file of several
// read windows (the lexer refills, its splices and text kept across them, operations in
// chunks), on one machine so that each run stays short.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  std::string big;
  const bool repeat = size > 1 && data[0] == 0xFF;
  if (repeat) {
    text.remove_prefix(1);
    while (big.size() < 1536 * 1024) big.append(text);
    text = big;
  }
  for (const clpc::Machine& m : machines()) {
    if (repeat && m.name != "fanuc-mill") continue;
    clpc::SourceFile src;
    src.open_memory("fuzz.cls", text);
    clpc::Diagnostics d(nullptr);
    d.set_source(&src);
    try {
      clpc::ir::ProgramInfo info = clpc::prescan_program(src, {});
      clpc::OutputFile out;
      out.open_null();
      auto be = clpc::make_backend(m, out, d);
      // The compile's own pipeline, on this thread, its IR checked after every pass.
      auto verify_ir = clpc::make_verify_ir();
      clpc::PipelineOptions po;
      po.schedule = clpc::Schedule::Single;
      po.instruments = {verify_ir.get()};
      clpc::Pipeline(m, m.pipeline, info, d, po).run(src, *be);
    } catch (const clpc::FatalError&) {
    }
  }
  return 0;
}
