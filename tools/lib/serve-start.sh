# Sourced by the scripts that run clients against `softslc serve` (tests/serve/clients/run_client.sh,
# tools/serve_load.sh). start_serve SOFTSLC WORKDIR ARGS... starts the server in the background on
# a free port (--port 0) with its output in WORKDIR/out and its log in WORKDIR/log, waits for the
# line that says where it listens, and sets $server (its pid) and $port. Returns 1 if it never
# listened. With serve_http=PORT set it also serves the online view there. stop_serve_and_replay SOFTSLC WORKDIR STATUS stops it (SIGINT), prints its last line
# and, when STATUS (the client's exit status) is 0, replays its journal WORKDIR/journal; it
# returns the first failure.
start_serve() {
  local softslc="$1" work="$2"
  shift 2
  # No online view unless the caller sets serve_http (a port; 0 picks a free one): tests running
  # in parallel must not compete for the default port.
  "$softslc" serve "$@" --port 0 --http "${serve_http:-off}" > "$work/out" 2> "$work/log" &
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

stop_serve_and_replay() {
  local softslc="$1" work="$2" status="$3"
  kill -INT "$server"
  wait "$server"
  tail -1 "$work/out"
  if [ "$status" -ne 0 ]; then echo "== server log"; cat "$work/log"; return "$status"; fi
  "$softslc" replay "$work/journal" || { echo "== journal"; cat "$work/journal"; return 1; }
}
