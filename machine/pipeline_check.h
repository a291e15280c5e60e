// Does a machine's pipeline make a program its backend may write? The passes' contracts
// (ir/stage.h) walked in the pipeline's order: each pass must find the facts it requires, and
// the end must hold every fact the machine's family needs. Called by the machine loader, which
// reports the problem at the machine's `pipeline` key.
#pragma once

#include <string>

#include "ir/stage.h"
#include "machine/machine.h"

namespace clpc {

// True of every program for `m` before any pass runs: a machine without rotaries is kinematic
// as lowered (the IR already is what its control is given); a lathe, which has no offset
// table, has its offsets as lowered.
ir::Facts given_facts(const Machine& m);
// What a program for `m` needs before its backend writes it: arcs decided, one turn and legal,
// cycles formed; a lathe's grooves formed, a mill's offsets assigned; tool axes made rotary
// positions where there are rotaries; positions checked where the machine states its travel.
ir::Facts legal_program(const Machine& m);
// The first problem of `m.pipeline`, as "needs 'drill-cycles' in its pipeline, ..." or
// "'drill-cycles' must come before 'kinematics'"; empty when the pipeline reaches a legal
// program. Unknown pass names are the caller's to report.
std::string check_pipeline(const Machine& m, const ir::PassContracts& passes);

}  // namespace clpc
