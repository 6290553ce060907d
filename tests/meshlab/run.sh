#!/usr/bin/env bash
# Builds sherd's MeshLab filter plugin (addons/meshlab) against MeshLab 2022.02's sources
# and runs it in a real MeshLab core: pymeshlab 2022.2.post4 loads it and applies every
# filter headless (tests/meshlab/test_meshlab_plugin.py).
#
#   bash tests/meshlab/run.sh
#
# From a clean Debian machine it installs what it needs: Qt 5, GLEW and Eigen headers and
# CMake (apt), a deb-src entry for Debian trixie, MeshLab's source archive from it
# (apt-get source), and a virtual environment with pymeshlab 2022.2.post4. Downloads and
# the venv are cached in $SHERD_MESHLAB_CACHE (default ~/.cache/sherd-meshlab); nothing of
# MeshLab enters the repository. The plugin is built in target/meshlab.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cache=${SHERD_MESHLAB_CACHE:-$HOME/.cache/sherd-meshlab}
meshlab_release=2022.02
meshlab_package=meshlab=2022.02+dfsg1-1
pymeshlab_version=2022.2.post4
mkdir -p "$cache"
if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
say() { printf -- '--- meshlab: %s\n' "$*"; }

packages=(qtbase5-dev libqt5opengl5-dev libglew-dev libeigen3-dev cmake g++ xz-utils python3-venv dpkg-dev)
missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  say "installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

source_dir="$cache/meshlab-$meshlab_release"
if [ ! -f "$source_dir/src/common/plugins/interfaces/filter_plugin.h" ]; then
  if ! apt-cache showsrc "${meshlab_package%%=*}" 2>/dev/null | grep -q "^Version: ${meshlab_package#*=}$"; then
    say "adding Debian trixie's source archive (deb-src) to apt"
    $SUDO tee /etc/apt/sources.list.d/sherd-trixie-src.sources >/dev/null <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: trixie
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
    $SUDO apt-get update -qq
  fi
  say "downloading MeshLab $meshlab_release's sources (apt-get source)"
  download="$cache/download"
  rm -rf "$download" && mkdir -p "$download"
  # Only the upstream tarball is needed (Debian's packaging is not built); --tar-only
  # also works where a mirror lacks the .dsc.
  (cd "$download" && apt-get source -qq --tar-only "$meshlab_package" 2>&1 | grep -v "unsandboxed" || true)
  tarball=$(ls "$download"/meshlab_*.orig.tar.* 2>/dev/null | head -1)
  [ -n "$tarball" ] || { echo "apt-get source $meshlab_package gave no tarball" >&2; exit 1; }
  rm -rf "$source_dir.tmp" && mkdir -p "$source_dir.tmp"
  tar -xf "$tarball" -C "$source_dir.tmp" --strip-components=1
  rm -rf "$source_dir" && mv "$source_dir.tmp" "$source_dir" && rm -rf "$download"
fi
[ "$(cat "$source_dir/ML_VERSION")" = "$meshlab_release" ] || { echo "unexpected MeshLab sources in $source_dir" >&2; exit 1; }

venv="$cache/venv-pymeshlab-$pymeshlab_version"
# numpy 1: pymeshlab 2022.2's compiled module crashes on numpy 2 arrays (a 4x4 matrix
# parameter such as set_matrix's segfaults).
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import pymeshlab, pytest, numpy; assert numpy.__version__ < '2'" >/dev/null 2>&1; then
  say "creating $venv with pymeshlab $pymeshlab_version"
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check "pymeshlab==$pymeshlab_version" "numpy<2" pytest
fi
# pymeshlab's wheel carries its MeshLab core; the plugin links against that very library.
common=$("$venv/bin/python" -c 'import os, pymeshlab; print(os.path.join(os.path.dirname(pymeshlab.__file__), "lib", "libmeshlab-common.so"))' 2>/dev/null)
# pymeshlab builds MeshLab with double precision, whose version string ends in "d".
if grep -aq "${meshlab_release}d" "$common"; then scalar=double; version="${meshlab_release}d"; else scalar=float; version=$meshlab_release; fi

say "building sherd and the plugin (MeshLab $version, $scalar)"
(cd "$root" && cargo build --release --quiet --lib --bin sherd)
build="$root/target/meshlab"
cmake -S "$root/addons/meshlab" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DMESHLAB_SOURCE_DIR="$source_dir" -DMESHLAB_VERSION="$version" -DMESHLAB_SCALAR="$scalar" \
  -DMESHLAB_COMMON_LIBRARY="$common" -DSHERD_STATIC_LIBRARY="$root/target/release/libsherd.a" >/dev/null
cmake --build "$build" -j 2 -- --quiet

say "running the filters in pymeshlab $pymeshlab_version"
SHERD_MESHLAB_PLUGIN="$build/libfilter_sherd.so" SHERD_LIBRARY="$root/target/release/libsherd.so" \
  "$venv/bin/python" -m pytest -q -p no:cacheprovider "$root/tests/meshlab"
