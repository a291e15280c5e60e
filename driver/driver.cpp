#include "driver/driver.h"

#include <sys/stat.h>

#include <iostream>

#include "backends/backend.h"
#include "driver/certify.h"
#include "lower/not_cl_data.h"
#include "driver/pipeline.h"
#include "ir/printer.h"
#include "lower/prescan.h"
#include "support/output.h"
#include "support/progress.h"

namespace clpc {

namespace {

// Writes the IR as text instead of G-code (--emit=ir).
class IrPrinter : public ProgramSink {
 public:
  explicit IrPrinter(OutputFile& out) : out_(out) {}
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

 private:
  OutputFile& out_;
};

class NullSink : public ProgramSink {
 public:
  void operation(const ir::Operation&) override {}
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
  for (const std::string& w : opt.no_warnings) d.disable(w);
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

  struct stat before {};
  const bool replacing = opt.say_replaced && opt.emit == Emit::Gcode && output != "-" && stat(output.c_str(), &before) == 0 &&
                         S_ISREG(before.st_mode);
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
    if (std::optional<std::string> bom = utf16_given(src)) {
      d.error({1, 1}, "the file is UTF-16 text (it starts with the byte-order mark " + *bom +
                          "): clpc reads CL data as ASCII or UTF-8; save the file as UTF-8 or ASCII");
      throw FatalError{};
    }
    if (std::optional<SourceLoc> nul = binary_file_given(src)) {
      d.error(*nul, "a binary file (NUL bytes from here on), not CL data: clpc reads CL data as text; a CAM system "
                    "that writes a binary CL file (an APT CLFILE) can write it as text (ASCII CL data, an APT source)");
      throw FatalError{};
    }
    if (std::optional<GcodeInput> g = gcode_program_given(src)) {
      d.error(g->loc, "this is a G-code program ('" + g->block +
                          "'), not CL data: clpc reads the cutter-location file a CAM system writes (APT, CLSF) and "
                          "makes the program; to check a program against its CL: clpc verify PART.cls --program " +
                          src.name());
      throw FatalError{};
    }
    if (!info.units_given) d.warning({}, info.units_reason + " (use --input-units to say)", "units");
    if (!info.units_doubt.empty())
      d.warning({}, "the file says its units are " + std::string(info.units == ir::Units::Inch ? "inches" : "millimetres") +
                        ", but " + info.units_doubt + ": if its numbers are " +
                        (info.units == ir::Units::Inch ? "millimetres, --input-units mm" : "inches, --input-units inch") +
                        " reads them so",
                    "units");
    const bool gcode = opt.emit == Emit::Gcode || opt.emit == Emit::Check;
    // Lathe data on a mill (G95 moves in a plane no mill turns in), or mill data on a lathe.
    const std::string family = machine.is_lathe() ? "lathe" : "mill";
    if (gcode && !info.family_said.empty() && info.family_said != family) {
      const std::string msg = "the CL data is for a " + info.family_said + " (" + info.family_record + ") but machine '" +
                              machine.name + "' is a " + family;
      if (opt.force_family) d.warning(info.family_loc, msg + " (--force-family)", "force-family");
      else d.error(info.family_loc, msg + "; --force-family posts it anyway");
    }
    if (opt.emit == Emit::Check) out.open_null();
    else if (opt.emit != Emit::Nothing && !out.open(output, why)) {
      err << "clpc: error: " << why << "\n";
      res.errors = 1;
      return res;
    }
    std::unique_ptr<ProgramSink> sink;
    std::unique_ptr<CertifyBeside> certificate;
    if (gcode) sink = make_backend(machine, out, d);
    else if (opt.emit == Emit::Ir) sink = std::make_unique<IrPrinter>(out);
    else sink = std::make_unique<NullSink>();

    std::unique_ptr<PassInstrument> print, verify;
    PipelineOptions popt;
    popt.latin1 = opt.latin1;
    popt.lower = opt.lower;
    popt.schedule = opt.schedule;
    if (!opt.print_after.empty()) popt.instruments.push_back((print = make_print_after(opt.print_after)).get());
    if (opt.verify_ir) popt.instruments.push_back((verify = make_verify_ir()).get());
    if (opt.certify && opt.emit == Emit::Gcode) {
      CertifyOptions c;
      c.tolerance = opt.tolerance;
      c.axis_tolerance = opt.axis_tolerance;
      c.latin1 = opt.latin1;
      c.dynamic_time = opt.certificate_json || opt.certificate_cycle_time;
      certificate = std::make_unique<CertifyBeside>(src, machine, out, c);
      sink = certificate->wrap(std::move(sink));
    }
    progress.phase("compile");
    Pipeline pipeline(machine, machine.pipeline, info, d, popt);
    const bool motion = pipeline.run(src, *sink);
    progress.clear();
    if (!motion && !d.has_errors()) d.error({}, "nothing to post: the file has no motion (GOTO, CIRCLE, ...)");
    // A file cut short (or written on) while it was read posts what was read: a program
    // without the rest of the part, certified against the part read.
    if (src.changed_since_open())
      d.error({}, "the file changed while it was read (its size or modification time is not what it was when the "
                  "compile began): the program would not be the file's; run again once it is written");
    if (opt.certify && opt.emit == Emit::Gcode && !d.has_errors()) {
      // The program is read back and compared with the CL before it is put in place.
      if (!out.finish_writing(why)) {
        err << "clpc: error: " << why << "\n";
        res.errors = 1;
        return res;
      }
      progress.phase("verify");
      VerifyReport r = certificate->finish(d);
      progress.clear();
      if (opt.certificate_json) print_report_json(err, r);
      else err << certificate_line(r, output == "-" ? "(standard output)" : output) << "\n";
      if (!r.ok)
        d.error({}, "the program does not follow the CL within the tolerance: it is not written (--no-verify writes "
                    "it unchecked)");
      res.certificate = std::move(r);
    }
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
  if (opt.emit != Emit::Nothing && opt.emit != Emit::Check && !out.commit(why)) {
    err << "clpc: error: " << why << "\n";
    res.errors = 1;
    return res;
  }
  // Overwriting the program of an earlier run is the point of running again; still, say so.
  if (replacing) err << "clpc: note: replaced '" << output << "', the program an earlier run wrote there\n";
  res.ok = true;
  return res;
}

std::string totals_line(size_t errors, size_t warnings) {
  if (!errors && !warnings) return "";
  return "clpc: " + std::to_string(errors) + (errors == 1 ? " error, " : " errors, ") + std::to_string(warnings) +
         (warnings == 1 ? " warning" : " warnings") + "\n";
}

}  // namespace clpc
