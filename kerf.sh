#!/usr/bin/env bash
# Kerf's one entry point on a fresh Debian 12 machine.
#
#   ./kerf.sh          install what is missing, build (Release), run the flagship demo
#   ./kerf.sh test     install what is missing, build (Release, warnings as errors), run every test
#   ./kerf.sh asan     the same test suite built with Address and UndefinedBehavior sanitizers
#   ./kerf.sh bench    build and run the benchmarks (one core), print the tables
#   ./kerf.sh book     build the book into build/release/book/html
#   ./kerf.sh assignment NN [--reference]
#                      build course assignment NN (assignments/NN_*: your code in its stubs/ in
#                      place of the library's) and grade it with the chapter's tests: a score per
#                      function and the first failing check of each failing test case;
#                      --reference grades the library's own code, which scores 100 %
#   ./kerf.sh fuzz     fuzz the mesh and surface readers and the scene parser with libFuzzer (clang), 60 s
#                      each or KERF_FUZZ_SECONDS, from the seeds in tests/fuzz/corpus
set -euo pipefail
cd "$(dirname "$0")"

# Debian packages Kerf needs, and why (see the book's design page):
packages=(
  cmake g++ make pkg-config
  libeigen3-dev                         # dense and sparse linear algebra
  libsuitesparse-dev libopenblas-dev    # CHOLMOD, on an optimised BLAS (4-12x faster than reference BLAS)
  libcgal-dev                           # exact geometry for cuts (chapter 3 on)
  libvtk9-dev                           # reading and writing meshes and results
  nlohmann-json3-dev                    # scene files
  doctest-dev                           # the tests
  doxygen libjs-mathjax                 # the book, with offline formulas
  calculix-ccx                          # independent reference solutions in the validation tests
  xvfb                                  # headless rendering for figures
  gnuplot-nox                           # the charts in figures/
)

install_missing_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "kerf.sh: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

configure_and_build() {
  local preset=$1; shift
  cmake --preset "$preset"
  cmake --build --preset "$preset" "$@"
}

# Runs every fuzz target (one per folder of tests/fuzz/corpus) for KERF_FUZZ_SECONDS seconds,
# starting from its committed seeds and regressions. What a fuzzer learns stays in
# build/fuzz/corpus/<reader>; an input that crashes, hangs (-timeout) or allocates too much
# (-rss_limit_mb) lands in build/fuzz/artifacts/<reader>. Prints one line per target and fails
# if any target found something: fix the reader, then copy the input to tests/fuzz/regressions.
run_fuzzers() {
  local seconds=${KERF_FUZZ_SECONDS:-60}
  local summary="" found=0
  for seeds in tests/fuzz/corpus/*/; do
    local reader corpus artifacts log leaks=1 status=0
    reader=$(basename "$seeds")
    corpus=build/fuzz/corpus/$reader
    artifacts=build/fuzz/artifacts/$reader/
    log=build/fuzz/$reader.log
    mkdir -p "$corpus" "$artifacts"
    local inputs=("$corpus" "$seeds")
    [ -d "tests/fuzz/regressions/$reader" ] && inputs+=("tests/fuzz/regressions/$reader")
    # VTK 9.1's readers leak what they had allocated when they give up on a malformed file (see
    # tests/lsan_suppressions.txt; the XML reader leaks array iterators too). The leaks are VTK's,
    # and suppressions need the slow unwinder, which would cut the fuzzer's speed several times:
    # no leak detection for the VTK targets, neither per input (-detect_leaks) nor at exit
    # (ASAN_OPTIONS). Leaks in Kerf's own code are still caught by the other targets and by
    # ./kerf.sh asan.
    case $reader in vtk | vtu | surface_vtk) leaks=0 ;; esac
    echo "kerf.sh: fuzzing $reader for ${seconds} s (log: $log)"
    ASAN_OPTIONS=detect_leaks=$leaks UBSAN_OPTIONS=print_stacktrace=1 "./build/fuzz/bin/fuzz_$reader" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -detect_leaks=$leaks \
      -artifact_prefix="$artifacts" -print_final_stats=1 "${inputs[@]}" >"$log" 2>&1 || status=$?
    local runs
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    summary+=$(printf '%-11s %10s runs  %5d inputs in its corpus' "$reader" "${runs:-?}" \
      "$(find "$corpus" -type f | wc -l)")
    if [ "$status" -ne 0 ]; then
      summary+="  FOUND A BUG: $(ls "$artifacts")"
      found=1
    fi
    summary+=$'\n'
  done
  printf '%s' "$summary"
  return $found
}

jobs=$(nproc)
case "${1:-demo}" in
  demo)
    install_missing_packages
    configure_and_build release --target 08_real_time -j "$jobs"
    # The flagship, chapter 8: the cut in real time. Its frames are drawn through X, so without
    # a display xvfb-run lends one; with a display the window follows, in which the mouse cuts.
    if [ -n "${DISPLAY:-}" ]; then
      ./build/release/bin/08_real_time --out output/08_real_time
      ./build/release/bin/08_real_time --interactive --out output/08_real_time_window
    else
      xvfb-run -a ./build/release/bin/08_real_time --out output/08_real_time
    fi
    ;;
  test)
    install_missing_packages
    configure_and_build release -j "$jobs"
    ctest --preset release -j "$jobs"
    ;;
  asan)
    install_missing_packages
    configure_and_build asan -j "$jobs"
    ctest --preset asan -j "$jobs"
    ;;
  bench)
    install_missing_packages
    configure_and_build release --target bench
    ;;
  book)
    install_missing_packages
    configure_and_build release --target book
    echo "kerf.sh: open build/release/book/html/index.html"
    ;;
  assignment)
    shift
    number=${1:-}
    [[ $number =~ ^[0-9]{1,2}$ ]] && number=$(printf '%02d' "$((10#$number))")
    # A number with no assignment folder (or no number): the grader says so in one line,
    # before anything is built.
    compgen -G "assignments/${number:-none}_*/grading.txt" >/dev/null || exec assignments/grade.sh "$@"
    install_missing_packages
    # Only what the graded tests need: the library, the graded suites' test objects, the
    # stubs, and the links of the graded executables (and of the suites' own, for --reference).
    configure_and_build release --target "assignment_$number" -j "$jobs"
    assignments/grade.sh "$@" --build-dir build/release
    ;;
  fuzz)
    packages+=(clang libclang-rt-14-dev) # clang and its libFuzzer runtime, for the fuzz targets only
    install_missing_packages
    configure_and_build fuzz -j "$jobs"
    run_fuzzers
    ;;
  *)
    echo "usage: ./kerf.sh [demo|test|asan|bench|book|fuzz|assignment NN [--reference]]" >&2
    exit 2
    ;;
esac
