#!/usr/bin/env bash
# tools/report.py on synthetic campaigns, the standard one and its edge cases (no intact
# runs, no failure runs, no detectors, every run failed, a single run, no factors, no
# verdict columns): each
# report builds and its numbers equal those recomputed from campaign.h5 by
# tests/tools/report_test.py. Usage: report_cases_test.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for case in standard no-intact no-failure no-detectors all-failed single no-factors no-verdict; do
  /usr/bin/python3 "$source_dir/tests/tools/make_fake_campaign.py" "$work/$case" --case "$case" >/dev/null
  /usr/bin/python3 "$source_dir/tests/tools/report_test.py" "$work/$case" >/dev/null ||
    { echo "report check failed for the $case campaign"; exit 1; }
done
echo "report: 8 synthetic campaigns checked"
