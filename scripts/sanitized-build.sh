# Sourced by test-sanitized.sh and fuzz.sh: builds the named targets with clang,
# AddressSanitizer, UBSan and libFuzzer's coverage into build-sanitized/, and sets the sanitizer
# options both run with. One build serves the test suite and the fuzz targets.
sanitized_build=build-sanitized

build_sanitized() {
  scripts/install-deps.sh --sanitizers
  # Line tables only: reports keep their file and line, without the bulk of full debug info.
  CC=clang CXX=clang++ cmake -S . -B "$sanitized_build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS_RELEASE="-O2 -gline-tables-only -DNDEBUG" -DBAKER_SANITIZE=ON -DBAKER_FUZZ=ON > /dev/null
  cmake --build "$sanitized_build" -j2 --target "$@"
}

# Any report fails the run. Leak suppressions name third-party code only, each with its reason;
# UBSan's exceptions are compile-time (tests/sanitizers/ubsan-ignorelist.txt).
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$(pwd)/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
