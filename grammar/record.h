// What the front end produces: one Record per CL statement, with its source location.
// Records are views into the parser's per-record storage: valid only inside the sink call.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "support/source.h"

namespace clpc {

enum class MajorId : uint8_t {
#define X(id, spelling) id,
#include "grammar/majors.def"
#undef X
  Unknown,
};

std::string_view major_spelling(MajorId id);
// The id of a major word as written (any case), or Unknown.
MajorId major_id(std::string_view word);

// The record a word begins with when that record moves the tool or changes how it cuts and
// the rest is glued to it: a number (GOTO10.0, LOADTL2, FEDRAT1000), or another such record
// (RAPIDGOTO), or UNITS' word (UNITSINCHES). A missing '/' that would lose the record. Else "".
std::string_view glued_record(std::string_view word);

// Records that only name or describe (text, header facts, tolerances): nothing in them moves
// the tool or changes how it cuts, so one written wrong is skipped, never a stopped post.
bool carries_nothing_to_cut(MajorId id);

// Whether a record of this name moves the tool or changes how it cuts (GOTO, CIRCLE, RAPID,
// FEDRAT, SPINDL, LOADTL, UNITS, CUTCOM, COOLNT, ...): one skipped loses motion. (Records named
// by common words, THREAD, COPY, SELECT, ROTATE, stand in tool names and notes: not these.)
bool moves_or_changes_the_cut(std::string_view name);

// Where such a record starts, as "NAME/" in capitals (or NX's "LOAD/TOOL"), inside a text: a
// parameter ("31 GOTO/10" in PAINT/COLOR,31 GOTO/10,0,10: a line end missing), or a line
// skipped as no record. The offset of its name, or npos. Reading past it would lose the record.
size_t record_inside(std::string_view text);

// ASCII case-insensitive equality (CL words are upper case by convention, not by rule).
bool iequals(std::string_view a, std::string_view b);

// A record's parameter. Names are names: whatever is not a number as a whole is a word, so a
// parameter only becomes a number where lowering asks for one (docs/cl-input.md).
struct Param {
  enum class Kind : uint8_t {
    Number,
    Word,    // any text that is not a number: CLW, 1STPECK, 6_KONTUR_125, T1 End Mill D 10
    String,  // 'quoted' or "quoted"
    Empty,   // nothing between two commas (CATIA: TOOLNO/2,MILL,2,0,20.,150.,,90.)
    Group,   // (NAME/ ... ) or ( ... ): the next `group_size` parameters are inside it
  };
  Kind kind = Kind::Number;
  double number = 0;
  std::string_view text;  // the word or string, the group's name; for numbers the digits as
                          // written when the record went through the grammar (simple records:
                          // empty)
  SourceLoc loc;
  uint32_t group_size = 0;
  bool is_number() const { return kind == Kind::Number; }
  bool is_word() const { return kind == Kind::Word; }
  bool is_empty() const { return kind == Kind::Empty; }
  bool is_group() const { return kind == Kind::Group; }
  bool is(std::string_view word) const { return kind == Kind::Word && iequals(text, word); }
  // A name at this position: a word or string as written, a number as written.
  std::string_view name() const { return text; }
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
  std::span<const Param> head;  // words before the major word: TLON in TLON,GOFWD/(...)
  std::span<const Param> params;
  std::string_view text;      // free text or comment text
  SourceLoc loc;              // of the major word (or of "$$")
  SourceLoc end;              // just past the last token: where a missing value would go
  // Records that move the tool (GOTO, CIRCLE, GOHOME, GOFWD, ...) a pre-scan skipped before this one, counted from the file's
  // start: a pre-scan that wants no motion still sees where some came between two records.
  uint32_t motion_skipped = 0;
};

class RecordSink {
 public:
  virtual ~RecordSink() = default;
  virtual void record(const Record& r) = 0;
};

}  // namespace clpc
