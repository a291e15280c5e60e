#include "lower/not_cl_data.h"

#include "grammar/record.h"

#include <cctype>
#include <string_view>

namespace clpc {

namespace {

bool upper(char c) { return c >= 'A' && c <= 'Z'; }
bool lower_or_upper(char c) { return upper(char(std::toupper(static_cast<unsigned char>(c)))); }
bool digit(char c) { return c >= '0' && c <= '9'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// A CL record: a word (letters first; blanks, digits, '-' and '_' after) then '/', a '$$'
// comment, or a line that starts with a major word clpc knows (grammar/majors.def).
bool cl_record(std::string_view s) {
  if (s.substr(0, 2) == "$$") return true;
  size_t i = 0;
  if (i >= s.size() || !lower_or_upper(s[i])) return false;
  while (i < s.size() && (lower_or_upper(s[i]) || digit(s[i]) || s[i] == ' ' || s[i] == '-' || s[i] == '_' || s[i] == ','))
    ++i;
  if (i < s.size() && s[i] == '/') return true;
  return major_id(s.substr(0, s.find_first_of(" \t,/"))) != MajorId::Unknown;  // PARTNO text, FINI, RAPID, ...
}

// A G-code block: `%`, or address words (a letter, then a signed number) with comments in
// parentheses and an end ';', at least one of them G, M, X, Y, Z or a program number O.
bool gcode_block(std::string_view s) {
  if (s == "%") return true;
  if (!s.empty() && s.front() == '/') s.remove_prefix(1);  // block delete
  bool motion_or_code = false, any = false;
  size_t i = 0;
  while (i < s.size()) {
    char c = s[i];
    if (c == ' ' || c == '\t') {
      ++i;
      continue;
    }
    if (c == '(') {
      size_t close = s.find(')', i);
      if (close == std::string_view::npos) return false;
      i = close + 1;
      continue;
    }
    if (c == ';') break;
    const char letter = char(std::toupper(static_cast<unsigned char>(c)));
    if (!upper(letter)) return false;
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    const size_t digits = i;
    while (i < s.size() && (digit(s[i]) || s[i] == '.')) ++i;
    if (i == digits) return false;  // a letter without a number: a word, not an address
    any = true;
    if (letter == 'G' || letter == 'M' || letter == 'X' || letter == 'Y' || letter == 'Z' || letter == 'O') motion_or_code = true;
  }
  return any && motion_or_code;
}

constexpr size_t kHead = 64 * 1024;

std::string head_of(const SourceFile& src) {
  std::string head(kHead, '\0');
  const long n = src.read_at(0, head.data(), head.size());
  head.resize(n > 0 ? size_t(n) : 0);
  return head;
}

}  // namespace

std::optional<std::string> utf16_given(const SourceFile& src) {
  unsigned char bom[2];
  if (src.read_at(0, reinterpret_cast<char*>(bom), 2) != 2) return std::nullopt;
  if (bom[0] == 0xFF && bom[1] == 0xFE) return "FF FE";
  if (bom[0] == 0xFE && bom[1] == 0xFF) return "FE FF";
  return std::nullopt;
}

std::optional<SourceLoc> binary_file_given(const SourceFile& src) {
  const std::string head = head_of(src);
  size_t nuls = 0, first = std::string::npos;
  for (size_t i = 0; i < head.size(); ++i)
    if (head[i] == '\0') {
      if (first == std::string::npos) first = i;
      ++nuls;
    }
  if (nuls < 16 || nuls * 1000 < head.size()) return std::nullopt;
  uint32_t line = 1;
  size_t line_start = 0;
  for (size_t i = 0; i < first; ++i)
    if (head[i] == '\n') ++line, line_start = i + 1;
  return SourceLoc{line, uint32_t(first - line_start + 1)};
}

std::optional<GcodeInput> gcode_program_given(const SourceFile& src) {
  const std::string head = head_of(src);
  std::string_view text = head;
  if (head.size() == kHead) text = text.substr(0, text.rfind('\n') + 1);  // whole lines only
  std::optional<GcodeInput> first;
  int blocks = 0, said = 0;
  uint32_t line = 0;
  size_t at = 0;
  while (at < text.size() && said < 200) {
    size_t nl = text.find('\n', at);
    std::string_view l = trim(text.substr(at, nl == std::string_view::npos ? std::string_view::npos : nl - at));
    at = nl == std::string_view::npos ? text.size() : nl + 1;
    ++line;
    // Blank lines and the comments a program may start with ("(PART 1)", ISO's "! ...") say nothing.
    if (l.empty() || l.front() == '!' || (l.front() == '(' && l.back() == ')')) continue;
    ++said;
    if (cl_record(l)) return std::nullopt;
    if (gcode_block(l)) {
      if (!first && l != "%") first = GcodeInput{{line, 1}, std::string(l.substr(0, 60))};
      ++blocks;
    }
  }
  if (blocks >= 3 && first) return first;
  return std::nullopt;
}

}  // namespace clpc
