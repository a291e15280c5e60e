// The machine description's keys, once: section, key, kind, range or choices, the
// placeholders a code template may use, one line of doc, and the member it fills (as the
// value explain prints). The reader takes each key's kind and range from here and refuses a
// key that is not here, `clpc explain` prints the keys of this table in its order, and a test
// checks docs/machines.md's key reference against it (tests/machine/test_schema.cpp).
//
// To add a key: a member in machine/machine.h, a row here, a read in machine_loader.cpp's
// build_machine (which says what the key does), a row in docs/machines.md.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "machine/machine.h"

namespace clpc {

enum class KeyKind {
  Bool,
  Integer,
  Number,     // a plain number
  Length,     // a length or a rate in the machine's units (converted when inherited across units)
  String,
  Choice,     // one of `choices`
  Strings,    // an array of strings (of `choices` when given)
  Template,   // a code template, with the placeholders `vars` allows
  Templates,  // an array of code templates without placeholders
  Vec3,       // [x, y, z]
  Length3,    // [x, y, z] in the machine's units
  Range,      // [min, max] in the machine's units
  Format,     // an address format: a table of the "address" section's keys
  Table,      // a section: the keys of section "<this section>.<key>" (or its own name)
  Tables,     // an array of tables
};

// Where a section shows in explain: always, only for a lathe, only with rotary axes, or only
// when given (keys with no default).
enum class Shown { Always, Lathe, Rotaries, WhenGiven, Never };

struct KeySpec {
  std::string_view section;  // "" (top level), "program", "kinematics.axes", "address", ...
  std::string key;
  KeyKind kind;
  double lo = 0, hi = 0;          // Integer, Number, Length
  std::string_view choices;       // Choice, Strings: "off|tool-change|operation"
  uint32_t vars = 0;              // Template: the Var bits allowed
  std::string_view doc;
  Shown shown = Shown::Always;
  // The value as explain writes it (TOML), from the resolved machine; `item` is the rotary
  // axis for section "kinematics.axes". Null for sections (Table, Tables).
  std::string (*value)(const Machine&, size_t item) = nullptr;
  CodeTemplate Codes::*code = nullptr;  // section "codes": the member read and written

  std::vector<std::string> choice_list() const;
  // The type as docs/machines.md writes it: "integer 0–9", "`\"mm\"` \| `\"inch\"`", ...
  std::string type_text() const;
};

// Every key, sections in explain's order.
const std::vector<KeySpec>& machine_keys();
// The key `key` of `section`, or null.
const KeySpec* find_key(std::string_view section, std::string_view key);
// The section a sub-table `key` of `section` opens: "program", "kinematics.axes", "address"
// (an address format, in "format" and "feeds").
std::string sub_section(std::string_view section, std::string_view key);

// clpc explain: the resolved machine as TOML, every key of the table with its value.
std::string explain_machine(const Machine& m);

}  // namespace clpc
