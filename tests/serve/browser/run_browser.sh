#!/usr/bin/env bash
# Runs one browser scenario against a live `softslc serve`: Debian's chromium, driven by the pinned
# playwright-core, opens the online view; then the server's journal is replayed.
#   run_browser.sh SOFTSLC DIR PROGRAM SCRIPT.js OUTDIR [serve options...]
# The server listens on free ports (--port 0 --http 0, 127.0.0.1); the script gets the page's URL
# and OUTDIR (screenshots). After the script the server is stopped with SIGINT, and `softslc
# replay` must reproduce every data-table state the page's writes, forces and mode changes made.
# Exit 77 (skipped) without node or chromium.
set -uo pipefail
softslc="$1" dir="$2" program="$3" script="$4" outdir="$5"
shift 5
if ! command -v node > /dev/null; then echo "SKIPPED: no node on this machine"; exit 77; fi
chromium="${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}"
if [ -z "$chromium" ]; then echo "SKIPPED: no chromium on this machine (apt-get install chromium)"; exit 77; fi
if [ ! -d "$dir/node_modules/playwright-core" ]; then echo "SKIPPED: playwright-core not installed (setup failed?)"; exit 77; fi
work="$(mktemp -d)"
mkdir -p "$outdir"
trap 'kill -INT "$server" 2>/dev/null; rm -rf "$work"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/../../../tools/lib/serve-start.sh"
serve_http=0 start_serve "$softslc" "$work" "$program" --journal "$work/journal" "$@" || exit 1
url=""
for _ in $(seq 1 50); do
  url="$(sed -n 's/.*online view on \(http:[^ ]*\).*/\1/p' "$work/out")"
  [ -n "$url" ] && break
  sleep 0.1
done
if [ -z "$url" ]; then echo "no online view:"; cat "$work/out" "$work/log"; exit 1; fi
echo "online view at $url"
CHROMIUM="$chromium" NODE_PATH="$dir/node_modules" timeout 90 node "$script" "$url" "$outdir"
stop_serve_and_replay "$softslc" "$work" $?
