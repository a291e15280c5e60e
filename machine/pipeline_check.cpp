#include "machine/pipeline_check.h"

#include <algorithm>

namespace clpc {

ir::Facts given_facts(const Machine& m) {
  ir::Facts f = m.kinematics.has_rotaries() ? 0 : ir::Kinematic;
  if (m.is_lathe()) f |= ir::OffsetsAssigned;  // a lathe has no offset table: G54 as lowered
  return f;
}

ir::Facts legal_program(const Machine& m) {
  ir::Facts f = ir::ArcsDecided | ir::ArcsOneTurn | ir::ArcsLegal | ir::CyclesFormed | ir::Kinematic;
  f |= m.is_lathe() ? ir::GroovesFormed : ir::OffsetsAssigned;
  if (m.kinematics.travel.set) f |= ir::LimitsChecked;
  if (!m.motion.rapids_linear) f |= ir::RapidsSplit;
  return f;
}

std::string check_pipeline(const Machine& m, const ir::PassContracts& passes) {
  auto contract = [&](const std::string& name) -> const ir::PassContract* {
    for (const ir::PassContract& c : passes)
      if (c.name == name) return &c;
    return nullptr;
  };
  // The pass that provides `f`, preferring one of the pipeline's after position `from`.
  auto provider = [&](ir::Fact f, size_t from) -> std::pair<std::string, bool> {
    for (size_t i = from; i < m.pipeline.size(); ++i)
      if (const ir::PassContract* c = contract(m.pipeline[i]); c && (c->provides & f)) return {c->name, true};
    for (const ir::PassContract& c : passes)
      if (c.provides & f) return {c.name, false};
    return {"", false};
  };
  auto missing = [&](ir::Fact f, size_t from, const std::string& user) -> std::string {
    const auto [pass, later] = provider(f, from);
    if (later) return "'" + pass + "' must come before '" + user + "'";
    std::string why;
    for (const ir::FactInfo& i : ir::all_facts())
      if (i.fact == f) why = std::string(i.why);
    if (pass.empty()) return "machine '" + m.name + "' needs a pass that provides " + ir::fact_names(f) + ", " + why;
    return "machine '" + m.name + "' needs '" + pass + "' in its pipeline, " + why;
  };

  ir::Facts have = given_facts(m);
  for (size_t i = 0; i < m.pipeline.size(); ++i) {
    const ir::PassContract* c = contract(m.pipeline[i]);
    if (!c) continue;
    for (const ir::FactInfo& f : ir::all_facts())
      if ((c->needs & f.fact) && !(have & f.fact)) return missing(f.fact, i + 1, c->name);
    have = (have & ~c->breaks) | c->provides;
  }
  const ir::Facts need = legal_program(m);
  for (const ir::FactInfo& f : ir::all_facts())
    if ((need & f.fact) && !(have & f.fact)) {
      // Broken by a later pass and not re-established: name the pass that must follow it.
      for (size_t i = m.pipeline.size(); i-- > 0;)
        if (const ir::PassContract* c = contract(m.pipeline[i]); c && (c->breaks & f.fact)) {
          const auto [pass, later] = provider(f.fact, 0);
          return "'" + pass + "' must come after '" + c->name + "', which leaves " + ir::fact_names(f.fact) +
                 " undone";
        }
      return missing(f.fact, m.pipeline.size(), "");
    }
  return "";
}

}  // namespace clpc
