#!/usr/bin/env bash
# run_closest.sh BUILD LARGE MESHES: point-mesh closest point, trigeo against Embree 3 (rtcPointQuery
# with a double-precision callback) and CGAL (AABB_tree), on the same query files, in one table.
#
# For each mesh, `bench_closest gen` writes six query files of N points (env TG_BENCH_QUERIES,
# default 100000): on the surface, within 1% of the bounding-box diagonal, uniform in the 1.5x box;
# each in random order and Morton-sorted. Each program builds its structure REPS times (env
# TG_BENCH_REPS, default 3) and runs every file REPS times per thread count; the table shows
# medians: ns per query with 1 and 2 threads (OpenMP over a loop of single queries, in file
# order), build seconds (single-threaded for Embree; trigeo uses all cores in that column, and a
# second table gives its single-threaded build: `bench_closest build`), bytes per triangle of
# the structure (excluding the mesh). "batch" is tg_bvh_closest_batch, which reorders the queries
# itself. "max rel" is the largest |d_peer - d_trigeo| / d_trigeo (d >= 1e-9 diagonal) over all
# queries: how far the peers' distances are from trigeo's exact ones.
set -euo pipefail
build=${1:?usage: run_closest.sh BUILD LARGE MESHES}
large=${2:?usage: run_closest.sh BUILD LARGE MESHES}
meshes=${3:?usage: run_closest.sh BUILD LARGE MESHES}
n=${TG_BENCH_QUERIES:-100000}
reps=${TG_BENCH_REPS:-3}
bc=$build/bench/bench_closest
emb=$build/bench/peers/closest_embree
cg=$build/bench/peers/closest_cgal
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

sets="surface.random surface.sorted near.random near.sorted box.random box.sorted"
builds=$tmp/builds.txt
: > "$builds"
printf '| mesh | faces | queries | trigeo 1T | trigeo 2T | trigeo batch 1T | trigeo batch 2T | Embree 1T | Embree 2T | CGAL 1T | CGAL 2T | build s trigeo / Embree / CGAL | bytes/tri trigeo / Embree / CGAL | max rel Embree / CGAL |\n'
printf '|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|\n'
for m in "$meshes/fcpw_kitten.obj" "$meshes/igl_armadillo.obj" "$large/armadillo_1m.ply" "$large/bunny_loop_1m.ply"; do
    [ -e "$m" ] || { echo "run_closest.sh: missing $m" >&2; continue; }
    name=$(basename "$m")
    diag=$("$bc" gen "$m" "$tmp/q" "$n")
    files=()
    for s in $sets; do files+=("$tmp/q.$s.q"); done
    "$bc" run "$m" "$reps" "${files[@]}" > "$tmp/trigeo.txt"
    "$bc" build "$m" "$reps" >> "$builds"
    : > "$tmp/embree.txt"
    : > "$tmp/cgal.txt"
    [ -x "$emb" ] && "$emb" "$m" "$reps" "${files[@]}" > "$tmp/embree.txt"
    [ -x "$cg" ] && "$cg" "$m" "$reps" "${files[@]}" > "$tmp/cgal.txt"
    for s in $sets; do
        f=$tmp/q.$s.q
        read -r _ _ faces tb tbytes t1 t2 tb1 tb2 <<< "$(grep " $f " "$tmp/trigeo.txt")"
        e1=- e2=- eb=- ebytes=- c1=- c2=- cb=- cbytes=- erel=- crel=-
        if line=$(grep " $f " "$tmp/embree.txt"); then
            read -r _ _ _ eb ebytes e1 e2 <<< "$line"
            erel=$("$bc" compare "$f.trigeo.d" "$f.embree.d" "$diag" | cut -d' ' -f1)
        fi
        if line=$(grep " $f " "$tmp/cgal.txt"); then
            read -r _ _ _ cb cbytes c1 c2 <<< "$line"
            crel=$("$bc" compare "$f.trigeo.d" "$f.cgal.d" "$diag" | cut -d' ' -f1)
        fi
        printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s / %s / %s | %s / %s / %s | %s / %s |\n' \
            "$name" "$faces" "${s/./ }" "$t1" "$t2" "$tb1" "$tb2" "$e1" "$e2" "$c1" "$c2" "$tb" "$eb" "$cb" \
            "$tbytes" "$ebytes" "$cbytes" "$erel" "$crel"
    done
done
echo
echo "ns per query (medians of $reps), $n queries per set; build seconds are medians of $reps builds."
echo
echo "trigeo BVH build by thread count (bench_closest build: medians of $reps builds; CPU = process CPU time, least = the least CPU time of the $reps):"
echo
printf '| mesh | faces | threads | wall s | CPU s | least CPU s |\n'
printf '|---|---:|---:|---:|---:|---:|\n'
while read -r _ path faces threads wall cpu least; do
    printf '| %s | %s | %s | %s | %s | %s |\n' "$(basename "$path")" "$faces" "$threads" "$wall" "$cpu" "$least"
done < "$builds"
