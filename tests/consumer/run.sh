#!/usr/bin/env bash
# The consumer build: installs spatter's build tree into a temporary prefix, configures and builds
# the project beside this script against it (find_package(spatter)), and runs its minimal host; with
# "examples", it also builds the example hosts from their installed sources and runs each on the
# gallery with a few rays: spatter-example-deferred on both of its paths (G-buffer blend, --dbuffer)
# and spatter-example-forward.
#   run.sh BUILD_DIR WORK_DIR [EXTRA_FLAGS] [examples]
# Exit 0 on success, 77 (skipped) when the host finds no headless OpenGL context outside CI.
set -euo pipefail
build=$1 work=$2 flags=${3:-} examples=${4:-}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work.install.log" 2>&1 || { cat "$work.install.log"; exit 1; }
examples_dir=
if [[ -n $examples ]]; then
  examples_dir="$work/prefix/share/spatter/examples"
  [[ -f $examples_dir/CMakeLists.txt ]] || { echo "the example hosts' sources are not installed" >&2; exit 1; }
fi
cmake -S "$here" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O3 -DNDEBUG $flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DSPATTER_EXAMPLES_DIR="$examples_dir" \
  >"$work.configure.log" 2>&1 || { cat "$work.configure.log"; exit 1; }
cmake --build "$work/build" -j "$(nproc 2>/dev/null || echo 2)" >"$work.build.log" 2>&1 || { cat "$work.build.log"; exit 1; }
status=0
"$work/build/spatter-consumer" || status=$?
if [[ $status -eq 77 && ${CI:-} == true ]]; then
  echo "CI=true but the minimal host found no headless OpenGL context" >&2
  exit 1
fi
# Runs an example host (its name, then its switches) on the gallery; fails when it wrote no image.
run_example() {
  local name=$1 image="$work/$1${2:-}.png"
  shift
  "$work/build/examples/$name" builtin:gallery --rays "$work/rays.txt" --size 160x120 --out "$image" "$@" ||
    return
  [[ -s $image ]] || { echo "$name $* wrote no image" >&2; return 1; }
}
if [[ $status -eq 0 && -n $examples ]]; then
  printf '0 1.7 4 -0.3 -0.05 -1\n0 1.7 4 0.2 -0.1 -1\n0 1.7 4 0.6 -0.2 -1\n' >"$work/rays.txt"
  run_example spatter-example-deferred &&
    run_example spatter-example-deferred --dbuffer &&
    run_example spatter-example-forward || status=$?
fi
exit $status
