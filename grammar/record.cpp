#include "grammar/record.h"

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

}  // namespace clpc
