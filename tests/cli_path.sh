#!/usr/bin/env bash
# cli_path.sh: `trigeo path` per the CLI contract - single paths (summary, -o OBJ polyline,
# --json), every endpoint spec (v:, f:, e:, p: snapped to the surface), every method (exact the
# default, proven; straighten and relax unproven without --certify), batches (--pairs, CSV to
# stdout and -o), unreachable endpoints, exit codes 0/1/2 and error format.
# Known answers come from a flat triangulated square written here (geodesic = Euclidean).
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" <<'PY'
import json, math, os, random, subprocess, sys, tempfile
trigeo, meshes = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(*args, stdin=None):
    return subprocess.run([trigeo, "path", *args], capture_output=True, text=True, input=stdin)

tmp = tempfile.mkdtemp()
# a flat square [0,1]^2, jittered 8x8 grid, plus a far second component (a lone triangle)
n = 8
flat, vs, fs = cli_common.flat_square(tmp, 4, n)
base = len(vs) - 3  # the far triangle's first vertex
def pos_face(fi, b): return cli_common.pos_face(vs, fs, fi, b)
def dist(p, q): return math.sqrt(sum((p[c] - q[c]) ** 2 for c in range(3)))

# summary output and the OBJ polyline
obj = os.path.join(tmp, "p.obj")
r = run(flat, "--from", "v:0", "--to", "v:%d" % (n * (n + 1) + n), "-o", obj)
check(r.returncode == 0, "single path exit %d: %s" % (r.returncode, r.stderr))
check("status             converged" in r.stdout and "global             proven" in r.stdout
      and "edge path length   none" in r.stdout, "default (exact) summary: %s" % r.stdout)
lines = open(obj).read().splitlines() if os.path.exists(obj) else []
vrec = [l for l in lines if l.startswith("v ")]
lrec = [l for l in lines if l.startswith("l ")]
check(len(vrec) >= 2 and len(lrec) == 1 and lrec[0].split()[1:] == [str(i + 1) for i in range(len(vrec))],
      "OBJ polyline: %d v records, l record %s" % (len(vrec), lrec))
if vrec:
    p0 = [float(x) for x in vrec[0].split()[1:]]; p1 = [float(x) for x in vrec[-1].split()[1:]]
    check(dist(p0, vs[0]) == 0 and dist(p1, vs[n * (n + 1) + n]) == 0, "OBJ endpoints")

# JSON for every spec kind, every shortening method and the default: length = Euclidean distance
# on the flat square
cases = [("v:3", "v:70"), ("f:10:0.2,0.3,0.5", "f:100:0.6,0.2,0.2"), ("e:31:0.25", "f:5:0.1,0.1,0.8"),
         ("p:0.3,0.4,0.7", "p:0.9,0.1,-2")]
for a, b in cases:
    res = {}
    for method in ("straighten", "relax", None):
        r = run(flat, "--from", a, "--to", b, "--json", *(["--method", method] if method else []))
        check(r.returncode == 0, "%s -> %s %s: exit %d %s" % (a, b, method, r.returncode, r.stderr))
        try: j = json.loads(r.stdout)
        except Exception: check(False, "JSON parse: %r" % r.stdout[:200]); continue
        keys = {"status", "length", "initial_length", "max_angle_defect", "points", "xyz", "faces", "point_count"}
        check(keys <= set(j), "JSON keys: %s" % sorted(j))
        check(len(j["points"]) == len(j["xyz"]) == j["point_count"] == len(j["faces"]) + 1, "JSON array sizes")
        p, q = j["xyz"][0], j["xyz"][-1]
        res[method] = j["length"]
        tol = 1e-6 if method == "relax" else 1e-12
        check(abs(j["length"] - dist(p, q)) <= tol, "%s -> %s %s: length %.17g vs euclidean %.17g" % (a, b, method, j["length"], dist(p, q)))
        if method != "relax":
            check(j["status"] == "converged" and j["max_angle_defect"] <= 1e-10, "certificate %s" % j["max_angle_defect"])
        check(j["global"] == ("proven" if method is None else "unproven") and j["method"] == (method or "exact"),
              "%s -> %s %s: global %s, method %s" % (a, b, method, j["global"], j["method"]))
        if a.startswith("p:"):
            # snapped: the closest point of the plane z = 0 inside the square
            check(abs(p[0] - 0.3) < 1e-12 and abs(p[1] - 0.4) < 1e-12 and p[2] == 0, "p: snapped to %s" % p)
            check(j["points"][0]["kind"] in ("face", "edge", "vertex"), "p: gives a surface point")
        if a.startswith("f:10:"):
            check(j["points"][0] == {"kind": "face", "face": 10, "bary": [0.2, 0.3, 0.5]}, "f: endpoint kept: %s" % j["points"][0])
    if len(res) == 3: check(abs(res["straighten"] - res["relax"]) <= 1e-6 and abs(res["straighten"] - res[None]) <= 1e-12,
                            "methods agree: %s" % res)

# unreachable: the lone triangle is another component
r = run(flat, "--from", "v:0", "--to", "v:%d" % base, "--json")
check(r.returncode == 0, "unreachable exit %d" % r.returncode)
try:
    j = json.loads(r.stdout)
    check(j["status"] == "unreachable" and j["length"] is None and j["point_count"] == 0, "unreachable JSON: %s" % j)
except Exception: check(False, "unreachable JSON parse")

# batch: CSV to stdout and to -o, v and p lines, comments and blank lines
pairs = os.path.join(tmp, "pairs.txt")
plist = [("v", 0, 80), ("p", 3, (0.2, 0.3, 0.5), 90, (0.1, 0.1, 0.8)), ("v", 5, base)]
with open(pairs, "w") as f:
    f.write("# pairs\n\nv 0 80\np 3 0.2 0.3 0.5 90 0.1 0.1 0.8\nv 5 %d\n" % base)
for out in (None, os.path.join(tmp, "out.csv")):
    r = run(flat, "--pairs", pairs, "--method", "straighten", *(["-o", out] if out else []))
    check(r.returncode == 0, "batch exit %d %s" % (r.returncode, r.stderr))
    text = open(out).read() if out else r.stdout
    rows = [l.split(",") for l in text.strip().splitlines()]
    check(rows and rows[0] == ["i", "length", "points", "status", "max_angle_defect", "microseconds", "global"],
          "CSV header %s" % rows[:1])
    check(all(r[6] == "unproven" for r in rows[1:]), "straightening without --certify proves nothing: %s" % rows[1:])
    check(len(rows) == 4, "CSV rows: %d" % len(rows))
    if len(rows) == 4:
        check(abs(float(rows[1][1]) - dist(vs[0], vs[80])) <= 1e-12, "batch v row %s" % rows[1])
        check(abs(float(rows[2][1]) - dist(pos_face(3, (0.2, 0.3, 0.5)), pos_face(90, (0.1, 0.1, 0.8)))) <= 1e-12, "batch p row %s" % rows[2])
        check(rows[3][3] == "unreachable" and rows[3][1] == "inf" and rows[3][2] == "0", "batch unreachable row %s" % rows[3])
        check(all(r[3] in ("converged", "unreachable") and float(r[5]) >= 0 for r in rows[1:]), "batch statuses")

# the default (exact), --method exact and straightening with --certify: proven, with the exact
# length (Euclidean on the flat sheet)
for extra in ([], ["--method", "exact"], ["--method", "straighten", "--certify"]):
    r = run(flat, "--pairs", pairs, *extra)
    rows = [l.split(",") for l in r.stdout.strip().splitlines()]
    check(r.returncode == 0 and len(rows) == 4, "%s: exit %d %s" % (extra, r.returncode, r.stderr))
    if len(rows) == 4:
        check(rows[1][6] == "proven" and rows[2][6] == "proven", "%s: proven rows %s" % (extra, rows[1:3]))
        check(abs(float(rows[2][1]) - dist(pos_face(3, (0.2, 0.3, 0.5)), pos_face(90, (0.1, 0.1, 0.8)))) <= 1e-12,
              "%s: exact length %s" % (extra, rows[2]))
r = run(flat, "--from", "f:3:0.2,0.3,0.5", "--to", "v:80", "--method", "exact", "--json")
check(r.returncode == 0 and '"global": "proven"' in r.stdout, "--json global key: %s" % r.stdout[:300])
r = run(flat, "--from", "f:3:0.2,0.3,0.5", "--to", "v:80", "--method", "straighten")
check(r.returncode == 0 and "global             unproven (locally shortest only; --certify or --method exact proves)"
      in r.stdout and "edge path length   none" not in r.stdout, "straighten summary global line: %s" % r.stdout)
r = run(flat, "--from", "f:3:0.2,0.3,0.5", "--to", "v:80")
check(r.returncode == 0 and "global             proven shortest" in r.stdout, "default summary global line: %s" % r.stdout)

# errors: usage (1), input (2), message format
def err(args, code, needle, stdin=None):
    r = run(*args, stdin=stdin)
    check(r.returncode == code and r.stderr.startswith("trigeo: ") and needle in r.stderr,
          "%s: exit %d (want %d), stderr %r" % (args, r.returncode, code, r.stderr))
err([flat, "--from", "x:1", "--to", "v:1"], 1, "--from")
err([flat, "--from", "v:1"], 1, "--to")
err([flat, "--from", "v:1", "--to", "v:2", "--method", "fast"], 1, "--method")
err([flat, "--pairs", pairs, "--json"], 1, "--json")
err([flat, "--from", "v:1", "--to", "v:99999"], 2, "out of range")
err([flat, "--from", "f:1:0.5,0.6,0.5", "--to", "v:2"], 2, "sum")
err([os.path.join(tmp, "missing.obj"), "--from", "v:1", "--to", "v:2"], 2, "missing.obj")
bad = os.path.join(tmp, "bad.txt")
with open(bad, "w") as f: f.write("v 0 1\nv 0\n")
err([flat, "--pairs", bad], 2, "bad.txt:2:")
with open(bad, "w") as f: f.write("p 0 0.5 0.5 0.5 1 0.2 0.2 0.6\n")
err([flat, "--pairs", bad], 2, "bad.txt:1:")
err([flat, "--pairs", "-"], 2, "-:1:", stdin="v 1 1000000\n")

# a corpus mesh, batch from stdin (the default, exact): every pair proven, certified straight
spot = os.path.join(meshes, "nvd_spot.obj")
r = run(spot, "--pairs", "-", stdin="p 100 0.2 0.3 0.5 4000 0.3 0.3 0.4\nv 0 2000\nv 17 17\n")
rows = [l.split(",") for l in r.stdout.strip().splitlines()[1:]]
check(r.returncode == 0 and len(rows) == 3, "spot batch: exit %d, %d rows" % (r.returncode, len(rows)))
check(all(x[3] == "converged" and float(x[4]) <= 1e-10 and x[6] == "proven" for x in rows), "spot batch certified: %s" % rows)
check(len(rows) == 3 and float(rows[2][1]) == 0.0, "a vertex to itself has length 0: %s" % rows[-1:])

cli_common.finish()
PY
