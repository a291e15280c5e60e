#include "machine/code_template.h"

#include <cctype>

namespace clpc {

std::string_view var_name(Var v) {
  switch (v) {
    case Var::Tool: return "tool";
    case Var::Offset: return "offset";
    case Var::Register: return "register";
    case Var::Seconds: return "seconds";
    case Var::Milliseconds: return "milliseconds";
    case Var::Speed: return "speed";
    case Var::Max: return "max";
    case Var::Number: return "number";
    case Var::Level: return "level";
    case Var::Tolerance: return "tolerance";
    case Var::X: return "x";
    case Var::Y: return "y";
    case Var::Z: return "z";
    case Var::I: return "i";
    case Var::J: return "j";
    case Var::K: return "k";
    case Var::Angle: return "angle";
    case Var::Tip: return "tip";
    case Var::Count: break;
  }
  return "?";
}

uint32_t CodeTemplate::vars_used() const {
  uint32_t m = 0;
  for (const Word& w : words)
    for (const Piece& p : w)
      if (p.var >= 0) m |= 1u << unsigned(p.var);
  return m;
}

char CodeTemplate::letter(const Word& w) {
  if (w.empty() || w[0].var >= 0 || w[0].literal.empty()) return 0;
  // (An address is a letter: a comment's "(LOAD{tool})" has none, and its '(' indexed the
  // formats out of bounds; UBSan, helper-72's test.)
  const char c = char(std::toupper(static_cast<unsigned char>(w[0].literal[0])));
  return c >= 'A' && c <= 'Z' ? c : 0;
}

bool CodeTemplate::has_g_code() const {
  for (const Word& w : words)
    if (letter(w) == 'G') return true;
  return false;
}

bool parse_template(std::string_view text, CodeTemplate& out, std::string& error) {
  out = CodeTemplate{};
  out.text = std::string(text);
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
    if (i >= text.size()) break;
    CodeTemplate::Word word;
    while (i < text.size() && text[i] != ' ' && text[i] != '\t') {
      if (text[i] == '}') {
        error = "'}' without '{'";
        return false;
      }
      if (text[i] != '{') {
        if (word.empty() || word.back().var >= 0) word.push_back({});
        word.back().literal.push_back(text[i++]);
        continue;
      }
      size_t close = text.find('}', i);
      if (close == std::string_view::npos) {
        error = "'{' without '}'";
        return false;
      }
      std::string_view inner = text.substr(i + 1, close - i - 1);
      int width = 0;
      if (size_t colon = inner.find(':'); colon != std::string_view::npos) {
        std::string_view w = inner.substr(colon + 1);
        if (w.empty() || w.size() > 1 || w[0] < '1' || w[0] > '9') {
          error = "width in {" + std::string(inner) + "} must be a digit 1-9";
          return false;
        }
        width = w[0] - '0';
        inner = inner.substr(0, colon);
      }
      int var = -1;
      for (int v = 0; v < int(Var::Count); ++v)
        if (inner == var_name(Var(v))) var = v;
      if (var < 0) {
        error = "unknown placeholder {" + std::string(inner) + "}";
        return false;
      }
      CodeTemplate::Piece p;
      p.var = var;
      p.width = width;
      word.push_back(p);
      i = close + 1;
    }
    out.words.push_back(std::move(word));
  }
  return true;
}

}  // namespace clpc
