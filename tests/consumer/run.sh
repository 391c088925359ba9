#!/usr/bin/env bash
# The install and consumer-package test (./setup.sh test-install; CI). Needs the release build (./setup.sh build).
#   1. The runtime alone, as shared libraries: configured with COIF_BUILD_AUTHORING=OFF, so with the runtime's
#      dependencies only, built and installed to build/install-runtime.
#   2. This folder's consumer project, copied out of the tree so that it cannot reach the sources, configured against
#      that prefix alone (find_package(coif COMPONENTS runtime); its CMakeLists.txt fails if the runtime's link
#      interface names Ceres, Embree, FLANN, GLFW, GoogleTest or Benchmark), built, its ldd checked for them, and run
#      on an asset baked by the release build: the example host (example_host.cpp) draws a head and the hair with the
#      public API only, and checks occlusion, its untouched pixels and its GL state; with ../shared/data, again with
#      the Ratboy's body posed through a head turn and the mohawk following its bones.
#   3. The release build installed whole to build/install-full: the installed coif runs and bakes.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
forbidden='ceres|embree|glfw|gtest|gmock|benchmark|flann'

echo "test-install: building the runtime alone (shared libraries)"
cmake -S . -B build/runtime -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOIF_BUILD_AUTHORING=OFF -DBUILD_SHARED_LIBS=ON \
      -DCOIF_WERROR=ON > build/runtime-configure.log
if grep -Ei "$forbidden" build/runtime/CMakeCache.txt | grep -Ei '_DIR:PATH=/' ; then
  echo "test-install: the runtime-only configuration found an authoring or tool dependency" >&2
  exit 1
fi
cmake --build build/runtime -j2
rm -rf build/install-runtime
cmake --install build/runtime --prefix build/install-runtime > /dev/null

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp tests/consumer/CMakeLists.txt tests/consumer/example_host.cpp "$work/"
echo "test-install: the consumer against $root/build/install-runtime"
cmake -S "$work" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$root/build/install-runtime"
cmake --build "$work/build"
ldd "$work/build/coif_example_host" > "$work/ldd.txt"
if grep -Ei "$forbidden" "$work/ldd.txt"; then
  echo "test-install: the consumer links an authoring or tool library (above)" >&2
  exit 1
fi
grep -q "install-runtime/lib/libcoif_online.so" "$work/ldd.txt" || { echo "test-install: not the installed shared runtime" >&2; cat "$work/ldd.txt"; exit 1; }
build/release/coif bake @default -o "$work/hair.coif"
"$work/build/coif_example_host" "$work/hair.coif" "$work/hair.ppm"
# The same host with a character, when the shared data is there: the Ratboy posed through a head turn, the mohawk
# (imported with its skinning and baked by the release build) following its bones.
data=$root/../shared/data
if [[ -f $data/Ratboy_mohawk.tfx && -f $data/Ratboy_mohawk.tfxbone && -f $data/Ratboy_body.tfxmesh ]]; then
  build/release/coif style import "$data/Ratboy_mohawk.tfx" --skinning "$data/Ratboy_mohawk.tfxbone" --clusters 32 \
      -o "$work/ratboy.json" > /dev/null
  build/release/coif bake "$work/ratboy.json" -o "$work/ratboy.coif" 2> /dev/null
  "$work/build/coif_example_host" "$work/ratboy.coif" --body "$data/Ratboy_body.tfxmesh" \
      --animate docs/examples/ratboy_head_turn.json "$work/ratboy.ppm"
else
  echo "test-install: skipped the Ratboy host: the real test data in $data is absent"
fi

echo "test-install: the full install"
rm -rf build/install-full
cmake --install build/release --prefix build/install-full > /dev/null
test -f build/install-full/lib/cmake/coif/coifAuthoringTargets.cmake
test -f build/install-full/include/coif/coif.h
test -f build/install-full/share/coif/assets/default_style.json
build/install-full/bin/coif --version
build/install-full/bin/coif bake @default -o "$work/full.coif" 2> /dev/null
echo "test-install: passed"
