#!/usr/bin/env bash
# Builds the platform wheel of the Python binding with the native library inside:
#   target/wheels/sherd_pottery-<version>-py3-none-manylinux_2_28_x86_64.whl
# libsherd.so is built against glibc 2.28 with cargo-zigbuild and zig (both from PyPI,
# in the tools venv target/wheel-tools), so the wheel loads on every manylinux_2_28
# system: Blender's own builds, RHEL 8, Debian 10 and later. auditwheel checks that the
# library needs nothing newer than the tag says. The wheel works with any Python 3
# (ctypes, no extension module), hence py3-none.
#
#   bash bindings/python/build_wheel.sh          (prints the wheel's path last)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
tag=manylinux_2_28_x86_64
tools="$root/target/wheel-tools"
if [ ! -x "$tools/bin/cargo-zigbuild" ] || [ ! -x "$tools/bin/auditwheel" ] || [ ! -x "$tools/bin/wheel" ]; then
  python3 -m venv "$tools"
  "$tools/bin/pip" install -q --disable-pip-version-check ziglang cargo-zigbuild auditwheel wheel setuptools
fi
export PATH="$tools/bin:$PATH"

cargo zigbuild --release --lib --target x86_64-unknown-linux-gnu.2.28 >&2
library="$root/target/x86_64-unknown-linux-gnu/release/libsherd.so"

stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
cp bindings/python/pyproject.toml bindings/python/setup.py "$stage/"
mkdir "$stage/sherd"
cp bindings/python/sherd/*.py "$stage/sherd/"
cp "$library" "$stage/sherd/libsherd.so"
# Debug information is three quarters of the library; a wheel does not need it.
strip --strip-debug "$stage/sherd/libsherd.so"

out="$root/target/wheels"
mkdir -p "$out"
"$tools/bin/pip" wheel -q --disable-pip-version-check --no-deps --no-build-isolation -w "$stage/dist" "$stage" >&2
built=$(ls "$stage"/dist/sherd_pottery-*.whl)
"$tools/bin/wheel" tags --remove --python-tag py3 --abi-tag none --platform-tag "$tag" "$built" >&2
wheel=$(ls "$stage"/dist/sherd_pottery-*-py3-none-$tag.whl)
# auditwheel names the most compatible tag the library's symbol versions allow.
"$tools/bin/auditwheel" show "$wheel" >&2
"$tools/bin/auditwheel" show "$wheel" 2>&1 | tr -s ' \n' ' ' | grep -q "\"$tag\"" ||
  { echo "build_wheel.sh: auditwheel does not confirm $tag" >&2; exit 1; }
mv "$wheel" "$out/"
echo "$out/$(basename "$wheel")"
