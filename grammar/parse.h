// The front end's entry point: bytes in, records out.
#pragma once

#include "grammar/record.h"
#include "support/diagnostics.h"
#include "support/source.h"

namespace clpc {

// Which majors a pre-scan wants; indexed by MajorId. All false = nothing.
struct MajorSet {
  bool on[int(MajorId::Unknown) + 1] = {};
  MajorSet& add(MajorId id) { on[int(id)] = true; return *this; }
};

// Parses all of `src`, calling `sink.record` for every statement and comment in order.
// Problems are reported to `diags`; the parse goes on after an error (to the next record)
// until Diagnostics stops it. With `only`, records of other majors are skipped unread and
// nothing is reported (the compile pass will): that is the cheap pre-scan.
struct ParseOptions {
  bool simple_records = true;  // the lexer's fast path for MAJOR/numbers lines (off: all through the grammar)
  bool latin1 = false;         // comments and text in Latin-1 rather than UTF-8
};
void parse_cl(SourceFile& src, Diagnostics& diags, RecordSink& sink, ParseOptions opt = {});
void prescan_cl(SourceFile& src, RecordSink& sink, const MajorSet& only);

}  // namespace clpc
