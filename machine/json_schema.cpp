#include "machine/json_schema.h"

#include <map>
#include <string_view>

#include "machine/schema.h"
#include "support/text.h"

namespace clpc {

namespace {

// The definition name of a section: "machine" for the machine's own keys.
std::string def_name(std::string_view section) { return section.empty() ? "machine" : std::string(section); }
std::string ref_to(std::string_view section) { return "{\"$ref\": \"#/definitions/" + def_name(section) + "\"}"; }

std::string bounds(const KeySpec& k) {
  std::string o = ", \"minimum\": " + num_text(k.lo);
  if (k.hi < 1e300) o += ", \"maximum\": " + num_text(k.hi);
  return o;
}

std::string enum_of(const KeySpec& k) {
  std::string o = "\"enum\": [";
  const std::vector<std::string> c = k.choice_list();
  for (size_t i = 0; i < c.size(); ++i) o += (i ? ", " : "") + json_text(c[i]);
  return o + "]";
}

std::string numbers(int n) {
  const std::string c = std::to_string(n);
  return "\"type\": \"array\", \"items\": {\"type\": \"number\"}, \"minItems\": " + c + ", \"maxItems\": " + c;
}

// The schema of one key, its doc as the description.
std::string key_schema(const KeySpec& k) {
  if (k.kind == KeyKind::Table) return ref_to(sub_section(k.section, k.key));
  if (k.kind == KeyKind::Format) return ref_to(sub_section(k.section, k.key));
  std::string body;
  switch (k.kind) {
    case KeyKind::Bool: body = "\"type\": \"boolean\""; break;
    case KeyKind::Integer: body = "\"type\": \"integer\"" + bounds(k); break;
    case KeyKind::Number:
    case KeyKind::Length: body = "\"type\": \"number\"" + bounds(k); break;
    case KeyKind::String:
    case KeyKind::Template: body = "\"type\": \"string\""; break;
    case KeyKind::Choice: body = "\"type\": \"string\", " + enum_of(k); break;
    case KeyKind::Strings:
      body = "\"type\": \"array\", \"items\": {\"type\": \"string\"" + (k.choices.empty() ? std::string() : ", " + enum_of(k)) + "}";
      break;
    case KeyKind::Templates: body = "\"type\": \"array\", \"items\": {\"type\": \"string\"}"; break;
    case KeyKind::Vec3:
    case KeyKind::Length3: body = numbers(3); break;
    case KeyKind::Range: body = numbers(2); break;
    case KeyKind::Tables:
      body = "\"type\": \"array\", \"items\": " + ref_to(sub_section(k.section, k.key));
      break;
    case KeyKind::Table:
    case KeyKind::Format: break;
  }
  return "{" + body + ", \"description\": " + json_text(k.doc) + "}";
}

}  // namespace

std::string machine_json_schema() {
  // Sections in the table's order, each with its keys in order.
  std::vector<std::string> order;
  std::map<std::string, std::vector<const KeySpec*>> keys;
  for (const KeySpec& k : machine_keys()) {
    const std::string s(k.section);
    if (!keys.count(s)) order.push_back(s);
    keys[s].push_back(&k);
  }
  std::string o = "{\n  \"$schema\": \"http://json-schema.org/draft-07/schema#\",\n";
  o += "  \"title\": \"clpc machine descriptions\",\n";
  o += "  \"description\": \"A clpc machines file (TOML): each top-level table is one machine (docs/machines.md).\",\n";
  o += "  \"type\": \"object\",\n  \"additionalProperties\": " + ref_to("") + ",\n  \"definitions\": {";
  for (size_t i = 0; i < order.size(); ++i) {
    o += std::string(i ? "," : "") + "\n    " + json_text(def_name(order[i])) + ": {\n      \"type\": \"object\",\n";
    o += "      \"additionalProperties\": false,\n      \"properties\": {";
    const std::vector<const KeySpec*>& ks = keys[order[i]];
    for (size_t j = 0; j < ks.size(); ++j)
      o += std::string(j ? "," : "") + "\n        " + json_text(ks[j]->key) + ": " + key_schema(*ks[j]);
    o += "\n      }\n    }";
  }
  return o + "\n  }\n}\n";
}

}  // namespace clpc
