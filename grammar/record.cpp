#include "grammar/record.h"

#include <algorithm>
#include <cctype>

namespace clpc {

std::string_view major_spelling(MajorId id) {
  switch (id) {
#define X(id, spelling) \
  case MajorId::id: return spelling;
#include "grammar/majors.def"
#undef X
    case MajorId::Unknown: break;
  }
  return "?";
}

MajorId major_id(std::string_view word) {
#define X(id, spelling) \
  if (iequals(word, spelling)) return MajorId::id;
#include "grammar/majors.def"
#undef X
  return MajorId::Unknown;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    unsigned char x = a[i], y = b[i];
    if (x >= 'a' && x <= 'z') x -= 32;
    if (y >= 'a' && y <= 'z') y -= 32;
    if (x != y) return false;
  }
  return true;
}

namespace {
constexpr std::string_view kGluable[] = {"GOTO",   "GODLTA", "GOHOME", "FROM",   "CIRCLE", "MOVARC", "RAPID",
                                         "FEDRAT", "SPINDL", "LOADTL", "UNITS",  "CUTCOM", "MULTAX", "CYCLE",
                                         "TLAXIS", "DELAY",  "TURRET", "INDIRV", "GOFWD"};

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && iequals(s.substr(0, prefix.size()), prefix);
}
}  // namespace

std::string_view glued_record(std::string_view word) {
  for (std::string_view name : kGluable) {
    if (word.size() <= name.size() || !starts_with(word, name)) continue;
    const std::string_view rest = word.substr(name.size());
    const char c = rest[0];
    if ((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+') return name;
    for (std::string_view other : kGluable)
      if (starts_with(rest, other)) return name;
    if (name == "UNITS")
      for (std::string_view u : {"INCHES", "INCH", "MM", "CM"})
        if (iequals(rest, u)) return name;
  }
  return {};
}

bool carries_nothing_to_cut(MajorId id) {
  switch (id) {
    case MajorId::Pprint: case MajorId::Tprint: case MajorId::Comment: case MajorId::Partno: case MajorId::Remark:
    case MajorId::Paint: case MajorId::Ppword: case MajorId::Mfgno: case MajorId::Setstart: case MajorId::Toolno:
    case MajorId::Autops: case MajorId::Intol: case MajorId::Outtol: case MajorId::Toler: case MajorId::Featno:
      return true;
    default: return false;
  }
}

bool moves_or_changes_the_cut(std::string_view name) {
  static constexpr std::string_view kMore[] = {"COOLNT", "GOLFT", "GORGT", "GOBACK", "GOUP", "GODOWN"};
  for (std::string_view g : kGluable)
    if (iequals(name, g)) return true;
  for (std::string_view g : kMore)
    if (iequals(name, g)) return true;
  return false;
}

size_t record_inside(std::string_view text) {
  for (size_t slash = text.find('/'); slash != std::string_view::npos; slash = text.find('/', slash + 1)) {
    size_t end = slash;
    while (end > 0 && (text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
    size_t start = end;
    while (start > 0 && std::isalpha(static_cast<unsigned char>(text[start - 1]))) --start;
    // A name's own letters before it ("MY_GOTO/", "D10/R2", "1/2") make it no record; a blank,
    // APT's ';' statement separator or a label's ')' before it do not.
    if (start > 0 && (std::isalnum(static_cast<unsigned char>(text[start - 1])) || text[start - 1] == '_')) continue;
    // In capitals, as CAM systems write records ("copy/paste", "load/unload" are words of a
    // note); NX's tool change LOAD/TOOL, not LOAD/UNLOAD (helper-69).
    const std::string_view name = text.substr(start, end - start);
    if (name.empty() || std::any_of(name.begin(), name.end(), [](char c) { return c >= 'a' && c <= 'z'; })) continue;
    size_t after = slash + 1;
    while (after < text.size() && (text[after] == ' ' || text[after] == '\t')) ++after;
    if (moves_or_changes_the_cut(name) || (name == "LOAD" && text.substr(after, 4) == "TOOL")) return start;
  }
  return std::string_view::npos;
}

}  // namespace clpc
