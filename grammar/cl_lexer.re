// The CL lexer: re2c rules, one block per mode. See lexer.h for the contract and
// docs/cl-input.md for the lexical rules it implements.
#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <cstring>

#include "grammar/lexer.h"
#include "support/decimal.h"

namespace clpc::grammar {

namespace {

constexpr size_t kWindow = 1 << 20;  // read window; a token may use up to kMaxToken of it
constexpr int kMaxDepth = 16;        // nested parameter groups

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

bool is_ws(unsigned char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v' || c == '\r'; }
bool is_letter(unsigned char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }

// Splices the continuations out of the complete lines in [p, e): a "$" followed by blanks (and
// perhaps a "$$" comment) up to the line end joins the next line to it with nothing between,
// so a number or word cut anywhere (CATIA cuts at column 72) is whole again. A "$" inside a
// "$$" comment does not continue; a "$$->" data comment does (Creo's CSYS spans lines). The
// text moves down in place; `mark(at, removed)` hears of each splice. Returns the new end.
template <class Mark>
unsigned char* splice_lines(unsigned char* p, unsigned char* e, Mark&& mark) {
  unsigned char* w = p;
  while (p < e) {
    auto* nl = static_cast<unsigned char*>(std::memchr(p, '\n', size_t(e - p)));
    unsigned char* le = nl ? nl : e;
    unsigned char* next = nl ? nl + 1 : e;
    unsigned char* cut = nullptr;
    if (nl && std::memchr(p, '$', size_t(le - p))) {
      unsigned char* q = p;
      while (q < le && is_ws(*q)) ++q;
      if (le - q >= 4 && std::memcmp(q, "$$->", 4) == 0) {
        unsigned char* r = q + 4;
        while (r < le && is_ws(*r)) ++r;
        q = r < le && is_letter(*r) ? r : le;  // a data record: scan it; else all comment
      } else {
        q = p;
      }
      while (q < le) {
        auto* d = static_cast<unsigned char*>(std::memchr(q, '$', size_t(le - q)));
        if (!d) break;
        if (d + 1 < le && d[1] == '$') break;  // a comment: nothing after it continues
        unsigned char* t = d + 1;
        while (t < le && is_ws(*t)) ++t;
        if (t == le || (le - t >= 2 && t[0] == '$' && t[1] == '$')) {
          cut = d;
          break;
        }
        q = d + 1;
      }
    }
    unsigned char* keep_end = cut ? cut : next;
    if (w != p) std::memmove(w, p, size_t(keep_end - p));
    w += keep_end - p;
    if (cut) mark(w, size_t(next - cut));
    p = next;
  }
  return w;
}

// The record the text [q, e) starts as, if it starts as one of its own, else Unknown: after
// blanks and an optional statement label ("L1) "), a major word (NX's TOOL PATH counts as one)
// and '/', words and commas before one (TLON,GOFWD/), or in capitals one of the words that
// stand alone and change the program (RAPID, STOP, OPSTOP, GOHOME, END-OF-PATH) alone on the
// line or before a '$$' comment ("Thread" or "END" ending a sentence is text). The text
// records (PPRINT, PARTNO, REMARK, TPRINT, INSERT) count as none: joined to text, they stay text.
MajorId record_at(const unsigned char* q, const unsigned char* e, const unsigned char** word = nullptr) {
  auto blanks = [&](const unsigned char* p) {
    while (p < e && (*p == ' ' || *p == '\t')) ++p;
    return p;
  };
  auto alpha = [](unsigned char c) { return std::isalpha(c) != 0; };
  q = blanks(q);
  {  // a statement label
    const unsigned char* l = q;
    while (l < e && l - q < 6 && std::isalnum(*l)) ++l;
    if (l > q && alpha(*q) && l < e && *l == ')') q = blanks(l + 1);
  }
  const unsigned char* w = q;
  // A word may hold hyphens (END-OF-PATH); NX's TOOL PATH is two words.
  while (w < e && (alpha(*w) || (*w == '-' && w > q && w + 1 < e && alpha(w[1])))) ++w;
  if (w == q) return MajorId::Unknown;
  bool tool_path = false;
  if (w - q == 4 && iequals(std::string_view(reinterpret_cast<const char*>(q), 4), "TOOL")) {
    const unsigned char* p = blanks(w);
    if (p > w && e - p >= 4 && iequals(std::string_view(reinterpret_cast<const char*>(p), 4), "PATH") &&
        (e - p == 4 || !alpha(p[4]))) {
      w = p + 4;
      tool_path = true;
    }
  }
  const unsigned char* after = blanks(w);
  const unsigned char *name = q, *name_end = w;
  const std::string_view alone(reinterpret_cast<const char*>(q), size_t(w - q));
  const bool alone_record =
      alone == "RAPID" || alone == "STOP" || alone == "OPSTOP" || alone == "GOHOME" || alone == "END-OF-PATH";
  const bool alone_on_line = after == e || *after == '\r' || (e - after >= 2 && after[0] == '$' && after[1] == '$');
  bool record = (alone_on_line && alone_record) || (after < e && *after == '/');
  if (!record && after < e && *after == ',') {
    // Words and commas up to a '/': the word before the '/' is the record's.
    const unsigned char* sl = after;
    while (sl < e && (alpha(*sl) || *sl == ',' || *sl == ' ' || *sl == '\t')) ++sl;
    if (sl < e && *sl == '/') {
      name_end = sl;
      while (name_end > after && (name_end[-1] == ' ' || name_end[-1] == '\t')) --name_end;
      name = name_end;
      while (name > after && alpha(name[-1])) --name;
      record = name < name_end;
    }
  }
  if (!record) return MajorId::Unknown;
  const MajorId id = tool_path && name == q ? MajorId::ToolPath
                                            : major_id(std::string_view(reinterpret_cast<const char*>(name), size_t(name_end - name)));
  if (id == MajorId::Pprint || id == MajorId::Partno || id == MajorId::Remark || id == MajorId::Tprint || id == MajorId::Insert)
    return MajorId::Unknown;
  if (word) *word = q;
  return id;
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
  raw_end_ = buf_.get();
  buf_[0] = 0;
  // A UTF-8 byte-order mark (Windows editors and CAM systems write one) is no text: the file's
  // first line starts after it, and its columns count from there, as an editor shows them.
  char bom[3];
  if (src_.read_at(0, bom, 3) == 3 && bom[0] == '\xEF' && bom[1] == '\xBB' && bom[2] == '\xBF')
    base_ = read_pos_ = line_start_ = 3;
  src_.note_line_start(1, base_);
  char head[4096];
  const long got = src_.read_at(base_, head, sizeof head);
  card_image_ = got > 0 && looks_like_card_image(std::string_view(head, size_t(got)));
  if (card_image_ && diags_ && !wanted_)
    diags_->note(SourceLoc{1, 73}, "a card-image file (every line 80 columns, 73-80 a sequence field): columns 73-80 "
                                   "are not read, as APT reads its cards");
}

// The first (up to eight) non-blank lines of the file are 80 columns, and columns 73-80 of
// each are a card's identification field: letters, digits and blanks, ending in a number
// that grows from card to card (`00000010`, `APT00030`), after a blank or a continuation in
// column 72. Lines of a free-form file written in fixed columns (Creo, CATIA) can all be 80
// long and end in eight digits of a number: those digits follow a digit or a point, and
// blanking them would move the tool, so the test is strict; a deck it misses is refused at
// its first record, as before.
bool Lexer::looks_like_card_image(std::string_view head) {
  int lines = 0;
  long last = -1;
  size_t i = 0;
  while (i < head.size() && lines < 8) {
    const size_t nl = head.find('\n', i);
    if (nl == std::string_view::npos) break;  // the last, partial line is not judged
    std::string_view line = head.substr(i, nl - i);
    i = nl + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    if (line.size() != 80 || (line[71] != ' ' && line[71] != '$')) return false;
    const std::string_view field = line.substr(72);
    if (!std::isdigit(static_cast<unsigned char>(field.back()))) return false;
    for (char c : field)
      if (!(std::isdigit(static_cast<unsigned char>(c)) || (c >= 'A' && c <= 'Z') || c == ' ')) return false;
    size_t d = field.size();
    while (d > 0 && std::isdigit(static_cast<unsigned char>(field[d - 1]))) --d;
    const long number = std::stol(std::string(field.substr(d)));
    if (number <= last) return false;
    last = number;
    ++lines;
  }
  return lines >= 2;
}

// Blanks columns 73-80 of each whole line in [b, e) (b is a line's start).
void Lexer::blank_card_columns(unsigned char* b, unsigned char* e) {
  for (unsigned char* p = b; p < e;) {
    auto* nl = static_cast<unsigned char*>(std::memchr(p, '\n', size_t(e - p)));
    unsigned char* end = nl ? nl : e;
    size_t len = size_t(end - p);
    if (len && p[len - 1] == '\r') --len;
    if (len > 72) std::memset(p + 72, ' ', std::min<size_t>(len, 80) - 72);
    p = nl ? nl + 1 : e;
  }
}

// Reads more of the file. The rules see only spliced text, and only whole lines of it (so a
// continuation is always seen with the line end after it): what follows the last line end
// waits, unspliced, in [lim_, raw_end_) for the next read — unless the window is full of one
// line, or the file has ended.
int Lexer::fill() {
  if (eof_) return 1;
  unsigned char* b = buf_.get();
  if (raw_end_ > lim_) b[lim_ - b] = saved_;
  if (size_t(cur_ - tok_) > kMaxToken) {
    // The token is too long to keep: drop what we have of it and remember. The rule that
    // ends up matching reports it and skips the record.
    if (!overflow_) overflow_at_ = loc_of(tok_);
    overflow_ = true;
    tok_ = cur_;
  }
  size_t drop = size_t(tok_ - b);
  if (drop != 0) {
    std::memmove(b, tok_, size_t(raw_end_ - tok_));
    auto shift = [&](const unsigned char*& p) { p = p >= tok_ ? p - drop : b; };
    shift(cur_);
    shift(mar_);
    shift(ctx_);
    lim_ -= drop;
    raw_end_ -= drop;
    tok_ = b;
    base_ += drop;
  }
  const unsigned char* old_lim = lim_;
  for (;;) {
    size_t room = cap_ - size_t(raw_end_ - b);
    long n = room ? src_.read_at(read_pos_, reinterpret_cast<char*>(raw_end_), room) : 0;
    if (n < 0 && diags_) diags_->error(loc_of(cur_), "read error in " + src_.name());
    if (n > 0) {
      read_pos_ += uint64_t(n);
      src_.reached(read_pos_);
      raw_end_ += n;
    }
    const bool end = room != 0 && n <= 0;
    unsigned char* upto = raw_end_;
    if (!end && room != 0) {
      unsigned char* s = const_cast<unsigned char*>(lim_);
      unsigned char* last_nl = nullptr;
      for (unsigned char* q = raw_end_; q > s;)
        if (*--q == '\n') {
          last_nl = q;
          break;
        }
      upto = last_nl ? last_nl + 1 : s;
    }
    unsigned char* from = const_cast<unsigned char*>(lim_);
    if (upto > from) {
      const size_t first_splice = splices_.size();
      if (card_image_) blank_card_columns(from, upto);
      unsigned char* w = splice_lines(from, upto, [&](unsigned char* at, size_t removed) {
        splices_.push_back({base_ + uint64_t(at - b), uint32_t(removed)});
      });
      find_hidden_records(from, w, first_splice);
      if (w != upto) {
        std::memmove(w, upto, size_t(raw_end_ - upto));
        raw_end_ -= upto - w;
      }
      lim_ = w;
    }
    if (end) {
      eof_ = true;
      // A continuation on the last line continues into nothing: give its '$' back, for the
      // rules to report.
      if (!splices_.empty() && splices_.back().at == base_ + uint64_t(lim_ - b)) {
        Splice& s = splices_.back();
        b[lim_ - b] = '$';
        ++lim_;
        ++s.at;
        --s.removed;
        if (raw_end_ < lim_) raw_end_ = b + (lim_ - b);
      }
    }
    if (lim_ > old_lim || end || room == 0) break;
  }
  unsigned char* l = b + (lim_ - b);
  saved_ = raw_end_ > l ? *l : 0;
  *l = 0;  // the sentinel must follow the data even when nothing more arrives
  return lim_ > old_lim ? 0 : 1;
}

void Lexer::pass_splices(uint64_t before) {
  while (splice_head_ < splices_.size() && splices_[splice_head_].at < before) {
    const Splice& s = splices_[splice_head_++];
    removed_passed_ += s.removed;
    ++line_;
    line_start_ = s.at;
    src_.note_line_start(line_, s.at + removed_passed_);
  }
  if (splice_head_ != 0 && splice_head_ == splices_.size()) {
    splices_.clear();
    splice_head_ = 0;
  }
}

// In the text just spliced, [b, e): a record joined to the line before by a continuation
// (`FEDRAT/250,$` then `GOTO/...`: the GOTO read as FEDRAT's words and lost), or one after a
// carriage return alone (`$$ note\rGOTO/...`: in the comment). Both are refused where the
// hidden record starts: which line it belongs to is not the file's to say.
void Lexer::find_hidden_records(unsigned char* b, unsigned char* e, size_t first_splice) {
  // Joins come in file order: one search per line, not one per join (100 000 lines joined by
  // '$' into one took 35 s; helper-64).
  const unsigned char* known_end = nullptr;
  auto line_end = [&](const unsigned char* p) {
    if (known_end && p <= known_end) return known_end;
    auto* nl = static_cast<const unsigned char*>(std::memchr(p, '\n', size_t(e - p)));
    return known_end = nl ? nl : e;
  };
  unsigned char* buf = buf_.get();
  // The line before the join is a record's head, words and commas before its major word
  // (`TLON,$` then `GOFWD/...`): the joined word is that record's own.
  auto head_before = [&](const unsigned char* q) {
    const unsigned char* p = q;
    // A head is a few words (TLON,): one longer than a line is text.
    for (int n = 0; p > buf && p[-1] != '\n'; --p)
      if (++n > 256) return false;
    enum { Start, InWord, AfterWord, AfterComma } st = Start;
    for (; p < q; ++p) {
      if (std::isalnum(*p) || *p == '_') {
        if (st == AfterWord) return false;  // two words with no comma between: text
        st = InWord;
      } else if (*p == ',') {
        if (st != InWord && st != AfterWord) return false;
        st = AfterComma;
      } else if (*p == ' ' || *p == '\t') {
        if (st == InWord) st = AfterWord;
      } else {
        return false;
      }
    }
    return st == AfterComma;
  };
  for (size_t i = first_splice; i < splices_.size(); ++i) {
    const unsigned char* q = buf + (splices_[i].at - base_);
    if (q > e) break;
    // The joined text runs on to the line end, through any later joins (GO$ / TO/1,2,3).
    // (Most joins continue numbers: a word is looked for first, the line before only then.)
    const unsigned char* word = q;
    if (MajorId id = record_at(q, line_end(q), &word); id != MajorId::Unknown && !head_before(q))
      hidden_.push_back({splices_[i].at + uint64_t(word - q), id, false});
  }
  known_end = nullptr;  // (from the window's start again)
  for (const unsigned char* p = b; p < e;) {
    auto* cr = static_cast<const unsigned char*>(std::memchr(p, '\r', size_t(e - p)));
    if (!cr) break;
    p = cr + 1;
    if (p >= e || *p == '\n' || *p == '\r') continue;
    const unsigned char* word = p;
    if (MajorId id = record_at(p, line_end(p), &word); id != MajorId::Unknown) {
      Hidden h{abs(word), id, true};
      // In file order with the joins found above.
      auto at = std::upper_bound(hidden_.begin() + std::ptrdiff_t(hidden_head_), hidden_.end(), h.at,
                                 [](uint64_t a, const Hidden& x) { return a < x.at; });
      hidden_.insert(at, h);
    }
  }
}

// At a record's start: the error for a record hidden in its line, if there is one.
std::optional<Lexer::Symbol> Lexer::hidden_record_error() {
  const unsigned char* nl = static_cast<const unsigned char*>(std::memchr(cur_, '\n', size_t(lim_ - cur_)));
  const uint64_t from = abs(cur_), to = nl ? abs(nl) : abs(lim_);
  while (hidden_head_ < hidden_.size() && hidden_[hidden_head_].at < from) ++hidden_head_;
  if (hidden_head_ == hidden_.size()) {
    hidden_.clear();
    hidden_head_ = 0;
    return std::nullopt;
  }
  const Hidden h = hidden_[hidden_head_];
  if (h.at > to) return std::nullopt;
  ++hidden_head_;
  record_start_ = loc_of(cur_);
  const std::string name(major_spelling(h.id));
  const unsigned char* p = buf_.get() + (h.at - base_);
  if (h.after_cr)
    return error_token(loc_of(p), "a carriage return alone (no line feed after it) stands before this " + name +
                                      " record: a line end to some editors and transfer programs, a blank to others, so "
                                      "whether it is a record of its own or part of the text before is not known: end "
                                      "the line with a line feed");
  return error_token(loc_of(p), "a '$' at the end of the line before joins this " + name +
                                    " record to that line, where it would be lost in its text or words: end that line without '$'");
}

void Lexer::newline(const unsigned char* after) {
  uint64_t a = abs(after);
  pass_splices(a);
  ++line_;
  line_start_ = a;
  src_.note_line_start(line_, a + removed_passed_);
}

SourceLoc Lexer::loc_of(const unsigned char* p) const {
  uint64_t a = abs(p);
  uint32_t line = line_;
  uint64_t start = line_start_;
  for (size_t i = splice_head_; i < splices_.size() && splices_[i].at <= a; ++i) {
    ++line;
    start = splices_[i].at;
  }
  uint64_t col = a >= start ? a - start + 1 : 1;
  return {line, uint32_t(std::min<uint64_t>(col, UINT32_MAX))};
}

namespace {

// A number: digits with an optional point, sign and exponent (12, 12., .5, -55., 1.25E-3).
// Fortran's double-precision exponent is read too (0.1000000D+02: APT processors are Fortran
// programs, and list-directed output writes D), only in that strict form (a point, a signed
// exponent), so that a name like 6D10 stays a name. Returns its end, or null.
const unsigned char* match_num(const unsigned char* p, const unsigned char* e) {
  if (p < e && (*p == '+' || *p == '-')) ++p;
  const unsigned char* digits = p;
  while (p < e && *p >= '0' && *p <= '9') ++p;
  bool any = p > digits, point = false;
  if (p < e && *p == '.') {
    ++p;
    point = true;
    const unsigned char* frac = p;
    while (p < e && *p >= '0' && *p <= '9') ++p;
    any = any || p > frac;
  }
  if (!any) return nullptr;
  const bool fortran = point && p + 1 < e && (*p == 'd' || *p == 'D') && (p[1] == '+' || p[1] == '-');
  if (p < e && (*p == 'e' || *p == 'E' || fortran)) {
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

// NX's information window frames a CLSF listing with lines that are no records: a header of
// "Information listing created by<TAB>user", "Date<TAB>...", "Current work part<TAB>...",
// "Node name<TAB>..." and a last line "Tool Path Listing has N lines." (nx-course/ in the
// corpus). They are skipped without a word.
bool is_listing_line(const unsigned char* b, const unsigned char* e) {
  std::string_view line(reinterpret_cast<const char*>(b), size_t(e - b));
  for (std::string_view head : {"Information listing created by\t", "Date\t", "Current work part\t", "Node name\t"})
    if (line.substr(0, head.size()) == head) return true;
  std::string_view tail = "Tool Path Listing has ";
  if (line.substr(0, tail.size()) != tail) return false;
  line.remove_prefix(tail.size());
  size_t digits = 0;
  while (digits < line.size() && line[digits] >= '0' && line[digits] <= '9') ++digits;
  if (digits == 0) return false;
  line.remove_prefix(digits);
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
  return line == " lines." || line == " line.";
}

}  // namespace

bool Lexer::listing_line() const {
  const unsigned char* e = static_cast<const unsigned char*>(std::memchr(tok_, '\n', size_t(lim_ - tok_)));
  return is_listing_line(tok_, e ? e : lim_);
}

bool Lexer::simple_record(Simple& s) {
  if (!simple_on_ || wanted_ || mode_ != Mode::LineStart || pending_ || at_end_) return false;
  const unsigned char* p = cur_;
  const unsigned char* nl = static_cast<const unsigned char*>(std::memchr(p, '\n', size_t(lim_ - p)));
  if (!nl || size_t(nl - p) > kMaxToken) return false;
  // A line that continuations joined (Creo writes every five-axis GOTO over two): its numbers'
  // columns are found through the splices, as the grammar's are.
  if (hidden_head_ < hidden_.size() && hidden_[hidden_head_].at <= abs(nl)) return false;
  const bool spliced = splice_head_ < splices_.size() && splices_[splice_head_].at <= abs(nl);
  static constexpr struct {
    const char* word;
    size_t len;
    MajorId id;
  } kMajors[] = {{"GOTO", 4, MajorId::Goto}, {"CIRCLE", 6, MajorId::Circle}, {"FROM", 4, MajorId::From},
                 {"GODLTA", 6, MajorId::Godlta}};
  MajorId id = MajorId::Unknown;
  for (const auto& m : kMajors)
    if (size_t(nl - p) > m.len && std::memcmp(p, m.word, m.len) == 0) {
      // The word, blanks perhaps (Creo's "GOTO / "), the slash.
      const unsigned char* q = p + m.len;
      while (q < nl && is_ws(*q)) ++q;
      if (q == nl || *q != '/') return false;
      id = m.id;
      p = q + 1;
      break;
    }
  if (id == MajorId::Unknown) return false;
  s.n = 0;
  const uint32_t line = line_;
  for (;;) {
    while (p < nl && is_ws(*p)) ++p;
    const unsigned char* e = match_num(p, nl);
    if (!e || s.n == kMaxSimple) return false;
    if (e < nl && !is_ws(*e) && *e != ',') return false;  // a word, "1.2.3", "$": the grammar's
    const char* b = reinterpret_cast<const char*>(*p == '+' ? p + 1 : p);
    auto [end, ec] = read_decimal(b, reinterpret_cast<const char*>(e), s.value[s.n]);
    if (ec != std::errc() || end != reinterpret_cast<const char*>(e)) return false;
    s.loc[s.n++] = spliced ? loc_of(p) : SourceLoc{line, uint32_t(abs(p) - line_start_ + 1)};
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

std::string Lexer::too_long() const {
  return "line too long: a word, number or text of more than " + std::to_string(kMaxToken) + " characters";
}

// Comments and free text are UTF-8 (ASCII in practice). A byte that is not (a Windows code page,
// CAMWorks) is a warning where it is: text carries no motion, and the program's comments are
// ASCII anyway. A file declared Latin-1 (--input-encoding latin1) has no such bytes.
void Lexer::check_text(const unsigned char* b, const unsigned char* e, const char* what) {
  if (latin1_ || !diags_) return;
  if (const unsigned char* bad = invalid_utf8(b, e)) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02X", *bad);
    diags_->warning(loc_of(bad), std::string("invalid UTF-8 in a ") + what + ": byte " + hex +
                                     ", read as a one-byte code page (--input-encoding latin1 says so for the file)",
                    "invalid-utf8");
  }
}

// A record that only names or describes (PAINT, INTOL, TOOLNO, ...) written wrong moves nothing,
// so it never stops the post: it is skipped with a warning, unless the rest of its line holds
// a motion record that skipping it would lose (helper-64: PAINT/1e400 stopped the post).
void Lexer::report(SourceLoc loc, const std::string& msg) {
  if (!diags_) return;
  if (data_comment_)
    diags_->warning(loc, "malformed '$$->' data comment ignored: " + msg, "data-comment");
  else if (carries_nothing_to_cut(record_id_) && motion_word_in_line().empty())
    diags_->warning(loc, "malformed " + std::string(major_spelling(record_id_)) +
                             " record ignored (it carries nothing to cut): " + msg,
                    "malformed-record");
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

// An error that stands whatever record it is in (a record read as another's parameter is lost
// whether or not that one carries anything to cut); in a '$$->' data comment, a warning.
Lexer::Symbol Lexer::hard_error_token(SourceLoc loc, const std::string& msg) {
  if (diags_ && !data_comment_) {
    diags_->error(loc, msg);
    mode_ = Mode::SkipRecord;
    return Parser::make_YYerror(loc);
  }
  return error_token(loc, msg);
}

Lexer::Symbol Lexer::error_token(SourceLoc loc, const std::string& msg) {
  report(loc, msg);
  mode_ = Mode::SkipRecord;
  return Parser::make_YYerror(loc);
}

// A line that starts with a word clpc does not know and goes on as no record does ("Date
// 12-Jan", a sentence typed into the file): it carries nothing a post could use, so it is
// skipped with a warning, not an error. (A known major word written wrong is an error.)
Lexer::Symbol Lexer::not_a_record() {
  if (diags_ && !data_comment_) {
    // GOTO10.0,10,-1 and CIRCLE90.03,..: a record glued to its first number. Skipped, the
    // plunge was lost and the arc cut as a chord, with a warning (helper-64).
    if (const std::string_view g = glued_record(unknown_major_); !g.empty())
      diags_->error(record_start_, "'" + std::string(unknown_major_) + "' reads as " + std::string(g) +
                                       " glued to what follows (a '/' missing?): skipped, its motion or setting would be "
                                       "lost; write " + std::string(g) + "/...");
    else if (const std::string motion = motion_word_in_line(); !motion.empty())
      diags_->error(record_start_, "not a CL record, yet the line holds " + motion +
                                       " further on: skipped, its motion would be lost (an APT statement label is "
                                       "written 'NAME)' before the record)");
    else
      diags_->warning(record_start_, "not a CL record (a word that is no major word, then neither '/' nor the line "
                                     "end): the line is ignored",
                      "not-a-record");
  }
  mode_ = Mode::SkipRecord;
  return Parser::make_YYerror(record_start_);
}

// The first motion record name followed by '/' in the rest of the line (what the buffer holds
// of it: "GOTO/"), or the line's last word where it is, in capitals, one of the records that
// stand alone and move the tool or change how it moves ("RAPID", "GOHOME", "STOP", "OPSTOP"),
// or "". A line skipped as no record must not hide a move ("Date 12-Jan RAPID": the rapid after
// it was fed).
std::string Lexer::motion_word_in_line(bool prose) const {
  const unsigned char* e = cur_;
  while (e < lim_ && *e != '\n' && *e != '\0') ++e;
  std::string_view text(reinterpret_cast<const char*>(tok_), size_t(e - tok_));
  if (size_t c = text.find("$$"); c != std::string_view::npos) text = text.substr(0, c);
  // "(CHECK FEDRAT/ BEFORE RUN)", "(OP 2 (SEE SHEET 2) COOLNT/FLOOD)": the parentheses hold a note.
  if (prose && !text.empty() && text[0] == '(') {
    size_t i = 0;
    for (int depth = 0; i < text.size(); ++i) {
      if (text[i] == '(') ++depth;
      if (text[i] == ')' && --depth == 0) break;
    }
    text = text.substr(std::min(text.size(), i + 1));
  }
  if (const size_t at = record_inside(text); at != std::string_view::npos) {
    std::string name(text.substr(at, text.find_first_of("/ \t", at) - at));
    for (char& c : name) c = char(std::toupper(static_cast<unsigned char>(c)));
    return name + "/";
  }
  if (prose) return "";  // "* RETRACT AT RAPID", "; PROGRAM STOP": words of a note
  while (!text.empty() && is_ws(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  size_t b = text.size();
  while (b > 0 && !is_ws(static_cast<unsigned char>(text[b - 1])) && text[b - 1] != ',') --b;
  const std::string_view last = text.substr(b);
  for (const char* w : {"RAPID", "GOHOME", "STOP", "OPSTOP"})
    if (b > 0 && last == w) return w;
  return "";
}

Lexer::Symbol Lexer::major(MajorId id, const unsigned char* b, const unsigned char* e) {
  record_start_ = loc_of(b);
  arena_used_ = 0;
  arena_full_ = false;
  depth_ = 0;
  numbers_end_ = 0;
  comma_seen_ = false;
  known_major_ = id != MajorId::Unknown;
  record_id_ = id;
  MajorTok t;
  t.id = id;
  t.text = id == MajorId::Unknown ? keep(b, e) : major_spelling(id);
  unknown_major_ = id == MajorId::Unknown ? t.text : std::string_view();
  t.data_comment = data_comment_;
  mode_ = Mode::AfterMajor;
  return Parser::make_MAJOR(t, record_start_);
}

// PARTNO, PPRINT, INSERT, REMARK, TPRINT: the rest of the line, after an optional '/', is text.
Lexer::Symbol Lexer::free_text_major(MajorId id, size_t keyword_len) {
  const unsigned char* b = tok_ + keyword_len;
  const unsigned char* e = cur_;
  while (b < e && (*b == ' ' || *b == '\t')) ++b;
  if (b < e && *b == '/') ++b;
  while (b < e && (*b == ' ' || *b == '\t')) ++b;
  while (e > b && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) --e;
  // A record joined to the text by a '$' is refused at the record's start (find_hidden_records).
  check_text(b, e, "text");
  Symbol m = major(id, tok_, tok_ + keyword_len);
  pending_.emplace(Parser::make_TEXT(keep(b, e), loc_of(b)));
  mode_ = Mode::AfterComment;  // only the line end may follow
  return m;
}

// To the end of the record: its line (continuations are spliced away already).
bool Lexer::skip_record() {
  for (;;) {
    tok_ = cur_;
    if (cur_ >= lim_) {
      if (fill() != 0) return false;
      continue;
    }
    auto* nl = static_cast<const unsigned char*>(std::memchr(cur_, '\n', size_t(lim_ - cur_)));
    if (!nl) {
      cur_ = lim_;
      continue;
    }
    cur_ = nl + 1;
    newline(cur_);
    return true;
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

// Records that move the tool, for a pre-scan that skips them (Record::motion_skipped): what the
// offset-table pass counts as motion (a move, an arc, a hole), record by record.
constexpr bool moves_the_tool(MajorId id) {
  switch (id) {
    case MajorId::Goto: case MajorId::Circle: case MajorId::Godlta: case MajorId::Movarc: case MajorId::Gohome:
    case MajorId::Gofwd: case MajorId::Golft: case MajorId::Gorgt: case MajorId::Goback: case MajorId::Goup:
    case MajorId::Godown:
      return true;
    default: return false;
  }
}

#define MAJOR(id)                                                        \
  {                                                                      \
    if (overflow_) return error_token(overflow_at_, too_long());    \
    if (!wanted_ || wanted_[int(MajorId::id)]) return major(MajorId::id, tok_, cur_); \
    if (moves_the_tool(MajorId::id)) ++motion_skipped_; \
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
    record_id_ = MajorId::Unknown;
    if (hidden_head_ < hidden_.size() && !wanted_ && !data_mark)
      if (auto e = hidden_record_error()) return *e;
    /*!re2c
      $ {
        at_end_ = true;
        return Parser::make_END(loc_of(tok_));
      }
      ws+ { continue; }
      nl  { newline(cur_); continue; }

      "$$->" [ \t]* / [A-Za-z_] { data_mark = true; continue; }
      // An APT statement label ("L1) GOTO/..."): a letter, up to five more letters and digits,
      // and ')' before a record (a word, then '/', ',' or the line end), which is read as if the
      // label were not there (docs/cl-input.md). A numbered note ("1) Set up the vise") is none.
      [A-Za-z][A-Za-z0-9]{0,5} ")" [ \t]* / mword [ \t]* [/,\n] { continue; }
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
      'TPRINT' [ \t/] text { FREE_TEXT(Tprint, 6) }
      'COMMENT' [ \t/] text { FREE_TEXT(Comment, 7) }

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
      'TPRINT'      { MAJOR(Tprint) }
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
      'TLAXIS'      { MAJOR(Tlaxis) }
      'TOOLNO'      { MAJOR(Toolno) }
      'MOVARC'      { MAJOR(Movarc) }
      'GOFWD'       { MAJOR(Gofwd) }
      'GOLFT'       { MAJOR(Golft) }
      'GORGT'       { MAJOR(Gorgt) }
      'GOBACK'      { MAJOR(Goback) }
      'GOUP'        { MAJOR(Goup) }
      'GODOWN'      { MAJOR(Godown) }
      'INDIRV'      { MAJOR(Indirv) }
      'INDIRP'      { MAJOR(Indirp) }
      'ROTABL'      { MAJOR(Rotabl) }
      'ROTHED'      { MAJOR(Rothed) }
      'TRACUT'      { MAJOR(Tracut) }
      'COPY'        { MAJOR(Copy) }
      'INDEX'       { MAJOR(Index) }
      'PSIS'        { MAJOR(Psis) }
      'AUTOPS'      { MAJOR(Autops) }
      'INTOL'       { MAJOR(Intol) }
      'OUTTOL'      { MAJOR(Outtol) }
      'TOLER'       { MAJOR(Toler) }
      'COMMENT'     { MAJOR(Comment) }
      majorw        {
        if (listing_line()) { skip_record(); continue; }
        MAJOR(Unknown)
      }

      "%" {
        // A tape mark alone on its line (the first and last line of a punched-tape or DNC file,
        // left when the CL went through one): nothing, not an error (helper-64).
        const unsigned char* q = cur_;
        while (q < lim_ && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
        if (q >= lim_ || *q == '\n') {
          if (!wanted_ && diags_ && !data_comment_)
            diags_->warning(loc_of(tok_), "a tape mark ('%' alone on its line, from a punched tape or a DNC transfer) "
                                          "is ignored", "not-a-record");
          skip_record();
          continue;
        }
        if (wanted_) { skip_record(); continue; }
        return error_token(loc_of(tok_), "expected a major word at the start of a record, found " + describe(*tok_));
      }
      [(;*#!] {
        // A line that opens as a comment does in other languages ("(SETUP 2)", "; roughing",
        // "* note"): no record, so it moves nothing. Skipped with a warning unless it hides a
        // motion record further on (helper-64: these stopped the post).
        if (wanted_) { skip_record(); continue; }
        if (diags_ && !data_comment_) {
          if (const std::string motion = motion_word_in_line(true); !motion.empty())
            return hard_error_token(loc_of(tok_), "not a CL record (a line starting with " + describe(*tok_) +
                                                      "), yet the line holds " + motion +
                                                      " further on: skipped, it would be lost");
          diags_->warning(loc_of(tok_), "not a CL record (a line starting with " + describe(*tok_) +
                                            "): the line is ignored", "not-a-record");
          skip_record();
          continue;
        }
        return error_token(loc_of(tok_), "expected a major word at the start of a record, found " + describe(*tok_));
      }
      * {
        if (wanted_) { skip_record(); continue; }
        // "    7  GOTO/0,0,10": a printed CL listing's line numbers (APT's CLPRNT, a print
        // utility). Said once, at the first; the later numbered lines are skipped unsaid (the
        // run fails), not fifty errors that each say "found '8'" (helper-66).
        if (numbered_line()) {
          if (numbered_said_) { skip_record(); continue; }
          numbered_said_ = true;
          return error_token(loc_of(tok_), "a number before the record: the lines are numbered, as in a printed CL "
                                           "listing (APT's CLPRNT), not a CL file; strip the numbers (the later "
                                           "numbered lines are not said again)");
        }
        return error_token(loc_of(tok_), "expected a major word at the start of a record, found " + describe(*tok_));
      }
    */
  }
}

// A line that is a whole number, blanks, then a record's major word and '/', or its end.
bool Lexer::numbered_line() const {
  const unsigned char* e = static_cast<const unsigned char*>(std::memchr(tok_, '\n', size_t(lim_ - tok_)));
  if (!e) e = lim_;
  const unsigned char* p = tok_;
  while (p < e && *p >= '0' && *p <= '9') ++p;
  if (p == tok_ || p == e || !is_ws(*p)) return false;
  while (p < e && is_ws(*p)) ++p;
  const unsigned char* w = p;
  while (p < e && (std::isalpha(*p) || *p == '-')) ++p;
  if (p == w || major_id(std::string_view(reinterpret_cast<const char*>(w), size_t(p - w))) == MajorId::Unknown)
    return false;
  return p == e || *p == '/' || is_ws(*p);  // (PARTNO and PPRINT take their text after a blank)
}

Lexer::Symbol Lexer::lex_after_major() {
  for (;;) {
    tok_ = cur_;
    /*!re2c
      $    { mode_ = Mode::LineStart; return Parser::make_EOL(loc_of(tok_)); }
      ws+  { continue; }
      nl   { SourceLoc at = loc_of(tok_); newline(cur_); mode_ = Mode::LineStart; return Parser::make_EOL(at); }
      "/"  { mode_ = Mode::Params; return Parser::make_SLASH(loc_of(tok_)); }
      "," ws* mword ws* / "/" {
        // TLON,GOFWD/...: a word before the major word.
        const unsigned char* w = tok_ + 1;
        while (is_ws(*w)) ++w;
        const unsigned char* we = w;
        while (we < cur_ && !is_ws(*we)) ++we;
        pending_.emplace(Parser::make_WORD(keep(w, we), loc_of(w)));
        return Parser::make_COMMA(loc_of(tok_));
      }
      "$$" { mode_ = Mode::CommentText; return lex_comment(); }
      "$" ws* {
        if (cur_ >= lim_ && fill() != 0)
          return error_token(loc_of(tok_), "unterminated continuation: '$' at the end of the file");
        if (!known_major_) return not_a_record();
        return error_token(loc_of(tok_), "expected '/' or the end of the record, found '$'");
      }
      * {
        if (!known_major_) return not_a_record();
        return error_token(loc_of(tok_), "expected '/' or the end of the record, found " + describe(*tok_));
      }
    */
  }
}

// A number token for [b, e) (a whole number as match_num reads it).
Lexer::Symbol Lexer::number_token(const unsigned char* b, const unsigned char* e, bool& bad) {
  bad = false;
  const char* s = reinterpret_cast<const char*>(b);
  const char* end_text = reinterpret_cast<const char*>(e);
  const char* digits = *s == '+' ? s + 1 : s;
  const char* digits_end = end_text;
  // Fortran's D exponent (match_num) reads as E: the number is copied with the letter changed.
  std::array<char, 128> fortran{};
  if (const char* d = std::find_if(digits, end_text, [](char c) { return c == 'd' || c == 'D'; });
      d != end_text && size_t(end_text - digits) <= fortran.size()) {
    std::copy(digits, end_text, fortran.begin());
    fortran[size_t(d - digits)] = 'E';
    digits_end = fortran.data() + (end_text - digits);
    digits = fortran.data();
  }
  double v = 0;
  auto [end, ec] = read_decimal(digits, digits_end, v);
  if (ec == std::errc::result_out_of_range) {
    // Underflow reads as zero; overflow is an error. Which one is the number's order of
    // magnitude: the digits before the point (less leading zeros), or the zeros after it, plus
    // the exponent. A 400-digit whole number without an exponent was taken for underflow and
    // read as 0: GOTO/<400 digits> posted X0. (helper-64).
    const char* exp = digits;
    while (exp < digits_end && *exp != 'e' && *exp != 'E') ++exp;
    long order = 0;
    const char* p = digits + (digits < exp && *digits == '-');
    while (p < exp && *p == '0') ++p;
    if (p < exp && *p != '.') {
      while (p < exp && *p != '.') ++p, ++order;
    } else {
      if (p < exp && *p == '.') ++p;
      while (p < exp && *p == '0') ++p, --order;
    }
    if (exp + 1 < digits_end) {
      const char* q = exp + 1;
      const bool minus = *q == '-';
      if (*q == '-' || *q == '+') ++q;
      long e10 = 0;
      for (; q < digits_end && *q >= '0' && *q <= '9'; ++q) e10 = std::min(e10 * 10 + (*q - '0'), 100000L);
      order += minus ? -e10 : e10;
    }
    if (order > 0) {
      bad = true;
      return error_token(loc_of(b), "number out of range: '" + std::string(s, end_text) + "'");
    }
    v = 0;
  } else if (ec != std::errc() || end != digits_end) {
    bad = true;
    return error_token(loc_of(b), "bad number '" + std::string(s, end_text) + "'");
  }
  return Parser::make_NUMBER(NumTok{v, keep(b, e)}, loc_of(b));
}

// A parameter that is not punctuation, from tok_: everything up to the next ',' (or the line
// end, a "$$" comment, the ')' of an open group), less trailing blanks. Names are names: it is
// a number only if it is one as a whole, otherwise a word whatever it starts with
// (6_KONTUR_125, 1STPECK, T1 End Mill D 10); lowering asks for numbers where the record's
// grammar has them. Numbers apart by blanks ("1.0 2.0", CAMWorks) are numbers one by one.
Lexer::Symbol Lexer::lex_run() {
  if (overflow_) return error_token(overflow_at_, too_long());
  const unsigned char* e = cur_;
  for (;;) {
    if (e >= lim_) {
      cur_ = e;
      if (fill() != 0) {
        e = cur_;
        break;
      }
      e = cur_;
      continue;
    }
    unsigned char c = *e;
    if (c == ',' || c == '\n') break;
    if (c == ')' && depth_ > 0) break;
    if (c == '$' && e + 1 < lim_ && e[1] == '$') break;
    if (c < 0x20 && !is_ws(c)) {
      cur_ = e;
      return error_token(loc_of(e), "unexpected " + describe(c) + " in a record");
    }
    ++e;
  }
  if (overflow_) return error_token(overflow_at_, too_long());
  cur_ = e;
  const unsigned char* t = e;
  while (t > tok_ && is_ws(t[-1])) --t;
  if (t - tok_ == 1 && *tok_ == '$' && e >= lim_)
    return error_token(loc_of(tok_), "unterminated continuation: '$' at the end of the file");
  bool bad = false;
  if (match_num(tok_, t) == t) return number_token(tok_, t, bad);
  // Blank-separated numbers?
  const unsigned char* first_end = nullptr;
  bool all = true;
  for (const unsigned char* p = tok_; p < t;) {
    const unsigned char* ne = match_num(p, t);
    if (!ne || (ne < t && !is_ws(*ne))) {
      all = false;
      break;
    }
    if (!first_end) first_end = ne;
    p = ne;
    while (p < t && is_ws(*p)) ++p;
  }
  if (all && first_end) {
    // "GOTO/10,20                  0080": a sequence number right of the record (not in
    // columns 73-80) was read as Z. Numbers apart by blanks where the record's others are apart
    // by commas are no CAMWorks list: which is meant is not known (helper-66).
    // (A comma with nothing after it ends CAMWorks' lists: GOTO/1.0 0.0 0.5,)
    bool more_after_a_comma = false;
    for (const unsigned char* q = e; q < lim_ && *q != '\n'; ++q) {
      if (q + 1 < lim_ && q[0] == '$' && q[1] == '$') break;
      if (*q == ',') {  // (a number after it: a word, CIRCLE/0.0 0.0 0.5 ... 1.0,CCLW, is CAMWorks')
        const unsigned char* n = q + 1;
        while (n < lim_ && is_ws(*n)) ++n;
        if (n < lim_ && ((*n >= '0' && *n <= '9') || *n == '-' || *n == '+' || *n == '.')) more_after_a_comma = true;
      }
    }
    const unsigned char* second = first_end;
    while (second < t && is_ws(*second)) ++second;
    if (comma_seen_ || more_after_a_comma)
      return error_token(loc_of(second), "numbers apart by blanks ('" +
                                                std::string(reinterpret_cast<const char*>(tok_), size_t(t - tok_)) +
                                                "') in a record whose others are apart by commas: a sequence number "
                                                "beside the record, or a comma missing? which is meant is not known");
    numbers_end_ = abs(t);
    cur_ = first_end;
    return number_token(tok_, first_end, bad);
  }
  // "PAINT/COLOR,31 GOTO/10,0,10": two records on a line. Read as one word, the GOTO was lost
  // (helper-64), whichever record it followed.
  // The same for the records that stand alone: "INTOL/0.01 RAPID" lost the rapid.
  {
    const std::string_view run(reinterpret_cast<const char*>(tok_), size_t(t - tok_));
    size_t at = std::memchr(tok_, '/', size_t(t - tok_)) ? record_inside(run) : std::string_view::npos;
    std::string name;
    if (at != std::string_view::npos) {
      name = std::string(run.substr(at, run.find_first_of("/ \t", at) - at)) + "/";
    } else if (const size_t blank = run.find_last_of(" \t"); blank != std::string_view::npos) {
      const std::string_view last = run.substr(blank + 1);  // (in capitals: "Face then rapid" is a name)
      if (last == "RAPID" || last == "GOHOME") at = blank + 1, name = std::string(last);
    }
    if (at != std::string_view::npos)
      return hard_error_token(loc_of(tok_ + at), "'" + name + "' inside a parameter: a record of its own on this line "
                                                              "(a line end missing?); read as a parameter, it would be lost");
  }
  check_text(tok_, t, "word");
  return Parser::make_WORD(keep(tok_, t), loc_of(tok_));
}

Lexer::Symbol Lexer::lex_params() {
  for (;;) {
    tok_ = cur_;
    if (numbers_end_ != 0) {
      // Inside "1.0 2.0 3.0": a comma between each two.
      if (abs(cur_) < numbers_end_) {
        while (is_ws(*cur_)) ++cur_;
        if (abs(cur_) < numbers_end_) {
          const unsigned char* ne = match_num(cur_, lim_);
          tok_ = cur_;
          cur_ = ne;
          bool bad = false;
          pending_.emplace(number_token(tok_, ne, bad));
          if (bad) {
            Symbol err = std::move(*pending_);
            pending_.reset();
            numbers_end_ = 0;
            return err;
          }
          return Parser::make_COMMA(loc_of(tok_));
        }
      }
      numbers_end_ = 0;
    }
    /*!re2c
      $    { mode_ = Mode::LineStart; return Parser::make_EOL(loc_of(tok_)); }
      ws+  { continue; }
      nl   { SourceLoc at = loc_of(tok_); newline(cur_); mode_ = Mode::LineStart; return Parser::make_EOL(at); }
      ","  { comma_seen_ = true; return Parser::make_COMMA(loc_of(tok_)); }
      "$$" { mode_ = Mode::CommentText; return lex_comment(); }
      ['] [^'\n\x00]* ['] | ["] [^"\n\x00]* ["] {
        if (overflow_) return error_token(overflow_at_, too_long());
        check_text(tok_ + 1, cur_ - 1, "string");
        return Parser::make_STRING(keep(tok_ + 1, cur_ - 1), loc_of(tok_));
      }
      ['"] { return error_token(loc_of(tok_), "unterminated string"); }
      "(" ws* mword ws* "/" {
        if (++depth_ > kMaxDepth) return error_token(loc_of(tok_), "parentheses nest more than 16 deep");
        const unsigned char* w = tok_ + 1;
        while (is_ws(*w)) ++w;
        const unsigned char* we = w;
        while (we < cur_ && !is_ws(*we) && *we != '/') ++we;
        return Parser::make_GROUP(keep(w, we), loc_of(tok_));
      }
      "(" {
        if (++depth_ > kMaxDepth) return error_token(loc_of(tok_), "parentheses nest more than 16 deep");
        return Parser::make_LPAREN(loc_of(tok_));
      }
      ")" {
        if (depth_ > 0) {
          --depth_;
          return Parser::make_RPAREN(loc_of(tok_));
        }
        cur_ = tok_;
        return lex_run();
      }
      "\x00" { return error_token(loc_of(tok_), "unexpected NUL byte in a record"); }
      * { cur_ = tok_; return lex_run(); }
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
