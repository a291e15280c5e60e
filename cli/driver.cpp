#include "cli/driver.h"

#include <sys/stat.h>

#include <iostream>

#include "backends/backend.h"
#include "backends/output.h"
#include "cli/progress.h"
#include "grammar/parse.h"
#include "ir/lower.h"
#include "ir/printer.h"
#include "ir/tables.h"
#include "passes/pass_manager.h"

namespace clpc {

namespace {

// Writes the IR as text instead of G-code (--emit=ir).
class IrBackend : public Backend {
 public:
  explicit IrBackend(OutputFile& out) : out_(out) {}
  void begin(const ir::ProgramInfo& info) override {
    std::ostringstream o;
    ir::print_header(o, info);
    out_.write(o.str());
  }
  void operation(const ir::Operation& op) override {
    std::ostringstream o;
    ir::print_operation(o, op);
    out_.write(o.str());
  }
  void end() override {}

 private:
  OutputFile& out_;
};

class NullBackend : public Backend {
 public:
  void begin(const ir::ProgramInfo&) override {}
  void operation(const ir::Operation&) override {}
  void end() override {}
};

class Pipeline : public OperationSink {
 public:
  Pipeline(PassManager& pm, Backend& be, Diagnostics& d) : pm_(pm), be_(be), d_(d) {}
  void operation(ir::Operation& op) override {
    for (const ir::Instr& in : op.body)
      if (std::holds_alternative<ir::Move>(in.op) || std::holds_alternative<ir::Arc>(in.op)) {
        motion_ = true;
        break;
      }
    pm_.run(op);
    // After an error no output is written: skip the backend's work.
    if (!d_.has_errors()) be_.operation(op);
  }
  bool motion_ = false;

 private:
  PassManager& pm_;
  Backend& be_;
  Diagnostics& d_;
};

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (stat(a.c_str(), &sa) != 0 || stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace

std::string default_output(const std::string& input, const Machine& machine) {
  if (input == "-") return "-";
  size_t slash = input.rfind('/');
  size_t dot = input.find('.', slash == std::string::npos ? 0 : slash + 1);
  std::string stem = dot == std::string::npos ? input : input.substr(0, dot);
  return stem + machine.extension;
}

CompileResult compile_file(const std::string& input, const std::string& output, const Machine& machine,
                           const CompileOptions& opt, std::ostream& err) {
  SourceFile src;
  std::string why;
  if (!src.open(input, why)) {
    err << "clpc: error: " << why << "\n";
    CompileResult res;
    res.errors = 1;
    return res;
  }
  return compile_source(src, output, machine, opt, err);
}

CompileResult compile_source(SourceFile& src, const std::string& output, const Machine& machine, const CompileOptions& opt,
                             std::ostream& err) {
  CompileResult res;
  const std::string& input = src.name();
  std::string why;
  Diagnostics d(&err);
  d.set_werror(opt.werror);
  d.set_source(&src);
  Progress progress(input, src.size(), opt.progress);
  if (progress.active()) {
    src.on_progress([&](uint64_t at) { progress.update(at); });
    d.set_before_print([&] { progress.clear(); });
  }
  struct Detach {
    SourceFile& s;
    ~Detach() { s.on_progress(nullptr); }
  } detach{src};
  if (output != "-" && input != "-" && same_file(input, output)) {
    err << "clpc: error: the output '" << output << "' is the input file; refusing to overwrite it\n";
    res.errors = 1;
    return res;
  }

  OutputFile out;
  try {
    PrescanOptions po;
    po.units = opt.input_units;
    progress.phase("pre-scan");
    ir::ProgramInfo info = prescan_program(src, po);
    if (src.size() == 0) {
      d.error({}, "the file is empty");
      throw FatalError{};
    }
    if (!info.units_given) d.warning({}, info.units_reason + " (use --input-units to say)");
    if (info.lathe && !machine.is_lathe() && opt.emit == Emit::Gcode)
      d.warning({}, "the CL data is for a lathe (MACHIN/TURN) but machine '" + machine.name + "' is a mill");
    if (opt.emit != Emit::Nothing && !out.open(output, why)) {
      err << "clpc: error: " << why << "\n";
      res.errors = 1;
      return res;
    }
    std::unique_ptr<Backend> be;
    if (opt.emit == Emit::Gcode) be = make_backend(machine, out, d);
    else if (opt.emit == Emit::Ir) be = std::make_unique<IrBackend>(out);
    else be = std::make_unique<NullBackend>();

    PassContext ctx{info, machine, d};
    PassManager pm(ctx, machine.pipeline, opt.print_after, opt.print_after.empty() ? nullptr : &err, opt.verify_ir);
    pm.begin();
    be->begin(info);
    Pipeline pipe(pm, *be, d);
    Lowerer low(info, d, pipe);
    progress.phase("compile");
    parse_cl(src, d, low);
    low.finish();
    progress.clear();
    if (!pipe.motion_ && !d.has_errors()) d.error({}, "nothing to post: the file has no motion (GOTO, CIRCLE, ...)");
    if (!d.has_errors()) be->end();
    res.info = std::move(info);
  } catch (const FatalError&) {
  }
  d.finish();
  res.errors = d.error_count();
  res.warnings = d.warning_count();
  if (d.has_errors()) {
    out.discard();
    return res;
  }
  if (opt.emit != Emit::Nothing && !out.commit(why)) {
    err << "clpc: error: " << why << "\n";
    res.errors = 1;
    return res;
  }
  res.ok = true;
  return res;
}

}  // namespace clpc
