#!/usr/bin/env bash
# coif's one setup script: installs the Debian 12 packages of cmake/apt-packages.txt (apt), configures
# and builds, then does what was asked:
#   ./setup.sh render      build (release) and render the embedded default scene to coif-default.png
#   ./setup.sh test        build (release) and run the whole test suite (what CI runs)
#   ./setup.sh test-slow   build (release) and run the slow validation (label "slow": brute-force checks)
#   ./setup.sh test-install  build (release), then the install and consumer-package test (tests/consumer/run.sh):
#                          the runtime alone built shared and installed, a project outside the tree built against it
#   ./setup.sh test-asan   build the asan preset (AddressSanitizer + UBSan) and run the suite under it
#   ./setup.sh fuzz [S]    build the fuzz preset (clang-14 libFuzzer + ASan + UBSan) and fuzz every parser for S
#                          seconds each (default 60); new inputs go to build/fuzz/corpus/, crashes to build/fuzz/crashes/
#   ./setup.sh build       install and build only
set -euo pipefail
cd "$(dirname "$0")"
action=${1:-build}

install_packages() {
  mapfile -t wanted < <(grep -v '^\s*#' cmake/apt-packages.txt | grep -v '^\s*$')
  local missing=()
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
    local sudo=""
    [[ $(id -u) -eq 0 ]] || sudo="sudo"
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
  # Dear ImGui's GLFW and OpenGL 3 backends ship as example sources in libimgui-dev's documentation; where dpkg
  # leaves /usr/share/doc out, they are taken from the package itself (cmake/CoifDependencies.cmake looks there too).
  if [[ ! -f /usr/share/doc/libimgui-dev/examples/backends/imgui_impl_glfw.cpp &&
        ! -f build/deb/root/usr/share/doc/libimgui-dev/examples/backends/imgui_impl_glfw.cpp ]]; then
    echo "setup: extracting Dear ImGui's backend sources from the libimgui-dev package"
    mkdir -p build/deb
    (cd build/deb && apt-get download libimgui-dev && dpkg-deb -x libimgui-dev_*.deb root)
  fi
}

build() {  # build <preset>
  cmake --preset "$1"
  cmake --build --preset "$1"
}

fuzz_all() {  # fuzz_all <seconds per target>
  local seconds=$1 failed=0
  mkdir -p build/fuzz/crashes
  for exe in build/fuzz/fuzz/coif_fuzz_*; do
    local name=${exe##*/coif_fuzz_}
    mkdir -p "build/fuzz/corpus/$name"
    echo "setup: fuzzing $name for ${seconds} s"
    # The first folder gets the new inputs; the repository's seeds stay as they are. -rss_limit_mb: a parser must
    # refuse an absurd count before allocating, so 2 GiB is a crash.
    if ! "$exe" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=30 -print_final_stats=1 \
         -artifact_prefix="build/fuzz/crashes/$name-" "build/fuzz/corpus/$name" "tests/fuzz/corpus/$name" \
         2> "build/fuzz/$name.log"; then
      echo "setup: fuzz target $name FAILED; see build/fuzz/$name.log and build/fuzz/crashes/" >&2
      tail -n 40 "build/fuzz/$name.log" >&2
      failed=1
    fi
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build/fuzz/$name.log" | sed "s/^/  $name /"
  done
  return $failed
}

install_packages
case "$action" in
  build)     build release ;;
  render)    build release
             ./build/release/coif render -o coif-default.png
             echo "setup: wrote $(pwd)/coif-default.png" ;;
  test)      build release
             ctest --preset release ;;
  test-slow) build release
             ctest --preset release-slow ;;
  test-install) build release
             tests/consumer/run.sh ;;
  test-asan) build asan
             ctest --preset asan ;;
  fuzz)      build fuzz
             fuzz_all "${2:-60}" ;;
  *)         echo "usage: $0 [build|render|test|test-slow|test-install|test-asan|fuzz [seconds]]" >&2; exit 2 ;;
esac
