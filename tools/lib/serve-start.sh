# Sourced by the scripts that run clients against `softslc serve` (tests/serve/clients/run_client.sh,
# tools/serve_load.sh). start_serve SOFTSLC WORKDIR ARGS... starts the server in the background on
# a free port (--port 0) with its output in WORKDIR/out and its log in WORKDIR/log, waits for the
# line that says where it listens, and sets $server (its pid) and $port. Returns 1 if it never
# listened.
start_serve() {
  local softslc="$1" work="$2"
  shift 2
  "$softslc" serve "$@" --port 0 > "$work/out" 2> "$work/log" &
  server=$!
  port=""
  for _ in $(seq 1 100); do
    port="$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$work/out")"
    [ -n "$port" ] && return 0
    sleep 0.1
  done
  echo "softslc serve did not start:"
  cat "$work/out" "$work/log"
  return 1
}
