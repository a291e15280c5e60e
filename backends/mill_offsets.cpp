// The work-offset table at the head of a mill program (the offset-table pass's entries) and
// the seed's macro program after it, as the machine's offsets.table says:
//   none       a comment per register: which frame the operator sets it to;
//   g10        G10 L2 Pn / G10 L20 Pn with the offset clpc computed (machine coordinates);
//   g65-macro  G65 P2013 B<register> X Y Z A C, every argument with its decimal point; the
//              macro computes the offset on the control (docs/offsets.md).
#include <cmath>

#include "machine/format.h"
#include "backends/mill.h"
#include "support/text.h"

namespace clpc {

namespace {

const char* source_name(const ir::WorkOffset& w) {
  if (w.base) return "BASE FRAME";
  switch (w.source) {
    case ir::FrameSource::Msys: return "MSYS";
    case ir::FrameSource::Camera: return "CAMERA";
    case ir::FrameSource::Csys: break;
  }
  return "CSYS";
}

// The format of a G65 argument: the machine's, with a decimal point whatever it says (a
// macro argument without one is read in least increments on a Fanuc).
AddressFormat with_point(AddressFormat f) {
  f.point = AddressFormat::Point::Always;
  f.scale = 1;
  return f;
}

}  // namespace

void MillBackend::start_program() { write_offset_table(); }

void MillBackend::after_finish() { write_offset_macro(); }

void MillBackend::write_offset_table() {
  const auto& table = info_->offsets;
  if (table.empty()) return;
  const OffsetSettings& s = m_.offsets;
  const int standard = s.standard_last - s.standard_first + 1;
  e_.comment(s.table == OffsetTable::None ? "WORK OFFSETS - SET ON THE MACHINE" : "WORK OFFSETS");
  for (const ir::WorkOffset& w : table) {
    // Which frame the register holds, and where the rotaries stand for it.
    auto [select, vars] = offset_select(w.index);
    std::string note = e_.render(*select, vars) + " = ";
    if (w.set_register) note += "SET/" + std::to_string(w.set_register) + " ";
    note += std::string(source_name(w)) + " LINE " + std::to_string(w.loc.line);
    if (s.table == OffsetTable::None) {
      const ir::Vec3 o = w.frame.origin * k_;
      note += " ORIGIN X" + num_text(std::round(o.x() * 1e4) / 1e4) + " Y" + num_text(std::round(o.y() * 1e4) / 1e4) +
              " Z" + num_text(std::round(o.z() * 1e4) / 1e4);
    }
    if (w.has_rotary)
      for (size_t i = 0; i < m_.kinematics.rotaries.size(); ++i) {
        char l = m_.kinematics.rotaries[i].name[0];
        std::string v;
        int64_t q;
        if (quantize(w.rotary[i], m_.format(l), q)) append_quantized(q, m_.format(l), v);
        note += std::string(" ") + l + v;
      }
    e_.comment(note);

    switch (s.table) {
      case OffsetTable::None: break;
      case OffsetTable::G10: {
        e_.begin(w.loc);
        const bool extended = w.index > standard;
        e_.code(extended ? m_.codes.offset_set_extended : m_.codes.offset_set,
                TemplateVars().with(Var::Number, extended ? w.index - standard : w.index));
        e_.argument('X', w.machine.x(), m_.format('X'));
        e_.argument('Y', w.machine.y(), m_.format('Y'));
        e_.argument('Z', w.machine.z(), m_.format('Z'));
        e_.end();
        after_template(m_.codes.offset_set);
        break;
      }
      case OffsetTable::G65Macro: {
        e_.begin(w.loc);
        e_.code(m_.codes.macro_call, TemplateVars().with(Var::Number, double(s.macro)));
        const ir::Vec3 o = w.frame.origin * k_;
        e_.argument('B', w.index, with_point(m_.format('B')));
        e_.argument('X', o.x(), with_point(m_.format('X')));
        e_.argument('Y', o.y(), with_point(m_.format('Y')));
        e_.argument('Z', o.z(), with_point(m_.format('Z')));
        e_.argument('A', w.seed_a, with_point(m_.format('A')));
        e_.argument('C', w.seed_c, with_point(m_.format('C')));
        e_.end();
        after_template(m_.codes.macro_call);
        break;
      }
    }
  }
}

// The seed paper's macro, word for word: valid where the machine's origin is the point the A
// and C axes intersect, #503 the reference base's height above it.
void MillBackend::write_offset_macro() {
  const OffsetSettings& s = m_.offsets;
  if (s.table != OffsetTable::G65Macro || !s.macro_program || info_->offsets.empty()) return;
  std::string o = "O";
  int64_t q;
  if (quantize(double(s.macro), m_.format('O'), q)) append_quantized(q, m_.format('O'), o);
  e_.line(o + m_.block_end);
  e_.comment("WORK OFFSET FROM SET/CAMERA: A=#1 B=#2 C=#3 X=#24 Y=#25 Z=#26");
  e_.comment("#503 = REFERENCE BASE HEIGHT ABOVE THE TABLE CENTRE");
  static const char* const body[] = {
      "#16 = #26 + #503",
      "#104 = #24*COS[-#3] - #25*SIN[-#3]",
      "#105 = #24*COS[-#1]*SIN[-#3] + #25*COS[-#1]*COS[-#3] - #16*SIN[-#1]",
      "#106 = #24*SIN[-#1]*SIN[-#3] + #25*SIN[-#1]*COS[-#3] + #16*COS[-#1]",
      "G90 G10 L2 P#2 X#104 Y#105 Z#106",
      "M99",
  };
  for (const char* l : body) e_.line(std::string(l) + m_.block_end);
}

}  // namespace clpc
