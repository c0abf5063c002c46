#!/usr/bin/env bash
# run_trace.sh BUILD LARGE MESHES: geodesic tracing. On armadillo_1m.ply (and igl_armadillo.obj):
# TG_BENCH_TRACES random traces (default 10000) of length one tenth of the bounding-box diagonal,
# time per face crossed (one trace at a time, thread CPU; then the batch call on one thread and on
# all), beside the exact path method's time per face crossed between the same start and end
# points for the first TG_BENCH_TRACE_EXACT traces (default 200), in the same run.
set -euo pipefail
build=${1:?usage: run_trace.sh BUILD LARGE MESHES}
large=${2:?usage: run_trace.sh BUILD LARGE MESHES}
meshes=${3:?usage: run_trace.sh BUILD LARGE MESHES}
traces=${TG_BENCH_TRACES:-10000}
exact=${TG_BENCH_TRACE_EXACT:-200}
for m in "$meshes/igl_armadillo.obj" "$large/armadillo_1m.ply"; do
    [ -e "$m" ] || { echo "run_trace.sh: missing $m" >&2; continue; }
    "$build/bench/bench_trace" "$m" --traces "$traces" --exact "$exact"
    echo
done
