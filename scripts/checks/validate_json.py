#!/usr/bin/env python3
"""Validates JSON files against a JSON Schema (Debian's python3-jsonschema).

  validate_json.py SCHEMA FILE...            every FILE must be valid
  validate_json.py --invalid SCHEMA FILE...  every FILE must be rejected (the
                                             schema's own test: a schema that
                                             accepts anything would pass the first form)

Prints one line per file (the first error's path and message when rejected);
exits 1 if any file is not as expected, 2 on a usage error."""
import json
import sys

try:
    import jsonschema
except ImportError:
    sys.exit("validate_json: needs python3-jsonschema (scripts/install-deps installs it)")


def main(argv):
    expect_valid = True
    if argv and argv[0] == "--invalid":
        expect_valid, argv = False, argv[1:]
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[0]) as f:
        schema = json.load(f)
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)  # a broken schema is an error, not a pass
    validator = cls(schema)
    bad = 0
    for path in argv[1:]:
        with open(path) as f:
            doc = json.load(f)
        errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))
        if errors:
            where = "/".join(str(p) for p in errors[0].absolute_path) or "(top)"
            print(f"{path}: rejected at {where}: {errors[0].message[:200]}")
        else:
            print(f"{path}: valid")
        bad += (not errors) != expect_valid
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
