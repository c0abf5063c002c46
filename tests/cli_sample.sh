#!/usr/bin/env bash
# cli_sample.sh: `trigeo sample` and `trigeo field --labels` per the CLI contract (run under the
# sanitizers too, unlike the Python suite): on a flat square with a far second component, whose
# distances are Euclidean, the labels are the nearest source's (checked against distances computed
# here), FPS picks the other component second (+inf is farthest), the sample file feeds `field
# --sources`, the outputs agree with each other, the boundaries' crossings are equidistant from their
# two sources (OBJ and JSON), render draws cells and boundaries, and bad input exits 1 or 2 with no
# file.
set -u
trigeo=${TG_TRIGEO:?}
exec /usr/bin/env python3 - "$trigeo" <<'PY'
import math, os, subprocess, sys, tempfile
trigeo = sys.argv[1]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(*args):
    return subprocess.run([trigeo, *args], capture_output=True, text=True)
def rows(path):
    with open(path) as f:
        return [line.strip().split(",") for line in f.readlines()[1:]]

tmp = tempfile.mkdtemp()
flat, vs, fs = cli_common.flat_square(tmp, 11, 8)
far = len(vs) - 3  # the lone far triangle's first vertex
src = [0, 40, 80]
lab = os.path.join(tmp, "l.csv")
r = run("field", flat, "--from", ";".join("v:%d" % s for s in src), "--labels", "-o", lab)
check(r.returncode == 0, "field --labels: %s" % r.stderr)
bad = 0
for v, l, d in rows(lab):
    v, l, d = int(v), int(l), float(d)
    if v >= far:
        bad += not (l == -1 and math.isinf(d))
        continue
    e = [math.dist(vs[v], vs[s]) for s in src]
    best = min(e)
    bad += not (abs(d - best) <= 1e-12 * (1 + best) and abs(e[l] - best) <= 1e-12 * (1 + best))
check(bad == 0, "labels: %d vertices not at their nearest source" % bad)

smp, fld = os.path.join(tmp, "s.txt"), os.path.join(tmp, "f.csv")
r = run("sample", flat, "--count", "6", "--start", "v:0", "-o", smp, "--field", fld)
check(r.returncode == 0, "sample: %s" % r.stderr)
samples = [int(s[2:]) for s in open(smp).read().split()]
check(len(samples) == 6 and samples[0] == 0 and samples[1] == far, "sample order %s (far %d)" % (samples, far))
lab2 = os.path.join(tmp, "l2.csv")
r = run("field", flat, "--sources", smp, "--labels", "-o", lab2)
check(r.returncode == 0 and rows(lab2) == rows(fld), "sample --field equals field --sources --labels")
ply = os.path.join(tmp, "f.ply")
r = run("sample", flat, "--count", "3", "--seed", "2", "--field", ply, "-o", os.path.join(tmp, "s.csv"))
check(r.returncode == 0 and os.path.getsize(ply) > 0, "sample --field .ply: %s" % r.stderr)

# boundaries: OBJ and JSON agree; every crossing is equidistant (here Euclidean) from its two cells'
# sources; render draws the cells and the boundaries
bo, bj = os.path.join(tmp, "b.obj"), os.path.join(tmp, "b.json")
r1 = run("field", flat, "--from", ";".join("v:%d" % s for s in src), "--labels", "--boundaries", bo)
r2 = run("field", flat, "--from", ";".join("v:%d" % s for s in src), "--labels", "--boundaries", bj, "-o", lab)
check(r1.returncode == 0 and r2.returncode == 0, "field --boundaries: %s %s" % (r1.stderr, r2.stderr))
import json
polys = json.load(open(bj))["polylines"]
objv = [list(map(float, l.split()[1:])) for l in open(bo) if l.startswith("v ")]
check(len(polys) >= 2 and sum(len(p["points"]) for p in polys) == len(objv), "OBJ and JSON: %d polylines" % len(polys))
worst = 0
for p in polys:
    a, b = p["cells"]
    for x, sp in zip(p["points"], p["surface"]):
        if sp.startswith("e:"):
            da, db = math.dist(x, vs[src[a]]), math.dist(x, vs[src[b]])
            worst = max(worst, abs(da - db) / max(da, db))
check(0 <= worst <= 1e-9, "boundary crossings equidistant (worst %g)" % worst)
png = os.path.join(tmp, "v.png")
lply = os.path.join(tmp, "l.ply")
r = run("field", flat, "--from", ";".join("v:%d" % s for s in src), "--labels", "-o", lply)
r = run("render", flat, "--labels", lply, "--boundaries", bo, "--size", "64x48", "-o", png)
check(r.returncode == 0 and open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n", "render --labels --boundaries: %s" % r.stderr)

for args, code in [(["render", flat, "--labels", flat, "-o", os.path.join(tmp, "bad.png")], 2),
                   (["render", flat, "--labels", lply, "--field", lply, "-o", os.path.join(tmp, "bad.png")], 1),
                   (["field", flat, "--from", "v:0", "--boundaries", os.path.join(tmp, "bad.obj")], 1),
                   (["field", flat, "--from", "v:0", "--labels", "--boundaries", os.path.join(tmp, "bad.txt")], 1),(["sample", flat, "--count", "0"], 1), (["sample", flat], 1),
                   (["sample", flat, "--count", "3", "--start", "v:1", "--seed", "2"], 1),
                   (["sample", flat, "--count", "3", "--start", "f:0:1,0,0"], 1),
                   (["sample", flat, "--count", "3", "-o", os.path.join(tmp, "bad.npy")], 1),
                   (["sample", flat, "--count", "100000", "-o", os.path.join(tmp, "bad.txt")], 2),
                   (["sample", flat, "--count", "3", "--start", "v:100000", "-o", os.path.join(tmp, "bad.txt")], 2),
                   (["field", flat, "--from", "v:0", "--labels", "-o", os.path.join(tmp, "bad.npy")], 1)]:
    r = run(*args)
    check(r.returncode == code and r.stderr.startswith("trigeo: "), "%s: exit %d (%s)" % (args[1:], r.returncode, r.stderr.strip()))
check(not any(f.startswith("bad") for f in os.listdir(tmp)), "no partial output")
# more samples than vertices: the message says how many there are (the flat square's and the far
# triangle's, every one used by a face)
r = run("sample", flat, "--count", "100000")
check(r.returncode == 2 and "has only %d vertices used by faces" % len(vs) in r.stderr, "--count 100000: %s" % r.stderr)
# --threads N: the same samples and field for every N > 1, and here one thread's (no ties on spot)
spot = os.path.join(os.environ["TG_MESHES_DIR"], "nvd_spot.obj")
got = {}
for t in ("1", "2", "3"):
    o, fo = os.path.join(tmp, "s%s.txt" % t), os.path.join(tmp, "sf%s.csv" % t)
    r = run("sample", spot, "--count", "12", "--threads", t, "-o", o, "--field", fo, "--quiet")
    got[t] = (open(o).read(), open(fo).read()) if r.returncode == 0 else (r.stderr, "")
check(got["2"] == got["3"], "sample --threads 2 and 3 differ")
check(got["1"][0] == got["2"][0] and got["1"][0].count("v:") == 12, "sample --threads 2 vs 1: %r vs %r" % (got["2"][0], got["1"][0]))
r = run("sample", spot, "--count", "3", "--threads", "many")
check(r.returncode == 1 and "--threads" in r.stderr, "sample --threads many: exit %d %r" % (r.returncode, r.stderr))

cli_common.finish()
PY
