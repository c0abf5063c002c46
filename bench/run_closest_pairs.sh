#!/usr/bin/env bash
# run_closest_pairs.sh BUILD MESH ROUNDS: trigeo against Embree per query class on one mesh, for a
# machine shared with other work. Each round runs `bench_closest run` and the Embree comparator
# once (one pass per file and mode) back to back on the same six query files (those of
# run_closest.sh); the table shows, per class, the least ns per query of the ROUNDS rounds of each
# program (other work can only slow a run down) and the ratios trigeo / Embree, for tg_bvh_closest
# in a loop (1T) and for tg_bvh_closest_batch (batch 1T), one thread. N queries per file (env
# TG_BENCH_QUERIES, default 100000). Each pass is timed by the CPU time of the thread that runs it
# (TG_BENCH_CLOCK=thread, the default here; TG_BENCH_CLOCK=wall for wall time): on a machine whose
# cores are oversubscribed a process gets a varying fraction of a core, which wall time would
# count against it. TG_BENCH_BEFORE=BUILD2 (optional): a second build's bench_closest (say, of the
# previous commit) runs in each round too, between the two, and the table gains its loop and batch
# columns and the ratios after / before.
set -euo pipefail
build=${1:?usage: run_closest_pairs.sh BUILD MESH ROUNDS}
mesh=${2:?usage: run_closest_pairs.sh BUILD MESH ROUNDS}
rounds=${3:-5}
n=${TG_BENCH_QUERIES:-100000}
export TG_BENCH_CLOCK=${TG_BENCH_CLOCK:-thread} TG_BENCH_THREADS=1
bc=$build/bench/bench_closest
emb=$build/bench/peers/closest_embree
[ -x "$emb" ] || { echo "run_closest_pairs.sh: no $emb (make bench-deps, then configure with -DTG_BENCH=ON)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sets="surface.random surface.sorted near.random near.sorted box.random box.sorted"
"$bc" gen "$mesh" "$tmp/q" "$n" > /dev/null
files=()
for s in $sets; do files+=("$tmp/q.$s.q"); done
: > "$tmp/t.txt"
: > "$tmp/e.txt"
before=${TG_BENCH_BEFORE:-}
: > "$tmp/b.txt"
for r in $(seq "$rounds"); do
    "$bc" run "$mesh" 1 "${files[@]}" >> "$tmp/t.txt"
    [ -z "$before" ] || "$before/bench/bench_closest" run "$mesh" 1 "${files[@]}" >> "$tmp/b.txt"
    "$emb" "$mesh" 1 "${files[@]}" >> "$tmp/e.txt"
done
python3 - "$tmp" "$(basename "$mesh")" "$rounds" $sets <<'PY'
import os, sys
tmp, name, rounds, sets = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
with_before = os.path.getsize(tmp + "/b.txt") > 0
def least(path, col):
    best = {}
    for line in open(path):
        f = line.split()
        key = f[1].rsplit("/", 1)[-1][2:-2]  # q.surface.random.q -> surface.random
        v = float(f[col])
        best[key] = min(best.get(key, v), v)
    return best
loop, batch, emb = least(tmp + "/t.txt", 5), least(tmp + "/t.txt", 7), least(tmp + "/e.txt", 5)
head = "| mesh | queries | trigeo 1T | trigeo batch 1T | Embree 1T | 1T / Embree | batch / Embree |"
rule = "|---|---|---:|---:|---:|---:|---:|"
if with_before:
    bloop, bbatch = least(tmp + "/b.txt", 5), least(tmp + "/b.txt", 7)
    head += " before 1T | before batch | 1T after / before | batch after / before |"
    rule += "---:|---:|---:|---:|"
print(head)
print(rule)
for s in sets:
    row = "| %s | %s | %.0f | %.0f | %.0f | %.2f | %.2f |" % (name, s.replace(".", " "), loop[s], batch[s], emb[s],
                                                           loop[s] / emb[s], batch[s] / emb[s])
    if with_before:
        row += " %.0f | %.0f | %.2f | %.2f |" % (bloop[s], bbatch[s], loop[s] / bloop[s], batch[s] / bbatch[s])
    print(row)
print("\nns per query (%s time), least of %s rounds (each program once per round, back to back)."
      % ("thread CPU" if os.environ["TG_BENCH_CLOCK"].startswith("t") else "wall", rounds))
PY
