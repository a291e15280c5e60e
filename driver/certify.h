// Certification: a program read back and compared with the CL it was made from, by verify's
// own rules (readback/verify.h), before anyone runs it. clpc compile certifies every program
// before it renames it into place (unless --no-verify); clpc verify does the same and prints
// the whole report.
#pragma once

#include <memory>
#include <string>
#include <thread>

#include "ir/ir.h"
#include "machine/machine.h"
#include "readback/verify.h"
#include "ir/sink.h"
#include "support/diagnostics.h"
#include "support/output.h"
#include "support/source.h"
#include "support/text_channel.h"

namespace clpc {

struct CertifyOptions {
  double tolerance = 0;          // output units; 0: default_tolerance(m)
  double axis_tolerance = 0.01;  // degrees, tool axis (five-axis)
  bool latin1 = false;           // the CL's comments in Latin-1
  bool collect_samples = false;  // keep the CL points' deviations (the HTML report's map)
  bool dynamic_time = true;      // the cycle time with the machine's accelerations (the JSON report's)
};

// Reads the program at `program` back and walks it beside the CL of `src` lowered again, with
// none of the compile's passes: the reference is the CL's own meaning (readback/verify.h).
// `info` is the compile's program tables (tools, offset table), read to follow the program.
// Each problem is an error on `d`, located at its CL record; the report has them all.
VerifyReport certify(SourceFile& src, const std::string& program, const Machine& m, const ir::ProgramInfo& info,
                     const CertifyOptions& opt, Diagnostics& d);

// The certificate made beside the compile (clpc compile): the program is read back as the
// backend writes it (handed over through a TextChannel, never read from the disk) and compared
// on a thread of its own while the compile goes on, so the two share the processors. wrap()
// the compile's sink; the certificate starts when the pipeline begins (the program tables
// complete) and finish() waits for it and replays its problems into the compile's
// diagnostics, in order, after the compile's own. Destroyed unfinished (a compile that
// failed), it stops and is waited for. Without threads (support/threads.h: the browser
// build) finish() reads the written program back instead, after the compile.
class CertifyBeside {
 public:
  CertifyBeside(SourceFile& src, const Machine& m, OutputFile& out, CertifyOptions opt);
  ~CertifyBeside();
  CertifyBeside(const CertifyBeside&) = delete;
  CertifyBeside& operator=(const CertifyBeside&) = delete;

  std::unique_ptr<ProgramSink> wrap(std::unique_ptr<ProgramSink> sink);
  VerifyReport finish(Diagnostics& d);

 private:
  class Sink;
  void start(const ir::ProgramInfo& info);
  SourceFile& src_;
  const Machine& m_;
  OutputFile& out_;
  CertifyOptions opt_;
  Diagnostics diags_;
  VerifyReport report_;
  ir::ProgramInfo info_;
  TextChannel channel_;
  std::thread thread_;
};

// The one line a certified compile ends with, on standard error:
//   clpc: certified part.nc: 1204 points, 37 arcs, 8 holes; max deviation 0.0021 mm at
//   part.cls:310 (G-code line 288), tool axis 0.0004 deg at part.cls:512 (G-code line 490);
//   tolerance 0.0110 mm, 0.01 deg
std::string certificate_line(const VerifyReport& r, const std::string& program_name);

}  // namespace clpc
