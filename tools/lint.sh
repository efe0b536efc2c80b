#!/usr/bin/env bash
# Static checks of the robustness-critical code and of what a change touches: clang-tidy (a focused
# bug-finding set) and cppcheck, each finding an error.
#
#   tools/lint.sh [BASE]        BASE: also check the C++ sources changed since BASE (git ref)
#
# Always checked: the code that must never lose or misread data or crash on bad bytes (state
# files, atomic writes, the fuzz targets and their properties, the 1747-SN block-transfer checks).
# clang-tidy reads the compile commands of an existing build (SOFTSLC_LINT_BUILD_DIR, default
# build/): run after a build. A finding that is a deliberate choice is silenced where it occurs
# (NOLINT / cppcheck-suppress) with the reason beside it.
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
if [[ $# -ge 1 ]]; then
  while IFS= read -r f; do
    # Only sources a build compiles (the fuzz targets are not in its compile commands).
    [[ -f "$f" ]] && grep -q "\"$root/$f\"" "$build/compile_commands.json" && files+=("$f")
  done < <(git diff --name-only --diff-filter=AM "$1"...HEAD -- '*.cpp')
fi
mapfile -t files < <(printf '%s\n' "${files[@]}" | sort -u)

checks='-*,bugprone-*,performance-*,clang-analyzer-*,-bugprone-easily-swappable-parameters,-bugprone-narrowing-conversions,-clang-analyzer-optin.*'
echo "== clang-tidy (${#files[@]} files)"
status=0
out="$(clang-tidy -p "$build" --quiet --warnings-as-errors='*' --checks="$checks" "${files[@]}" 2>&1)" || status=1
# Drop clang-tidy's counting chatter; keep every finding.
grep -v -E '^[0-9]+ warnings? (and [0-9]+ errors? )?generated\.$|^Suppressed [0-9]+ warnings|^Use -header-filter' <<<"$out" || true

echo "== cppcheck"
cppcheck --quiet --language=c++ --std=c++20 --enable=warning,performance,portability --inline-suppr \
  --library=googletest --error-exitcode=1 "${files[@]}" || status=1
exit "$status"
