#!/usr/bin/env bash
# Installs the pinned client packages (package.json, package-lock.json) into DIR/node_modules
# with `npm ci`, once per lockfile: the ctest fixture that every client test requires.
#   setup.sh DIR [SOURCE]
# SOURCE is the directory holding package.json and package-lock.json (default: this script's; the
# browser tests pass tests/serve/browser).
# Exit 77 (ctest: skipped) with a message when the machine has no Node at all; tools/bootstrap.sh
# installs Debian's nodejs and npm, so that happens only on a machine set up by hand.
set -euo pipefail
dir="$1"
here="${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)}"
if ! command -v node > /dev/null || ! command -v npm > /dev/null; then
  echo "SKIPPED: no node/npm on this machine (apt-get install nodejs npm, or tools/bootstrap.sh test)"
  exit 77
fi
mkdir -p "$dir"
if [ -d "$dir/node_modules" ] && cmp -s "$here/package-lock.json" "$dir/package-lock.json"; then
  echo "client packages already installed in $dir"
  exit 0
fi
cp "$here/package.json" "$here/package-lock.json" "$dir/"
cd "$dir"
npm ci --no-audit --no-fund --loglevel=error
echo "installed: $(node -e 'const p=require("./package.json");console.log(Object.entries(p.dependencies).map(e=>e.join("@")).join(" "))')"
