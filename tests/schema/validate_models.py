#!/usr/bin/env python3
"""docs/model.schema.json is a valid draft 2020-12 JSON Schema, and every bundled example model
validates against it (the reader accepts them all: examples_test). Session 14: the schema had a
property whose schema was `null` (profile tolerances' "distribution"), which no validator accepts.

usage: validate_models.py SOURCE_DIR
exit: 0 valid; 1 a schema or model error (printed); 77 python3-jsonschema missing (skipped)."""
import glob
import json
import os
import sys

try:
    import jsonschema
except ImportError:
    print("python3-jsonschema is not installed: skipped")
    sys.exit(77)

source = sys.argv[1]
schema = json.load(open(os.path.join(source, "docs", "model.schema.json")))
try:
    jsonschema.Draft202012Validator.check_schema(schema)
except jsonschema.SchemaError as error:
    print("docs/model.schema.json is not a valid JSON Schema:", error.message, "at", "/".join(map(str, error.path)))
    sys.exit(1)
validator = jsonschema.Draft202012Validator(schema)
failures = 0
models = sorted(glob.glob(os.path.join(source, "examples", "models", "*.json")))
for path in models:
    for error in validator.iter_errors(json.load(open(path))):
        failures += 1
        print(f"{os.path.relpath(path, source)}: /{'/'.join(map(str, error.absolute_path))}: {error.message[:200]}")
print(f"{len(models)} example models checked against docs/model.schema.json, {failures} errors")
sys.exit(1 if failures else 0)
