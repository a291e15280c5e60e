// clpc: the command line.
#include <unistd.h>

#include <charconv>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <map>

#include <CLI/CLI.hpp>
#include <atomic>
#include <condition_variable>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "cli/usage.h"
#include "driver/driver.h"
#include "driver/readback_commands.h"
#include "passes/describe.h"
#include "passes/pass.h"
#include "support/output.h"
#include "support/suggest.h"
#include "machine/machine_loader.h"
#include "machine/json_schema.h"
#include "machine/schema.h"

using namespace clpc;

namespace {

// Exit codes: 0 success, 1 input or machine errors, 2 usage errors.
constexpr int kOk = 0, kFailed = 1, kUsage = 2;

// An output path as one file: its folder resolved (a./b.nc and a/b.nc are one file).
std::string canonical_output(const std::string& path) {
  size_t slash = path.rfind('/');
  std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + (slash == 0));
  char buf[PATH_MAX];
  if (!realpath(dir.c_str(), buf)) return path;
  return std::string(buf) + "/" + (slash == std::string::npos ? path : path.substr(slash + 1));
}

std::optional<ir::Units> parse_units(const std::string& s) {
  if (s == "mm") return ir::Units::Mm;
  if (s == "inch") return ir::Units::Inch;
  return std::nullopt;
}

// Several files at once: `jobs` workers take the next file in turn; each file's diagnostics
// are held and printed whole, in input order, as soon as the files before it are done. No
// progress bars (they would fight over the terminal).
// What a run of several files found, for the line it ends with.
struct Totals {
  bool ok = true;
  size_t errors = 0, warnings = 0;
  void add(const CompileResult& r) {
    ok = ok && r.ok;
    errors += r.errors;
    warnings += r.warnings;
  }
  // "2 errors, 1 warning" on standard error when there were any; the exit status.
  int finish() const {
    std::cerr << totals_line(errors, warnings);
    return ok ? 0 : 1;
  }
};

template <class OutputFor>
Totals compile_parallel(const std::vector<std::string>& inputs, OutputFor output_for, const Machine& m, CompileOptions opt,
                        unsigned jobs) {
  opt.progress = false;
  const size_t n = inputs.size();
  std::vector<std::string> diags(n);
  std::vector<char> done(n, 0);
  std::vector<CompileResult> results(n);
  std::mutex lock;
  std::condition_variable finished;
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t i; (i = next.fetch_add(1)) < n;) {
      std::ostringstream err;
      CompileResult r = compile_file(inputs[i], output_for(inputs[i]), m, opt, err);
      std::lock_guard<std::mutex> g(lock);
      diags[i] = err.str();
      results[i] = r;
      done[i] = 1;
      finished.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned j = 0; j < std::min<size_t>(jobs, n); ++j) pool.emplace_back(worker);
  Totals all;
  for (size_t i = 0; i < n; ++i) {
    std::unique_lock<std::mutex> g(lock);
    finished.wait(g, [&] { return done[i] != 0; });
    std::cerr << diags[i];
    all.add(results[i]);
  }
  for (std::thread& t : pool) t.join();
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  install_output_cleanup_handlers();
  CLI::App app{"clpc - a CNC postprocessor built as a compiler: CL data (APT/CLSF) in, G-code out", "clpc"};
  app.set_version_flag("--version", std::string("clpc ") + CLPC_VERSION);
  app.require_subcommand(1);
  app.fallthrough();

  std::vector<std::string> inputs, machine_files;
  std::string machine_name, output, emit = "gcode", print_after, input_units;
  bool werror = false, verify_ir = false, force_family = false;
  std::vector<std::string> wflags;

  auto add_target = [&](CLI::App* c) {
    c->add_option("-t,--target", machine_name, "Machine name, or a TOML file with one machine")
        ->required()
        ->check(CLI::Validator([](std::string& v) { return v.empty() ? std::string("the machine name is empty") : std::string(); }, "NAME"));
  };
  // A file clpc writes never has a name that starts with '-' (other than '-', standard output):
  // `-o --bogus part.cls` wrote a program named --bogus, certified, when an option was missed.
  // A file that must have such a name is written ./-name.
  const CLI::Validator written_file(
      [](std::string& v) {
        if (v.size() > 1 && v[0] == '-')
          return "'" + v + "' looks like an option, not a file name (write ./" + v + " if it is the file's name)";
        return std::string();
      },
      "FILE");
  // A tolerance is a finite number above zero: CLI::PositiveNumber lets "nan" through (every
  // comparison with it is false) and prints the range up to DBL_MAX digit by digit.
  const CLI::Validator positive_finite(
      [](std::string& v) {
        double x = 0;
        const char* end = v.data() + v.size();
        const char* from = v.size() > 1 && v[0] == '+' ? v.data() + 1 : v.data();  // from_chars takes no '+'
        auto [p, ec] = std::from_chars(from, end, x);
        if (ec != std::errc() || p != end || !std::isfinite(x) || x <= 0)
          return "'" + v + "' is not a number above zero";
        return std::string();
      },
      "POSITIVE");
  MachineRegistry::Job job;
  auto add_machine_files = [&](CLI::App* c) {
    // One value per occurrence (--machines a.toml --machines b.toml): taking every word after it,
    // it read the CL files after it as TOML.
    c->add_option("--machines", machine_files, "Machine descriptions (TOML) adding to or replacing the built-in ones")
        ->check(CLI::ExistingFile)
        ->allow_extra_args(false);
  };
  auto add_job = [&](CLI::App* c) {
    c->add_option("--set", job.sets, "KEY=VALUE: change one machine key for this job (program.optional_stop=operation, units=inch; docs/machines.md)")
        ->allow_extra_args(false);
    c->add_option("--job", job.files, "A TOML file whose [job] table changes machine keys for this job")
        ->check(CLI::ExistingFile)
        ->allow_extra_args(false);
  };
  std::string input_encoding = "utf-8";
  auto add_input_options = [&](CLI::App* c) {
    c->add_option("--input-units", input_units, "Units of the CL data when it has no UNITS record")
        ->check(CLI::IsMember({"mm", "inch"}));
    c->add_option("--input-encoding", input_encoding, "Encoding of comments and text in the CL data (default utf-8)")
        ->check(CLI::IsMember({"utf-8", "latin1"}));
    c->add_flag("--Werror", werror, "Treat warnings as errors");
    c->add_option("-W", wflags, "-Wno-NAME: do not give warning NAME (names: docs/reliability.md); -Werror as --Werror")
        ->allow_extra_args(false);
    c->add_flag("--force-family", force_family, "Post lathe CL data for a mill, or mill data for a lathe");
  };

  CLI::App* compile = app.add_subcommand("compile", "Compile CL files into G-code for one machine");
  compile->add_option("INPUT", inputs, "CL files ('-' reads standard input)")->required();
  add_target(compile);
  compile->add_option("-o,--output", output, "Output file ('-' = standard output); default: INPUT with the machine's extension")
      ->check(written_file);
  std::string output_dir;
  compile->add_option("--output-dir", output_dir, "Write each program into this folder (named as INPUT, with the machine's extension)")
      ->check(CLI::ExistingDirectory);
  compile->add_option("--emit", emit, "What to write")->check(CLI::IsMember({"gcode", "ir"}));
  compile->add_option("--print-after", print_after, "Print the IR after this pass ('lower', a pass name or 'all') to stderr");
  compile->add_flag("--verify-ir", verify_ir, "Check the IR's invariants after every pass");
  bool no_verify = false, compile_json = false;
  double compile_tolerance = 0, compile_axis_tolerance = 0.01;
  compile->add_flag("--no-verify", no_verify,
                    "Write the program without reading it back and comparing it with the CL (the certificate)");
  compile->add_option("--tolerance", compile_tolerance,
                      "The certificate's largest deviation, in the machine's units (default: its arc tolerance plus one output increment)")
      ->check(positive_finite);
  compile->add_option("--axis-tolerance", compile_axis_tolerance, "The certificate's largest tool-axis deviation, degrees (five-axis)")
      ->check(positive_finite);
  compile->add_flag("--json", compile_json, "Give each program's certificate whole, as JSON on standard error");
  unsigned jobs = 1;
  compile->add_option("-j,--jobs", jobs, "Compile this many files at once (each file's diagnostics stay together, in input order)")
      ->check(CLI::Range(1u, 256u));
  add_machine_files(compile);
  add_job(compile);
  add_input_options(compile);

  CLI::App* check = app.add_subcommand("check", "Report problems in CL files without writing anything");
  check->add_option("INPUT", inputs, "CL files ('-' reads standard input)")->required();
  check->add_option("-t,--target", machine_name, "Also check against this machine");
  add_machine_files(check);
  add_job(check);
  add_input_options(check);

  std::string verify_input;
  double tolerance = 0, axis_tolerance = 0.01;
  bool json = false;
  CLI::App* verify = app.add_subcommand("verify", "Compile a CL file, read the program back and compare its path with the CL path");
  verify->add_option("INPUT", verify_input, "CL file ('-' reads standard input)")->required();
  add_target(verify);
  verify->add_option("--tolerance", tolerance, "Largest deviation allowed, in the machine's units (default: its arc tolerance plus one output increment)")
      ->check(positive_finite);
  verify->add_option("--axis-tolerance", axis_tolerance, "Largest tool-axis deviation allowed, degrees (five-axis)")
      ->check(positive_finite);
  verify->add_flag("--json", json, "Write the report as JSON");
  std::string verify_program;
  verify->add_option("-o,--output", output, "Also keep the program in this file")->check(written_file);
  std::string verify_report;
  verify->add_option("--report", verify_report, "Also write the report as an HTML page (operations, deviations, backplot)")
      ->check(written_file);
  verify->add_option("--program", verify_program, "Check this program (say, one edited by hand) against the CL instead of clpc's own")
      ->check(CLI::ExistingFile);
  add_machine_files(verify);
  add_job(verify);
  add_input_options(verify);

  std::string plot_input, plot_program;
  int plot_width = 1200, plot_height = 900;
  CLI::App* plot = app.add_subcommand("plot", "Draw the emitted program's tool path (SVG: top, front, side, isometric)");
  plot->add_option("INPUT", plot_input, "CL file ('-' reads standard input)")->required();
  add_target(plot);
  plot->add_option("-o,--output", output, "SVG file ('-' = standard output); default: INPUT with .svg")->check(written_file);
  plot->add_option("--program", plot_program, "Plot this program instead of clpc's own")->check(CLI::ExistingFile);
  plot->add_option("--width", plot_width, "Width in pixels")->check(CLI::Range(200, 20000));
  plot->add_option("--height", plot_height, "Height in pixels")->check(CLI::Range(200, 20000));
  add_machine_files(plot);
  add_job(plot);
  add_input_options(plot);

  CLI::App* machines = app.add_subcommand("machines", "List the machines clpc knows");
  add_machine_files(machines);

  CLI::App* explain = app.add_subcommand("explain", "Print a machine's resolved description (TOML)");
  explain->add_option("MACHINE", machine_name, "Machine name, or a TOML file with one machine")->required();
  add_machine_files(explain);
  add_job(explain);

  CLI::App* schema = app.add_subcommand("schema", "Print the JSON Schema of machine files (for editors that check TOML; docs/machines.md)");

  CLI::App* passes = app.add_subcommand("passes", "List the passes a pipeline may use, with their contracts");
  bool passes_markdown_flag = false;
  passes->add_flag("--markdown", passes_markdown_flag, "As the generated section of docs/passes.md");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return report_parse_error(app, e, argc, argv, std::cout, std::cerr);
  }

  Diagnostics diags(&std::cerr);
  MachineRegistry reg(pass_contracts());

  if (*schema) {
    std::cout << machine_json_schema();
    return kOk;
  }
  if (*passes) {
    std::cout << (passes_markdown_flag ? passes_markdown() : describe_passes());
    return kOk;
  }
  if (*machines) {
    if (!reg.load_builtin_and(machine_files, diags)) return kFailed;
    for (const auto& [name, desc] : reg.list()) std::cout << name << "\t" << desc << "\n";
    return kOk;
  }
  if (*explain) {
    if (!reg.load_builtin_and(machine_files, diags)) return kFailed;
    auto m = reg.resolve(machine_name, diags, job);
    if (!m) return kFailed;
    std::cout << explain_machine(*m);
    return kOk;
  }

  CompileOptions opt;
  opt.werror = werror;
  opt.verify_ir = verify_ir;
  opt.print_after = print_after;
  opt.input_units = parse_units(input_units);
  opt.progress = true;  // shown only on a terminal, for large inputs
  opt.latin1 = input_encoding == "latin1";
  opt.force_family = force_family;
  for (const std::string& w : wflags) {
    if (w == "error") {
      opt.werror = true;
      continue;
    }
    std::string name = w.rfind("no-", 0) == 0 ? w.substr(3) : std::string();
    if (!is_warning_name(name)) {
      std::vector<std::string> all;
      for (const WarningName& n : warning_names()) all.push_back(std::string("no-") + n.name);
      std::string near = closest(w, all);
      std::cerr << "clpc: error: -W" << w << ": no such warning switch (-Wno-NAME, -Werror)"
                << (near.empty() ? std::string() : "; did you mean '-W" + near + "'?") << "\n";
      return kUsage;
    }
    opt.no_warnings.push_back(name);
  }
  if (!print_after.empty() && print_after != "lower" && print_after != "all" && !find_pass(print_after)) {
    std::cerr << "clpc: error: --print-after: no pass named '" << print_after << "' (see 'clpc passes')\n";
    return kUsage;
  }

  // The machine and job files this run reads are inputs too: no output may replace one (-o
  // shop.toml destroyed it, with a note that a program was replaced).
  for (const std::string& f : machine_files) protect_input(f);
  for (const std::string& f : job.files) protect_input(f);
  if (machine_name.find('/') != std::string::npos || machine_name.find(".toml") != std::string::npos) protect_input(machine_name);
  if (machine_name.empty() && !job.empty()) {
    std::cerr << "clpc: error: --set and --job change a machine: name it with -t\n";
    return kUsage;
  }
  std::optional<Machine> machine;
  if (!machine_name.empty()) {
    if (!reg.load_builtin_and(machine_files, diags)) return kFailed;
    machine = reg.resolve(machine_name, diags, job);
    if (!machine) return kFailed;
  }

  if (*verify) {
    VerifyOptions vo;
    vo.tolerance = tolerance;
    vo.axis_tolerance = axis_tolerance;
    vo.compile = opt;
    vo.keep = output;
    vo.program = verify_program;
    vo.report = verify_report;
    VerifyReport r = verify_file(verify_input, *machine, vo, std::cerr);
    // With the program on standard output (-o -), the report goes to standard error.
    std::ostream& report_out = output == "-" ? std::cerr : std::cout;
    if (json) print_report_json(report_out, r);
    else print_report(report_out, r);
    return r.ok && r.written ? kOk : kFailed;
  }

  if (*plot) {
    PlotFileOptions po;
    po.compile = opt;
    po.program = plot_program;
    po.plot.width = plot_width;
    po.plot.height = plot_height;
    std::string out = output;
    if (out.empty()) {
      Machine svg = *machine;
      svg.extension = ".svg";
      out = default_output(plot_input, svg);
    }
    return plot_file(plot_input, out, *machine, po, std::cerr).ok ? kOk : kFailed;
  }

  if (*check) {
    // With a machine, everything compile does, the backend's checks included.
    opt.emit = machine ? Emit::Check : Emit::Nothing;
    Totals t;
    for (const std::string& in : inputs) {
      Machine m = machine ? *machine : default_machine(Family::Mill, ir::Units::Mm);
      if (!machine) m.pipeline = {"arc-direction"};
      t.add(compile_file(in, "-", m, opt, std::cerr));
    }
    return t.finish() == 0 ? kOk : kFailed;
  }

  // compile
  opt.emit = emit == "ir" ? Emit::Ir : Emit::Gcode;
  opt.say_replaced = true;
  opt.certify = !no_verify && opt.emit == Emit::Gcode;
  opt.tolerance = compile_tolerance;
  opt.axis_tolerance = compile_axis_tolerance;
  opt.certificate_json = compile_json;
  if (!output.empty() && inputs.size() > 1 && output != "-") {
    std::cerr << "clpc: error: -o names one output but " << inputs.size() << " inputs were given\n";
    return kUsage;
  }
  if (!output.empty() && !output_dir.empty()) {
    std::cerr << "clpc: error: -o and --output-dir: name the output, or the folder for it, not both\n";
    return kUsage;
  }
  auto output_for = [&](const std::string& in) -> std::string {
    if (!output.empty()) return output;
    if (opt.emit == Emit::Ir) return "-";
    std::string out = default_output(in, *machine);
    if (output_dir.empty() || out == "-") return out;
    size_t slash = out.rfind('/');
    return output_dir + "/" + (slash == std::string::npos ? out : out.substr(slash + 1));
  };
  // Two inputs that map to one output (Creo's numbered versions, part.ncl.1 and part.ncl.2):
  // the second would replace the first. Refused before anything is written.
  if (output != "-" && opt.emit == Emit::Gcode) {
    std::map<std::string, std::string> first;  // output -> the input that writes it
    for (const std::string& in : inputs) {
      const std::string out = output_for(in);
      if (out == "-") continue;
      auto [it, fresh] = first.emplace(canonical_output(out), in);
      if (!fresh) {
        std::cerr << "clpc: error: '" << it->second << "' and '" << in << "' would both be written to '" << out
                  << "': compile them one at a time with -o, or into other folders with --output-dir\n";
        return kUsage;
      }
    }
  }
  Totals t;
  if (jobs <= 1 || inputs.size() <= 1) {
    for (const std::string& in : inputs) t.add(compile_file(in, output_for(in), *machine, opt, std::cerr));
  } else {
    t = compile_parallel(inputs, output_for, *machine, opt, jobs);
  }
  return t.finish() == 0 ? kOk : kFailed;
}
