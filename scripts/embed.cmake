# Writes OUT, a C++ file defining clpc::builtin_machines_toml() with the bytes of IN.
file(READ ${IN} hex HEX)
string(LENGTH "${hex}" n)
math(EXPR bytes "${n} / 2")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," body "${hex}")
string(REGEX REPLACE "((0x[0-9a-f][0-9a-f],){24})" "\\1\n" body "${body}")
file(WRITE ${OUT} "// Generated from machines.toml by scripts/embed.cmake. Do not edit.\n"
  "#include <string_view>\nnamespace clpc {\nstatic const char kData[] = {\n${body}0};\n"
  "std::string_view builtin_machines_toml() { return {kData, ${bytes}}; }\n}\n")
