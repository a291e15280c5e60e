#include <cctype>
#include "ir/ir.h"

#include <charconv>
#include <cmath>

#include "ir/params.h"

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

namespace ir {

std::string_view units_name(Units u) { return u == Units::Inch ? "inch" : "mm"; }

std::string_view cycle_kind_name(CycleKind k) {
  switch (k) {
    case CycleKind::Drill: return "drill";
    case CycleKind::SpotDwell: return "spot-dwell";
    case CycleKind::Peck: return "peck";
    case CycleKind::ChipBreak: return "chip-break";
    case CycleKind::Tap: return "tap";
    case CycleKind::Bore: return "bore";
    case CycleKind::BoreDwell: return "bore-dwell";
    case CycleKind::BoreStop: return "bore-stop";
    case CycleKind::FineBore: return "fine-bore";
    case CycleKind::BackBore: return "back-bore";
  }
  return "?";
}

bool Frame::is_identity(double tol) const {
  return (rotation - Mat3::Identity()).cwiseAbs().maxCoeff() <= tol && origin.cwiseAbs().maxCoeff() <= tol;
}

bool Frame::same_as(const Frame& o, double lin_tol, double rot_tol) const {
  return (rotation - o.rotation).cwiseAbs().maxCoeff() <= rot_tol &&
         (origin - o.origin).cwiseAbs().maxCoeff() <= lin_tol;
}

TextRef Operation::add_text(std::string_view s) {
  TextRef r{uint32_t(text.size()), uint32_t(s.size())};
  text.append(s);
  return r;
}

void Operation::clear() {
  body.clear();
  text.clear();
  points.clear();
  cycles.clear();
  grooves.clear();
  name.clear();
  continued = false;
  last_chunk = true;
}

const ToolInfo* ProgramInfo::tool(int number) const {
  for (const ToolInfo& t : tools)
    if (t.number == number) return &t;
  return nullptr;
}

int ProgramInfo::tool_number_for_name(std::string_view name) const {
  for (const ToolInfo& t : tools)
    if (t.name == name) return t.number;
  return 0;
}

int ProgramInfo::named_tool_at(uint32_t line) const {
  for (const auto& [l, tool] : named_tool_ops)
    if (l == line) return tool;
  return 0;
}

}  // namespace ir
}  // namespace clpc
