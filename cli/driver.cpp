#include "cli/driver.h"

#include <sys/stat.h>

#include <iostream>

#include "backends/backend.h"
#include "backends/output.h"
#include "cli/stages.h"
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
      d.error({1, 1}, "the file is empty");
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

    // The passes report into a deferred Diagnostics, replayed here in order: the same
    // whether they run on this thread (printing the IR between passes) or their own.
    Diagnostics pass_diags(nullptr);
    pass_diags.set_source(&src);
    pass_diags.set_deferred(true);
    PassContext ctx{info, machine, pass_diags};
    PassManager pm(ctx, machine.pipeline, opt.print_after, opt.print_after.empty() ? nullptr : &err, opt.verify_ir);
    pm.begin();
    for (const Diagnostics::Deferred& x : pass_diags.take_deferred()) d.replay(x);
    be->begin(info);
    Backend& backend = *be;
    bool motion = false;
    auto write = [&](Piece& p) {
      for (const Diagnostics::Deferred& x : p.diags) d.replay(x);
      if (p.end) return false;
      for (const ir::Instr& in : p.op.body)
        if (std::holds_alternative<ir::Move>(in.op) || std::holds_alternative<ir::Arc>(in.op)) {
          motion = true;
          break;
        }
      // After an error no output is written: skip the backend's work.
      if (!d.has_errors()) backend.operation(p.op);
      return true;
    };
    progress.phase("compile");
    PieceQueue lowered, passed;
    struct StopOnExit {
      PieceQueue &a, &b;
      ~StopOnExit() {
        a.stop();
        b.stop();
      }
    };
    if (opt.print_after.empty()) {
      // The passes up to the costliest on their own thread, the rest here before the backend.
      const size_t split = pm.split_point();
      Diagnostics late_diags(nullptr);
      late_diags.set_source(&src);
      late_diags.set_deferred(true);
      PassContext late{info, machine, late_diags};
      FrontEnd front(src, info, lowered, opt.latin1, opt.lower);
      PassStage passes(pm, split, ctx, lowered, passed);
      StopOnExit stop{lowered, passed};  // on an exception here: the threads give up, then join
      for (;;) {
        Piece p = passed.pop();
        if (!p.end && split < pm.size()) {
          pm.run(p.op, split, pm.size(), late);
          for (auto& x : late_diags.take_deferred()) p.diags.push_back(std::move(x));
        }
        if (!write(p)) break;
        lowered.give_spare(std::move(p.op));
      }
    } else {
      // The IR printed between passes goes to the diagnostics' stream: passes here, in order.
      FrontEnd front(src, info, lowered, opt.latin1, opt.lower);
      StopOnExit stop{lowered, passed};
      for (;;) {
        Piece p = lowered.pop();
        if (!p.end) {
          pm.run(p.op);
          for (auto& x : pass_diags.take_deferred()) p.diags.push_back(std::move(x));
        }
        if (!write(p)) break;
        lowered.give_spare(std::move(p.op));
      }
    }
    progress.clear();
    if (!motion && !d.has_errors()) d.error({}, "nothing to post: the file has no motion (GOTO, CIRCLE, ...)");
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
