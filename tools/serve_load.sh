#!/usr/bin/env bash
# Load benchmark for `softslc serve` (docs/performance.md): starts the server on the HMI example
# with a journal, runs tests/serve/clients/load.js (default 50 clients x 100 words x 10 Hz x 60 s
# on loopback), stops the server, and replays the journal (every write must be in the history).
#   tools/serve_load.sh [CLIENTS] [HZ] [SECONDS]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
softslc="${SOFTSLC:-$root/build/tools/softslc/softslc}"
work="$(mktemp -d)"
trap 'kill -INT "$server" 2>/dev/null || true; rm -rf "$work"' EXIT
source "$root/tools/lib/serve-start.sh"
start_serve "$softslc" "$work" "$root/examples/ladder/serve/hmi_panel.slc" --max-connections 256 \
  --journal "$work/journal"
start=$(date +%s.%N)
status=0
node "$root/tests/serve/clients/load.js" "$port" "${1:-50}" "${2:-10}" "${3:-60}" || status=$?
kill -INT "$server"
wait "$server" || true
end=$(date +%s.%N)
tail -1 "$work/out"
echo "server wall time $(echo "$end - $start" | bc) s; journal $(wc -l < "$work/journal") lines"
grep -c -E 'warn|error' "$work/log" | sed 's/^/server warnings: /' || true
"$softslc" replay "$work/journal"
exit $status
