#!/usr/bin/env bash
# Writes the command-line reference, docs/cli-reference.md, from the program's own help:
#   tools/dev/cli_reference.sh build/release/tools/moorsim > docs/cli-reference.md
# The test CliReference.EqualsTheProgramsHelp fails when the two differ.
set -euo pipefail
moorsim=$1
version=$("$moorsim" --version)
help() { "$moorsim" "$@" --help | sed "s/${version//./\\.}/<version>/g"; }

cat <<'HEADER'
# Command-line reference

Every command's `--help`, as the program prints it (generated from it by
`tools/dev/cli_reference.sh`, and tested equal). What the commands do and how to use them
together: [The command line](cli.md).

HEADER
echo '## moorsim'
echo
echo '```text'
help
echo '```'
# The commands in the order the program lists them.
for command in $(help | sed -n '/^Subcommands:/,$p' | sed -n 's/^  \([a-z-]*\) .*/\1/p'); do
  echo
  echo "## moorsim $command"
  echo
  echo '```text'
  help "$command"
  echo '```'
done
