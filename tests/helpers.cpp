#include "helpers.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "driver/readback_commands.h"
#include "lower/params.h"
#include "ir/printer.h"
#include "passes/pass_manager.h"

namespace clpc::test {

std::string source_path(const std::string& rel) { return std::string(CLPC_SOURCE_DIR) + "/" + rel; }

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

TempDir::TempDir() {
  static std::mt19937_64 rng(std::random_device{}());
  dir_ = std::filesystem::temp_directory_path() / ("clpc-test-" + std::to_string(getpid()) + "-" + std::to_string(rng()));
  std::filesystem::create_directories(dir_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

namespace {

void show_params(std::ostream& o, std::span<const Param> ps) {
  for (size_t i = 0; i < ps.size(); ++i) {
    const Param& p = ps[i];
    o << (i ? "," : "");
    if (p.is_number()) o << num_text(p.number);
    else if (p.kind == Param::Kind::String) o << "'" << p.text << "'";
    else if (p.is_group()) {
      o << "(" << p.text << (p.text.empty() ? "" : "/");
      show_params(o, ps.subspan(i + 1, std::min<size_t>(p.group_size, ps.size() - i - 1)));
      o << ")";
      i += p.group_size;
    } else o << p.text;
  }
}

std::string show(const Record& r) {
  std::ostringstream o;
  o << r.loc.line << ":" << r.loc.col << " ";
  if (r.kind == Record::Kind::Comment) {
    o << "$$" << r.text;
    return o.str();
  }
  if (r.data_comment) o << "$$-> ";
  for (const Param& h : r.head) o << h.text << ",";
  o << r.major;
  if (r.has_slash) o << "/";
  show_params(o, r.params);
  if (!r.text.empty()) o << " [" << r.text << "]";
  return o.str();
}

struct Collect : RecordSink {
  std::vector<std::string> out;
  void record(const Record& r) override { out.push_back(show(r)); }
};

struct KeepOps : OperationSink {
  PassManager* pm = nullptr;
  std::vector<ir::Operation> ops;
  std::ostringstream ir;
  void operation(ir::Operation& op) override {
    if (pm) pm->run(op);
    ir::print_operation(ir, op);
    ops.push_back(op);
  }
};

}  // namespace

Parsed parse_text(const std::string& text) {
  Parsed p;
  SourceFile src;
  src.open_memory("test.cls", text);
  Diagnostics d(nullptr);
  d.set_keep(true);
  d.set_source(&src);
  Collect c;
  try {
    parse_cl(src, d, c);
  } catch (const FatalError&) {
  }
  p.records = c.out;
  p.diags = d.all();
  return p;
}

Lowered lower_text(const std::string& text, const std::vector<std::string>& passes, const Machine* m,
                   std::optional<ir::Units> units) {
  Lowered l;
  SourceFile src;
  src.open_memory("test.cls", text);
  Diagnostics d(nullptr);
  d.set_keep(true);
  d.set_source(&src);
  PrescanOptions po;
  po.units = units;
  l.info = prescan_program(src, po);
  Machine generic = default_machine(Family::Mill, ir::Units::Mm);
  PassContext ctx{l.info, m ? *m : generic, d};
  auto verify_ir = make_verify_ir();
  PassManager pm(ctx, passes, {verify_ir.get()});
  pm.begin();
  KeepOps k;
  k.pm = &pm;
  try {
    Lowerer low(l.info, d, k);
    parse_cl(src, d, low);
    low.finish();
  } catch (const FatalError&) {
  }
  std::ostringstream o;
  ir::print_header(o, l.info);
  l.ir = o.str() + k.ir.str();
  l.ops = std::move(k.ops);
  l.diags = d.all();
  return l;
}

Machine machine(const std::string& name, const std::string& extra_toml) {
  std::ostringstream err;
  Diagnostics d(&err);
  MachineRegistry reg(pass_contracts());
  EXPECT_TRUE(reg.load_builtin(d)) << err.str();
  if (!extra_toml.empty()) {
    EXPECT_TRUE(reg.load_text("extra.toml", extra_toml, d)) << err.str();
  }
  auto m = reg.resolve(name, d);
  EXPECT_TRUE(m.has_value()) << err.str();
  return m ? *m : Machine{};
}

std::string machine_errors(const std::string& toml, std::string name) {
  if (name.empty()) name = toml.substr(1, toml.find(']') - 1);
  std::ostringstream err;
  Diagnostics d(&err);
  MachineRegistry reg(pass_contracts());
  reg.load_builtin(d);
  if (reg.load_text("shop.toml", toml, d)) reg.resolve(name, d);
  return err.str();
}

Compiled compile_path(const std::string& path, const Machine& m, CompileOptions opt) {
  TempDir t;
  std::string out = t.path("out.nc");
  std::ostringstream err;
  opt.verify_ir = true;  // every compile of the tests checks the IR's invariants after each pass
  CompileResult r = compile_file(path, out, m, opt, err);
  Compiled c;
  c.ok = r.ok;
  c.diags = err.str();
  if (r.ok) c.output = read_file(out);
  return c;
}

Compiled compile_text(const std::string& cl, const Machine& m, CompileOptions opt) {
  TempDir t;
  std::string in = t.path("part.cls");
  write_file(in, cl);
  return compile_path(in, m, opt);
}

RunResult run_clpc(const std::string& args, const std::string& stdin_text) {
  return run_shell(std::string(CLPC_BINARY) + " " + args, stdin_text);
}

RunResult run_shell(const std::string& command, const std::string& stdin_text) {
  TempDir t;
  std::string in = t.path("stdin"), out = t.path("stdout"), err = t.path("stderr");
  write_file(in, stdin_text);
  std::string cmd = "(" + command + ") <" + in + " >" + out + " 2>" + err;
  int st = std::system(cmd.c_str());
  RunResult r;
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

std::string corpus_dir() {
  std::string d = CLPC_CORPUS_DIR;
  return std::filesystem::is_directory(d) ? d : std::string();
}

std::vector<std::string> corpus_files() {
  std::vector<std::string> files;
  std::string d = corpus_dir();
  if (d.empty()) return files;
  for (auto& e : std::filesystem::recursive_directory_iterator(d)) {
    if (!e.is_regular_file()) continue;
    std::string n = e.path().filename().string();
    if (n.rfind("LICENSE", 0) == 0 || n == "MANIFEST.md" || e.path().extension() == ".tap") continue;
    if (e.path().parent_path().filename() == "licenses") continue;
    files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

bool is_lathe_file(const std::string& path) {
  std::string t = read_file(path);
  if (t.find("MACHIN / TURN") != std::string::npos || t.find("MACHIN/TURN") != std::string::npos) return true;
  return path.find("basic_turning") != std::string::npos;
}

bool is_five_axis_file(const std::string& path) {
  Lowered l = lower_text(read_file(path));
  for (const auto& op : l.ops)
    for (const auto& in : op.body)
      if (auto* m = std::get_if<ir::Move>(&in.op))
        if ((m->axis - ir::Vec3::UnitZ()).norm() > 1e-6) return true;
  return false;
}

std::string first_error(const std::vector<Diagnostic>& d) {
  for (const auto& x : d)
    if (x.severity == Severity::Error)
      return std::to_string(x.loc.line) + ":" + std::to_string(x.loc.col) + ": " + x.message;
  return "";
}

size_t count(const std::vector<Diagnostic>& d, Severity s) {
  return size_t(std::count_if(d.begin(), d.end(), [&](const Diagnostic& x) { return x.severity == s; }));
}

Compiled verify_text(const std::string& cl, const Machine& m, const std::string& program) {
  TempDir t;
  write_file(t.path("part.cl"), cl);
  VerifyOptions opt;
  if (!program.empty()) {
    write_file(t.path("given.nc"), program);
    opt.program = t.path("given.nc");
  }
  std::ostringstream err;
  Compiled v;
  v.ok = verify_file(t.path("part.cl"), m, opt, err).ok;
  v.diags = err.str();
  return v;
}

}  // namespace clpc::test
