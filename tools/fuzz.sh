#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs each for a bounded time.
#
#   tools/fuzz.sh [SECONDS_PER_TARGET]     default 60
#
# Environment: SOFTSLC_FUZZ_MAX_LEN=N gives every target inputs up to N bytes (issue 17's long run:
# 1048576); SOFTSLC_FUZZ_PARALLEL=1 runs the targets one at a time (default two, one per core);
# SOFTSLC_FUZZ_TIMEOUT=S is the time one input may take (default 1 s); SOFTSLC_FUZZ_TARGETS="a b"
# runs only those targets (names without _fuzz).
#
# Seed corpora come from examples/ and ../shared/fixtures/ (copied into a scratch corpus so the
# tree is never written). A crash, a hang (> 1 s per input), a leak or a UB report fails the run;
# libFuzzer leaves the input as TARGET-crash-*/TARGET-timeout-* in the build directory (its report
# is printed): fix the bug and add the input as a regression test. The seed is fixed (-seed=1) so a run is repeatable: CI explores the
# same inputs a developer's run of the same length did; run longer or with another seed to explore.
set -euo pipefail
seconds="${1:-60}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# SOFTSLC_FUZZ_BUILD_DIR may name an existing clang build configured with -DSOFTSLC_FUZZ=ON (CI's
# sanitizer build is one): its targets are reused, not rebuilt.
build="${SOFTSLC_FUZZ_BUILD_DIR:-$root/build-fuzz}"

source "$root/tools/lib/ensure-packages.sh"
ensure_packages clang libclang-rt-14-dev cmake ninja-build tao-pegtl-dev libcli11-dev libspdlog-dev libgtest-dev \
  libgmock-dev libeigen3-dev nlohmann-json3-dev libtinyxml2-dev libolecf-dev libbfio-dev zlib1g-dev libboost-dev \
  libmodbus-dev pkg-config

mkdir -p "$build"
CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSOFTSLC_FUZZ=ON \
  -DSOFTSLC_TESTS=ON -DSOFTSLC_BENCHMARKS=OFF > "$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
all_targets=(program address testfile bench scanport_message transaction dem rss pccc eip modbus modbus_rtu web)
targets=("${all_targets[@]}")
if [ -n "${SOFTSLC_FUZZ_TARGETS:-}" ]; then read -r -a targets <<< "$SOFTSLC_FUZZ_TARGETS"; fi
parallel="${SOFTSLC_FUZZ_PARALLEL:-2}"
cmake --build "$build" --target "${targets[@]/%/_fuzz}"

corpus="$build/corpus"
rm -rf "$corpus"
for target in "${all_targets[@]}"; do mkdir -p "$corpus/$target"; done
find "$root/examples" -name '*.test' -exec cp {} "$corpus/testfile/" \;
find "$root/examples" -name '*.slc' -exec cp {} "$corpus/program/" \;
find "$root/examples" -name '*.bench' -exec cp {} "$corpus/bench/" \;
cp "$root"/../shared/fixtures/rslogix500/*.SLC "$corpus/program/" 2>/dev/null || true
find "$root"/../shared/fixtures/rss -name '*.RSS' -exec cp {} "$corpus/rss/" \; 2>/dev/null || true
for a in 'I:1/3' 'O:2.1/15' 'B3/62' 'T4:0.ACC' 'C5:1/OV' '#N7:10' 'N7:[N10:1]' 'N[N10:0]:5' 'B3/[N7:0]' \
         'M0:1.100/13' 'L41:0' 'ST9:0' 'F8:2' 'S:1/15'; do
  printf '%s' "$a" > "$corpus/address/$(printf '%s' "$a" | md5sum | cut -c1-12)"
done

# The message decoders start from words the manuals' own examples write (little-endian bytes):
# SCANport Figure B.3/B.4 (read the last parameter number of the drive) and B.7 (set parameter
# 1 to 5); a 1747-SDN Get_Attribute_Single of the drive's identity vendor ID (appendix E) with
# TXID 1, port 0, size 6, service 0x0E to node 20; and the same as a DEM control block with a
# 2 s timeout followed by steps that set the rung, wait, and drop it.
words() { for w in "$@"; do printf '\\x%02x\\x%02x' $((w & 0xFF)) $((w >> 8)); done; }
printf "$(words 0x0E 0x0F 0 2 0)" > "$corpus/scanport_message/b4-last-parameter"
printf "$(words 0x10 0x0F 1 1 2 5)" > "$corpus/scanport_message/b7-set-parameter"
printf "$(words 0x0101 0x0006 0x0E14 0x0001 0x0001 0x0001)" > "$corpus/transaction/get-vendor-id"
printf "$(words 0 2 0 0 0 0 0x0001 0x0000 0x0E14 0x0001 0x0001 0x0001)" > "$corpus/dem/get-vendor-id"
head -c $((4 * 70 - 24)) /dev/zero >> "$corpus/dem/get-vendor-id"
printf '\x01\x31\x31\x00\x01\x00' >> "$corpus/dem/get-vendor-id"

# `softslc serve`: a typed read of N7:0 (1770-6.5.16 CMD 0F FNC A2), a masked bit write (FNC AB),
# a diagnostic status (CMD 06 FNC 03); nodepccc's RegisterSession frame, and the CPF of a
# SendRRData carrying Execute PCCC with the same read.
printf '\x0f\x00\x34\x12\xa2\x02\x07\x89\x00\x00' > "$corpus/pccc/read-n7-0"
printf '\x0f\x00\x01\x00\xab\x02\x03\x85\x00\x00\x02\x00\x02\x00' > "$corpus/pccc/mask-b3-0-1"
printf '\x06\x00\x01\x00\x03' > "$corpus/pccc/diagnostic-status"
printf '\x65\x00\x04\x00\x00\x00\x00\x00\x00\x00\x00\x00\x0a\x0b\x0c\x0d\x0e\x0f\x0a\x0b\x00\x00\x00\x00\x01\x00\x00\x00' > "$corpus/eip/register-session"
printf '\x02\x00\x00\x00\x00\x00\xb2\x00\x17\x00\x4b\x02\x20\x67\x24\x01\x07\x00\x00\x01\x02\x03\x04\x0f\x00\x34\x12\xa2\x02\x07\x89\x00\x00' > "$corpus/eip/execute-pccc-cpf"
# Modbus TCP (server/modbus.h): read holding registers 40001-40002 and write coil 00002 on.
printf '\x00\x01\x00\x00\x00\x06\x01\x03\x00\x00\x00\x02' > "$corpus/modbus/read-holding"
printf '\x00\x02\x00\x00\x00\x06\x01\x05\x00\x01\xff\x00' > "$corpus/modbus/write-coil"
# Modbus RTU (server/modbus_rtu.h; the first byte says how the line delivers the rest): the same read
# to slave 1 in one chunk; FC 16 of two registers then FC 8 echo in one chunk, then the silence.
printf '\x3f\x01\x03\x00\x00\x00\x02\xc4\x0b' > "$corpus/modbus_rtu/read-holding"
printf '\x7f\x01\x10\x00\x00\x00\x02\x04\x00\x07\x00\x08\x43\xa8\x01\x08\x00\x00\xa5\x37\xda\x8d' > "$corpus/modbus_rtu/write-then-echo"
# The online view's requests (server/web.h), as the page sends them.
printf '%s' '{"op":"view","file":2,"first":0,"last":30}' > "$corpus/web/view"
printf '%s' '{"op":"table","name":"N7","offset":0}' > "$corpus/web/table"
printf '%s' '{"op":"set","address":"N7:0","value":"12"}' > "$corpus/web/set"
printf '%s' '{"op":"force","address":"I:1/0","state":"on"}' > "$corpus/web/force"
printf '%s' '{"op":"trend","addresses":["N7:0","T4:0.ACC"]}' > "$corpus/web/trend"
printf '%s' '{"op":"mode","mode":"program"}' > "$corpus/web/mode"

# The targets run two at a time (one per core of the 2-core machines CI runs on); each one's
# output is kept in its own log and printed in target order, so the log reads the same whatever
# finishes first.
logs="$build/fuzz-logs"
rm -rf "$logs"
mkdir -p "$logs"
run_target() {
  local target="$1" len=()
  # The message decoders read whole buffers: let inputs reach them from the start (four 100-word
  # SCANport buffers; four 32-word transaction blocks with their gaps; two 70-word DEM control
  # blocks and 64 steps). Elsewhere libFuzzer's default length control applies.
  case "$target" in
    scanport_message) len=(-max_len=800 -len_control=20) ;;
    transaction) len=(-max_len=264 -len_control=20) ;;
    dem) len=(-max_len=344 -len_control=20) ;;
    # Project files are 38-131 KiB; mutations must be able to keep a whole one.
    rss) len=(-max_len=140000) ;;
    # Inputs long enough to reach the nesting limits (17 nested BSTs are 255 bytes, 65
    # parentheses or bench blocks a few hundred) and the error caps; the time per run is unchanged.
    program|testfile|bench) len=(-max_len=16384) ;;
  esac
  if [ -n "${SOFTSLC_FUZZ_MAX_LEN:-}" ]; then
    # Keep the decoders' -len_control; only the maximum length changes.
    local i
    for i in "${!len[@]}"; do
      if [[ "${len[$i]}" == -max_len=* ]]; then unset 'len[i]'; fi
    done
    len+=(-max_len="$SOFTSLC_FUZZ_MAX_LEN")
  fi
  # libolecf's own leaks on damaged files are suppressed by the reader (parser/rss/rss_reader.cpp).
  (cd "$build" && ASAN_OPTIONS=detect_leaks=1 "./tests/fuzz/${target}_fuzz" -max_total_time="$seconds" -timeout="${SOFTSLC_FUZZ_TIMEOUT:-1}" \
    -seed=1 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/${target}-" "${len[@]}" \
    "$corpus/$target" > "$logs/$target.log" 2>&1) && echo ok > "$logs/$target.status" || echo failed > "$logs/$target.status"
}
pids=()
for target in "${targets[@]}"; do
  run_target "$target" &
  pids+=($!)
  if ((${#pids[@]} >= parallel)); then wait "${pids[@]}"; pids=(); fi
done
((${#pids[@]})) && wait "${pids[@]}"

status=0
for target in "${targets[@]}"; do
  echo "== fuzzing ${target}_fuzz for ${seconds}s: $(cat "$logs/$target.status")"
  if [[ "$(cat "$logs/$target.status")" == ok ]]; then
    tail -6 "$logs/$target.log"
  else
    # The whole report of a failing target: the finding, its stack and the input's file name.
    grep -v -E '^#[0-9]+' "$logs/$target.log" | tail -60
    status=1
  fi
done
exit $status
