#!/usr/bin/env python3
"""The commands the README shows work as written.

Every `moorsim ...` command of the README's indented code blocks (continuation lines
joined) is run from a scratch folder holding links to the repository's scenarios/ and
tools/, in the README's order (a later command may read what an earlier one wrote):
`moorsim template` as written; `moorsim run` as written plus --quiet, an --out in the
scratch folder and a --duration that ends 5 s after the failure the command sets (the
scenario, its --set values, the start and the failure are what the README promises; the
rest of the run is the tests' business elsewhere); `moorsim batch` with --dry-run (every
run of the campaign loaded and checked, nothing run). Every
`tools/...` script the blocks name must exist and answer --help.

Usage: readme_commands_test.py MOORSIM SOURCE_DIR
"""

import os
import re
import shlex
import subprocess
import sys
import tempfile

moorsim, source = sys.argv[1], sys.argv[2]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what)


def code_lines(text):
    """The README's indented code lines, continuations joined, comments cut."""
    lines, pending = [], ""
    for line in text.splitlines():
        if not line.startswith("    ") or not line.strip():
            pending = ""
            continue
        code = line.strip()
        if pending:
            code = pending + " " + code
        if code.endswith("\\"):
            pending = code[:-1].strip()
            continue
        pending = ""
        lines.append(code)
    return lines


with open(os.path.join(source, "README.md"), encoding="utf-8") as f:
    readme = f.read()
commands = [c for c in code_lines(readme) if re.match(r"(moorsim|tools/)\S*\s", c + " ")]
check(any(c.startswith("moorsim template") for c in commands), "the README shows a template")
check(any(c.startswith("moorsim run") for c in commands), "the README shows a run")
check(any(c.startswith("moorsim batch") for c in commands), "the README shows a campaign")

with tempfile.TemporaryDirectory(prefix="readme_commands_") as scratch:
    for folder in ("data", "scenarios", "tools"):
        os.symlink(os.path.join(source, folder), os.path.join(scratch, folder))
    for command in commands:
        words = shlex.split(command, comments=True)
        if words[0].startswith("tools/"):
            script = os.path.join(source, words[0])
            check(os.access(script, os.X_OK), f"{words[0]} exists and is executable")
            if os.access(script, os.X_OK) and words[0].endswith(".py"):
                r = subprocess.run([script, "--help"], cwd=scratch, capture_output=True, text=True)
                check(r.returncode == 0, f"{words[0]} --help exits 0: {r.stderr.strip()}")
            continue
        args = words[1:]
        if args[0] == "run":
            failure = re.search(r"failure=\{[^}]*time:\s*([0-9.e+]+)", " ".join(words))
            duration = float(failure.group(1)) + 5 if failure else 5
            args += ["--duration", str(duration), "--quiet", "--out", os.path.join(scratch, "run")]
        elif args[0] == "batch":
            args += ["--dry-run"]
        elif args[0] != "template":
            check(False, f"a README command this test does not know how to check: {command}")
            continue
        r = subprocess.run([moorsim] + args, cwd=scratch, capture_output=True, text=True,
                           timeout=300)
        check(r.returncode == 0,
              f"`{command}` exits 0 (got {r.returncode}): {r.stderr.strip()[-400:]}")
        print(f"ok: {command}")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
