#!/usr/bin/env bash
# The consumer build: installs spatter's build tree into a temporary prefix, configures and builds
# the project beside this script against it (find_package(spatter)), and runs its minimal host.
#   run.sh BUILD_DIR WORK_DIR [EXTRA_FLAGS]
# Exit 0 on success, 77 (skipped) when the host finds no headless OpenGL context outside CI.
set -euo pipefail
build=$1 work=$2 flags=${3:-}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work.install.log" 2>&1 || { cat "$work.install.log"; exit 1; }
cmake -S "$here" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" >"$work.configure.log" 2>&1 ||
  { cat "$work.configure.log"; exit 1; }
cmake --build "$work/build" >"$work.build.log" 2>&1 || { cat "$work.build.log"; exit 1; }
status=0
"$work/build/spatter-consumer" || status=$?
if [[ $status -eq 77 && ${CI:-} == true ]]; then
  echo "CI=true but the minimal host found no headless OpenGL context" >&2
  exit 1
fi
exit $status
