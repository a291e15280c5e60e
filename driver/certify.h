// Certification: a program read back and compared with the CL it was made from, by verify's
// own rules (readback/verify.h), before anyone runs it. clpc compile certifies every program
// before it renames it into place (unless --no-verify); clpc verify does the same and prints
// the whole report.
#pragma once

#include <string>

#include "ir/ir.h"
#include "machine/machine.h"
#include "readback/verify.h"
#include "support/diagnostics.h"
#include "support/source.h"

namespace clpc {

struct CertifyOptions {
  double tolerance = 0;          // output units; 0: default_tolerance(m)
  double axis_tolerance = 0.01;  // degrees, tool axis (five-axis)
  bool latin1 = false;           // the CL's comments in Latin-1
  bool collect_samples = false;  // keep the CL points' deviations (the HTML report's map)
};

// Reads the program at `program` back and walks it beside the CL of `src` lowered again, with
// none of the compile's passes: the reference is the CL's own meaning (readback/verify.h).
// `info` is the compile's program tables (tools, offset table), read to follow the program.
// Each problem is an error on `d`, located at its CL record; the report has them all.
VerifyReport certify(SourceFile& src, const std::string& program, const Machine& m, const ir::ProgramInfo& info,
                     const CertifyOptions& opt, Diagnostics& d);

// The one line a certified compile ends with, on standard error:
//   clpc: certified part.nc: 1204 points, 37 arcs, 8 holes; max deviation 0.0021 mm at
//   part.cls:310 (G-code line 288), tool axis 0.0004 deg at part.cls:512 (G-code line 490);
//   tolerance 0.0110 mm, 0.01 deg
std::string certificate_line(const VerifyReport& r, const std::string& program_name);

}  // namespace clpc
