// Loading machine descriptions: the built-in machines.toml, any number of --machines files
// (adding machines or replacing them by name), and -t path/to/machine.toml. Every value is
// validated; a mistake names the file, line, key and what was expected.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ir/stage.h"
#include "machine/machine.h"
#include "support/diagnostics.h"

namespace toml {
inline namespace v3 {
class table;
}
}  // namespace toml

namespace clpc {

std::string_view builtin_machines_toml();  // generated from machines.toml at build time

class MachineRegistry {
 public:
  // `passes` are the passes a pipeline may name, with their contracts (passes/registry.cpp):
  // a machine's pipeline must reach a legal program through them (machine/pipeline_check.h).
  // None: pipelines are taken as they are (default_machine).
  explicit MachineRegistry(ir::PassContracts passes);
  ~MachineRegistry();

  bool load_builtin(Diagnostics& d);
  // The built-ins, then each file in order (--machines): false after errors, all tried.
  bool load_builtin_and(const std::vector<std::string>& files, Diagnostics& d);
  // Adds the machines of a TOML file (or text, for tests); later ones replace earlier ones
  // of the same name.
  bool load_file(const std::string& path, Diagnostics& d);
  bool load_text(const std::string& name, std::string text, Diagnostics& d);

  // What one job changes in the machine (docs/machines.md, "Per-job options"): the [job]
  // tables of --job files, then --set KEY=VALUE in order (a later one wins). Each is a layer
  // on top of the machine, as a machine that inherits it would be.
  struct Job {
    std::vector<std::string> files;
    std::vector<std::string> sets;
    bool empty() const { return files.empty() && sets.empty(); }
  };
  // A machine by name, or by path to a TOML file holding one machine, with the job's
  // changes. nullopt after errors.
  std::optional<Machine> resolve(const std::string& name_or_path, Diagnostics& d, const Job& job = {});
  std::vector<std::pair<std::string, std::string>> list() const;  // name, description

  struct Source;  // a loaded TOML file: its path, text and parsed table

 private:
  struct Entry {
    const Source* source;
    const toml::table* table;
  };
  bool add_source(std::unique_ptr<Source> src, Diagnostics& d, std::vector<std::string>* names);
  std::optional<Machine> resolve_unguarded(const std::string& name_or_path, Diagnostics& d, const Job& job);
  // The job's layers (appended to `layers`); false after a reported error.
  bool job_layers(const Job& job, std::vector<const toml::table*>& layers, Diagnostics& d);
  bool flatten(const std::string& name, std::vector<const toml::table*>& layers, std::vector<std::string>& chain,
               Diagnostics& d);

  ir::PassContracts passes_;
  std::vector<std::unique_ptr<Source>> sources_;
  std::map<std::string, Entry> machines_;
  std::map<std::string, Entry> bases_;  // the built-in abstract bases (machines.toml)
};

// A machine with every default of its family (the abstract base of machines.toml) and no
// description behind it (clpc check without -t, tests).
Machine default_machine(Family family, ir::Units units);

}  // namespace clpc
