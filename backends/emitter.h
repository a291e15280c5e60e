// The one table-driven emitter both backends share: it formats words per the machine's
// address formats, drops modal words whose rounded value has not changed, numbers blocks,
// cleans comments and writes the text into the output buffer. It knows nothing of motion or
// tools: backends decide which words a block holds.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "machine/code_template.h"
#include "machine/format.h"
#include "machine/machine.h"
#include "support/output.h"
#include "support/diagnostics.h"

namespace clpc {

class Emitter {
 public:
  Emitter(const Machine& m, OutputFile& out, Diagnostics& d);

  // A block: begin, add words, end. Words keep the order they are added in.
  void begin(SourceLoc loc);
  void code(const CodeTemplate& t, const TemplateVars& v = {});
  // Writes `letter` with `value` always; returns false if the value is out of range.
  bool word(char letter, double value);
  // Writes `letter` only when its rounded value differs from the last one written (or the
  // machine does not suppress coordinates). Returns true if written.
  bool modal_word(char letter, double value);
  // Writes `letter` in format `f`, leaving the modal memory alone: a value that is no
  // position (a G10 or G65 argument).
  bool argument(char letter, double value, const AddressFormat& f);
  // The text `t` renders to, for comments.
  std::string render(const CodeTemplate& t, const TemplateVars& v = {});
  void text(std::string_view w);
  void trailing_comment(std::string_view c);
  // Ends the block; an empty block writes nothing. tool_change marks blocks that get a
  // sequence number when the machine numbers only tool changes.
  void end(bool tool_change = false);
  bool block_empty() const { return words_ == 0; }
  // A sequence number another block names (G71's P and Q): the next one, taken whatever the
  // numbering settings say. False once the numbers have wrapped past sequence.max, when one
  // could name two blocks. number_next() puts it on the next block written.
  bool reserve_number(long& n);
  void number_next(long n) { forced_n_ = n; }

  // The value a control holds for `letter` after the blocks written so far.
  bool last(char letter, double& value) const;
  void set_last(char letter, double value);
  // Whether `value` would be written differently from the last value of `letter` (or none
  // is known): the rounded integers compared, nothing converted back.
  bool differs(char letter, double value) const;
  // A value rounded once for `letter`, for differs() and modal_word() to share.
  struct Rounded {
    int64_t q = 0;
    bool ok = false;
    double value = 0;
  };
  Rounded round(char letter, double value) const {
    Rounded r;
    r.value = value;
    r.ok = quantize(value, m_.format(letter), r.q);
    return r;
  }
  bool differs(char letter, const Rounded& r) const {
    const size_t i = size_t(letter - 'A');
    return !r.ok || !known_[i] || r.q != last_q_[i];
  }
  bool modal_word(char letter, const Rounded& r);  // e.g. after a move the emitter did not write
  void forget(char letter) { known_[size_t(letter - 'A')] = false; }
  void forget_all();
  void forget_all_but(std::string_view letters);  // the letters named stay known
  void forget_linear();  // X Y Z U V W: after something moved or reframed them
  // Rounds as the control would: the value it will take for `value` at this address.
  double as_written(char letter, double value) const;

  void comment(std::string_view text);  // a comment line (nothing if comments are off)
  void line(std::string_view text);     // a line as it is, no sequence number
  std::string clean_comment(std::string_view text) const;

  long block_count() const { return blocks_; }
  const Machine& machine() const { return m_; }

 private:
  void add_word_text(std::string_view w);
  void render_word(const CodeTemplate::Word& w, const TemplateVars& v, std::string& out);
  void check_dwell(Var var, double value, double written);  // a dwell that rounds to nothing or far off: an error
  void add_quantized(char letter, int64_t q);

  const Machine& m_;
  OutputFile& out_;
  Diagnostics& d_;
  SourceLoc loc_;
  std::string block_;
  std::string comment_;
  int words_ = 0;
  long next_n_;
  long forced_n_ = -1;
  bool wrapped_ = false;
  long blocks_ = 0;
  int64_t last_q_[26] = {};
  bool known_[26] = {};
};

}  // namespace clpc
