#!/usr/bin/env bash
# Builds the Blender add-on and tests it headless in two real Blenders:
# - Debian's Blender 3.x, as a legacy add-on installed from its zip into a throw-away
#   user scripts folder (BLENDER names another executable; default blender on PATH);
# - Blender 4.2 as the bpy module (pip install bpy==4.2.0 pytest for Python 3.11, kept in
#   target/bpy-venv: 0.5 GB to download once), with pytest, the add-on installed as an
#   extension with Blender's extension installer. SHERD_BPY_PYTHON names another Python
#   that has bpy and pytest; SHERD_SKIP_BPY=1 leaves this part out.
# A missing Blender or Python 3.11 skips that part, unless SHERD_REQUIRE_TOOLS=1 (then fails).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
missing() {
  if [ "${SHERD_REQUIRE_TOOLS:-0}" = 1 ]; then
    echo "tests/blender/run.sh: $1 (SHERD_REQUIRE_TOOLS=1)" >&2
    exit 1
  fi
  echo "SKIP: $1"
}

bpy_python=""
if [ "${SHERD_SKIP_BPY:-0}" != 1 ]; then
  if [ -n "${SHERD_BPY_PYTHON:-}" ]; then
    bpy_python=$SHERD_BPY_PYTHON
  elif python3 -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
    bpy_python="$root/target/bpy-venv/bin/python"
    if ! "$bpy_python" -c 'import bpy, pytest' >/dev/null 2>&1; then
      echo "installing bpy 4.2.0 into target/bpy-venv"
      rm -rf "$root/target/bpy-venv"
      python3 -m venv "$root/target/bpy-venv"
      "$root/target/bpy-venv/bin/pip" install -q --disable-pip-version-check bpy==4.2.0 pytest
    fi
  else
    missing "the bpy 4.2 module needs Python 3.11, python3 is $(python3 --version)"
  fi
fi

# With bpy present the extension zip is built by Blender's own extension tool. The test
# compares the add-on's measurements with the sherd command's.
BPY_PYTHON=${bpy_python:-none} bash addons/blender/build.sh
cargo build --release --bin sherd --quiet

blender=${BLENDER:-blender}
if command -v "$blender" >/dev/null 2>&1; then
  scripts=$(mktemp -d)
  # The add-on must find its bundled library, not one named by the environment.
  env -u SHERD_LIBRARY BLENDER_USER_SCRIPTS="$scripts" \
    "$blender" -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon_blender.py
  rm -rf "$scripts"
else
  missing "$blender is not installed"
fi

if [ -n "$bpy_python" ]; then
  home=$(mktemp -d)
  trap 'rm -rf "$home"' EXIT
  env -u SHERD_LIBRARY HOME="$home" "$bpy_python" -m pytest -q -p no:cacheprovider tests/blender
fi
