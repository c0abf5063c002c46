#!/usr/bin/env bash
# run_path.sh BUILD LARGE MESHES: geodesic paths. For fcpw_kitten.obj, igl_armadillo.obj
# and armadillo_1m.ply: 1000 random vertex pairs and 1000 random face-point pairs (and, on
# armadillo_1m.ply, 1000 face-point pairs at most 10% of the bounding-box diagonal apart), timed
# per path (thread CPU time, median of TG_BENCH_REPS runs per pair, default 3) with the
# straightener; the exact method (the default) and straightening with --certify on the first
# TG_BENCH_EXACT_PAIRS pairs of each set (default 200); the seed's relaxation on the first
# TG_BENCH_RELAX_PAIRS pairs of each set (default 10; on armadillo_1m.ply only in the near set,
# its long paths take minutes each). One table; a footer line per mesh with setup time and memory.
set -euo pipefail
build=${1:?usage: run_path.sh BUILD LARGE MESHES}
large=${2:?usage: run_path.sh BUILD LARGE MESHES}
meshes=${3:?usage: run_path.sh BUILD LARGE MESHES}
pairs=${TG_BENCH_PATH_PAIRS:-1000}
reps=${TG_BENCH_REPS:-3}
relax=${TG_BENCH_RELAX_PAIRS:-10}
bp=$build/bench/bench_path
exact=${TG_BENCH_EXACT_PAIRS:-200}
printf '| mesh | faces | set | method | pairs | median ms | p90 ms | max ms | median wall ms | initial path median ms | initial share | converged | max certificate rad | median points | globally shortest |\n'
printf '|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n'
footer=()
for m in "$meshes/fcpw_kitten.obj" "$meshes/igl_armadillo.obj" "$large/armadillo_1m.ply"; do
    [ -e "$m" ] || { echo "run_path.sh: missing $m" >&2; continue; }
    extra=()
    case "$m" in *armadillo_1m.ply) extra=(--near 0.1 --relax-near-only) ;; *) extra=(--near 0.1) ;; esac
    out=$("$bp" "$m" --pairs "$pairs" --reps "$reps" --relax "$relax" --exact "$exact" "${extra[@]}")
    grep '^|' <<<"$out"
    footer+=("$(grep '^#' <<<"$out")")
done
printf '%s\n' "${footer[@]}"

# CGAL's Surface_mesh_shortest_path answers one pair only after propagating from the source over
# the whole mesh (build_sequence_tree): its per-pair time is that of one source's field
# (bench/peers/field_cgal, vertex 0, thread CPU). Beside it, the exact method's median per random
# vertex pair in the same run (bench_path --exact on TG_BENCH_CGAL_PAIRS pairs, default 20).
cgal=$build/bench/peers/field_cgal
cpairs=${TG_BENCH_CGAL_PAIRS:-20}
if [ -x "$cgal" ]; then
    printf '\n| mesh | faces | CGAL s per pair | trigeo exact median ms per pair (random vertex pairs) | CGAL / trigeo |\n|---|---:|---:|---:|---:|\n'
    for m in "$meshes/c3d_stanford-bunny.obj" "$meshes/igl_armadillo.obj" "$meshes/fcpw_kitten.obj"; do
        c=$(OMP_NUM_THREADS=1 "$cgal" "$m" --vertex 0 2>/dev/null | tail -n 1 | awk -F'|' '{gsub(/ /, "", $8); print $8}')
        row=$("$bp" "$m" --pairs "$cpairs" --reps 1 --relax 0 --exact "$cpairs" | grep '| vertex pairs | exact (default) |')
        faces=$(awk -F'|' '{gsub(/ /, "", $3); print $3}' <<<"$row")
        t=$(awk -F'|' '{gsub(/ /, "", $7); print $7}' <<<"$row")
        awk -v m="$(basename "$m")" -v f="$faces" -v c="$c" -v t="$t" \
            'BEGIN { printf "| %s | %s | %s | %s | %.0fx |\n", m, f, c, t, (c * 1000) / t }'
    done
fi
