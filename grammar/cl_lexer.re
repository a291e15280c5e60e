// The CL lexer: re2c rules, one block per mode. See lexer.h for the contract and
// docs/cl-input.md for the lexical rules it implements.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>

#include "grammar/lexer.h"

namespace clpc::grammar {

namespace {

constexpr size_t kWindow = 1 << 20;  // read window; a token may use up to kMaxToken of it

std::string describe(unsigned char c) {
  if (c == 0) return "NUL byte";
  if (c == '\n') return "the end of the line";
  if (c < 0x20 || c >= 0x7f) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "byte 0x%02X", c);
    return buf;
  }
  return std::string("'") + char(c) + "'";
}

}  // namespace

/*!re2c
  re2c:api:style = free-form;
  re2c:define:YYCTYPE = "unsigned char";
  re2c:define:YYCURSOR = "cur_";
  re2c:define:YYLIMIT = "lim_";
  re2c:define:YYMARKER = "mar_";
  re2c:define:YYCTXMARKER = "ctx_";
  re2c:define:YYFILL = "fill() == 0";
  re2c:eof = 0;

  ws      = [ \t\f\v\r];
  nl      = "\n";
  mword   = [A-Za-z_] [A-Za-z0-9_-]*;
  majorw  = mword ([ \t]+ mword)*;
  num     = [+-]? ([0-9]+ ("." [0-9]*)? | "." [0-9]+) ([eE] [+-]? [0-9]+)?;
  numlike = [+.0-9-] [A-Za-z0-9_.+-]*;
  pchar   = [A-Za-z0-9_.#@-];
  pword   = [A-Za-z_#@] pchar* ([ \t]+ pchar+)*;
  dword   = [0-9]+ [A-Za-z] [A-Za-z_] pchar*;  // APT minor words such as 1STPECK
  cont    = "$" ws* ("$$" [^\n\x00]*)? nl;
  text    = [^\n\x00]*;
*/

namespace {
// Small files get small buffers (tests, fuzzing, the many short CL files): the window need
// only hold the file or twice the longest token, the arena only the file's text.
size_t window_for(uint64_t size) { return size_t(std::clamp<uint64_t>(size + 1, 2 * Lexer::kMaxToken + 1, kWindow)); }
size_t arena_for(uint64_t size) { return size_t(std::clamp<uint64_t>(size + 1, 4096, Lexer::kArenaSize)); }
}  // namespace

Lexer::Lexer(SourceFile& src, Diagnostics* diags, const bool* wanted)
    : src_(src),
      diags_(diags),
      wanted_(wanted),
      buf_(new unsigned char[window_for(src.size()) + 1]),
      cap_(window_for(src.size())),
      arena_(new char[arena_for(src.size())]),
      arena_cap_(arena_for(src.size())) {
  cur_ = lim_ = tok_ = mar_ = ctx_ = buf_.get();
  buf_[0] = 0;
  src_.note_line_start(1, 0);
}

int Lexer::fill() {
  if (eof_) return 1;
  unsigned char* b = buf_.get();
  if (size_t(cur_ - tok_) > kMaxToken) {
    // The token is too long to keep: drop what we have of it and remember. The rule that
    // ends up matching reports it and skips the record.
    if (!overflow_) overflow_at_ = loc_of(tok_);
    overflow_ = true;
    tok_ = cur_;
  }
  size_t drop = size_t(tok_ - b);
  size_t keep = size_t(lim_ - tok_);
  if (drop != 0) {
    std::memmove(b, tok_, keep);
    auto shift = [&](const unsigned char*& p) { p = p >= tok_ ? p - drop : b; };
    shift(cur_);
    shift(mar_);
    shift(ctx_);
    tok_ = b;
    lim_ = b + keep;
    base_ += drop;
    b[keep] = 0;  // the sentinel must follow the data even when nothing more arrives
  }
  long n = src_.read_at(read_pos_, reinterpret_cast<char*>(b + keep), cap_ - keep);
  if (n <= 0) {
    eof_ = true;
    if (n < 0 && diags_) diags_->error(loc_of(cur_), "read error in " + src_.name());
    return 1;
  }
  read_pos_ += uint64_t(n);
  src_.reached(read_pos_);
  lim_ = b + keep + n;
  b[keep + size_t(n)] = 0;
  return 0;
}

void Lexer::newline(const unsigned char* after) {
  ++line_;
  line_start_ = abs(after);
  src_.note_line_start(line_, line_start_);
}

namespace {

// A number as the grammar's `num` writes it; returns its end, or null.
const unsigned char* match_num(const unsigned char* p, const unsigned char* e) {
  if (p < e && (*p == '+' || *p == '-')) ++p;
  const unsigned char* digits = p;
  while (p < e && *p >= '0' && *p <= '9') ++p;
  bool any = p > digits;
  if (p < e && *p == '.') {
    ++p;
    const unsigned char* frac = p;
    while (p < e && *p >= '0' && *p <= '9') ++p;
    any = any || p > frac;
  }
  if (!any) return nullptr;
  if (p < e && (*p == 'e' || *p == 'E')) {
    const unsigned char* q = p + 1;
    if (q < e && (*q == '+' || *q == '-')) ++q;
    const unsigned char* exp = q;
    while (q < e && *q >= '0' && *q <= '9') ++q;
    if (q == exp) return nullptr;
    p = q;
  }
  return p;
}

// The first byte of [b, e) that is not part of valid UTF-8 (no overlong forms, no
// surrogates, nothing past U+10FFFF), or null.
const unsigned char* invalid_utf8(const unsigned char* b, const unsigned char* e) {
  while (b < e) {
    unsigned char c = *b;
    if (c < 0x80) {
      ++b;
      continue;
    }
    int n = 0;
    unsigned char lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) n = 1;
    else if (c == 0xE0) n = 2, lo = 0xA0;
    else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) n = 2;
    else if (c == 0xED) n = 2, hi = 0x9F;
    else if (c == 0xF0) n = 3, lo = 0x90;
    else if (c >= 0xF1 && c <= 0xF3) n = 3;
    else if (c == 0xF4) n = 3, hi = 0x8F;
    else return b;
    if (e - b <= n) return b;
    if (b[1] < lo || b[1] > hi) return b;
    for (int i = 2; i <= n; ++i)
      if (b[i] < 0x80 || b[i] > 0xBF) return b;
    b += n + 1;
  }
  return nullptr;
}

bool is_ws(unsigned char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v' || c == '\r'; }

}  // namespace

bool Lexer::simple_record(Simple& s) {
  if (!simple_on_ || wanted_ || mode_ != Mode::LineStart || pending_ || at_end_) return false;
  const unsigned char* p = cur_;
  const unsigned char* nl = static_cast<const unsigned char*>(std::memchr(p, '\n', size_t(lim_ - p)));
  if (!nl || size_t(nl - p) > kMaxToken) return false;
  static constexpr struct {
    const char* word;
    size_t len;
    MajorId id;
  } kMajors[] = {{"GOTO/", 5, MajorId::Goto}, {"CIRCLE/", 7, MajorId::Circle}, {"FROM/", 5, MajorId::From},
                 {"GODLTA/", 7, MajorId::Godlta}};
  MajorId id = MajorId::Unknown;
  for (const auto& m : kMajors)
    if (size_t(nl - p) > m.len && std::memcmp(p, m.word, m.len) == 0) {
      id = m.id;
      p += m.len;
      break;
    }
  if (id == MajorId::Unknown) return false;
  s.n = 0;
  for (;;) {
    while (p < nl && is_ws(*p)) ++p;
    const unsigned char* e = match_num(p, nl);
    if (!e || s.n == kMaxSimple) return false;
    if (e < nl && !is_ws(*e) && *e != ',') return false;  // a word, "1.2.3", "$": the grammar's
    const char* b = reinterpret_cast<const char*>(*p == '+' ? p + 1 : p);
    auto [end, ec] = std::from_chars(b, reinterpret_cast<const char*>(e), s.value[s.n]);
    if (ec != std::errc() || end != reinterpret_cast<const char*>(e)) return false;
    s.col[s.n++] = uint32_t(abs(p) - line_start_ + 1);
    p = e;
    while (p < nl && is_ws(*p)) ++p;
    if (p == nl) break;
    if (*p != ',') return false;
    ++p;
  }
  s.id = id;
  s.start = loc_of(cur_);
  s.end = loc_of(nl);
  cur_ = tok_ = nl + 1;
  newline(cur_);
  return true;
}

SourceLoc Lexer::loc_of(const unsigned char* p) const {
  uint64_t a = abs(p);
  uint64_t col = a >= line_start_ ? a - line_start_ + 1 : 1;
  return {line_, uint32_t(std::min<uint64_t>(col, UINT32_MAX))};
}

std::string Lexer::too_long() const {
  return "line too long: a word, number or text of more than " + std::to_string(kMaxToken) + " characters";
}

// Comments and free text are UTF-8 (ASCII in practice): a byte that is not is reported where
// it is, unless the file was declared Latin-1 (old CAM systems), where every byte is a letter.
void Lexer::check_text(const unsigned char* b, const unsigned char* e, const char* what) {
  if (latin1_) return;
  if (const unsigned char* bad = invalid_utf8(b, e)) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02X", *bad);
    report(loc_of(bad), std::string("invalid UTF-8 in a ") + what + ": byte " + hex +
                            " (if the file is Latin-1, --input-encoding latin1 reads it)");
  }
}

void Lexer::report(SourceLoc loc, const std::string& msg) {
  if (!diags_) return;
  if (data_comment_)
    diags_->warning(loc, "malformed '$$->' data comment ignored: " + msg, "malformed data comment");
  else
    diags_->error(loc, msg);
}

std::string_view Lexer::keep(const unsigned char* b, const unsigned char* e) {
  size_t n = size_t(e - b);
  if (arena_used_ + n > arena_cap_) {
    if (!arena_full_) report(record_start_, "record too long (its text exceeds 1 MiB)");
    arena_full_ = true;
    return {};
  }
  char* dst = arena_.get() + arena_used_;
  std::memcpy(dst, b, n);
  arena_used_ += n;
  return {dst, n};
}

Lexer::Symbol Lexer::error_token(SourceLoc loc, const std::string& msg) {
  report(loc, msg);
  mode_ = Mode::SkipRecord;
  return Parser::make_YYerror(loc);
}

Lexer::Symbol Lexer::major(MajorId id, const unsigned char* b, const unsigned char* e) {
  record_start_ = loc_of(b);
  arena_used_ = 0;
  arena_full_ = false;
  MajorTok t;
  t.id = id;
  t.text = id == MajorId::Unknown ? keep(b, e) : major_spelling(id);
  t.data_comment = data_comment_;
  mode_ = Mode::AfterMajor;
  return Parser::make_MAJOR(t, record_start_);
}

// PARTNO, PPRINT, INSERT, REMARK: the rest of the line, after an optional '/', is text.
Lexer::Symbol Lexer::free_text_major(MajorId id, size_t keyword_len) {
  const unsigned char* b = tok_ + keyword_len;
  const unsigned char* e = cur_;
  while (b < e && (*b == ' ' || *b == '\t')) ++b;
  if (b < e && *b == '/') ++b;
  while (b < e && (*b == ' ' || *b == '\t')) ++b;
  while (e > b && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) --e;
  check_text(b, e, "text");
  Symbol m = major(id, tok_, tok_ + keyword_len);
  pending_.emplace(Parser::make_TEXT(keep(b, e), loc_of(b)));
  mode_ = Mode::AfterComment;  // only the line end may follow
  return m;
}

bool Lexer::skip_record() {
  bool continued = false;   // this line ends in a continuation '$'
  bool in_comment = false;  // past "$$" on this line
  for (;;) {
    tok_ = cur_;
    if (cur_ >= lim_) {
      if (fill() != 0) return false;
      continue;
    }
    size_t avail = size_t(lim_ - cur_);
    auto* nl = static_cast<const unsigned char*>(std::memchr(cur_, '\n', avail));
    const unsigned char* end = nl ? nl : lim_;
    if (!continued && !in_comment) {
      auto* d = static_cast<const unsigned char*>(std::memchr(cur_, '$', size_t(end - cur_)));
      if (d) {
        if (d + 1 >= lim_) {  // need the next byte to tell "$" from "$$"
          cur_ = d;
          tok_ = d;
          if (fill() != 0) return false;
          continue;
        }
        if (d[1] == '$') in_comment = true; else continued = true;
      }
    }
    if (!nl) {
      cur_ = lim_;
      continue;
    }
    cur_ = nl + 1;
    newline(cur_);
    if (!continued) return true;
    continued = in_comment = false;
  }
}

Lexer::Symbol Lexer::lex() {
  if (pending_) {
    Symbol s = std::move(*pending_);
    pending_.reset();
    return s;
  }
  switch (mode_) {
    case Mode::LineStart: return lex_line_start();
    case Mode::AfterMajor: return lex_after_major();
    case Mode::Params: return lex_params();
    case Mode::CommentText: return lex_comment();
    case Mode::AfterComment: return lex_after_comment();
    case Mode::SkipRecord: {
      SourceLoc at = loc_of(cur_);
      mode_ = Mode::LineStart;
      overflow_ = false;
      if (!skip_record()) at_end_ = true;
      return Parser::make_EOL(at);
    }
  }
  return Parser::make_END(loc_of(cur_));
}

#define MAJOR(id)                                                        \
  {                                                                      \
    if (overflow_) return error_token(overflow_at_, too_long());    \
    if (!wanted_ || wanted_[int(MajorId::id)]) return major(MajorId::id, tok_, cur_); \
    skip_record();                                                       \
    continue;                                                            \
  }

#define FREE_TEXT(id, n)                                                 \
  {                                                                      \
    if (overflow_) return error_token(overflow_at_, too_long());    \
    if (!wanted_ || wanted_[int(MajorId::id)]) return free_text_major(MajorId::id, n); \
    skip_record();                                                       \
    continue;                                                            \
  }

Lexer::Symbol Lexer::lex_line_start() {
  bool data_mark = false;
  for (;;) {
    tok_ = cur_;
    data_comment_ = data_mark;
    /*!re2c
      $ {
        at_end_ = true;
        return Parser::make_END(loc_of(tok_));
      }
      ws+ { continue; }
      nl  { newline(cur_); continue; }
      cont { for (auto* p = tok_; p < cur_; ++p) if (*p == '\n') newline(p + 1); continue; }

      "$$->" [ \t]* / [A-Za-z_] { data_mark = true; continue; }
      "$$" {
        if (wanted_) { skip_record(); continue; }
        record_start_ = loc_of(tok_);
        arena_used_ = 0;
        arena_full_ = false;
        mode_ = Mode::CommentText;
        return lex_comment();
      }

      'PARTNO' [ \t/] text { FREE_TEXT(Partno, 6) }
      'PPRINT' [ \t/] text { FREE_TEXT(Pprint, 6) }
      'INSERT' [ \t/] text { FREE_TEXT(Insert, 6) }
      'REMARK' [ \t/] text { FREE_TEXT(Remark, 6) }

      'GOTO'        { MAJOR(Goto) }
      'FROM'        { MAJOR(From) }
      'GOHOME'      { MAJOR(Gohome) }
      'GODLTA'      { MAJOR(Godlta) }
      'CIRCLE'      { MAJOR(Circle) }
      'RAPID'       { MAJOR(Rapid) }
      'FEDRAT'      { MAJOR(Fedrat) }
      'SPINDL'      { MAJOR(Spindl) }
      'COOLNT'      { MAJOR(Coolnt) }
      'LOADTL'      { MAJOR(Loadtl) }
      'LOAD'        { MAJOR(Load) }
      'TURRET'      { MAJOR(Turret) }
      'SELECT'      { MAJOR(Select) }
      'TLDATA'      { MAJOR(Tldata) }
      'CUTTER'      { MAJOR(Cutter) }
      'TOOL' [ \t]+ 'PATH' { MAJOR(ToolPath) }
      'END-OF-PATH' { MAJOR(EndOfPath) }
      'FEATNO'      { MAJOR(Featno) }
      'MSYS'        { MAJOR(Msys) }
      'CSYS'        { MAJOR(Csys) }
      'CAMERA'      { MAJOR(Camera) }
      'SET'         { MAJOR(Set) }
      'CUTCOM'      { MAJOR(Cutcom) }
      'DELAY'       { MAJOR(Delay) }
      'OPSTOP'      { MAJOR(Opstop) }
      'STOP'        { MAJOR(Stop) }
      'END'         { MAJOR(End) }
      'FINI'        { MAJOR(Fini) }
      'UNITS'       { MAJOR(Units) }
      'UNIT'        { MAJOR(Unit) }
      'PARTNO'      { MAJOR(Partno) }
      'MACHIN'      { MAJOR(Machin) }
      'MULTAX'      { MAJOR(Multax) }
      'PPRINT'      { MAJOR(Pprint) }
      'INSERT'      { MAJOR(Insert) }
      'REMARK'      { MAJOR(Remark) }
      'CYCLE'       { MAJOR(Cycle) }
      'DEFSUB'      { MAJOR(Defsub) }
      'ENDSUB'      { MAJOR(Endsub) }
      'CALSUB'      { MAJOR(Calsub) }
      'ROTATE'      { MAJOR(Rotate) }
      'PAINT'       { MAJOR(Paint) }
      'PPWORD'      { MAJOR(Ppword) }
      'MODE'        { MAJOR(Mode) }
      'HEAD'        { MAJOR(Head) }
      'NURBS'       { MAJOR(Nurbs) }
      'KNOT'        { MAJOR(Knot) }
      'CNTRL'       { MAJOR(Cntrl) }
      'MFGNO'       { MAJOR(Mfgno) }
      'SETSTART'    { MAJOR(Setstart) }
      'CLRSRF'      { MAJOR(Clrsrf) }
      'RETRCT'      { MAJOR(Retract) }
      'AUXFUN'      { MAJOR(Auxfun) }
      'PREFUN'      { MAJOR(Prefun) }
      'ORIGIN'      { MAJOR(Origin) }
      'THREAD'      { MAJOR(Thread) }
      majorw        { MAJOR(Unknown) }

      * {
        if (wanted_) { skip_record(); continue; }
        return error_token(loc_of(tok_), "expected a major word at the start of a record, found " + describe(*tok_));
      }
    */
  }
}

Lexer::Symbol Lexer::lex_after_major() {
  for (;;) {
    tok_ = cur_;
    /*!re2c
      $    { mode_ = Mode::LineStart; return Parser::make_EOL(loc_of(tok_)); }
      ws+  { continue; }
      cont {
        SourceLoc dollar = loc_of(tok_);
        for (auto* p = tok_; p < cur_; ++p) if (*p == '\n') newline(p + 1);
        if (cur_ >= lim_ && fill() != 0)
          return error_token(dollar, "unterminated continuation: '$' at the end of the file");
        continue;
      }
      nl   { SourceLoc at = loc_of(tok_); newline(cur_); mode_ = Mode::LineStart; return Parser::make_EOL(at); }
      "/"  { mode_ = Mode::Params; return Parser::make_SLASH(loc_of(tok_)); }
      "$$" { mode_ = Mode::CommentText; return lex_comment(); }
      "$" ws* {
        if (cur_ >= lim_ && fill() != 0)
          return error_token(loc_of(tok_), "unterminated continuation: '$' at the end of the file");
        return error_token(loc_of(tok_), "'$' continues a record only at the end of a line");
      }
      * { return error_token(loc_of(tok_), "expected '/' or the end of the record, found " + describe(*tok_)); }
    */
  }
}

Lexer::Symbol Lexer::lex_params() {
  for (;;) {
    tok_ = cur_;
    /*!re2c
      $    { mode_ = Mode::LineStart; return Parser::make_EOL(loc_of(tok_)); }
      ws+  { continue; }
      cont {
        SourceLoc dollar = loc_of(tok_);
        for (auto* p = tok_; p < cur_; ++p) if (*p == '\n') newline(p + 1);
        if (cur_ >= lim_ && fill() != 0)
          return error_token(dollar, "unterminated continuation: '$' at the end of the file");
        continue;
      }
      nl   { SourceLoc at = loc_of(tok_); newline(cur_); mode_ = Mode::LineStart; return Parser::make_EOL(at); }
      ","  { return Parser::make_COMMA(loc_of(tok_)); }
      "$$" { mode_ = Mode::CommentText; return lex_comment(); }
      "$" ws* {
        if (cur_ >= lim_ && fill() != 0)
          return error_token(loc_of(tok_), "unterminated continuation: '$' at the end of the file");
        return error_token(loc_of(tok_), "'$' continues a record only at the end of a line");
      }
      num {
        if (overflow_) return error_token(overflow_at_, too_long());
        const char* b = reinterpret_cast<const char*>(tok_);
        const char* e = reinterpret_cast<const char*>(cur_);
        const char* digits = *b == '+' ? b + 1 : b;
        double v = 0;
        auto [end, ec] = std::from_chars(digits, e, v);
        if (ec == std::errc::result_out_of_range) {
          // Underflow reads as zero; overflow is an error.
          const char* exp = digits;
          while (exp < e && *exp != 'e' && *exp != 'E') ++exp;
          if (exp < e && exp[1] != '-')
            return error_token(loc_of(tok_), "number out of range: '" + std::string(lexeme()) + "'");
          v = 0;
        } else if (ec != std::errc() || end != e) {
          return error_token(loc_of(tok_), "bad number '" + std::string(lexeme()) + "'");
        }
        return Parser::make_NUMBER(v, loc_of(tok_));
      }
      dword {
        if (overflow_) return error_token(overflow_at_, too_long());
        return Parser::make_WORD(keep(tok_, cur_), loc_of(tok_));
      }
      numlike {
        if (overflow_) return error_token(overflow_at_, too_long());
        return error_token(loc_of(tok_), "bad number '" + std::string(lexeme()) + "'");
      }
      pword {
        if (overflow_) return error_token(overflow_at_, too_long());
        return Parser::make_WORD(keep(tok_, cur_), loc_of(tok_));
      }
      ['] [^'\n\x00]* ['] | ["] [^"\n\x00]* ["] {
        if (overflow_) return error_token(overflow_at_, too_long());
        return Parser::make_STRING(keep(tok_ + 1, cur_ - 1), loc_of(tok_));
      }
      ['"] { return error_token(loc_of(tok_), "unterminated string"); }
      * { return error_token(loc_of(tok_), "unexpected " + describe(*tok_) + " in a record"); }
    */
  }
}

// After "$$": the rest of the line is the comment's text.
Lexer::Symbol Lexer::lex_comment() {
  SourceLoc at = loc_of(cur_ >= buf_.get() + 2 ? cur_ - 2 : cur_);
  tok_ = cur_;
  mode_ = Mode::AfterComment;
  /*!re2c
    [^\n\x00]+ {
      if (overflow_) return error_token(at, too_long());
      const unsigned char* e = cur_;
      while (e > tok_ && e[-1] == '\r') --e;
      check_text(tok_, e, "comment");
      return Parser::make_COMMENT(keep(tok_, e), at);
    }
    $ { return Parser::make_COMMENT(std::string_view(), at); }
    * { cur_ = tok_; return Parser::make_COMMENT(std::string_view(), at); }
  */
}

Lexer::Symbol Lexer::lex_after_comment() {
  tok_ = cur_;
  /*!re2c
    $  { mode_ = Mode::LineStart; return Parser::make_EOL(loc_of(tok_)); }
    nl { SourceLoc at = loc_of(tok_); newline(cur_); mode_ = Mode::LineStart; return Parser::make_EOL(at); }
    *  { return error_token(loc_of(tok_), "unexpected " + describe(*tok_)); }
  */
}

}  // namespace clpc::grammar
