#!/usr/bin/env bash
# The MuJoCo library for the simulated benchmark (`pomdar sim`, `--physics`), without the outside
# world: the official `mujoco` wheel is taken from the Python package registry (PyPI; pip checks
# its hash) and its shared library and C headers are unpacked into `.mujoco/<version>/` in the
# checkout. Nothing else is installed; the README's two set-up commands do not need this.
#
# The version is the one the Rust bindings (`mujoco-rs` 7.0.0+mj-3.17.0) were generated for;
# .cargo/config.toml points the build at `.mujoco/<version>/lib` (MUJOCO_DYNAMIC_LINK_DIR) and
# teleop's build script bakes that directory into the binaries' run path.
#
# Usage: bash sim/setup_mujoco.sh      (idempotent; prints where the library is)
set -euo pipefail
cd "$(dirname "$0")/.."

VERSION=3.17.0
DEST=".mujoco/$VERSION"
if [ -f "$DEST/lib/libmujoco.so.$VERSION" ] && [ -L "$DEST/lib/libmujoco.so" ]; then
    echo "MuJoCo $VERSION is ready in $DEST/lib"
    exit 0
fi

PYTHON="${PYTHON:-python3}"
if ! "$PYTHON" -m pip --version >/dev/null 2>&1; then
    echo "error: $PYTHON has no pip; install Python 3 with pip (Debian: apt-get install python3-pip)" >&2
    exit 1
fi

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
echo "== downloading the mujoco $VERSION wheel from PyPI"
"$PYTHON" -m pip download --quiet --no-deps --only-binary=:all: "mujoco==$VERSION" -d "$tmp"
wheel="$(ls "$tmp"/mujoco-"$VERSION"-*.whl)"

echo "== unpacking libmujoco.so.$VERSION and the C headers into $DEST"
rm -rf "$DEST.partial"
mkdir -p "$DEST.partial/lib" "$DEST.partial/include"
"$PYTHON" - "$wheel" "$DEST.partial" "$VERSION" <<'PY'
import sys, zipfile, pathlib
wheel, dest, version = sys.argv[1], pathlib.Path(sys.argv[2]), sys.argv[3]
lib_name = f"libmujoco.so.{version}"
found = False
with zipfile.ZipFile(wheel) as z:
    for name in z.namelist():
        if name == f"mujoco/{lib_name}":
            (dest / "lib" / lib_name).write_bytes(z.read(name))
            found = True
        elif name.startswith("mujoco/include/") and not name.endswith("/"):
            out = dest / "include" / name[len("mujoco/include/"):]
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_bytes(z.read(name))
if not found:
    sys.exit(f"error: {wheel} holds no mujoco/{lib_name}")
PY
ln -s "libmujoco.so.$VERSION" "$DEST.partial/lib/libmujoco.so"
rm -rf "$DEST"
mv "$DEST.partial" "$DEST"
echo "MuJoCo $VERSION is ready in $DEST/lib"
