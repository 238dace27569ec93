#!/usr/bin/env bash
# The command-line reference in the user guide is the program's own help, word for word.
#   cli_reference_test.sh MOORSIM SOURCE_DIR
set -euo pipefail
moorsim=$1
source_dir=$2
if ! diff -u "$source_dir/docs/cli-reference.md" \
  <("$source_dir/tools/dev/cli_reference.sh" "$moorsim"); then
  echo "docs/cli-reference.md is not the program's help; regenerate it:"
  echo "  tools/dev/cli_reference.sh build/release/tools/moorsim > docs/cli-reference.md"
  exit 1
fi
