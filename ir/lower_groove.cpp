// Lathe groove cycle records (the seed paper's CYCLE/FACE|RADIUS): see the groove-cycles pass.
#include "ir/lower.h"

namespace clpc {

void Lowerer::lower_groove_cycle(const Record& r) {
  unknown(r, "lathe groove cycles are not supported yet", true);
}

}  // namespace clpc
