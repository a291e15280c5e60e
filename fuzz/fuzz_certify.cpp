// libFuzzer target, differential: the bytes choose a random but valid CL program
// (fuzz/cl_generator.h) and a machine; the compile runs with its certificate on. The property:
// it fails with a located error, or it writes a program the certificate accepts. A compile
// that the certificate stops (the program did not follow the CL) is a finding: a pass or a
// backend wrote wrong motion, or verify failed a correct program. Either way, a bug to fix
// and a seed for tests/readback/test_differential.cpp.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <string>

#include "driver/driver.h"
#include "fuzz/cl_generator.h"
#include "machine/machine_loader.h"

namespace {

const clpc::Machine& machine(int i) {
  static const std::vector<clpc::Machine> m = [] {
    clpc::Diagnostics d(nullptr);
    clpc::MachineRegistry reg(clpc::pass_contracts());
    reg.load_builtin(d);
    std::vector<clpc::Machine> out;
    for (const char* n : {"fanuc-mill", "haas-umc750", "haas-umc750", "fanuc-lathe"}) out.push_back(*reg.resolve(n, d));
    return out;
  }();
  return m[size_t(i)];
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const int which = data[0] % 4;
  const clpc::fuzz::Family family = which == 2 ? clpc::fuzz::Family::FiveAxis
                                    : which == 3 ? clpc::fuzz::Family::Lathe
                                                 : clpc::fuzz::Family::Mill;
  clpc::fuzz::Choices c(data + 1, size - 1);
  const std::string cl = clpc::fuzz::ClGenerator(family).program(c);
  static const std::string out = "/tmp/clpc-fuzz-certify-" + std::to_string(getpid()) + ".nc";
  clpc::SourceFile src;
  src.open_memory("fuzz.cls", cl);
  clpc::CompileOptions o;
  o.certify = true;
  o.schedule = clpc::Schedule::Single;
  std::ostringstream err;
  clpc::CompileResult r = clpc::compile_source(src, out, machine(which), o, err);
  static const std::regex located(":[0-9]+:[0-9]+: error: ");
  const std::string e = err.str();
  if (r.ok ? !(r.certificate && r.certificate->ok)
           : (!std::regex_search(e, located) || e.find("the program does not follow the CL") != std::string::npos)) {
    std::fprintf(stderr, "finding on %s:\n%s\n%s\n", machine(which).name.c_str(), cl.c_str(), e.c_str());
    std::abort();
  }
  std::remove(out.c_str());
  return 0;
}
