// The CL lexer (generated from cl_lexer.re by re2c). It reads the file through a fixed
// window (no whole-file copy), splices "$" continuations out of the text as it reads it (so a
// number or word cut at column 72 joins up again), tracks line and column of the physical
// lines, and copies the text of words into a per-record arena so the parser can hold them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "grammar/cl_parser.hpp"
#include "support/diagnostics.h"
#include "support/source.h"

namespace clpc::grammar {

class Lexer {
 public:
  // `diags` may be null (pre-scan: the compile pass reports). When `wanted` is non-null,
  // records whose major word it marks false are skipped without being tokenised.
  Lexer(SourceFile& src, Diagnostics* diags, const bool* wanted);

  Parser::symbol_type lex();

  // The commonest record — GOTO, CIRCLE, FROM or GODLTA, a slash (Creo puts blanks before
  // it) and numbers, on one line or on lines joined by continuations, nothing else — read here
  // without the parser. True with the line consumed and `s` filled;
  // false with nothing consumed, and the line goes through the grammar as any other. Both
  // give the same record (tests/grammar/test_lexer.cpp compares them on the corpus).
  static constexpr size_t kMaxSimple = 16;
  struct Simple {
    MajorId id = MajorId::Unknown;
    SourceLoc start, end;
    size_t n = 0;
    double value[kMaxSimple];
    SourceLoc loc[kMaxSimple];
  };
  bool simple_record(Simple& s);
  void set_simple_records(bool on) { simple_on_ = on; }
  void set_latin1(bool on) { latin1_ = on; }

  // True while the current record was written inside "$$->": its problems are warnings.
  bool in_data_comment() const { return data_comment_; }
  Diagnostics* diagnostics() const { return diags_; }
  void report(SourceLoc loc, const std::string& msg);

  static constexpr size_t kMaxToken = 64 * 1024;  // longest word, number, text or comment
  static constexpr size_t kArenaSize = 1 << 20;   // all text of one record

  // Records that move the tool (GOTO, CIRCLE, GOHOME, GOFWD, ...) skipped so far because the caller (a pre-scan) did not want them.
  uint32_t motion_skipped() const { return motion_skipped_; }

  // The head of a file is APT's card-image form (docs/cl-input.md, "Card images").
  static bool looks_like_card_image(std::string_view head);

 private:
  using Symbol = Parser::symbol_type;
  enum class Mode : uint8_t { LineStart, AfterMajor, Params, CommentText, AfterComment, SkipRecord };

  Symbol lex_line_start();
  Symbol lex_after_major();
  Symbol lex_params();
  Symbol lex_comment();
  Symbol lex_after_comment();
  Symbol lex_run();           // a parameter that is not punctuation: a number or a name
  Symbol number_token(const unsigned char* b, const unsigned char* e, bool& bad);
  Symbol not_a_record();
  bool listing_line() const;  // NX's information-window lines around a CLSF listing

  int fill();                       // YYFILL: 0 when more input arrived
  void newline(const unsigned char* after);
  void pass_splices(uint64_t before);  // counts the lines spliced away before `before`
  SourceLoc loc_of(const unsigned char* p) const;
  uint64_t abs(const unsigned char* p) const { return base_ + uint64_t(p - buf_.get()); }
  std::string_view keep(const unsigned char* b, const unsigned char* e);
  Symbol error_token(SourceLoc loc, const std::string& msg);  // report, then skip the record
  Symbol major(MajorId id, const unsigned char* b, const unsigned char* e);
  Symbol free_text_major(MajorId id, size_t keyword_len);
  bool skip_record();               // to the end of the record; false at end of input
  // `prose`: the line opens as a note ("* RETRACT AT RAPID"): only a "NAME/" record counts.
  std::string motion_word_in_line(bool prose = false) const;
  Symbol hard_error_token(SourceLoc loc, const std::string& msg);
  uint32_t motion_skipped_ = 0;  // records that move the tool skipped as not wanted
  void check_text(const unsigned char* b, const unsigned char* e, const char* what);
  std::string_view lexeme() const { return {reinterpret_cast<const char*>(tok_), size_t(cur_ - tok_)}; }

  SourceFile& src_;
  Diagnostics* diags_;
  const bool* wanted_;

  std::unique_ptr<unsigned char[]> buf_;
  size_t cap_;
  const unsigned char* cur_;
  const unsigned char* lim_;       // end of the spliced text the rules may read
  unsigned char* raw_end_;         // [lim_, raw_end_): read, not yet spliced (a line's start)
  unsigned char saved_ = 0;        // the byte the sentinel at lim_ covers
  const unsigned char* tok_;
  const unsigned char* mar_;
  const unsigned char* ctx_;
  uint64_t base_ = 0;       // file offset of buf_[0]
  uint64_t read_pos_ = 0;   // next file offset to read
  bool eof_ = false;
  // A card-image file (APT's fixed form: every line 80 columns, 73-80 an identification or
  // sequence field): those columns are no text and are blanked as each line is read.
  bool card_image_ = false;
  static void blank_card_columns(unsigned char* b, unsigned char* e);
  bool overflow_ = false;   // a token outgrew kMaxToken
  SourceLoc overflow_at_;   // where that token began
  std::string too_long() const;

  // A continuation ("$", blanks, an optional "$$" comment, the line end) removed from the text:
  // the next physical line's bytes start at `at` (an offset in the spliced text).
  struct Splice {
    uint64_t at;
    uint32_t removed;
  };
  std::vector<Splice> splices_;   // not yet passed by the lexer, in order
  size_t splice_head_ = 0;
  // A record hidden inside another's line: joined to it by a '$' continuation, or standing
  // after a carriage return alone (a line end to some editors and DNC programs, a blank to
  // others). Found as the text is spliced, reported when the lexer reaches the record that
  // holds it (`hidden_record_error`), in order.
  struct Hidden {
    uint64_t at;      // offset in the spliced text where the hidden record starts
    MajorId id;
    bool after_cr;    // after a lone CR, else after a continuation
  };
  std::vector<Hidden> hidden_;
  size_t hidden_head_ = 0;
  void find_hidden_records(unsigned char* b, unsigned char* e, size_t first_splice);
  std::optional<Symbol> hidden_record_error();
  uint64_t removed_passed_ = 0;   // bytes removed by the splices passed: file offset - text offset

  uint32_t line_ = 1;
  uint64_t line_start_ = 0;  // offset in the spliced text where the current line starts
  int depth_ = 0;            // open parentheses in the current record
  uint64_t numbers_end_ = 0; // inside "1.0 2.0 3.0" (numbers apart by blanks): where the run ends
  bool known_major_ = false; // the current record's major word is one clpc knows
  MajorId record_id_ = MajorId::Unknown;
  bool comma_seen_ = false;  // the record's parameters so far had a comma between two
  bool numbered_said_ = false;  // a numbered line (a CL listing's) was said
  bool numbered_line() const;  // and which it is (Unknown before one is read)
  std::string_view unknown_major_;  // its text where it is not (in the record's arena)
  Mode mode_ = Mode::LineStart;
  bool data_comment_ = false;
  bool at_end_ = false;
  bool simple_on_ = true;
  bool latin1_ = false;
  std::optional<Symbol> pending_;
  SourceLoc record_start_;

  std::unique_ptr<char[]> arena_;
  size_t arena_cap_;
  size_t arena_used_ = 0;
  bool arena_full_ = false;
};

}  // namespace clpc::grammar
