#!/usr/bin/env bash
# Static checks of the robustness-critical code and of what a change touches: clang-tidy (a focused
# bug-finding set) and cppcheck, each finding an error.
#
#   tools/lint.sh [BASE]        BASE: also check the C++ sources changed since BASE (git ref), and
#                               the FILE.cpp of every FILE.h changed since BASE
#   tools/lint.sh --all         every C++ source of the project that the build compiles
#
# Always checked: the code that must never lose or misread data or crash on bad bytes (state
# files, atomic writes, the fuzz targets and their properties, the 1747-SN block-transfer checks).
# clang-tidy reads the compile commands of an existing build (SOFTSLC_LINT_BUILD_DIR, default
# build/): run after a build. A finding that is a deliberate choice is silenced where it occurs
# (NOLINT / cppcheck-suppress) with the reason beside it.
#
# Not the whole tree in CI. Measured on the 2-core machine (session 18, clang-tidy 14): a file
# costs 12 s of clang-tidy CPU on average (103 files measured), 1 s to 47 s (vm/runtime.cpp,
# cmd_serve.cpp and the googletest files the most), so the 211 sources the build compiles take
# about 42 min of CPU, 21 min on two idle cores, against CI's 7-26 min now and its 45 min limit;
# cppcheck on all of them is 11 s of CPU. Once the
# tree is clean, a change can bring a finding only into the files it changes, into the includers
# of a header it changes (CI checks the header's own .cpp, not every includer), or with a new tool
# version or check set: CI keeps the changed-files rule, and `tools/lint.sh --all` is for a new
# clang-tidy/cppcheck, a changed check set, or a release. Session 18 left cppcheck clean on all
# 211 and clang-tidy clean on the 105 that are not tests (and msg_ethernet_test); session 19 ran
# clang-tidy over the 107 test sources and fixed its 33 findings (int products widened, const
# references, and two Google Benchmark idioms silenced where they occur): the whole tree is clean.
# clang-tidy runs one file per core (SOFTSLC_LINT_JOBS, default nproc), so CI's changed files
# cost half the wall time they did. It is clang reading a GCC build's compile commands, so a GCC-only
# warning option there (tests/parser's -Wno-maybe-uninitialized) is not an error to it.
#
# Check set: bugprone-*, performance-*, clang-analyzer-*, without the style-only
# easily-swappable-parameters and narrowing-conversions, and without
# performance-inefficient-string-concatenation: since C++11 `a + b + c` appends to the first
# temporary in place (operator+ on an rvalue string), so it costs about what `+=` does, and it
# fired on nearly every error message the project builds in a loop.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SOFTSLC_LINT_BUILD_DIR:-$root/build}"
cd "$root"
source "$root/tools/lib/ensure-packages.sh"
ensure_packages clang-tidy cppcheck

# The fuzz properties (tests/fuzz/*.h) are checked through the regression tests that include them:
# the fuzz targets themselves are compiled only in the clang fuzz build.
files=(vm/state_file.cpp vm/atomic_file.cpp modules/sn/block_transfer.cpp tests/fuzz/module_fuzz_regressions_test.cpp
       tests/parser/fuzz_regressions_test.cpp)
if [[ ! -f "$build/compile_commands.json" ]]; then
  echo "tools/lint.sh: no $build/compile_commands.json; build first" >&2
  exit 2
fi
if [[ "${1:-}" == --all ]]; then
  while IFS= read -r f; do
    grep -q "\"$root/$f\"" "$build/compile_commands.json" && files+=("$f")
  done < <(git ls-files '*.cpp')
elif [[ $# -ge 1 ]]; then
  while IFS= read -r f; do
    # A changed header is checked through its own source (most findings in a header show there).
    [[ "$f" == *.h ]] && f="${f%.h}.cpp"
    # Only sources a build compiles (the fuzz targets are not in its compile commands).
    [[ -f "$f" ]] && grep -q "\"$root/$f\"" "$build/compile_commands.json" && files+=("$f")
  done < <(git diff --name-only --diff-filter=AM "$1"...HEAD -- '*.cpp' '*.h')
fi
mapfile -t files < <(printf '%s\n' "${files[@]}" | sort -u)

checks='-*,bugprone-*,performance-*,clang-analyzer-*,-bugprone-easily-swappable-parameters,-bugprone-narrowing-conversions,-performance-inefficient-string-concatenation,-clang-analyzer-optin.*'
jobs="${SOFTSLC_LINT_JOBS:-$(nproc)}"
echo "== clang-tidy (${#files[@]} files, $jobs at a time)"
status=0
# One clang-tidy per file, $jobs at a time, each into its own log (printed in file order, so
# parallel runs do not interleave their findings); a failed file leaves a .failed mark.
logs="$(mktemp -d)"
trap 'rm -rf "$logs"' EXIT
export build checks logs
printf '%s\n' "${files[@]}" | xargs -P "$jobs" -I{} bash -c '
  log="$logs/$(tr / _ <<<"$1").log"
  clang-tidy -p "$build" --quiet --warnings-as-errors="*" --checks="$checks" --extra-arg=-Wno-unknown-warning-option "$1" >"$log" 2>&1 || touch "$log.failed"' _ {}
compgen -G "$logs/*.failed" >/dev/null && status=1
# Drop clang-tidy's counting chatter; keep every finding.
cat "$logs"/*.log | grep -v -E '^[0-9]+ warnings? (and [0-9]+ errors? )?generated\.$|^Suppressed [0-9]+ warnings|^Use -header-filter' || true

echo "== cppcheck"
cppcheck --quiet --language=c++ --std=c++20 --enable=warning,performance,portability --inline-suppr \
  --library=googletest --error-exitcode=1 "${files[@]}" || status=1
exit "$status"
