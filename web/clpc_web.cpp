// clpc in the browser: the entry points the page (web/app.js) calls through Emscripten. The
// page puts the CL file (and a pasted machine file) into Emscripten's in-memory file system,
// calls clpc_post, and reads the program and the backplot back from there; nothing leaves
// the machine. The compile is clpc compile's own (driver/driver.h), certificate included,
// run without threads (support/threads.h): the program is the native build's, byte for byte.
#include <emscripten/emscripten.h>

#include <optional>
#include <sstream>
#include <string>

#include "driver/driver.h"
#include "machine/machine_loader.h"
#include "passes/pass.h"
#include "readback/plot.h"
#include "support/diagnostics.h"
#include "support/text.h"

using namespace clpc;

namespace {

std::string result;  // what the last call returns: it lives until the next call

bool load(MachineRegistry& reg, const char* machines_file, Diagnostics& d) {
  if (machines_file && *machines_file) return reg.load_builtin_and({machines_file}, d);
  return reg.load_builtin(d);
}

}  // namespace

extern "C" {

// The machines to choose from, one per line, "name<TAB>description": the built-in ones, and
// those of `machines_file` ("" for none). Problems in the file come after a line "errors".
EMSCRIPTEN_KEEPALIVE const char* clpc_machines(const char* machines_file) {
  std::ostringstream err;
  Diagnostics d(&err);
  MachineRegistry reg(pass_contracts());
  load(reg, machines_file, d);
  d.finish();
  std::string o;
  for (const auto& [name, description] : reg.list()) o += name + "\t" + description + "\n";
  if (!err.str().empty()) o += "errors\n" + err.str();
  result = o;
  return result.c_str();
}

// Posts `input` for `machine` into `output`, certified as clpc compile does, and draws the
// program into `svg` (when it was written). Returns JSON: {"ok": bool, "log": "what clpc
// compile writes on standard error: diagnostics, the certificate line, the totals"}.
EMSCRIPTEN_KEEPALIVE const char* clpc_post(const char* input, const char* machine, const char* machines_file, const char* output,
                                           const char* svg) {
  std::ostringstream err;
  bool ok = false;
  {
    Diagnostics d(&err);
    MachineRegistry reg(pass_contracts());
    std::optional<Machine> m;
    if (load(reg, machines_file, d)) m = reg.resolve(machine, d);
    d.finish();
    if (m) {
      CompileOptions opt;
      opt.certify = true;
      opt.schedule = Schedule::Single;
      CompileResult r = compile_file(input, output, *m, opt, err);
      err << totals_line(r.errors, r.warnings);
      ok = r.ok;
      if (ok) {
        std::ostringstream plot_err;  // a program that cannot be drawn is still a program
        plot_program(output, input, r.info, svg, *m, PlotOptions{}, plot_err);
      }
    }
  }
  result = std::string("{\"ok\": ") + (ok ? "true" : "false") + ", \"log\": " + json_text(err.str()) + "}";
  return result.c_str();
}

}  // extern "C"
