#!/usr/bin/env bash
# run_before_after.sh BEFORE_BUILD AFTER_BUILD LARGE MESHES [ROUNDS]: the geodesic engine's
# timings before and after a change, side by side in one run. Each build is a Release build with
# -DTG_BENCH=ON of one commit (e.g. `git worktree add /tmp/before COMMIT` and cmake there). For
# fcpw_kitten.obj, igl_armadillo.obj, openfoam_DTC-scaled.stl.gz and armadillo_1m.ply: exact fields
# (bench_field, 5 random vertex sources, thread CPU seconds) and paths (bench_path: 100 random
# vertex pairs with straightening, the first 40 with the exact method; thread CPU ms), the two
# builds run alternately ROUNDS times (default 3) so that the machine's drift falls on both; the
# table gives the median over rounds of each figure and after / before.
set -euo pipefail
before=${1:?usage: run_before_after.sh BEFORE_BUILD AFTER_BUILD LARGE MESHES [ROUNDS]}
after=${2:?}
large=${3:?}
meshes=${4:?}
rounds=${5:-3}
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
field_s() { # BUILD MESH: the median seconds column of bench_field's row
    "$1/bench/bench_field" "$2" --sources 5 | grep '^|' | tail -n 1 | awk -F'|' '{gsub(/ /, "", $6); print $6}'
}
path_ms() { # BUILD MESH METHOD: bench_path's median ms for the random vertex pairs with METHOD
    "$1/bench/bench_path" "$2" --pairs 100 --reps 1 --relax 0 --exact 40 |
        awk -F'|' -v m="$3" '$4 ~ /vertex/ && $5 ~ m {gsub(/ /, "", $7); print $7; exit}'
}
echo "| mesh | measure | before | after | after / before |"
echo "|---|---|---:|---:|---:|"
for m in "$meshes/fcpw_kitten.obj" "$meshes/igl_armadillo.obj" "$meshes/openfoam_DTC-scaled.stl.gz" "$large/armadillo_1m.ply"; do
    [ -e "$m" ] || { echo "run_before_after.sh: missing $m" >&2; continue; }
    name=$(basename "$m")
    for measure in "field s" "exact path ms" "straighten path ms"; do
        b=() a=()
        for ((r = 0; r < rounds; ++r)); do
            case $measure in
            field*) b+=("$(field_s "$before" "$m")"); a+=("$(field_s "$after" "$m")") ;;
            exact*) b+=("$(path_ms "$before" "$m" exact)"); a+=("$(path_ms "$after" "$m" exact)") ;;
            *) b+=("$(path_ms "$before" "$m" straighten)"); a+=("$(path_ms "$after" "$m" straighten)") ;;
            esac
        done
        mb=$(printf '%s\n' "${b[@]}" | median) ma=$(printf '%s\n' "${a[@]}" | median)
        printf '| %s | %s | %s | %s | %.3f |\n' "$name" "$measure" "$mb" "$ma" "$(awk -v a="$ma" -v b="$mb" 'BEGIN {print a / b}')"
    done
done
