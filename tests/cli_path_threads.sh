#!/usr/bin/env bash
# cli_path_threads.sh: `trigeo path --pairs --threads N` shares the pairs out among N threads and
# writes the rows in input order, each the same as on one thread: 200 pairs of every kind (vertex,
# face point, position; a vertex to itself; pairs in the two components of c3d_beetle, unreachable)
# with the default exact method and with straighten, on 1, 2, 3 and 7 threads (more than the
# machine's cores) and the default (0: one per core), to stdout and to -o: the CSV byte for byte
# but for the microseconds column. More threads than pairs, no pairs; --threads refused like the
# other commands' (exit 1, nothing written), outside --pairs too; a bad pair still named by file
# and line. Ctrl-C under threads: cli_interrupt.sh.
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" <<'PY'
import json, os, random, shutil, subprocess, sys, tempfile
trigeo, meshes = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check

def run(*args, stdin=None):
    return subprocess.run([trigeo, "path", *args], capture_output=True, text=True, input=stdin)

def untimed(csv):
    """The CSV without its microseconds column (the one field that differs between runs)."""
    return "".join(",".join(f for k, f in enumerate(l.split(",")) if k != 5) + "\n" for l in csv.splitlines())

def first_difference(a, b):
    la, lb = a.splitlines(), b.splitlines()
    for k in range(max(len(la), len(lb))):
        x = la[k] if k < len(la) else "<none>"
        y = lb[k] if k < len(lb) else "<none>"
        if x != y:
            return "line %d: %r vs %r" % (k + 1, x, y)
    return "equal"

tmp = tempfile.mkdtemp()
mesh = os.path.join(meshes, "c3d_beetle.obj")  # 1148 vertices, 2 components, non-manifold vertices
info = subprocess.run([trigeo, "info", mesh, "--json"], capture_output=True, text=True)
j = json.loads(info.stdout)
nv, nf = j["vertices"], j["faces"]
lo, hi = [j["bbox_min"][c] for c in range(3)], [j["bbox_max"][c] for c in range(3)]
r = random.Random(32)
lines = []
for k in range(200):
    kind = k % 5
    if k == 17:
        lines.append("v 5 5")  # a vertex to itself
    elif kind < 3:
        lines.append("v %d %d" % (r.randrange(nv), r.randrange(nv)))
    elif kind == 3:
        b = [r.random() + 0.01 for _ in range(6)]
        lines.append("f %d %r %r %r %d %r %r %r" % (r.randrange(nf), b[0] / sum(b[:3]), b[1] / sum(b[:3]), b[2] / sum(b[:3]),
                                                   r.randrange(nf), b[3] / sum(b[3:]), b[4] / sum(b[3:]), b[5] / sum(b[3:])))
    else:
        lines.append("p " + " ".join("%r" % r.uniform(lo[c % 3], hi[c % 3]) for c in range(6)))
pairs = os.path.join(tmp, "pairs.txt")
with open(pairs, "w") as f:
    f.write("# 200 pairs\n" + "\n".join(lines) + "\n")

for method in ([], ["--method", "straighten"]):
    ref = run(mesh, "--pairs", pairs, "--threads", "1", *method)
    rows = ref.stdout.splitlines()
    check(ref.returncode == 0 and len(rows) == 201 and all(l.split(",")[0] == str(k) for k, l in enumerate(rows[1:])),
          "%s --threads 1: exit %d, %d lines, %r" % (method, ref.returncode, len(rows), ref.stderr[-300:]))
    statuses = {l.split(",")[3] for l in rows[1:]}
    check("unreachable" in statuses and "converged" in statuses,
          "%s: the pairs reach both components and converge: statuses %s" % (method, sorted(statuses)))
    want = untimed(ref.stdout)
    for threads in ("2", "3", "7", None):
        args = ["--threads", threads] if threads else []
        got = run(mesh, "--pairs", pairs, *args, *method)
        check(got.returncode == 0 and untimed(got.stdout) == want,
              "%s --threads %s to stdout: exit %d, against --threads 1: %s %r"
              % (method, threads or "(default)", got.returncode, first_difference(untimed(got.stdout), want), got.stderr[-300:]))
        out = os.path.join(tmp, "out_%s.csv" % (threads or "default"))
        got = run(mesh, "--pairs", pairs, *args, "-o", out, *method)
        text = open(out).read() if os.path.exists(out) else ""
        check(got.returncode == 0 and untimed(text) == want,
              "%s --threads %s to -o: exit %d, against --threads 1: %s %r"
              % (method, threads or "(default)", got.returncode, first_difference(untimed(text), want), got.stderr[-300:]))

# more threads than pairs; no pairs at all (the header only)
few = run(mesh, "--pairs", "-", "--threads", "7", stdin="v 0 1\nv 1 2\n")
one = run(mesh, "--pairs", "-", "--threads", "1", stdin="v 0 1\nv 1 2\n")
check(few.returncode == 0 and len(few.stdout.splitlines()) == 3 and untimed(few.stdout) == untimed(one.stdout),
      "2 pairs on 7 threads: exit %d %r, against 1 thread %r" % (few.returncode, few.stdout, one.stdout))
none = run(mesh, "--pairs", "-", "--threads", "3", stdin="# nothing\n")
check(none.returncode == 0 and none.stdout == "i,length,points,status,max_angle_defect,microseconds,global\n",
      "no pairs on 3 threads: exit %d, %r" % (none.returncode, none.stdout))

# --threads refused as the other commands refuse it: exit 1, nothing written
out = os.path.join(tmp, "never.csv")
for bad in ("x", "-1", "257", "1.5", "", "2x"):
    r2 = run(mesh, "--pairs", pairs, "--threads", bad, "-o", out)
    check(r2.returncode == 1 and "--threads needs a number in 0..256 (0 = all cores), not '%s'" % bad in r2.stderr
          and not os.path.exists(out), "--threads %r: exit %d, %r, output %s"
          % (bad, r2.returncode, r2.stderr, "written" if os.path.exists(out) else "absent"))
r2 = run(mesh, "--pairs", pairs, "--threads")
check(r2.returncode == 1 and "--threads needs a value" in r2.stderr, "--threads without a value: exit %d %r" % (r2.returncode, r2.stderr))
r2 = run(mesh, "--from", "v:0", "--to", "v:1", "--threads", "2")
check(r2.returncode == 1 and "--threads applies to --pairs" in r2.stderr, "--threads with --from: exit %d %r" % (r2.returncode, r2.stderr))
r2 = run(mesh, "--through", "v:0;v:1", "--threads", "2")
check(r2.returncode == 1 and "--threads applies to --pairs" in r2.stderr, "--threads with --through: exit %d %r" % (r2.returncode, r2.stderr))

# a bad pair is named by its file and line, whatever the threads, and nothing is written
bad = os.path.join(tmp, "bad.txt")
with open(bad, "w") as f:
    f.write("\n".join(lines[:150]) + "\nv 0 %d\n" % nv + "\n".join(lines[150:]) + "\n")
for threads in ("1", "2", "7"):
    r2 = run(mesh, "--pairs", bad, "--threads", threads, "-o", out)
    check(r2.returncode == 2 and r2.stderr.startswith("trigeo: %s:151: " % bad) and not os.path.exists(out),
          "a bad pair on line 151, --threads %s: exit %d, %r, output %s"
          % (threads, r2.returncode, r2.stderr, "written" if os.path.exists(out) else "absent"))

shutil.rmtree(tmp)
cli_common.finish()
PY
