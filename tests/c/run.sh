#!/usr/bin/env bash
# Builds the C (and C++) consumers of the sherd C ABI against include/sherd.h and the
# shared and the static library, found through the generated sherd.pc, and runs each
# under AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer: any error or leak
# fails.
#
#   bash tests/c/run.sh                  # release library (as tests/run_all.sh builds it)
#   SHERD_PROFILE=debug bash tests/c/run.sh
#   SHERD_C_TESTS="test_files test_wrapper" bash tests/c/run.sh   # only these programs
#   SHERD_C_CHECKER=valgrind bash tests/c/run.sh                  # valgrind's memcheck instead
#
# The sanitizers instrument the C and C++ programs (compiled with -fsanitize); the Rust
# library is built normally, and its allocations, which go through malloc, are still
# tracked and leak-checked by ASan's allocator. valgrind also checks the library's own
# memory accesses, but is many times slower; sanitizers are the default so that the
# property test can run many cases in the suite's time. No suppression is needed: the
# rayon pool's threads, alive at exit, are roots LeakSanitizer scans (valgrind.supp is
# for valgrind only).
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
checker=${SHERD_C_CHECKER:-sanitizers}
case "$checker" in
  sanitizers)
    # -fno-sanitize-recover: undefined behaviour stops the program (and fails it) instead
    # of printing and going on.
    sanitize=(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
    export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1:check_initialization_order=1"
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
    run() { timeout "$limit" "$@"; } ;;
  valgrind)
    if ! command -v valgrind >/dev/null 2>&1; then
      echo "SHERD_C_CHECKER=valgrind, but valgrind is not installed (apt-get install valgrind)" >&2
      exit 2
    fi
    sanitize=()
    run() { timeout "$limit" valgrind --quiet --error-exitcode=99 --suppressions="$root/tests/c/valgrind.supp" \
              --leak-check=full --show-leak-kinds=definite,indirect,possible \
              --errors-for-leak-kinds=definite,indirect,possible "$@"; } ;;
  *)
    echo "SHERD_C_CHECKER must be sanitizers (the default) or valgrind, not $checker" >&2
    exit 2 ;;
esac
echo "checker: $checker"

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
