// libFuzzer target: the TOML machine loader (with the built-in machines to inherit from),
// resolving and explaining every machine the text defines, on any bytes.
#include <cstdint>
#include <string>

#include "machine/machine_loader.h"
#include "machine/schema.h"
#include "passes/pass.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  clpc::Diagnostics d(nullptr);
  clpc::MachineRegistry reg(clpc::pass_contracts());
  reg.load_builtin(d);
  if (!reg.load_text("fuzz.toml", text, d)) return 0;
  for (const auto& [name, description] : reg.list()) {
    clpc::Diagnostics r(nullptr);
    if (auto m = reg.resolve(name, r)) (void)clpc::explain_machine(*m);
  }
  return 0;
}
