// clpc schema: the JSON Schema of machine files, made from the key table. Every key of the
// table is in it with its type and doc; Python's jsonschema (python3-jsonschema, installed by
// scripts/setup.sh --tests) accepts every built-in and example machine file against it and
// rejects a misspelled key and a wrong type, as an editor checking TOML would.
#include "helpers.h"
#include "machine/json_schema.h"
#include "machine/schema.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {


// The validator, or why it cannot run here.
std::string validator_missing() {
  RunResult r = run_shell("python3 -c 'import tomllib, jsonschema'");
  return r.status == 0 ? std::string() : "python3 with tomllib and jsonschema is not here (scripts/setup.sh --tests installs it): " + r.err;
}

RunResult validate(const std::string& schema, const std::string& files) {
  return run_shell("python3 " + source_path("tests/tools/validate_machines.py") + " " + schema + " " + files);
}

}  // namespace

TEST(JsonSchema, EveryKeyWithItsTypeAndDoc) {
  const std::string s = machine_json_schema();
  EXPECT_THAT(s, HasSubstr("\"$schema\": \"http://json-schema.org/draft-07/schema#\""));
  EXPECT_THAT(s, HasSubstr("\"additionalProperties\": {\"$ref\": \"#/definitions/machine\"}"));
  EXPECT_THAT(s, HasSubstr("\"units\": {\"type\": \"string\", \"enum\": [\"mm\", \"inch\"], "
                           "\"description\": \"output units; the CL's are converted\"}"));
  EXPECT_THAT(s, HasSubstr("\"max_rpm\": {\"type\": \"number\", \"minimum\": 0, \"maximum\": 1000000, "
                           "\"description\": \"the spindle's limit; a SPINDL above it is an error (0: none)\"}"));
  EXPECT_THAT(s, HasSubstr("\"axes\": {\"type\": \"array\", \"items\": {\"$ref\": \"#/definitions/kinematics.axes\"}"));
  EXPECT_THAT(s, HasSubstr("\"X\": {\"$ref\": \"#/definitions/address\"}"));
  EXPECT_THAT(s, HasSubstr("\"work_zero\": {\"type\": \"array\", \"items\": {\"type\": \"number\"}, \"minItems\": 3, \"maxItems\": 3"));
  for (const KeySpec& k : machine_keys()) {
    EXPECT_THAT(s, HasSubstr("\"" + k.key + "\": ")) << k.section << "." << k.key;
    const std::string def = "\"" + (k.section.empty() ? std::string("machine") : std::string(k.section)) + "\": {";
    EXPECT_THAT(s, HasSubstr(def)) << k.section;
  }
}

TEST(JsonSchema, CommandPrintsIt) {
  RunResult r = run_clpc("schema");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, machine_json_schema());
}

TEST(JsonSchema, BuiltInAndExampleMachinesValidate) {
  if (std::string why = validator_missing(); !why.empty()) GTEST_SKIP() << why;
  TempDir t;
  write_file(t.path("schema.json"), machine_json_schema());
  const std::string files = source_path("machines.toml") + " " + source_path("examples/*.toml") + " " + source_path("tests/machines/*.toml") + " " +
                            source_path("tests/offsets/machines.toml");
  RunResult r = validate(t.path("schema.json"), files);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_THAT(r.out, ::testing::MatchesRegex("ok [0-9]+ files\n"));
  EXPECT_EQ(r.err, "");
}

// What an editor flags as the user types, clpc's reader refuses too.
TEST(JsonSchema, RejectsAMisspelledKeyAndAWrongType) {
  if (std::string why = validator_missing(); !why.empty()) GTEST_SKIP() << why;
  TempDir t;
  write_file(t.path("schema.json"), machine_json_schema());
  const std::string bad =
      "[shop-mill]\n"
      "family = \"mill\"\n"
      "rapid_rat = 20000\n"
      "[shop-mill.arcs]\n"
      "max_radius = \"large\"\n";
  write_file(t.path("bad.toml"), bad);
  RunResult r = validate(t.path("schema.json"), t.path("bad.toml"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, t.path("bad.toml") + ": shop-mill: Additional properties are not allowed ('rapid_rat' was unexpected)\n" +
                       t.path("bad.toml") + ": shop-mill.arcs.max_radius: 'large' is not of type 'number'\n");
  const std::string clpc = machine_errors(bad, "shop-mill");
  EXPECT_THAT(clpc, HasSubstr("rapid_rat"));
  EXPECT_THAT(clpc, HasSubstr("max_radius"));
}
