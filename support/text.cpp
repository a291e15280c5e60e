#include "support/text.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>

namespace clpc {

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = char(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

std::string num_text(double v) {
  if (v == 0) return "0";  // also folds -0
  if (v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(int64_t(v));
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, ec == std::errc() ? end : buf);
}

}  // namespace clpc
