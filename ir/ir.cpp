#include "ir/ir.h"

#include <cmath>

#include "support/text.h"

namespace clpc {

namespace ir {

int register_index(int cl) {
  if (cl >= 54 && cl <= 59) return cl - 53;
  if (cl >= 101 && cl <= 1000) return cl - 100 + 6;
  return 0;
}

std::string_view units_name(Units u) { return u == Units::Inch ? "inch" : "mm"; }

std::string_view cam_system_name(CamSystem s) {
  switch (s) {
    case CamSystem::Nx: return "NX";
    case CamSystem::Creo: return "Creo";
    case CamSystem::Catia: return "CATIA";
    case CamSystem::Fusion: return "Fusion";
    case CamSystem::SolidWorks: return "SolidWorks CAM";
    case CamSystem::Ncl: return "NCL";
    case CamSystem::Unknown: break;
  }
  return "an unknown CAM system";
}

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

Frame Frame::inverse() const {
  Frame f;
  f.rotation = rotation.transpose();
  f.origin = -(f.rotation * origin);
  return f;
}

Frame compose(const Frame& outer, const Frame& inner) {
  Frame f;
  f.rotation = outer.rotation * inner.rotation;
  f.origin = outer.rotation * inner.origin + outer.origin;
  return f;
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
