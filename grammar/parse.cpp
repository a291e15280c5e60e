#include "grammar/parse.h"

#include "grammar/parse_state.h"

namespace clpc {

namespace grammar {

void ParseState::begin(const MajorTok& m, SourceLoc loc) {
  params_.clear();
  too_many_ = false;
  rec_ = Record{};
  rec_.kind = Record::Kind::Statement;
  rec_.id = m.id;
  rec_.major = m.text;
  rec_.data_comment = m.data_comment;
  rec_.loc = loc;
}

void ParseState::number(double v, SourceLoc loc) {
  if (params_.size() >= kMaxParams) {
    if (!too_many_) lexer.report(loc, "record has more than 4096 parameters");
    too_many_ = true;
    return;
  }
  Param p;
  p.kind = Param::Kind::Number;
  p.number = v;
  p.loc = loc;
  params_.push_back(p);
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

void ParseState::end_statement(SourceLoc end) {
  if (too_many_) return;
  rec_.params = params_;
  rec_.end = end;
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

void run(SourceFile& src, Diagnostics* diags, RecordSink& sink, const bool* wanted) {
  grammar::ParseState st(src, diags, sink, wanted);
  grammar::Parser parser(st);
  parser.parse();
}

}  // namespace

void parse_cl(SourceFile& src, Diagnostics& diags, RecordSink& sink) { run(src, &diags, sink, nullptr); }

void prescan_cl(SourceFile& src, RecordSink& sink, const MajorSet& only) { run(src, nullptr, sink, only.on); }

}  // namespace clpc
