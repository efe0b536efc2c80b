#!/usr/bin/env bash
# `softslc serve --modbus` and `--modbus-rtu` from the command line: refused for a processor without
# Modbus and for a map that names a file of another type, or a serial device that does not exist;
# on a MicroLogix 1400 it says where Modbus TCP listens (127.0.0.1 by default) and which
# pseudo-terminal Modbus RTU answers on; TCP answers a read of holding register 40001 (N7:0, DATA
# 500), RTU a write of 40002 (N7:1) that TCP then reads back, and the journal replays.
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
"$softslc" serve "$src/examples/ladder/serve/hmi_panel.slc" --port 0 --http off --modbus-rtu pty > "$work/o" 2> "$work/e" &&
  fail "--modbus-rtu accepted on an SLC 5/05"
grep -q "Modbus RTU is a MicroLogix 1100/1400" "$work/e" || fail "no reason given: $(cat "$work/e")"
"$softslc" serve "$src/examples/ladder/micrologix/ml1400_batch.slc" --port 0 --http off --modbus-rtu "$work/no-such-tty" \
  > "$work/o" 2> "$work/e" && fail "a missing serial device accepted"
grep -q "cannot open the Modbus RTU line $work/no-such-tty" "$work/e" || fail "no reason given: $(cat "$work/e")"

source "$src/tools/lib/serve-start.sh"
start_serve "$softslc" "$work" "$src/examples/ladder/micrologix/ml1400_batch.slc" --modbus 0 --modbus-rtu pty \
  --journal "$work/journal" || exit 1
mport=""
for _ in $(seq 1 50); do
  mport="$(sed -n 's/.*Modbus TCP on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$work/out")"
  [ -n "$mport" ] && break
  sleep 0.1
done
[ -n "$mport" ] || fail "no 'Modbus TCP on 127.0.0.1:PORT' line: $(cat "$work/out")"
grep "Modbus TCP" "$work/out"
# request PATH BYTES N: writes the bytes (printf escapes) to PATH (a bash /dev/tcp path or a tty)
# and sets $reply to the first N bytes that come back, in hex.
request() {
  exec 3<> "$1" || fail "cannot open $1"
  printf "$2" >&3
  reply="$(timeout 5 head -c "$3" <&3 | od -An -tx1 | tr -d ' \n')"
  exec 3>&-
}
# FC 3, address 0, one register, through bash's /dev/tcp: the reply's register is 01F4h = 500.
request "/dev/tcp/127.0.0.1/$mport" '\x00\x07\x00\x00\x00\x06\x01\x03\x00\x00\x00\x01' 11
[ "$reply" = "00070000000501030201f4" ] || fail "reply $reply, expected register 01f4"
echo "ok: holding register 40001 = 500"

# Modbus RTU on the printed pseudo-terminal, slave 1: FC 6 writes 002Ah to holding register 40002
# (N7:1); the reply echoes the request, CRC included (Modbus over Serial Line v1.02 §2.5.1).
pty="$(sed -n 's/.*Modbus RTU slave 1 on \(\/dev\/[^ ]*\) .*/\1/p' "$work/out")"
[ -n "$pty" ] || fail "no 'Modbus RTU slave 1 on /dev/...' line: $(cat "$work/out")"
grep "Modbus RTU" "$work/out"
request "$pty" '\x01\x06\x00\x01\x00\x2a\x59\xd5' 8
[ "$reply" = "01060001002a59d5" ] || fail "RTU reply $reply, expected the echo 01060001002a59d5"
request "/dev/tcp/127.0.0.1/$mport" '\x00\x08\x00\x00\x00\x06\x01\x03\x00\x01\x00\x01' 11
[ "$reply" = "000800000005010302002a" ] || fail "TCP reply $reply, expected register 002a written over RTU"
echo "ok: holding register 40002 written over Modbus RTU, read over Modbus TCP"
stop_serve_and_replay "$softslc" "$work" 0
