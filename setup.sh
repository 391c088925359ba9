#!/usr/bin/env bash
# coif's one setup script: installs the Debian 12 packages of cmake/apt-packages.txt (apt), configures
# and builds, then does what was asked:
#   ./setup.sh render      build (release) and render the embedded default scene to coif-default.png
#   ./setup.sh test        build (release) and run the whole test suite (what CI runs)
#   ./setup.sh test-slow   build (release) and run the slow validation (label "slow": brute-force checks)
#   ./setup.sh test-asan   build the asan preset (AddressSanitizer + UBSan) and run the suite under it
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
}

build() {  # build <preset>
  cmake --preset "$1"
  cmake --build --preset "$1"
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
  test-asan) build asan
             ctest --preset asan ;;
  *)         echo "usage: $0 [build|render|test|test-slow|test-asan]" >&2; exit 2 ;;
esac
