#!/usr/bin/env python3
"""Checks machine files (TOML) against clpc's JSON Schema (clpc schema), as an editor does.

    validate_machines.py SCHEMA.json FILE.toml...

Prints one line per problem, "FILE: KEY.PATH: message", and exits 1 if there is any; 0 and
"ok N files" otherwise. Needs Python 3.11 (tomllib) and python3-jsonschema.
"""
import json
import sys
import tomllib

import jsonschema


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1], encoding="utf-8") as f:
        schema = json.load(f)
    jsonschema.Draft7Validator.check_schema(schema)
    validator = jsonschema.Draft7Validator(schema)
    problems = 0
    for path in argv[2:]:
        with open(path, "rb") as f:
            data = tomllib.load(f)
        for e in sorted(validator.iter_errors(data), key=lambda e: list(map(str, e.absolute_path))):
            where = ".".join(str(p) for p in e.absolute_path) or "(top)"
            print(f"{path}: {where}: {e.message}")
            problems += 1
    if problems:
        return 1
    print(f"ok {len(argv) - 2} files")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
