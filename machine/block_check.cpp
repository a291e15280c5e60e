#include "machine/block_check.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <charconv>

#include "support/decimal.h"
#include "support/text.h"

namespace clpc {

namespace {

bool upper_letter(char c) { return c >= 'A' && c <= 'Z'; }
bool digit(char c) { return c >= '0' && c <= '9'; }
bool blank(char c) { return c == ' ' || c == '\t'; }

// A Fanuc custom macro statement: #100 = ..., IF [..] GOTO n, WHILE [..] DO n, END n, GOTO n.
bool macro_statement(std::string_view t) {
  auto starts = [&](std::string_view w) { return t.substr(0, w.size()) == w; };
  if (!(t.size() > 1 && t[0] == '#' && digit(t[1])) && !starts("IF") && !starts("WHILE") && !starts("END") &&
      !starts("GOTO"))
    return false;
  int depth = 0;
  for (char c : t) {
    if (c == '[') ++depth;
    else if (c == ']') {
      if (--depth < 0) return false;
    } else if (!(upper_letter(c) || digit(c) || blank(c) || c == '#' || c == '.' || c == '+' || c == '-' || c == '*' ||
               c == '/' || c == '=' || c == ','))
      return false;
  }
  return depth == 0;
}

}  // namespace

bool is_control_block(std::string_view t, std::string& why) {
  while (!t.empty() && blank(t.front())) t.remove_prefix(1);
  while (!t.empty() && blank(t.back())) t.remove_suffix(1);
  if (t.empty()) {
    why = "it is empty";
    return false;
  }
  // '%' is the tape mark: a control loading the file stops at it, even inside a comment.
  if (t.find('%') != std::string_view::npos) {
    why = "'%' is the tape mark, which ends the program where the control loads it";
    return false;
  }
  if (macro_statement(t)) return true;
  size_t i = 0;
  if (t[i] == '/') ++i;  // block delete
  bool words = false;
  while (i < t.size()) {
    char c = t[i];
    if (blank(c)) {
      ++i;
      continue;
    }
    if (c == '(') {
      size_t close = t.find(')', i);
      if (close == std::string_view::npos) {
        why = "a comment '(' is not closed";
        return false;
      }
      i = close + 1;
      continue;
    }
    if (!upper_letter(c)) {
      why = std::string("'") + c + "' at column " + std::to_string(i + 1) + " starts no address word";
      return false;
    }
    size_t v = i + 1;
    if (v < t.size() && t[v] == '#') {  // a variable: G#1, X#24
      ++v;
      size_t d = v;
      while (v < t.size() && digit(t[v])) ++v;
      if (v == d) {
        why = std::string("'") + c + "#' has no variable number";
        return false;
      }
    } else if (v < t.size() && t[v] == '[') {  // an expression: X[#1+2.]
      int depth = 0;
      for (; v < t.size(); ++v) {
        if (t[v] == '[') ++depth;
        else if (t[v] == ']' && --depth == 0) {
          ++v;
          break;
        }
      }
      if (depth != 0) {
        why = std::string("'") + c + "[' is not closed";
        return false;
      }
    } else {
      if (v < t.size() && (t[v] == '+' || t[v] == '-')) ++v;
      size_t d = v;
      bool point = false;
      for (; v < t.size() && (digit(t[v]) || (t[v] == '.' && !point)); ++v) point = point || t[v] == '.';
      if (v == d || (v == d + 1 && point)) {
        why = std::string("'") + c + "' at column " + std::to_string(i + 1) + " has no number after it";
        return false;
      }
    }
    words = true;
    i = v;
  }
  (void)words;  // comments alone are a block too
  return true;
}

std::string axis_words(std::string_view t) {
  std::string letters;
  bool dwell = false;
  for (size_t i = 0; i < t.size(); ++i) {
    const char c = t[i];
    if (c == '(') {  // a comment: on past its ')' (the rest of the block, unclosed)
      if ((i = t.find(')', i)) == std::string_view::npos) break;
      continue;
    }
    // A letter after a letter is part of a word (GOTO, SIN, LT); after a digit or a point it
    // starts the next address of a packed block (G00Z-30., X10.Y5.).
    if (!upper_letter(c) || (i > 0 && upper_letter(t[i - 1]))) continue;
    if (i + 1 >= t.size() || !(digit(t[i + 1]) || t[i + 1] == '-' || t[i + 1] == '+' || t[i + 1] == '.' ||
                               t[i + 1] == '#' || t[i + 1] == '['))
      continue;
    if (c == 'G') {
      size_t v = i + 1;
      while (v < t.size() && t[v] == '0') ++v;
      if (v < t.size() && t[v] == '4' && (v + 1 >= t.size() || !digit(t[v + 1]))) dwell = true;
    }
    if (std::string_view("XYZABCUVW").find(c) != std::string_view::npos && letters.find(c) == std::string::npos)
      letters.push_back(c);
  }
  return dwell ? std::string() : letters;
}

bool moves_axes_by_itself(std::string_view block) {
  if (!axis_words(block).empty()) return true;
  for (double g : code_numbers(block, 'G'))
    if ((g > 26.5 && g < 30.5) || std::abs(g - 53) < 1e-6 || std::abs(g - 65) < 1e-6 || std::abs(g - 66) < 1e-6 ||
        std::abs(g - 66.1) < 1e-6)
      return true;
  return false;
}

std::string system_variable_set(std::string_view t) {
  auto blank = [&](size_t& i) {
    while (i < t.size() && (t[i] == ' ' || t[i] == '\t')) ++i;
  };
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] == '(') {  // a comment: on past its ')' (the rest of the block, unclosed)
      if ((i = t.find(')', i)) == std::string_view::npos) break;
      continue;
    }
    // A '#' read as a value (X#101, #1=#5221) is preceded by a letter, '=', an operator or '['.
    if (t[i] != '#') continue;
    size_t before = i;
    while (before > 0 && (t[before - 1] == ' ' || t[before - 1] == '\t')) --before;
    if (before > 0 && !digit(t[before - 1]) && t[before - 1] != '.' && t[before - 1] != ')') continue;
    size_t j = i + 1;
    std::string name;
    if (j < t.size() && t[j] == '[') {
      const size_t close = t.find(']', j);
      if (close == std::string_view::npos) break;
      name = "#[" + std::string(t.substr(j + 1, close - j - 1)) + "]";
      j = close + 1;
    } else {
      const size_t start = j;
      while (j < t.size() && digit(t[j])) ++j;
      if (j == start) continue;
      name = "#" + std::string(t.substr(start, j - start));
    }
    blank(j);
    if (j >= t.size() || t[j] != '=' || (j + 1 < t.size() && t[j + 1] == '=')) continue;
    if (name[1] == '[') return name;
    long n = 0;
    for (char c : name.substr(1)) n = std::min(n * 10 + (c - '0'), 100000L);
    // Tool offsets (#2000-#2999, #10000 up), modal state and positions (#4000-#5999, with the
    // work offsets from #5201), extended work offsets (#7000-#7999). A message stop, an alarm,
    // a counter or a timer (#3000-#3999) changes no position (#3006=1 was refused; helper-58).
    if ((n >= 2000 && n < 3000) || (n >= 4000 && n < 6000) || (n >= 7000 && n < 8000) || n >= 10000) return name;
  }
  return "";
}

std::vector<double> code_numbers(std::string_view t, char letter) {
  std::vector<double> out;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] == '(') {  // a comment: on past its ')' (the rest of the block, unclosed)
      if ((i = t.find(')', i)) == std::string_view::npos) break;
      continue;
    }
    if (t[i] != letter || (i > 0 && upper_letter(t[i - 1]))) continue;
    size_t v = i + 1;
    while (v < t.size() && (digit(t[v]) || t[v] == '.')) ++v;
    if (v == i + 1) continue;
    double n = 0;
    if (from_chars_double(t.data() + i + 1, t.data() + v, n).ec != std::errc()) continue;
    out.push_back(n);
    i = v - 1;
  }
  return out;
}

namespace {

// An M code moves axes where the builder made it so (a pallet change, M60 on a Fanuc, M50 on
// a Haas; a macro called by M code): only the codes every control gives the same meaning,
// none of which moves an axis, are known not to.
bool has_m_code_that_may_move(std::string_view block) {
  static constexpr int kStill[] = {0, 1, 3, 4, 5, 7, 8, 9, 19, 29, 48, 49};
  for (double m : code_numbers(block, 'M'))
    if (m != std::floor(m) || std::find(std::begin(kStill), std::end(kStill), int(m)) == std::end(kStill)) return true;
  return false;
}

bool calls_a_macro(std::string_view block) {
  for (double g : code_numbers(block, 'G'))
    if (std::abs(g - 65) < 1e-6 || std::abs(g - 66) < 1e-6 || std::abs(g - 66.1) < 1e-6) return true;
  return false;
}

}  // namespace

bool may_move_axes(std::string_view block) {
  if (!axis_words(block).empty() || calls_a_macro(block) || has_m_code_that_may_move(block)) return true;
  for (double g : code_numbers(block, 'G'))
    if ((g > 26.5 && g < 30.5) || std::abs(g - 53) < 1e-6) return true;
  return false;
}

std::string control_words(std::string_view block) {
  std::string out;
  for (size_t i = 0; i < block.size(); ++i) {
    const char c = block[i];
    if (c == '(') {
      if ((i = block.find(')', i)) == std::string_view::npos) break;
      continue;
    }
    if (blank(c)) {
      // A blank between an address and its number goes ("G 28" is G28); one between words stays
      // ("L Z-0.5": L is no address of Z's).
      size_t n = i;
      while (n + 1 < block.size() && blank(block[n + 1])) ++n;
      const char next = n + 1 < block.size() ? block[n + 1] : ' ';
      if (!(digit(next) || next == '-' || next == '+' || next == '.' || next == '#' || next == '[') && !out.empty() &&
          out.back() != ' ')
        out += ' ';
      i = n;
      continue;
    }
    out += char(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

namespace {

// One address word of a block in control_words' form: its letter and value, or no value (a
// #variable, a [expression]) where it cannot be read.
struct AddressWord {
  char letter;
  bool known;
  double value;
};

std::vector<AddressWord> address_words(const std::string& t) {
  std::vector<AddressWord> out;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!upper_letter(t[i]) || (i > 0 && upper_letter(t[i - 1]))) continue;  // inside a word: SUPA, FMAX
    size_t v = i + 1;
    if (v < t.size() && (t[v] == '-' || t[v] == '+')) ++v;
    while (v < t.size() && (digit(t[v]) || t[v] == '.')) ++v;
    double x = 0;
    const bool number = v > i + 1 && from_chars_double(t.data() + i + 1 + (t[i + 1] == '+'), t.data() + v, x).ec == std::errc();
    if (!number && (i + 1 >= t.size() || upper_letter(t[i + 1]) || t[i + 1] == ' ')) continue;  // a word of letters
    out.push_back({t[i], number, x});
  }
  return out;
}

}  // namespace

std::string part_position_in(std::string_view block, bool lathe, bool& incremental, std::string_view free_axes) {
  const std::string t = control_words(block);
  const std::vector<AddressWord> words = address_words(t);
  bool machine = t.find("SUPA") != std::string::npos, reference = false, dwell = false, g53 = false;
  for (const AddressWord& w : words) {
    if (!w.known) continue;
    if (w.letter == 'G') {
      if (w.value == 91) incremental = true;
      if (w.value == 90) incremental = false;
      if (w.value == 53 || w.value == 153) machine = g53 = true;  // Fanuc, Siemens
      if (w.value == 28 || w.value == 30) reference = true;
      if (w.value == 4) dwell = true;
      // A macro call's words are its arguments (#24 #25 #26), no positions: what the shop's
      // macro moves is not seen here, whatever it is given (G65 P9000 loads as it is).
      if (w.value == 65 || w.value == 66 || w.value == 66.1) return "";
    }
    // Heidenhain's (in its L blocks; a Fanuc's M91 is the builder's own).
    if (w.letter == 'M' && (w.value == 91 || w.value == 92) && t.rfind("L ", 0) == 0) machine = true;
  }
  // A Fanuc ignores G53 in G91 (machine coordinates are absolute only): "G91 G53 Z0." moved
  // nothing, and the tool change after it came with the tool in the part (helper-71: certified).
  if (g53 && incremental && !axis_words(t).empty())
    return "'" + std::string(block) + "' gives machine coordinates (G53) in G91, where the control ignores them (the "
           "tool stays where it is)";
  if (machine || dwell) return "";
  for (const AddressWord& w : words) {
    if (std::string_view("XYZABCUVW").find(w.letter) == std::string_view::npos) continue;
    // (A free axis is free to go, not to pass through a G28's intermediate point: a lathe's
    // "G28 X0. Z0." goes to the face's centre first.)
    if (!reference && free_axes.find(w.letter) != std::string_view::npos) continue;
    const bool zero = w.known && w.value == 0;
    // U, V, W are incremental X, Y, Z on a lathe (and in a Mazak's G28 U0 V0 W0).
    const bool in_place = incremental || ((lathe || reference) && std::string_view("UVW").find(w.letter) != std::string_view::npos);
    if (zero && in_place) continue;
    const std::string word = std::string(1, w.letter) + (w.known ? num_text(w.value) : std::string("#"));
    if (reference)
      return "'" + std::string(block) + "' goes home through an intermediate point " +
             (in_place ? "away from where the tool is (" + word + ")"
                       : "in the part's coordinates (G90: " + word + " of the part, at rapid)");
    return "'" + std::string(block) + "' moves " + std::string(1, w.letter) + " to a position in the part's coordinates (" +
           word + (incremental ? ", from where the tool is" : "") + ")";
  }
  return "";
}

bool returns_z_home(std::string_view block) {
  if (axis_words(block) != "Z" || calls_a_macro(block) || has_m_code_that_may_move(block)) return false;
  bool reference = false, machine = false;
  for (double g : code_numbers(block, 'G')) {
    if (std::abs(g - 28) < 1e-6 || std::abs(g - 30) < 1e-6) reference = true;
    if (std::abs(g - 53) < 1e-6) machine = true;
  }
  if (reference) return true;
  if (!machine) return false;
  const std::vector<double> z = code_numbers(block, 'Z');  // (a negative Z's sign is not read: no number)
  return !z.empty() && z.front() == 0;
}

}  // namespace clpc
