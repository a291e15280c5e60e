#include "grammar/parse.h"

#include "grammar/parse_state.h"

namespace clpc {

namespace grammar {

void ParseState::begin(const MajorTok& m, SourceLoc loc) {
  in_record_ = true;
  params_.clear();
  head_.clear();
  groups_.clear();
  too_many_ = false;
  rec_ = Record{};
  rec_.kind = Record::Kind::Statement;
  rec_.id = m.id;
  rec_.major = m.text;
  rec_.data_comment = m.data_comment;
  rec_.loc = loc;
}

// TLON,GOFWD/...: the words before the last are the record's head; the last is its major.
void ParseState::head_word(std::string_view word, SourceLoc loc) {
  if (head_.size() >= kMaxHead) {
    if (!too_many_) lexer.report(loc, "more than 8 words before the record's '/'");
    too_many_ = true;
    return;
  }
  Param h;
  h.kind = Param::Kind::Word;
  h.text = rec_.major;
  h.loc = rec_.loc;
  head_.push_back(h);
  rec_.major = word;
  rec_.id = major_id(word);
}

void ParseState::number(double v, std::string_view text, SourceLoc loc) {
  if (params_.size() >= kMaxParams) {
    if (!too_many_) lexer.report(loc, "record has more than 4096 parameters");
    too_many_ = true;
    return;
  }
  Param& p = params_.emplace_back();
  p.kind = Param::Kind::Number;
  p.number = v;
  p.text = text;
  p.loc = loc;
}

void ParseState::group_begin(std::string_view name, SourceLoc loc) {
  word(name, loc, Param::Kind::Group);
  if (!too_many_) groups_.push_back(uint32_t(params_.size() - 1));
}

// Trailing empty parameters say nothing (GOTO/1,2,3, and CAMWorks' trailing commas).
void ParseState::group_end() {
  if (too_many_ || groups_.empty()) return;
  uint32_t g = groups_.back();
  groups_.pop_back();
  while (params_.size() > g + 1 && params_.back().is_empty()) params_.pop_back();
  params_[g].group_size = uint32_t(params_.size() - g - 1);
}

void ParseState::word(std::string_view text, SourceLoc loc, Param::Kind kind) {
  if (params_.size() >= kMaxParams) {
    if (!too_many_) lexer.report(loc, "record has more than 4096 parameters");
    too_many_ = true;
    return;
  }
  Param p;
  p.kind = kind;
  p.text = text;
  p.loc = loc;
  params_.push_back(p);
}

void ParseState::simple_record(const Lexer::Simple& s) {
  MajorTok m;
  m.id = s.id;
  m.text = major_spelling(s.id);
  begin(m, s.start);
  for (size_t i = 0; i < s.n; ++i) number(s.value[i], {}, s.loc[i]);
  slash();
  end_statement(s.end);
}

void ParseState::end_statement(SourceLoc end) {
  in_record_ = false;
  if (too_many_) return;
  while (!params_.empty() && params_.back().is_empty()) params_.pop_back();
  rec_.params = params_;
  rec_.head = head_;
  rec_.end = end;
  rec_.motion_skipped = lexer.motion_skipped();
  sink_.record(rec_);
}

void ParseState::comment(std::string_view text, SourceLoc loc) {
  Record c;
  c.kind = Record::Kind::Comment;
  c.text = text;
  c.loc = loc;
  c.end = loc;
  sink_.record(c);
}

void ParseState::syntax_error(SourceLoc loc, const std::string& msg) {
  lexer.report(loc, msg);
}

}  // namespace grammar

namespace {

void run(SourceFile& src, Diagnostics* diags, RecordSink& sink, const bool* wanted, ParseOptions opt = {}) {
  grammar::ParseState st(src, diags, sink, wanted);
  st.lexer.set_simple_records(opt.simple_records);
  st.lexer.set_latin1(opt.latin1);
  grammar::Parser parser(st);
  parser.parse();
}

}  // namespace

void parse_cl(SourceFile& src, Diagnostics& diags, RecordSink& sink, ParseOptions opt) {
  run(src, &diags, sink, nullptr, opt);
}

void prescan_cl(SourceFile& src, RecordSink& sink, const MajorSet& only) { run(src, nullptr, sink, only.on); }

}  // namespace clpc
