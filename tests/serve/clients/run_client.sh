#!/usr/bin/env bash
# Runs one client script against a live `softslc serve`, then replays the server's journal.
#   run_client.sh SOFTSLC CLIENT_DIR PROGRAM SCRIPT.js [BENCH]
# The server listens on 127.0.0.1 on a free port (--port 0; the script gets it as its argument)
# with a journal; after the script the server is stopped with SIGINT, and `softslc replay` must
# reproduce every data-table state the script's writes produced. Exit 77 (skipped) without node.
set -uo pipefail
softslc="$1" dir="$2" program="$3" script="$4" bench="${5:-}"
if ! command -v node > /dev/null; then echo "SKIPPED: no node on this machine"; exit 77; fi
if [ ! -d "$dir/node_modules" ]; then echo "SKIPPED: client packages not installed (setup.sh failed?)"; exit 77; fi
work="$(mktemp -d)"
trap 'kill -INT "$server" 2>/dev/null; rm -rf "$work"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/../../../tools/lib/serve-start.sh"
start_serve "$softslc" "$work" "$program" ${bench:+--bench "$bench"} --journal "$work/journal" || exit 1
head -1 "$work/out"
NODE_PATH="$dir/node_modules" node "$script" "$port"
stop_serve_and_replay "$softslc" "$work" $?
