#include "backends/emitter.h"

#include "support/text.h"

namespace clpc {

Emitter::Emitter(const Machine& m, OutputFile& out, Diagnostics& d) : m_(m), out_(out), d_(d) {
  next_n_ = m.sequence.start;
  block_.reserve(256);
}

void Emitter::begin(SourceLoc loc) {
  loc_ = loc;
  block_.clear();
  comment_.clear();
  words_ = 0;
}

void Emitter::add_word_text(std::string_view w) {
  if (words_ > 0) block_.append(m_.separator);
  block_.append(w);
  ++words_;
}

void Emitter::text(std::string_view w) { add_word_text(w); }

void Emitter::add_quantized(char letter, int64_t q) {
  if (words_ > 0) block_.append(m_.separator);
  block_.push_back(letter);
  append_quantized(q, m_.format(letter), block_);
  ++words_;
}

bool Emitter::word(char letter, double value) {
  int64_t q;
  if (!quantize(value, m_.format(letter), q)) {
    d_.error(loc_, std::string("value out of range for address ") + letter + ": " + num_text(value));
    return false;
  }
  add_quantized(letter, q);
  last_q_[letter - 'A'] = q;
  known_[letter - 'A'] = true;
  return true;
}

bool Emitter::modal_word(char letter, double value) { return modal_word(letter, round(letter, value)); }

bool Emitter::modal_word(char letter, const Rounded& r) {
  if (!r.ok) {
    d_.error(loc_, std::string("value out of range for address ") + letter + ": " + num_text(r.value));
    return false;
  }
  size_t i = size_t(letter - 'A');
  if (m_.modal.coordinates && known_[i] && last_q_[i] == r.q) return false;
  add_quantized(letter, r.q);
  last_q_[i] = r.q;
  known_[i] = true;
  return true;
}

bool Emitter::last(char letter, double& value) const {
  size_t i = size_t(letter - 'A');
  if (!known_[i]) return false;
  value = dequantize(last_q_[i], m_.format(letter));
  return true;
}

void Emitter::set_last(char letter, double value) {
  int64_t q;
  size_t i = size_t(letter - 'A');
  if (quantize(value, m_.format(letter), q)) {
    last_q_[i] = q;
    known_[i] = true;
  } else {
    known_[i] = false;
  }
}

bool Emitter::differs(char letter, double value) const {
  size_t i = size_t(letter - 'A');
  int64_t q;
  return !known_[i] || !quantize(value, m_.format(letter), q) || q != last_q_[i];
}

double Emitter::as_written(char letter, double value) const {
  int64_t q;
  if (!quantize(value, m_.format(letter), q)) return value;
  return dequantize(q, m_.format(letter));
}

void Emitter::forget_linear() {
  for (char l : {'X', 'Y', 'Z', 'U', 'V', 'W'}) forget(l);
}

void Emitter::forget_all() {
  for (bool& k : known_) k = false;
}

void Emitter::forget_all_but(std::string_view letters) {
  for (size_t i = 0; i < 26; ++i)
    if (letters.find(char('A' + i)) == std::string_view::npos) known_[i] = false;
}

// A dwell keeps its meaning after formatting, as a feed does (feeds.max_rounding): 0.4 s written
// P0 with a whole-seconds P, or 1.5 s as P2, was certified (verify reads the block's dwell as
// written and has no CL time to hold it to).
void Emitter::check_dwell(Var var, double value, double written) {
  if ((var != Var::Seconds && var != Var::Milliseconds) || !(value > 0)) return;
  if (written != 0 && std::abs(written - value) <= m_.feeds.max_rounding * value) return;
  const bool ms = var == Var::Milliseconds;
  d_.error(loc_, "the dwell of " + num_text(ms ? value / 1000 : value) + " s would be written as " + num_text(written) +
                     (ms ? " ms" : " s") + ": " + (written == 0 ? "no dwell at all" : "rounding changes it by more than " +
                                                                        num_text(m_.feeds.max_rounding * 100) + "%") +
                     "; give the dwell's address more decimals (format.P, or the placeholder's width)");
}

void Emitter::render_word(const CodeTemplate::Word& w, const TemplateVars& v, std::string& word) {
  char letter = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    const CodeTemplate::Piece& p = w[i];
    if (p.var < 0) {
      word += p.literal;
      continue;
    }
    double x = (v.set >> unsigned(p.var)) & 1u ? v.value[size_t(p.var)] : 0.0;
    if (p.width > 0) {
      // A width pads to so many digits. Where another number or a digit stands against it in
      // the same word it is also the most there is room for: T{tool:2}{offset:2} with tool 112 would read as
      // another tool and offset (T112112).
      const long long n = std::llround(x);
      long long room = 1;
      for (int k = 0; k < p.width; ++k) room *= 10;
      auto digit_at = [](const std::string& l, bool end) {
        return !l.empty() && (end ? l.back() : l.front()) >= '0' && (end ? l.back() : l.front()) <= '9';
      };
      const bool joined = (i + 1 < w.size() && (w[i + 1].var >= 0 || digit_at(w[i + 1].literal, false))) ||
                          (i > 0 && (w[i - 1].var >= 0 || digit_at(w[i - 1].literal, true)));
      if (joined && (n < 0 || n >= room)) {
        d_.error(loc_, std::string(var_name(Var(p.var))) + " " + std::to_string(n) + " does not fit the " +
                           std::to_string(p.width) + " digits the machine's code gives it ({" + std::string(var_name(Var(p.var))) +
                           ":" + std::to_string(p.width) + "}): the control would read another number");
        continue;
      }
      check_dwell(Var(p.var), x, double(n));
      append_int(n, p.width, word);
      continue;
    }
    if (!word.empty()) letter = word[0];
    if (letter >= 'a' && letter <= 'z') letter = char(letter - 32);
    if (letter >= 'A' && letter <= 'Z') {
      // Only a length takes the letter's scale: a dwell written G04 X{seconds} on a diameter
      // lathe is seconds, not a diameter (X1. for 0.5 s dwelt twice as long).
      AddressFormat f = m_.format(letter);
      if (Var(p.var) != Var::X && Var(p.var) != Var::Y && Var(p.var) != Var::Z) f.scale = 1;
      int64_t q;
      if (!quantize(x, f, q)) {
        d_.error(loc_, std::string("value out of range for address ") + letter + ": " + num_text(x));
        continue;
      }
      check_dwell(Var(p.var), x, dequantize(q, f));
      append_quantized(q, f, word);
    } else {
      word += num_text(x);
    }
  }
}

void Emitter::code(const CodeTemplate& t, const TemplateVars& v) {
  for (const CodeTemplate::Word& w : t.words) {
    std::string word;
    render_word(w, v, word);
    add_word_text(word);
  }
}

std::string Emitter::render(const CodeTemplate& t, const TemplateVars& v) {
  std::string out;
  for (const CodeTemplate::Word& w : t.words) {
    if (!out.empty()) out += m_.separator;
    render_word(w, v, out);
  }
  return out;
}

bool Emitter::argument(char letter, double value, const AddressFormat& f) {
  int64_t q;
  if (!quantize(value, f, q)) {
    d_.error(loc_, std::string("value out of range for address ") + letter + ": " + num_text(value));
    return false;
  }
  if (words_ > 0) block_.append(m_.separator);
  block_.push_back(letter);
  append_quantized(q, f, block_);
  ++words_;
  return true;
}

void Emitter::trailing_comment(std::string_view c) {
  if (!m_.comments.enabled) return;
  std::string t = clean_comment(c);
  if (!t.empty()) comment_ = m_.comments.open + t + m_.comments.close;
}

bool Emitter::reserve_number(long& n) {
  if (wrapped_) return false;
  n = next_n_;
  const SequenceSettings& s = m_.sequence;
  next_n_ += s.step;
  if (next_n_ > s.max) next_n_ = s.wrap_to > 0 ? s.wrap_to : s.start, wrapped_ = true;
  return true;
}

void Emitter::end(bool tool_change) {
  if (words_ == 0) return;
  const SequenceSettings& s = m_.sequence;
  if (forced_n_ >= 0 || (s.enabled && (!s.tool_change_only || tool_change))) {
    std::string n = "N";
    append_int(forced_n_ >= 0 ? forced_n_ : next_n_, m_.format('N').digits, n);  // format.N: digits pads
    out_.write(n);
    out_.write(m_.separator.empty() ? std::string_view() : std::string_view(m_.separator));
    if (forced_n_ >= 0) {
      forced_n_ = -1;
    } else {
      next_n_ += s.step;
      if (next_n_ > s.max) next_n_ = s.wrap_to > 0 ? s.wrap_to : s.start, wrapped_ = true;
    }
  }
  out_.write(block_);
  if (!comment_.empty()) {
    out_.write(m_.separator.empty() ? std::string_view() : std::string_view(" "));
    out_.write(comment_);
  }
  out_.write(m_.block_end);
  out_.write("\n");
  ++blocks_;
  words_ = 0;
  block_.clear();
  comment_.clear();
}

std::string Emitter::clean_comment(std::string_view text) const {
  const CommentSettings& c = m_.comments;
  std::string out;
  out.reserve(text.size());
  for (unsigned char ch : text) {
    // '%' is the tape mark: a control loading the file stops at the first one, wherever it stands.
    bool bad = ch < 0x20 || ch >= 0x7f || ch == '%' || c.open.find(char(ch)) != std::string::npos ||
               c.close.find(char(ch)) != std::string::npos;
    if (bad) {
      out += c.replacement;
      continue;
    }
    out.push_back(c.upper_case && ch >= 'a' && ch <= 'z' ? char(ch - 32) : char(ch));
  }
  // Collapse the runs of spaces cleaning may leave, and trim.
  std::string tidy;
  for (char ch : out) {
    if (ch == ' ' && (tidy.empty() || tidy.back() == ' ')) continue;
    tidy.push_back(ch);
  }
  size_t room = c.max_length > 0 ? size_t(c.max_length) : std::string::npos;
  if (tidy.size() > room) tidy.resize(room);
  while (!tidy.empty() && tidy.back() == ' ') tidy.pop_back();
  return tidy;
}

void Emitter::comment(std::string_view text) {
  if (!m_.comments.enabled) return;
  std::string t = clean_comment(text);
  if (t.empty()) return;
  out_.write(m_.comments.open);
  out_.write(t);
  out_.write(m_.comments.close);
  out_.write("\n");
}

void Emitter::line(std::string_view text) {
  out_.write(text);
  out_.write("\n");
}

}  // namespace clpc
