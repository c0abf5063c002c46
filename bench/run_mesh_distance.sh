#!/usr/bin/env bash
# run_mesh_distance.sh BUILD LARGE MESHES: the certified Hausdorff distance (tg_mesh_distance) of
# armadillo_1m (LARGE/armadillo_1m.ply, make_large_meshes.sh) against igl_armadillo
# (MESHES/igl_armadillo.obj) and the other way, and of the elephants both ways (coarse over fine:
# the closest pass over A's vertices is tiny there, compare with the reverse row), to 1e-6 of
# the diagonal, against one closest-point pass over A's vertices (the target: at most 10x),
# beside the sampled estimate libigl and MeshLab report (10^6 points uniform by area on A;
# TG_BENCH_SAMPLES), on 1 and 2 threads, medians of TG_BENCH_REPS runs (default 3). One table
# row per pair and thread count.
set -euo pipefail
build=${1:?usage: run_mesh_distance.sh BUILD LARGE MESHES}
large=${2:?usage: run_mesh_distance.sh BUILD LARGE MESHES}
meshes=${3:?usage: run_mesh_distance.sh BUILD LARGE MESHES}
reps=${TG_BENCH_REPS:-3}
samples=${TG_BENCH_SAMPLES:-1000000}
bm=$build/bench/bench_mesh_distance
pairs="$large/armadillo_1m.ply:$meshes/igl_armadillo.obj
$meshes/cgal_refined_elephant.off:$meshes/cgal_elephant.off
$meshes/cgal_elephant.off:$meshes/cgal_refined_elephant.off
$meshes/igl_armadillo.obj:$large/armadillo_1m.ply"
printf '| A -> B | threads | closest pass s | certified s | ratio | pieces | queries / vertex | Hausdorff [lower, upper] | width / diag | sampled max | sampled below lower / diag | sampled s | mean [lo, hi] | sampled mean |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n'
for pair in $pairs; do
  a=${pair%%:*} b=${pair##*:}
  [ -f "$a" ] && [ -f "$b" ] || { echo "skipping $a -> $b (missing)" >&2; continue; }
  for t in 1 2; do
    out=$("$bm" "$a" "$b" --threads "$t" --repeat "$reps" --samples "$samples")
    v() { printf '%s\n' "$out" | awk -v k="$1" '$1 == k { $1 = ""; sub(/^ /, ""); print; exit }'; }
    printf '| %s -> %s | %s | %s | %s | %s | %s | %s | [%s, %s] | %s | %s | %s | %s | %s | %s |\n' \
      "$(basename "$a")" "$(basename "$b")" "$t" "$(v closest_pass_s)" "$(v certified_s)" "$(v certified_over_pass)" \
      "$(v pieces)" "$(v queries | awk '{print $2}' | tr -d '(')" "$(v hausdorff_lower)" "$(v hausdorff_upper)" \
      "$(v width_rel)" "$(v sampled_max)" "$(v sampled_below_lower_rel)" "$(v sampled_s)" "$(v mean)" "$(v sampled_mean)"
  done
done
