#!/usr/bin/env bash
# run_field.sh BUILD_DIR LARGE_DIR MESHES_DIR: exact geodesic distance fields, trigeo side by side
# with CGAL's Surface_mesh_shortest_path (bench/peers/field_cgal, same process, same mesh and source
# vertex, largest relative difference) and VTP (../shared/peers/vtp/run.sh: the authors' code, its
# own propagation time and window count), one core each; then the batch throughput.
# Times: trigeo and CGAL thread CPU seconds; VTP its own clock() of the propagation.
set -euo pipefail
build=${1:?usage: run_field.sh BUILD_DIR LARGE_DIR MESHES_DIR}
large=${2:?}
meshes=${3:?}
here=$(cd "$(dirname "$0")" && pwd)
vtp=$here/../../shared/peers/vtp/run.sh
cgal=$build/bench/peers/field_cgal
echo "| mesh | faces | source | trigeo s | trigeo windows | trigeo MiB | CGAL s | CGAL MiB | max rel diff (CGAL) | VTP s | VTP windows | CGAL / trigeo | VTP / trigeo |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
row() { # MESH VERTEX [--no-cgal]
  local mesh=$1 v=$2 extra=${3:-}
  local r
  r=$(OMP_NUM_THREADS=1 "$cgal" "$mesh" --vertex "$v" $extra | tail -n 1)
  if grep -q "refuses" <<<"$r"; then # CGAL's Surface_mesh takes only manifold meshes
    r=$(OMP_NUM_THREADS=1 "$cgal" "$mesh" --vertex "$v" --no-cgal | tail -n 1 | sed 's/| - | - | - |$/| refused (non-manifold) | - | - |/')
  fi
  local vt vw
  if out=$(bash "$vtp" "$mesh" "$v" 2>&1); then
    vt=$(sed -n 's/.*propagation step took \([0-9.e+-]*\) seconds.*/\1/p' <<<"$out")
    vw=$(sed -n 's/.*total interval propagation number \([0-9]*\).*/\1/p' <<<"$out")
    vw=$(awk -v w="$vw" 'BEGIN{printf "%.2fM", w / 1e6}')
  else
    vt="fails"; vw="$(grep -o 'list link error\|Assertion.*' <<<"$out" | head -n 1 | cut -c1-40)"
    [ -n "$vw" ] || vw="exit $(tail -n 1 <<<"$out" | grep -o 'exit [0-9]*' | head -n 1)"
  fi
  awk -F'|' -v vt="$vt" -v vw="$vw" '{
    t = $5 + 0; c = $8; r1 = (c !~ /^ *[0-9.]+ *$/ || t == 0) ? "-" : sprintf("%.1fx", c / t);
    r2 = (vt ~ /^[0-9.]+$/ && t > 0) ? sprintf("%.2fx", vt / t) : "-";
    sub(/ *$/, "", $0); printf "%s %s | %s | %s | %s |\n", $0, vt, vw, r1, r2 }' <<<"$r"
}
row "$meshes/fcpw_kitten.obj" 0
row "$meshes/c3d_stanford-bunny.obj" 0
row "$meshes/igl_armadillo.obj" 0
row "$meshes/openfoam_terrain.stl.gz" 0
row "$meshes/openfoam_DTC-scaled.stl.gz" 0
row "$meshes/openfoam_buildings.obj.gz" 106529
[ -s "$large/armadillo_1m.ply" ] && row "$large/armadillo_1m.ply" 0 --no-cgal
echo
echo "Batch (tg_geodesic_field_batch, 16 random vertex sources, fields per second):"
echo
echo "| mesh | faces | 1 thread | 2 threads |"
echo "|---|---|---|---|"
for m in "$meshes/fcpw_kitten.obj" "$meshes/igl_armadillo.obj"; do
  "$build/bench/bench_field" "$m" --batch 16
done
