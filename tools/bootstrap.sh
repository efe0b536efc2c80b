#!/usr/bin/env bash
# Set up softslc on a fresh Debian 12 machine and run it. Idempotent: installs only the Debian
# packages that are missing, configures the build once, rebuilds what changed.
#
#   tools/bootstrap.sh demo   install, build, run softslc on the shipped example program
#   tools/bootstrap.sh test   install, build, run the whole test suite
set -euo pipefail

mode="${1:-}"
case "$mode" in
  demo|test) ;;
  *) echo "usage: tools/bootstrap.sh demo|test" >&2; exit 2 ;;
esac

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SOFTSLC_BUILD_DIR:-$root/build}"

source "$root/tools/lib/ensure-packages.sh"
ensure_packages g++ cmake ninja-build pkg-config tao-pegtl-dev libcli11-dev libspdlog-dev libgtest-dev libgmock-dev \
  libbenchmark-dev libeigen3-dev nlohmann-json3-dev libtinyxml2-dev python3 \
  libolecf-dev libbfio-dev zlib1g-dev poppler-utils \
  libboost-dev libmodbus-dev nodejs chromium
# The serve client tests run npm. NodeSource's nodejs ships its own npm and conflicts with
# Debian's npm package, so that package is installed only where no npm came with Node.
command -v npm >/dev/null 2>&1 || ensure_packages npm

# Extra configure options (the sanitizer job of .ci/run passes -DSOFTSLC_SANITIZE=ON).
read -r -a extra <<< "${SOFTSLC_CMAKE_ARGS:-}"
if [ "${CI:-}" = "true" ]; then extra+=(-DSOFTSLC_WERROR=ON); fi
mkdir -p "$build"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${extra[@]}" > "$build/configure.log" 2>&1 \
  || { cat "$build/configure.log"; exit 1; }
# The demo needs one program, not the tests and benchmarks (169 targets, minutes on a fresh machine).
if [ "$mode" = demo ]; then
  cmake --build "$build" -j "$(nproc)" --target softslc
else
  cmake --build "$build" -j "$(nproc)"
fi

softslc="$build/tools/softslc/softslc"
case "$mode" in
  demo)
    example="$root/examples/ladder/seal_in/seal_in.slc"
    echo "== softslc check examples/ladder/seal_in/seal_in.slc"
    "$softslc" check "$example"
    echo "== softslc run: press START for 3 scans, then hold the overload contact for 1.5 s of virtual time"
    "$softslc" run "$example" --set START_PB=1 --scans 3 --print MOTOR --print C5:0.ACC
    "$softslc" run "$example" --set OL_CONTACT=1 --for 1.5s --print OL_TRIPPED --print TRIP_LAMP --print T4:0.ACC
    echo "== softslc scantime on an SLC 5/03 and an SLC 5/05"
    "$softslc" scantime "$example" --processor 1747-L532 --processor 1747-L552
    ;;
  test)
    echo "== softslc test examples (every example program's ladder tests)"
    "$softslc" test "$root/examples" -j "$(nproc)" --junit "$build/examples-junit.xml"
    echo "== ctest (the whole suite)"
    cd "$build"
    ctest --output-on-failure -j "$(nproc)"
    ;;
esac
