// The machine description as a JSON Schema (draft-07), made from the key table
// (machine/schema.h), so it cannot drift from what the reader accepts: editors that check TOML
// against a schema (Taplo, Even Better TOML) complete the keys, show each key's doc and flag
// a misspelled key or a wrong type as the user types. `clpc schema` prints it;
// docs/machines.md says how to use it.
#pragma once

#include <string>

namespace clpc {

// A machines file: every top-level table is one machine.
std::string machine_json_schema();

}  // namespace clpc
