#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs each for a bounded time.
#
#   tools/fuzz.sh [SECONDS_PER_TARGET]     default 60
#
# Seed corpora come from examples/ and ../shared/fixtures/ (copied into a scratch corpus so the
# tree is never written). A crash, a hang (> 1 s per input), a leak or a UB report fails the run;
# libFuzzer leaves the input as crash-*/timeout-* in the build directory: fix the bug and add the
# input as a regression test. The seed is fixed (-seed=1) so a run is repeatable: CI explores the
# same inputs a developer's run of the same length did; run longer or with another seed to explore.
set -euo pipefail
seconds="${1:-60}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SOFTSLC_FUZZ_BUILD_DIR:-$root/build-fuzz}"

source "$root/tools/lib/ensure-packages.sh"
ensure_packages clang libclang-rt-14-dev cmake ninja-build tao-pegtl-dev libcli11-dev libspdlog-dev libgtest-dev \
  libgmock-dev libeigen3-dev nlohmann-json3-dev libtinyxml2-dev

mkdir -p "$build"
CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSOFTSLC_FUZZ=ON \
  -DSOFTSLC_TESTS=ON -DSOFTSLC_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS=-Wno-unused-command-line-argument > "$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" --target program_fuzz address_fuzz testfile_fuzz

corpus="$build/corpus"
rm -rf "$corpus"
mkdir -p "$corpus/program" "$corpus/address" "$corpus/testfile"
find "$root/examples" -name '*.test' -exec cp {} "$corpus/testfile/" \;
find "$root/examples" -name '*.slc' -exec cp {} "$corpus/program/" \;
cp "$root"/../shared/fixtures/rslogix500/*.SLC "$corpus/program/" 2>/dev/null || true
for a in 'I:1/3' 'O:2.1/15' 'B3/62' 'T4:0.ACC' 'C5:1/OV' '#N7:10' 'N7:[N10:1]' 'N[N10:0]:5' 'B3/[N7:0]' \
         'M0:1.100/13' 'L41:0' 'ST9:0' 'F8:2' 'S:1/15'; do
  printf '%s' "$a" > "$corpus/address/$(printf '%s' "$a" | md5sum | cut -c1-12)"
done

status=0
for target in program address testfile; do
  echo "== fuzzing ${target}_fuzz for ${seconds}s"
  (cd "$build" && ASAN_OPTIONS=detect_leaks=1 "./tests/fuzz/${target}_fuzz" -max_total_time="$seconds" -timeout=1 -seed=1 \
    -rss_limit_mb=2048 -print_final_stats=1 "$corpus/$target" 2>&1 | tail -15) || status=1
done
exit $status
