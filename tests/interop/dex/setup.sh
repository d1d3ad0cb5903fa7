#!/usr/bin/env bash
# Installs dex-retargeting (PyPI dex_retargeting 0.5.0, MIT, by Yuzhe Qin; not vendored) and the
# MCAP tools the comparison script needs into a project-local virtual environment,
# target/dex-venv, from PyPI, at pinned versions. Idempotent: when the environment already
# holds these pins it only says so. Prints what it did on stderr and the interpreter's path on
# stdout (compare.sh runs `python="$(setup.sh)"`).
#
# Notes on the pins:
# - dex_retargeting imports torch (its optimisers compute the loss gradients with autograd) and
#   six (its copy of yourdfpy) without declaring either; both are pinned here. Only PyPI is
#   reachable, whose Linux torch wheel brings the CUDA libraries along (about 5 GB in the
#   venv); they are never used, everything runs on the CPU.
# - mcap and mcap-ros2-support are the versions tests/interop/requirements.txt pins.
# - The rest are dex_retargeting's dependencies at the versions this comparison was run with.
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
venv="$root/target/dex-venv"
pins=(
    dex_retargeting==0.5.0
    torch==2.15.0
    six==1.17.0
    mcap==1.6.0
    mcap-ros2-support==0.6.0
    numpy==2.4.6
    pin==4.1.0
    nlopt==2.11.0
    lxml==6.1.3
    pytransform3d==3.17.0
    anytree==2.13.0
    PyYAML==6.0.4
)
stamp="$venv/.dex-pins"
wanted="$(printf '%s\n' "${pins[@]}")"
if [ -x "$venv/bin/python" ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$wanted" ] \
    && "$venv/bin/python" -c 'import dex_retargeting, torch, mcap_ros2' 2>/dev/null; then
    echo "dex setup: $venv already has the pinned packages" \
        "(dex_retargeting 0.5.0, torch 2.15.0)" >&2
else
    if [ ! -x "$venv/bin/python" ]; then
        python3.11 -m venv "$venv"
        echo "dex setup: created $venv (python3.11)" >&2
    fi
    echo "dex setup: installing ${pins[*]} from PyPI" \
        "(torch is large: a few minutes the first time)" >&2
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${pins[@]}" >&2
    "$venv/bin/python" -c 'import dex_retargeting, torch, mcap_ros2'
    printf '%s\n' "$wanted" > "$stamp"
    echo "dex setup: installed; $(du -sh "$venv" | cut -f1) in $venv" >&2
fi
echo "$venv/bin/python"
