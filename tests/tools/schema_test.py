#!/usr/bin/env python3
"""The JSON Schema that `moorsim schema` writes, checked from outside the program.

1. The schema files in scenarios/ are what `moorsim schema` prints now (regenerate with
   `moorsim schema > scenarios/moorsim.schema.json` and
   `moorsim schema --campaign > scenarios/moorsim-campaign.schema.json`), and the key
   table in scenarios/README.md what `moorsim schema --markdown` prints.
2. Every library scenario and campaign carries the editors' modeline and validates against
   its schema (python3-jsonschema, draft-07).
3. Known-bad scenarios are rejected by both the schema and `moorsim validate` (exit 2, one
   located line naming the key).

The YAML is read as YAML 1.2 reads numbers (`3.0e6`, `1e-5` are floats, as yaml-cpp and
the editors' YAML servers read them; PyYAML's YAML 1.1 rules would make them strings).

Usage: schema_test.py MOORSIM SOURCE_DIR WORK_DIR
"""
import json
import os
import re
import subprocess
import sys

import jsonschema
import yaml

MOORSIM, SOURCE, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
failures = []


class Yaml12Loader(yaml.SafeLoader):
    pass


Yaml12Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    # Numbers with a fraction or an exponent (whole numbers stay integers: the int resolver
    # comes first for them).
    re.compile(r"^[-+]?(?:[0-9]+\.[0-9]*|\.[0-9]+|[0-9]+(?=[eE]))(?:[eE][-+]?[0-9]+)?$"),
    list("-+0123456789."))


def load_yaml(text):
    return yaml.load(text, Loader=Yaml12Loader)


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def run(*args):
    return subprocess.run([MOORSIM, *args], capture_output=True, text=True)


schemas = {}
for flag, name in (([], "moorsim.schema.json"), (["--campaign"], "moorsim-campaign.schema.json")):
    printed = run("schema", *flag)
    check(printed.returncode == 0, f"moorsim schema {' '.join(flag)} exits 0")
    path = os.path.join(SOURCE, "scenarios", name)
    with open(path, encoding="utf-8") as f:
        stored = f.read()
    check(stored == printed.stdout,
          f"scenarios/{name} is what `moorsim schema {' '.join(flag)}` prints (regenerate it)")
    schema = json.loads(printed.stdout)
    jsonschema.Draft7Validator.check_schema(schema)
    schemas[name] = jsonschema.Draft7Validator(schema)

# The key table in scenarios/README.md is what `moorsim schema --markdown` prints.
table = run("schema", "--markdown")
check(table.returncode == 0, "moorsim schema --markdown exits 0")
with open(os.path.join(SOURCE, "scenarios", "README.md"), encoding="utf-8") as f:
    readme = f.read()
begin, end = "<!-- moorsim schema --markdown -->\n", "<!-- end of moorsim schema --markdown -->"
check(begin in readme and end in readme
      and readme[readme.index(begin) + len(begin):readme.index(end)] == table.stdout,
      "scenarios/README.md holds the table `moorsim schema --markdown` prints (regenerate it)")
check(table.stdout.count("\n| `") > 150, "the table has a row per key")


def errors_of(validator, document):
    return sorted(validator.iter_errors(document), key=lambda e: list(e.path))


# The training campaigns sit one folder further down: their modeline reaches one further up.
for folder, name in (("library", "moorsim.schema.json"),
                     ("campaigns", "moorsim-campaign.schema.json"),
                     ("campaigns/training", "moorsim-campaign.schema.json")):
    directory = os.path.join(SOURCE, "scenarios", folder)
    up = "../" * (folder.count("/") + 1)
    files = sorted(f for f in os.listdir(directory) if f.endswith(".yaml"))
    check(len(files) > 0, f"scenarios/{folder} holds YAML files")
    for file in files:
        with open(os.path.join(directory, file), encoding="utf-8") as f:
            text = f.read()
        check(text.startswith(f"# yaml-language-server: $schema={up}{name}\n"),
              f"scenarios/{folder}/{file} starts with the modeline for {name}")
        found = errors_of(schemas[name], load_yaml(text))
        check(not found, f"scenarios/{folder}/{file} validates against {name}: "
                         + "; ".join(f"{list(e.path)}: {e.message}" for e in found[:3]))

# Known-bad scenarios: one edit of the seed case each, rejected by both.
with open(os.path.join(SOURCE, "scenarios", "library", "seed_tapm.yaml"), encoding="utf-8") as f:
    seed = f.read().replace("../../data/fpso_wamit/fpso",
                            os.path.join(SOURCE, "data", "fpso_wamit", "fpso"))
BAD = [
    # (name, old, new, key path the loader names, what the schema says about it)
    ("unknown key", "depth: 1000}", "dept: 1000}", "mooring.water", "dept"),
    ("number as text", "diameter: 0.08", "diameter: thick", "mooring.line_types[1].diameter",
     "thick"),
    ("out of range", "mass: 1.0041e8", "mass: 1.0041e11", "vessel.mass", "1.0041e+11 kg must be <= 1e+09"),
    ("unknown choice", "max_order: 2", "max_order: 2\n  linear_solver: lu", "solver.linear_solver",
     "unknown linear solver 'lu'"),
    ("missing required key", "      diameter: 0.08 ", "      # diameter: 0.08 ", "mooring.line_types[1]",
     "required key 'diameter' is missing"),
    ("vector of two", "fairlead: [20, 0, 12]", "fairlead: [20, 0]", "mooring.lines[1].fairlead",
     "must be a list of 3 numbers"),
    ("integer with a fraction", "segments: 50}", "segments: 50.5}", "mooring.defaults.segments",
     "must be an integer"),
]
for name, old, new, key, loader_says in BAD:
    check(old in seed, f"bad case '{name}': '{old}' is in the seed case")
    text = seed.replace(old, new, 1)
    path = os.path.join(WORK, "bad_" + name.replace(" ", "_") + ".yaml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    found = errors_of(schemas["moorsim.schema.json"], load_yaml(text))
    check(len(found) > 0, f"bad case '{name}': the schema rejects it")
    result = run("validate", path)
    lines = result.stderr.strip().split("\n")
    check(result.returncode == 2, f"bad case '{name}': moorsim validate exits 2 (got {result.returncode})")
    check(len(lines) == 1 and re.match(re.escape("moorsim: " + path) + r":\d+:\d+: ", lines[0])
          and key in lines[0] and loader_says in lines[0],
          f"bad case '{name}': one located line naming {key} ({loader_says}): {result.stderr!r}")

# A file with a base: every key may come from the base, but what it writes is checked.
variant = os.path.join(WORK, "bad_variant.yaml")
try:
    with open(variant, "w", encoding="utf-8") as f:
        f.write("base: " + os.path.join(SOURCE, "scenarios", "library", "thesis_no_failure.yaml")
                + "\nfailure: {line: 6, time: 400, mode: snap}\n")
    with open(variant, encoding="utf-8") as f:
        found = errors_of(schemas["moorsim.schema.json"], load_yaml(f.read()))
    check(len(found) == 1 and list(found[0].path) == ["failure", "mode"],
          f"a variant's bad choice is the schema's one error: {[e.message for e in found]}")
    result = run("validate", variant)
    check(result.returncode == 2 and result.stderr.count("\n") == 1 and
          "failure.mode: unknown failure mode 'snap'" in result.stderr,
          f"a variant's bad choice: one line from moorsim validate: {result.stderr!r}")
finally:
    os.remove(variant)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("schema: all checks passed")
