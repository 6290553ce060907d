#!/usr/bin/env bash
# Builds the Blender add-on and tests it in Debian's Blender 3.x, headless, as a legacy
# add-on installed from its zip into a throw-away user scripts folder.
# Without blender: skips, unless SHERD_REQUIRE_TOOLS=1 (then fails). BLENDER names
# another executable (default: blender on PATH).
set -euo pipefail
cd "$(dirname "$0")/../.."
blender=${BLENDER:-blender}
if ! command -v "$blender" >/dev/null 2>&1; then
  if [ "${SHERD_REQUIRE_TOOLS:-0}" = 1 ]; then
    echo "tests/blender/run.sh: $blender is not installed (SHERD_REQUIRE_TOOLS=1)" >&2
    exit 1
  fi
  echo "SKIP tests/blender: $blender is not installed"
  exit 0
fi
bash addons/blender/build.sh
scripts=$(mktemp -d)
trap 'rm -rf "$scripts"' EXIT
# The add-on must find its bundled library, not one named by the environment.
env -u SHERD_LIBRARY BLENDER_USER_SCRIPTS="$scripts" \
  "$blender" -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon_blender.py

# Blender 4.2+ as the bpy wheel (pip install bpy==4.2.0 in a Python 3.11 venv): the
# extension zip through Blender's extension installer, when SHERD_BPY_PYTHON names that Python.
if [ -n "${SHERD_BPY_PYTHON:-}" ]; then
  home=$(mktemp -d)
  trap 'rm -rf "$scripts" "$home"' EXIT
  env -u SHERD_LIBRARY HOME="$home" "$SHERD_BPY_PYTHON" tests/blender/test_addon_blender.py
fi
