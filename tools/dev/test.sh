#!/usr/bin/env bash
# Quick start, tests: installs the dependencies (Debian packages), builds moorsim and runs
# the whole test suite twice: optimised (release preset) and under AddressSanitizer +
# UndefinedBehaviorSanitizer (asan preset). Also checks clang-format. CI runs exactly this.
# The asan test preset leaves out the long acceptance runs (detection on the coupled plant:
# 8 x 600 s + 3600 s of simulation; the analyze Monte-Carlo checks; the campaign tests that
# run whole campaigns, all but the threads-equal-one-thread one; the report's Python checks;
# the MPI batch): they take many minutes of CPU under the sanitizers and repeat code paths
# the shorter tests run there; the release pass runs them.
# What keeps it within CI's time (Ninja, the optimisation levels, unity batches, the sanitizer
# pass's shards): docs/development.md.
#   tools/dev/test.sh           everything
#   tools/dev/test.sh --fast    release build and tests only
set -euo pipefail
cd "$(dirname "$0")/../.."

./tools/setup.sh

echo "== clang-format check ($SECONDS s)"
git ls-files '*.cc' '*.h' | xargs clang-format --dry-run -Werror

echo "== user guide ($SECONDS s)"
# A broken link is an error (strict); so is a page left out of mkdocs.yml's navigation.
if ! guide=$(mkdocs build --strict 2>&1); then
  echo "$guide"
  exit 1
fi
if grep -q 'not included in the "nav"' <<<"$guide"; then
  echo "$guide"
  echo "user guide: a page in docs/ is missing from mkdocs.yml's nav"
  exit 1
fi

# What users read (documents, comments, scenario files) speaks of moorsim, not of how its
# work is organised: no issue numbers, numbered rounds, internal guides or machine paths
# (the bracketed letters keep this line from matching itself).
process='\b[Ii]ssues? #?[0-9]+\b|\b([Ff]irst|[Ss]econd|[Tt]hird|[Ff]ourth|[Ff]ifth|[Ss]ixth|[Ss]eventh|[Ee]ighth|[Nn]inth|[Tt]enth|[a-z]+teenth|[Tt]went[a-z-]+|[0-9]+(st|nd|rd|th)) rounds?\b|\b[Rr]ounds? [0-9]+\b|S[T]YLE\.md|D[E]SIGN\.md|\bseed 00[0-9]|/w[o]rk/|\.\./s[h]ared'
if found=$(git grep -n -I -E "$process" -- . ':!tools/dev/test.sh'); then
  echo "$found"
  echo "wording: the lines above speak of the project's process, not of moorsim"
  exit 1
fi

echo "== release build and tests ($SECONDS s)"
cmake --preset release >/dev/null
# The test executables and the program only: the benchmarks build with tools/main.sh.
cmake --build --preset release --target moorsim_tests
echo "== release tests ($SECONDS s)"
# Every test carries one of the three labels (set by its name, tests/CMakeLists.txt): an
# unlabelled one would be left out of the sanitizer pass unnoticed.
unlabelled=$(ctest --preset release -N -LE '^(unit|slow|acceptance)$' | sed -n 's/^ *Test *#[0-9]*: //p')
if [[ -n "$unlabelled" ]]; then
  echo "tests without a label (unit, slow or acceptance): $unlabelled"
  exit 1
fi
ctest --preset release

if [[ "${1:-}" != "--fast" ]]; then
  echo "== ASan + UBSan build and tests ($SECONDS s)"
  cmake --preset asan >/dev/null
  cmake --build --preset asan
  echo "== ASan + UBSan tests ($SECONDS s)"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --preset asan
fi
echo "== all tests passed ($SECONDS s)"
