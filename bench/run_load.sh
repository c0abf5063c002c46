#!/usr/bin/env bash
# run_load.sh BUILD LARGE MESHES: loading speed and bytes/face vs fgets/strtod and fscanf baselines.
set -euo pipefail
build=$1 large=$2 meshes=$3
"$build/bench/bench_load" "$large/armadillo_1m.ply" "$large/bunny_loop_1m.ply" \
    "$meshes/fcpw_kitten.obj" "$meshes/igl_armadillo.obj"
