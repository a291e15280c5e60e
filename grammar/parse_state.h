// The state the grammar actions build records in; one per parse. Internal to grammar/.
#pragma once

#include <vector>

#include "grammar/lexer.h"
#include "grammar/record.h"

namespace clpc::grammar {

class ParseState {
 public:
  ParseState(SourceFile& src, Diagnostics* diags, RecordSink& sink, const bool* wanted)
      : lexer(src, diags, wanted), sink_(sink) {
    params_.reserve(64);
  }

  Lexer lexer;

  void begin(const MajorTok& m, SourceLoc loc);
  void head_word(std::string_view word, SourceLoc loc);
  void slash() { rec_.has_slash = true; }
  void number(double v, std::string_view text, SourceLoc loc);
  void word(std::string_view text, SourceLoc loc, Param::Kind kind);
  void empty(SourceLoc loc) { word({}, loc, Param::Kind::Empty); }
  void group_begin(std::string_view name, SourceLoc loc);
  void group_end();
  void text(std::string_view t) { rec_.text = t; }
  void end_statement(SourceLoc end);
  void comment(std::string_view text, SourceLoc loc);
  void recovered() {
    too_many_ = false;
    in_record_ = false;
  }
  // Between records the lexer may hand over simple ones whole (Lexer::simple_record).
  bool between_records() const { return !in_record_; }
  void simple_record(const Lexer::Simple& s);
  Lexer::Simple simple;
  void syntax_error(SourceLoc loc, const std::string& msg);

  static constexpr size_t kMaxParams = 4096;
  static constexpr size_t kMaxHead = 8;

 private:
  RecordSink& sink_;
  Record rec_;
  std::vector<Param> params_;
  std::vector<Param> head_;
  std::vector<uint32_t> groups_;  // indices in params_ of the open groups
  bool too_many_ = false;
  bool in_record_ = false;
};

inline Parser::symbol_type yylex(ParseState& st) {
  while (st.between_records() && st.lexer.simple_record(st.simple)) st.simple_record(st.simple);
  return st.lexer.lex();
}

}  // namespace clpc::grammar
