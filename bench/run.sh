#!/usr/bin/env bash
# run.sh BUILD_DIR LARGE_DIR: runs every bench/run_*.sh in name order; each prints its tables.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:?usage: run.sh BUILD_DIR LARGE_DIR}
large=${2:?usage: run.sh BUILD_DIR LARGE_DIR}
for s in "$here"/run_*.sh; do
  [ -e "$s" ] || continue
  echo "### $(basename "$s")"
  bash "$s" "$build" "$large" "$here/../../shared/meshes"
done
