// Where a program's operations go after the passes: a backend writing G-code, the IR printer,
// verify's comparison with the program read back. The driver's pipeline calls begin once with
// the program-wide tables, operation for each operation in order (a long operation arrives in
// chunks, `continued` set on all but the first), and end once after the last — never after an
// error, when the program is dropped.
#pragma once

#include "ir/ir.h"

namespace clpc {

class ProgramSink {
 public:
  virtual ~ProgramSink() = default;
  virtual void begin(const ir::ProgramInfo& info) {}
  virtual void operation(const ir::Operation& op) = 0;
  virtual void end() {}
};

}  // namespace clpc
