#!/usr/bin/env bash
# Builds the C (and C++) consumers of the sherd C ABI against include/sherd.h and the
# shared and the static library, found through the generated sherd.pc, and runs each
# under valgrind: any error or leak fails.
#
#   bash tests/c/run.sh                  # release library (as tests/run_all.sh builds it)
#   SHERD_PROFILE=debug bash tests/c/run.sh
#   SHERD_C_TESTS="test_files test_wrapper" bash tests/c/run.sh   # only these programs
#
# Without valgrind the programs are built with AddressSanitizer instead (also leak checking).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
profile=${SHERD_PROFILE:-release}
cd "$root"

if [ "$profile" = release ]; then cargo build --release --lib --quiet; else cargo build --lib --quiet; fi
libdir="$root/target/$profile"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The build tree's pkg-config file, from the same template a packager fills in.
mkdir -p "$work/pkgconfig"
version=$(sed -n 's/^version *= *"\(.*\)"/\1/p' Cargo.toml | head -1)
sed -e "s|@PREFIX@|$root|" -e "s|@LIBDIR@|$libdir|" -e "s|@INCLUDEDIR@|$root/include|" \
    -e "s|@VERSION@|$version|" sherd.pc.in > "$work/pkgconfig/sherd.pc"
export PKG_CONFIG_PATH="$work/pkgconfig"
cflags=$(pkg-config --cflags sherd)
shared_libs="$(pkg-config --libs sherd) -Wl,-rpath,$libdir"
static_libs="-Wl,-Bstatic $(pkg-config --libs sherd) -Wl,-Bdynamic $(pkg-config --static --libs-only-l sherd | sed 's/-lsherd//')"

# Each program has a time limit, so that a hang (an option value that makes an operation
# run without bound, say) fails the suite instead of stalling it.
limit=${SHERD_C_TIMEOUT:-1200}
sanitize=()
if command -v valgrind >/dev/null 2>&1; then
  run() { timeout "$limit" valgrind --quiet --error-exitcode=99 --suppressions="$root/tests/c/valgrind.supp" \
            --leak-check=full --show-leak-kinds=definite,indirect,possible \
            --errors-for-leak-kinds=definite,indirect,possible "$@"; }
else
  echo "valgrind not found: using AddressSanitizer and LeakSanitizer"
  sanitize=(-fsanitize=address,undefined -fno-omit-frame-pointer)
  run() { timeout "$limit" "$@"; }
fi

c_flags=(-std=c99 -Wall -Wextra -Werror -pedantic -g -pthread)
cxx_flags=(-std=c++17 -Wall -Wextra -Werror -pedantic -g -pthread -I"$root/bindings/cpp")
failed=0
for source in tests/c/*.c tests/cpp/*.cpp; do
  [ -e "$source" ] || continue
  name=$(basename "${source%.*}")
  if [ -n "${SHERD_C_TESTS:-}" ] && [[ " $SHERD_C_TESTS " != *" $name "* ]]; then continue; fi
  for linkage in shared static; do
    if [ "$linkage" = shared ]; then libs=$shared_libs; else libs=$static_libs; fi
    binary="$work/$name-$linkage"
    case "$source" in
      *.c) compiler=(gcc "${c_flags[@]}") ;;
      *.cpp) compiler=(g++ "${cxx_flags[@]}") ;;
    esac
    # shellcheck disable=SC2086
    "${compiler[@]}" "${sanitize[@]}" $cflags -Itests/c "$source" -o "$binary" $libs -lm
    echo "--- $name ($linkage)"
    if ! (cd "$work" && run "$binary"); then
      echo "FAILED: $name ($linkage)"
      failed=1
    fi
  done
done
exit $failed
