#!/usr/bin/env bash
# `softslc serve --modbus` from the command line: refused for a processor without Modbus TCP and
# for a map that names a file of another type; on a MicroLogix 1400 it says where Modbus listens
# (127.0.0.1 by default) and answers a read of holding register 40001 (N7:0, DATA 500).
#   modbus_cli.sh SOFTSLC SOURCE_DIR
set -uo pipefail
softslc="$1" src="$2"
work="$(mktemp -d)"
trap 'kill -INT "$server" 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAIL $*"; exit 1; }

"$softslc" serve "$src/examples/ladder/serve/hmi_panel.slc" --port 0 --modbus 0 > "$work/o" 2> "$work/e" &&
  fail "--modbus accepted on an SLC 5/05"
grep -q "MicroLogix 1100/1400" "$work/e" || fail "no reason given: $(cat "$work/e")"
"$softslc" serve "$src/examples/ladder/micrologix/ml1400_batch.slc" --port 0 --modbus 0 --modbus-map B3,B3,L9,N7 \
  > "$work/o" 2> "$work/e" && fail "a map naming L9 accepted"
grep -q "B or N file" "$work/e" || fail "no reason given: $(cat "$work/e")"

source "$src/tools/lib/serve-start.sh"
start_serve "$softslc" "$work" "$src/examples/ladder/micrologix/ml1400_batch.slc" --modbus 0 || exit 1
mport=""
for _ in $(seq 1 50); do
  mport="$(sed -n 's/.*Modbus TCP on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$work/out")"
  [ -n "$mport" ] && break
  sleep 0.1
done
[ -n "$mport" ] || fail "no 'Modbus TCP on 127.0.0.1:PORT' line: $(cat "$work/out")"
grep "Modbus TCP" "$work/out"
# FC 3, address 0, one register, through bash's /dev/tcp: the reply's register is 01F4h = 500.
exec 3<> "/dev/tcp/127.0.0.1/$mport" || fail "cannot connect to $mport"
printf '\x00\x07\x00\x00\x00\x06\x01\x03\x00\x00\x00\x01' >&3
reply="$(timeout 5 head -c 11 <&3 | od -An -tx1 | tr -d ' \n')"
exec 3>&-
[ "$reply" = "00070000000501030201f4" ] || fail "reply $reply, expected register 01f4"
echo "ok: holding register 40001 = 500"
kill -INT "$server"
wait "$server"
