#!/usr/bin/env bash
# Installs the interop tests' JavaScript peers (Foxglove's WebSocket protocol client, MCAP reader
# and ROS 2 message decoders) into tests/interop/js/node_modules (git-ignored), from npm, exactly
# as pinned in tests/interop/js/package-lock.json. Idempotent; prints the path of node.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
js="$root/tests/interop/js"
node="$(command -v node || true)"
if [ -z "$node" ]; then
    echo "error: node is missing; install Node.js 20 or newer (Debian: apt-get install nodejs npm)" >&2
    exit 1
fi
major="$("$node" -p 'process.versions.node.split(".")[0]')"
if [ "$major" -lt 20 ]; then
    echo "error: $node is Node.js $("$node" --version); the interop scripts need 20 or newer" >&2
    exit 1
fi
# npm ci deletes node_modules and reinstalls: skip it while the lock it installed is unchanged.
stamp="$js/node_modules/.installed-package-lock.json"
if ! cmp -s "$js/package-lock.json" "$stamp"; then
    npm ci --prefix "$js" --no-audit --no-fund --loglevel=error >&2
    cp "$js/package-lock.json" "$stamp"
fi
echo "$node"
