// libFuzzer target: the whole compile after the parser — pre-scan tables, lowering, every pass
// of each built-in machine's pipeline and its backend (output dropped) — on any bytes.
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "backends/backend.h"
#include "backends/machine_loader.h"
#include "backends/output.h"
#include "grammar/parse.h"
#include "ir/lower.h"
#include "ir/tables.h"
#include "ir/verify.h"
#include "passes/pass_manager.h"

namespace {

const std::vector<clpc::Machine>& machines() {
  static const std::vector<clpc::Machine> m = [] {
    clpc::Diagnostics d(nullptr);
    clpc::MachineRegistry reg(clpc::pass_names());
    reg.load_builtin(d);
    std::vector<clpc::Machine> out;
    for (const char* n : {"haas-umc750", "fanuc-mill", "fanuc-lathe"}) out.push_back(*reg.resolve(n, d));
    return out;
  }();
  return m;
}

struct Run : clpc::OperationSink {
  clpc::PassManager& pm;
  clpc::Backend& be;
  clpc::Diagnostics& d;
  Run(clpc::PassManager& p, clpc::Backend& b, clpc::Diagnostics& dd) : pm(p), be(b), d(dd) {}
  void operation(clpc::ir::Operation& op) override {
    pm.run(op);
    if (!d.has_errors()) be.operation(op);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  for (const clpc::Machine& m : machines()) {
    clpc::SourceFile src;
    src.open_memory("fuzz.cls", text);
    clpc::Diagnostics d(nullptr);
    d.set_source(&src);
    try {
      clpc::ir::ProgramInfo info = clpc::prescan_program(src, {});
      clpc::OutputFile out;
      out.open_null();
      auto be = clpc::make_backend(m, out, d);
      clpc::PassContext ctx{info, m, d};
      clpc::PassManager pm(ctx, m.pipeline, {}, nullptr, /*verify=*/true);
      pm.begin();
      be->begin(info);
      Run run(pm, *be, d);
      clpc::Lowerer low(info, d, run);
      clpc::parse_cl(src, d, low);
      low.finish();
      if (!d.has_errors()) be->end();
    } catch (const clpc::FatalError&) {
    }
  }
  return 0;
}
