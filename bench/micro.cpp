// Google Benchmark micro benchmarks: the lexer (the pre-scan's skipping), the parser, lowering,
// each pass of the Haas UMC-750 pipeline, and the mill backend's emitter, each over the same
// generated mixed CL text (3-axis lines and arcs, 5-axis GOTOs with tool axes, drilling).
//
//   build/bench/clpc_micro [--benchmark_filter=Pass]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "machine/machine_loader.h"
#include "support/output.h"
#include "grammar/parse.h"
#include "lower/lower.h"
#include "lower/prescan.h"
#include "passes/pass.h"

using namespace clpc;

namespace {

// About 4 MB of CL: contour loops with arcs, a variable-axis zig-zag, a drill grid.
const std::string& text() {
  static const std::string t = [] {
    std::string s = "UNITS/MM\n";
    char b[256];
    for (int op = 0; op < 6; ++op) {
      std::snprintf(b, sizeof b, "TOOL PATH/OP%d,TOOL,T%d\nLOAD/TOOL,%d\nSPINDL/RPM,8000,CLW\nRAPID\nGOTO/20,20,50\nFEDRAT/MMPM,1500\n", op,
                    op + 1, op + 1);
      s += b;
      for (int i = 0; i < 4000; ++i) {
        double o = (i % 16) * 2.5, z = -(i / 16 % 40) * 0.5;
        std::snprintf(b, sizeof b,
                      "GOTO/%.4f,%.4f,%.4f\nGOTO/%.4f,%.4f,%.4f\nCIRCLE/%.4f,%.4f,%.4f,0.0000000,0.0000000,-1.0000000,15.0000,0.0600,"
                      "0.5000,12.0000,0.8000\nGOTO/%.4f,%.4f,%.4f\n",
                      35 + o, 20 + o, z, 205 - o, 20 + o, z, 205 - o, 35 + o, z, 220 - o, 35 + o, z);
        s += b;
        std::snprintf(b, sizeof b, "GOTO/%.4f,%.4f,%.4f\nGOTO/%.4f,%.4f,%.4f\nGOTO/%.4f,%.4f,%.4f\n", 220 - o, 125 - o, z, 35 + o,
                      140 - o, z, 20 + o, 35 + o, z);
        s += b;
      }
      s += "END-OF-PATH\n";
      std::snprintf(b, sizeof b, "TOOL PATH/FIVE%d,TOOL,B6\nLOAD/TOOL,7\nSPINDL/RPM,9000,CLW\nRAPID\nGOTO/40,30,20,0,0,1\nFEDRAT/MMPM,3000\n", op);
      s += b;
      for (int i = 0; i < 16000; ++i) {
        double x = 40 + (i % 800) * 0.25, y = 30 + (i / 800) * 1.2;
        double z = 6 * std::sin(x / 23) * std::sin(y / 31), tilt = (20 + 8 * std::sin(x / 41)) * M_PI / 180, az = 0.5 + 0.4 * std::sin(x / 53);
        std::snprintf(b, sizeof b, "GOTO/%.4f,%.4f,%.4f,%.7f,%.7f,%.7f\n", x, y, z, std::sin(tilt) * std::cos(az),
                      std::sin(tilt) * std::sin(az), std::cos(tilt));
        s += b;
      }
      s += "END-OF-PATH\nTOOL PATH/DRILL,TOOL,D8\nLOAD/TOOL,9\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/30,30,50,0,0,1\n"
           "CYCLE/DRILL,RAPTO,3,FEDTO,10,MMPM,150\n";
      for (int i = 0; i < 1000; ++i) {
        std::snprintf(b, sizeof b, "GOTO/%.4f,%.4f,0.0000,0.0000000,0.0000000,1.0000000\n", 30.0 + (i % 40) * 6, 30.0 + (i / 40) * 6);
        s += b;
      }
      s += "CYCLE/OFF\nEND-OF-PATH\n";
    }
    return s + "FINI\n";
  }();
  return t;
}

const Machine& haas() {
  static const Machine m = [] {
    Diagnostics d(nullptr);
    MachineRegistry reg(pass_contracts());
    reg.load_builtin(d);
    return *reg.resolve("haas-umc750", d);
  }();
  return m;
}

struct NullSink : RecordSink {
  long n = 0;
  void record(const Record&) override { ++n; }
};

struct KeepOps : OperationSink {
  std::vector<ir::Operation> ops;
  void operation(ir::Operation& op) override { ops.push_back(op); }
};

// The program's operations after the first `passes` passes of the Haas pipeline.
struct Lowered {
  ir::ProgramInfo info;
  std::vector<ir::Operation> ops;
};
Lowered lowered(size_t passes) {
  SourceFile src;
  src.open_memory("bench.cls", text());
  Diagnostics d(nullptr);
  Lowered l;
  l.info = prescan_program(src, {});
  KeepOps k;
  Lowerer low(l.info, d, k);
  parse_cl(src, d, low);
  low.finish();
  l.ops = std::move(k.ops);
  PassContext ctx{l.info, haas(), d};
  for (size_t i = 0; i < passes; ++i) {
    auto p = find_pass(haas().pipeline[i])->make();
    p->begin(ctx);
    for (ir::Operation& op : l.ops) p->run(op, ctx);
  }
  return l;
}

void BM_LexerSkip(benchmark::State& st) {
  SourceFile src;
  src.open_memory("bench.cls", text());
  MajorSet none;
  for (auto _ : st) {
    NullSink s;
    prescan_cl(src, s, none);
    benchmark::DoNotOptimize(s.n);
  }
  st.SetBytesProcessed(int64_t(st.iterations()) * int64_t(text().size()));
}
BENCHMARK(BM_LexerSkip)->Unit(benchmark::kMillisecond);

void BM_Parser(benchmark::State& st) {
  SourceFile src;
  src.open_memory("bench.cls", text());
  for (auto _ : st) {
    Diagnostics d(nullptr);
    NullSink s;
    parse_cl(src, d, s);
    benchmark::DoNotOptimize(s.n);
  }
  st.SetBytesProcessed(int64_t(st.iterations()) * int64_t(text().size()));
}
BENCHMARK(BM_Parser)->Unit(benchmark::kMillisecond);

void BM_Lowering(benchmark::State& st) {
  SourceFile src;
  src.open_memory("bench.cls", text());
  ir::ProgramInfo info = prescan_program(src, {});
  struct Count : OperationSink {
    size_t n = 0;
    void operation(ir::Operation& op) override { n += op.body.size(); }
  };
  for (auto _ : st) {
    Diagnostics d(nullptr);
    Count c;
    Lowerer low(info, d, c);
    parse_cl(src, d, low);
    low.finish();
    benchmark::DoNotOptimize(c.n);
  }
  st.SetBytesProcessed(int64_t(st.iterations()) * int64_t(text().size()));
}
BENCHMARK(BM_Lowering)->Unit(benchmark::kMillisecond);

// One pass of the pipeline over the whole program, given the passes before it.
void BM_Pass(benchmark::State& st) {
  const size_t index = size_t(st.range(0));
  static std::vector<std::unique_ptr<Lowered>> cache(haas().pipeline.size());
  if (!cache[index]) cache[index] = std::make_unique<Lowered>(lowered(index));
  const Lowered& in = *cache[index];
  st.SetLabel(haas().pipeline[index]);
  size_t instrs = 0;
  for (const ir::Operation& op : in.ops) instrs += op.body.size();
  for (auto _ : st) {
    st.PauseTiming();
    std::vector<ir::Operation> ops = in.ops;
    ir::ProgramInfo info = in.info;
    Diagnostics d(nullptr);
    PassContext ctx{info, haas(), d};
    auto p = find_pass(haas().pipeline[index])->make();
    st.ResumeTiming();
    p->begin(ctx);
    for (ir::Operation& op : ops) p->run(op, ctx);
  }
  st.SetItemsProcessed(int64_t(st.iterations()) * int64_t(instrs));
}
BENCHMARK(BM_Pass)->DenseRange(0, 6)->Unit(benchmark::kMillisecond);

void BM_Emitter(benchmark::State& st) {
  static const Lowered in = lowered(haas().pipeline.size());
  size_t instrs = 0;
  for (const ir::Operation& op : in.ops) instrs += op.body.size();
  for (auto _ : st) {
    Diagnostics d(nullptr);
    OutputFile out;
    std::string why;
    out.open("/tmp/clpc_micro_emitter.nc", why);  // discarded: only the temporary is written
    auto be = make_backend(haas(), out, d);
    be->begin(in.info);
    for (const ir::Operation& op : in.ops) be->operation(op);
    be->end();
    out.discard();
  }
  st.SetItemsProcessed(int64_t(st.iterations()) * int64_t(instrs));
}
BENCHMARK(BM_Emitter)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
