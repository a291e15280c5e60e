// The one compile pipeline: lowering -> passes -> sink, over a CL file already pre-scanned.
// Every command runs it: compile (the sink a backend or the IR printer), check, verify (the
// sink the comparison with the program read back) and plot. Its schedule is pluggable:
//   - threaded (the default): lowering on one thread, the passes up to the costliest on
//     another, the rest and the sink on the caller's, operations crossing over bounded queues
//     (driver/stages.h);
//   - single: everything on the caller's thread, one operation after the other.
// Both give the same output and the same diagnostics, in the same order: each stage's
// diagnostics travel with the operation they concern and are replayed on the caller's thread
// before the sink sees it. Instruments (--print-after, --verify-ir) look on from inside the
// pass manager whatever the schedule.
#pragma once

#include <string>
#include <vector>

#include "ir/ir.h"
#include "ir/sink.h"
#include "lower/lower.h"
#include "passes/pass_manager.h"
#include "support/diagnostics.h"
#include "support/source.h"
#include "machine/machine.h"

namespace clpc {

enum class Schedule { Threaded, Single };

struct PipelineOptions {
  Schedule schedule = Schedule::Threaded;
  bool latin1 = false;   // comments and text in Latin-1
  LowerOptions lower;    // how long operations are cut into chunks
  std::vector<PassInstrument*> instruments;
  // The sink sees every operation even after an error (verify's reference: the compile has
  // reported the CL's problems; the comparison goes on with what there is).
  bool sink_after_errors = false;
};

class Pipeline {
 public:
  // `passes` run in order (normally the machine's pipeline); `info` is the pre-scan's, and the
  // passes may fill its tables (the offset table). Diagnostics go to `d`.
  Pipeline(const Machine& m, std::vector<std::string> passes, ir::ProgramInfo& info, Diagnostics& d,
           PipelineOptions opt = {});
  // Lowers `src` and runs the passes, handing each operation to `sink`; begin() before the
  // first, end() after the last, unless there were errors. Stops early on FatalError (too many
  // errors), which it lets through after the threads have stopped. Returns whether any
  // operation moved the tool.
  bool run(SourceFile& src, ProgramSink& sink);

 private:
  const Machine& m_;
  std::vector<std::string> passes_;
  ir::ProgramInfo& info_;
  Diagnostics& d_;
  PipelineOptions opt_;
};

}  // namespace clpc
