#!/usr/bin/env bash
# The whole test suite of sherd, from a fresh Debian machine with Rust and Python:
# installs what the tests need (Debian packages, Python packages, cbindgen), builds,
# and runs the Rust tests, the header check, the C/C++ consumers and the Python tests.
#
#   bash tests/run_all.sh
#
# Tests that compare with MeshLab (pymeshlab) or use external tools fail instead of
# skipping here (SHERD_REQUIRE_*), so a green run means they really ran. Tests that read
# ../shared/data skip with a message where it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
step() { printf '\n==> %s\n' "$*"; }

step "system packages"
packages=(ghostscript libgl1 libglu1-mesa pkg-config blender python3-numpy python3-venv)
missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

step "python packages"
python3 -m pip install -q --disable-pip-version-check -r tests/requirements.txt

step "cbindgen"
export PATH="$HOME/.cargo/bin:$PATH"
command -v cbindgen >/dev/null 2>&1 || cargo install -q cbindgen --locked

export SHERD_REQUIRE_PYMESHLAB=1 SHERD_REQUIRE_TOOLS=1

step "build (release)"
cargo build --release --all-targets

step "header is up to date with src/ffi"
if [ -f cbindgen.toml ]; then
  cbindgen --quiet --config cbindgen.toml --crate sherd --verify --output include/sherd.h
fi

step "API documentation builds without warnings (broken or private links in doc comments)"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps -q
# The internals' links too: a moved or renamed private item leaves no broken link behind.
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --document-private-items -q

step "clippy finds nothing in the library, the tool, the tests, examples and benches"
# Clippy comes with rustup's default profile; a toolchain installed without it is told so.
if cargo clippy --version >/dev/null 2>&1 || rustup component add clippy >/dev/null 2>&1; then
  cargo clippy --release --all-targets -q -- -D warnings
else
  echo "clippy is not installed and rustup could not add it: lints skipped"
fi

step "Rust tests"
# Includes the hostile-file corpus (tests/io_malformed.rs), the replay of the fuzz
# targets' corpora and found inputs (tests/fuzz_regressions.rs; the long fuzz runs are in
# FUZZING.md) and the SIGKILLed batch (tests/batch_kill.rs).
cargo test --release --all-targets

step "C and C++ consumers under AddressSanitizer, LeakSanitizer and UBSan (gcc's runtimes come with gcc; SHERD_C_CHECKER=valgrind for valgrind), the C ABI property test among them"
if [ -f tests/c/run.sh ]; then bash tests/c/run.sh; fi

step "Python tests"
if compgen -G "tests/python/test_*.py" >/dev/null; then
  python3 -m pytest -q tests/python
fi

step "Python wheel (manylinux_2_28, installed in a fresh venv)"; bash tests/wheel/run.sh

step "Blender add-on (headless Blender 3.4 and the bpy 4.2 module)"; bash tests/blender/run.sh

step "MeshLab filter plugin (MeshLab 2022.02 sources, pymeshlab 2022.2.post4)"; bash tests/meshlab/run.sh

step "The drawings in Inkscape (SVG to PDF and PNG, no warnings) and Ghostscript (EPS, PDF)"; bash tests/inkscape/run.sh

step "all tests passed"
