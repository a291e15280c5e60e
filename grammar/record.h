// What the front end produces: one Record per CL statement, with its source location.
// Records are views into the parser's per-record storage: valid only inside the sink call.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "ir/source.h"

namespace clpc {

enum class MajorId : uint8_t {
#define X(id, spelling) id,
#include "grammar/majors.def"
#undef X
  Unknown,
};

std::string_view major_spelling(MajorId id);

// ASCII case-insensitive equality (CL words are upper case by convention, not by rule).
bool iequals(std::string_view a, std::string_view b);

struct Param {
  enum class Kind : uint8_t { Number, Word, String };
  Kind kind = Kind::Number;
  double number = 0;
  std::string_view text;  // the word or string; for numbers, the digits as written
  SourceLoc loc;
  bool is_number() const { return kind == Kind::Number; }
  bool is_word() const { return kind == Kind::Word; }
  bool is(std::string_view word) const { return kind == Kind::Word && iequals(text, word); }
};

struct Record {
  enum class Kind : uint8_t {
    Statement,  // MAJOR[/params] or a free-text statement (PARTNO, PPRINT, INSERT)
    Comment,    // $$ comment (whole line or trailing); text holds what follows "$$"
  };
  Kind kind = Kind::Statement;
  MajorId id = MajorId::Unknown;
  bool data_comment = false;  // written as "$$-> MAJOR / ..." (Creo)
  bool has_slash = false;
  std::string_view major;     // as written, for messages and passthrough
  std::span<const Param> params;
  std::string_view text;      // free text or comment text
  SourceLoc loc;              // of the major word (or of "$$")
  SourceLoc end;              // just past the last token: where a missing value would go
};

class RecordSink {
 public:
  virtual ~RecordSink() = default;
  virtual void record(const Record& r) = 0;
};

}  // namespace clpc
