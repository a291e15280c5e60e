// A code from the machine description, such as "T{tool} M06" or "G04 P{seconds}": words
// separated by spaces, each literal text and {placeholders}. Parsed once when the machine is
// loaded; rendered with values at emission time.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace clpc {

// The values a template may use. Which ones each code may use is checked by the loader.
enum class Var : uint8_t {
  Tool, Offset, Register, Seconds, Milliseconds, Speed, Max, Number, Level, Tolerance,
  X, Y, Z, I, J, K,  // a tilted plane: origin and Euler angles
  Angle,             // codes.unwind: the position a winding axis is renamed to
  Tip,               // lathe comp_left/comp_right: the tool's imaginary tip number (lathe.tip)
  Count
};
std::string_view var_name(Var v);

struct TemplateVars {
  std::array<double, size_t(Var::Count)> value{};
  uint32_t set = 0;
  TemplateVars& with(Var v, double x) {
    value[size_t(v)] = x;
    set |= 1u << unsigned(v);
    return *this;
  }
};

struct CodeTemplate {
  struct Piece {
    std::string literal;  // text, or empty for a placeholder
    int var = -1;         // Var, or -1 for literal text
    int width = 0;        // {tool:2}: whole number, zero-padded to 2 digits
  };
  using Word = std::vector<Piece>;
  std::vector<Word> words;
  std::string text;  // as written

  bool empty() const { return words.empty(); }
  uint32_t vars_used() const;
  bool uses(Var v) const { return (vars_used() >> unsigned(v)) & 1u; }
  // True if any literal word starts with G (the block may change modal state).
  bool has_g_code() const;
  // The address a word is written in, in capitals (G43 Z{offset}: 'Z'); 0 when the word starts
  // with a placeholder or with no letter (a comment).
  static char letter(const Word& w);
};

// Parses `text`; on failure returns false with a message in `error`.
bool parse_template(std::string_view text, CodeTemplate& out, std::string& error);

}  // namespace clpc
