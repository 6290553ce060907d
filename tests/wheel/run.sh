#!/usr/bin/env bash
# Builds the manylinux_2_28 wheel of the Python binding (bindings/python/build_wheel.sh),
# installs it into a fresh venv with pip, and runs tests/wheel/check_wheel.py there: the
# package must import and load the libsherd.so inside the wheel (SHERD_LIBRARY unset),
# and orient a synthetic sherd.
set -euo pipefail
cd "$(dirname "$0")/../.."
wheel=$(bash bindings/python/build_wheel.sh | tail -1)
venv=$(mktemp -d)
trap 'rm -rf "$venv"' EXIT
python3 -m venv "$venv"
"$venv/bin/pip" install -q --disable-pip-version-check "$wheel"
# Run from an empty folder so that bindings/python cannot be imported by accident.
(cd "$venv" && env -u SHERD_LIBRARY -u PYTHONPATH "$venv/bin/python" "$OLDPWD/tests/wheel/check_wheel.py" "$wheel")
