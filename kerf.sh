#!/usr/bin/env bash
# Kerf's one entry point on a fresh Debian 12 machine.
#
#   ./kerf.sh          install what is missing, build (Release), run the flagship demo
#   ./kerf.sh test     install what is missing, build (Release, warnings as errors), run every test
#   ./kerf.sh asan     the same test suite built with Address and UndefinedBehavior sanitizers
#   ./kerf.sh bench    build and run the benchmarks (one core), print the tables
#   ./kerf.sh book     build the book into build/release/book/html
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

jobs=$(nproc)
case "${1:-demo}" in
  demo)
    install_missing_packages
    configure_and_build release --target 03_xfem_heaviside
    ./build/release/bin/03_xfem_heaviside --out output/03_xfem_heaviside
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
  *)
    echo "usage: ./kerf.sh [demo|test|asan|bench|book]" >&2
    exit 2
    ;;
esac
