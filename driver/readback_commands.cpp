#include "driver/readback_commands.h"

#include <unistd.h>

#include <cstdlib>

#include "driver/certify.h"
#include "readback/report_html.h"
#include "support/output.h"

#include <fstream>
#include <sstream>
#include "support/progress.h"

namespace clpc {

TempProgram::TempProgram() {
  const char* dir = std::getenv("TMPDIR");
  std::string t = std::string(dir && *dir ? dir : "/tmp") + "/clpc-program-XXXXXX";
  int fd = mkstemp(t.data());
  if (fd < 0) return;
  close(fd);
  path_ = t;
}

TempProgram::~TempProgram() {
  if (!path_.empty()) std::remove(path_.c_str());
}

bool compile_for_readback(const std::string& input, const Machine& m, CompileOptions opt, const std::string& keep,
                          const std::string& given, std::ostream& err, CompiledProgram& out) {
  std::string why;
  if (!out.source.open(input, why)) {
    err << "clpc: error: " << why << "\n";
    return false;
  }
  const std::string target = keep.empty() ? out.temp.path() : keep;
  if (target.empty()) {
    err << "clpc: error: cannot create a temporary file for the program\n";
    return false;
  }
  opt.emit = Emit::Gcode;
  out.compiled = compile_source(out.source, target, m, opt, err);
  out.path = given.empty() ? target : given;
  return out.compiled.ok;
}

VerifyReport verify_file(const std::string& input, const Machine& m, const VerifyOptions& opt, std::ostream& err) {
  VerifyReport rep;
  rep.input = input;
  rep.machine = m.name;
  rep.units = m.units;
  rep.five_axis = m.kinematics.has_rotaries();
  rep.tolerance = opt.tolerance > 0 ? opt.tolerance : default_tolerance(m);
  rep.axis_tolerance = opt.axis_tolerance;

  CompiledProgram cp;
  CompileOptions co = opt.compile;
  co.certify = false;  // certified here, with the whole report (and --program's program)
  ProtectedInput program(opt.program);
  // The program goes to a temporary file first; -o gets it once it has passed (a program that
  // failed replaced the file there), and `-o -` then reads it back from a file, not from '-'.
  // The files to write are opened (as temporaries beside them) before any work: a folder that
  // does not exist is said at once, not after a report that says PASS.
  // The CL is protected before then (its SourceFile protects it only once open).
  ProtectedInput cl_input(input == "-" ? "/dev/stdin" : input);
  std::string why;
  OutputFile report_out, keep_out;
  if ((!opt.report.empty() && !report_out.open(opt.report, why)) || (!opt.keep.empty() && !keep_out.open(opt.keep, why))) {
    err << "clpc: error: " << why << "\n";
    return rep;
  }
  if (!compile_for_readback(input, m, co, {}, opt.program, err, cp)) return rep;
  SourceFile& src = cp.source;
  Diagnostics d(&err);
  d.set_source(&src);
  Progress progress(input, src.size(), opt.compile.progress);
  if (progress.active()) {
    src.on_progress([&](uint64_t at) { progress.update(at); });
    d.set_before_print([&] { progress.clear(); });
  }
  progress.phase("verify");
  CertifyOptions c;
  c.tolerance = opt.tolerance;
  c.axis_tolerance = opt.axis_tolerance;
  c.latin1 = opt.compile.latin1;
  c.collect_samples = !opt.report.empty();
  rep = certify(src, cp.path, m, cp.compiled.info, c, d);
  rep.input = input;
  src.on_progress(nullptr);
  progress.clear();
  if (!opt.report.empty() && !write_report(report_out, rep, cp, m, err)) rep.written = false;
  if (!opt.keep.empty()) {
    if (!rep.ok) {
      err << "clpc: error: the program does not pass: it is not written to '" << opt.keep
          << "' (compile --no-verify writes it unchecked)\n";
      rep.written = false;
    } else if (!copy_out(cp.temp.path(), keep_out, err)) {
      rep.written = false;
    }
  }
  return rep;
}

bool copy_out(const std::string& from, OutputFile& out, std::ostream& err) {
  std::ifstream in(from, std::ios::binary);
  std::string why;
  if (!in) {
    err << "clpc: error: cannot read the program back from '" << from << "'\n";
    return false;
  }
  std::string chunk(1 << 16, '\0');
  while (in.read(chunk.data(), std::streamsize(chunk.size())) || in.gcount() > 0)
    out.write(std::string_view(chunk.data(), size_t(in.gcount())));
  if (!out.commit(why)) {
    err << "clpc: error: " << why << "\n";
    return false;
  }
  return true;
}

bool write_report(OutputFile& out, const VerifyReport& rep, const CompiledProgram& cp, const Machine& m,
                  std::ostream& err) {
  // The backplot, drawn by clpc plot into a temporary file, goes inline.
  TempProgram svg;
  std::string drawing;
  if (!svg.path().empty()) {
    std::ostringstream quiet;
    if (plot_program(cp.path, rep.input, cp.compiled.info, svg.path(), m, PlotOptions{}, quiet).ok) {
      std::ifstream in(svg.path(), std::ios::binary);
      std::ostringstream all;
      all << in.rdbuf();
      drawing = all.str();
    }
  }
  std::ostringstream html;
  write_report_html(html, rep, drawing);
  std::string why;
  out.write(html.str());
  if (!out.commit(why)) {
    err << "clpc: error: " << why << "\n";
    return false;
  }
  return true;
}

PlotResult plot_file(const std::string& input, const std::string& output, const Machine& m, const PlotFileOptions& opt,
                     std::ostream& err) {
  CompiledProgram cp;
  ProtectedInput program(opt.program);
  if (!compile_for_readback(input, m, opt.compile, {}, opt.program, err, cp)) return {};
  return plot_program(cp.path, input, cp.compiled.info, output, m, opt.plot, err);
}

}  // namespace clpc
