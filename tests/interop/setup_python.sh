#!/usr/bin/env bash
# Installs the interop tests' independent tools (MCAP readers and writers, Eclipse Cyclone DDS)
# into a project-local virtual environment (target/interop-venv), from PyPI. Idempotent; prints
# the interpreter path.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
venv="$root/target/interop-venv"
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    -r "$root/tests/interop/requirements.txt"
echo "$venv/bin/python"
