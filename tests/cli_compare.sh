#!/usr/bin/env bash
# cli_compare.sh: `trigeo compare` per the CLI contract: a jittered flat grid against itself moved
# by h along its normal (Hausdorff h exactly, both ways; every vertex at h), the JSON and the text
# summary agree, the same numbers on 1 and 2 threads, -o writes a PLY that render --field draws and
# a CSV of the vertices' distances, and bad input (a broken file, a mesh without faces, bad
# tolerances, -o naming an input) exits 1 or 2 with a message and no file.
set -u
trigeo=${TG_TRIGEO:?}
exec /usr/bin/env python3 - "$trigeo" <<'PY'
import json, math, os, subprocess, sys, tempfile
trigeo = sys.argv[1]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(*args):
    return subprocess.run([trigeo, *args], capture_output=True, text=True)

tmp = tempfile.mkdtemp()
flat, vs, fs = cli_common.flat_square(tmp, 5, 9)
h = 0.0173
moved = os.path.join(tmp, "moved.obj")
with open(moved, "w") as f:
    for v in vs: f.write("v %.17g %.17g %.17g\n" % (v[0], v[1], v[2] + h))
    for t in fs: f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))

r = run("compare", flat, moved, "--json", "--symmetric", "--tolerance", "1e-11", "--threads", "1")
check(r.returncode == 0, "compare --json: %s" % r.stderr)
j = json.loads(r.stdout)
for k in ("a_to_b", "b_to_a"):
    d = j[k]
    check(d["lower"] <= h <= d["upper"], "%s: %r not in [%r, %r]" % (k, h, d["lower"], d["upper"]))
    # 1e-11 is below the distances' own rounding here (flat_square has a far triangle at 5..6):
    # raised to 4 * 2^-40 * (largest coordinate + larger diagonal)
    check(d["upper"] - d["lower"] <= d["tolerance"] == 4 * 2**-40 * (6 + math.sqrt(6**2 + 6**2 + 5**2)),
          "%s: width %r, tolerance %r" % (k, d["upper"] - d["lower"], d["tolerance"]))
    check(d["mean"][0] <= h <= d["mean"][1] and d["rms"][0] <= h <= d["rms"][1], "%s: mean %r rms %r" % (k, d["mean"], d["rms"]))
    check(abs(math.dist(d["point"], d["closest_point"]) - d["distance"]) <= 1e-15, "%s: point %r closest %r distance %r" % (k, d["point"], d["closest_point"], d["distance"]))
check(j["symmetric"]["lower"] == max(j["a_to_b"]["lower"], j["b_to_a"]["lower"]), "symmetric lower %r" % j["symmetric"])
r2 = run("compare", flat, moved, "--json", "--symmetric", "--tolerance", "1e-11", "--threads", "2")
j2 = json.loads(r2.stdout)
del j["seconds"], j2["seconds"]
check(j == j2, "1 thread %r\n2 threads %r" % (j, j2))
r = run("compare", flat, moved, "--tolerance", "1e-11")
check(r.returncode == 0 and ("[%s, " % repr(j["a_to_b"]["lower"])) in r.stdout, "text summary: %s %s" % (r.stdout, r.stderr))

# -o: a PLY for render --field, a CSV of every vertex's distance
ply, csv, png = os.path.join(tmp, "d.ply"), os.path.join(tmp, "d.csv"), os.path.join(tmp, "d.png")
r = run("compare", flat, moved, "-o", ply, "--quiet")
check(r.returncode == 0 and r.stdout == "" and os.path.getsize(ply) > 0, "-o .ply: %r %s" % (r.stdout, r.stderr))
r = run("render", ply, "--field", ply, "-o", png)
check(r.returncode == 0 and os.path.getsize(png) > 0, "render --field: %s" % r.stderr)
r = run("compare", flat, moved, "-o", csv, "--quiet")
rows = [l.split(",") for l in open(csv).read().split()[1:]]
check(len(rows) == len(vs) and all(abs(float(d) - h) <= 1e-15 for _, d in rows), "csv distances %r" % rows[:3])

# bad input: exit 1 (usage) or 2 (input), a message, no file
def refused(args, code, words, what):
    out = os.path.join(tmp, "never.ply")
    r = run("compare", *args)
    check(r.returncode == code and all(w in r.stderr for w in words) and not os.path.exists(out),
          "%s: exit %d (expected %d): %s" % (what, r.returncode, code, r.stderr))
broken = os.path.join(tmp, "broken.obj")
with open(broken, "w") as f: f.write("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
nofaces = os.path.join(tmp, "nofaces.obj")
with open(nofaces, "w") as f: f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
never = os.path.join(tmp, "never.ply")
refused([flat, broken, "-o", never], 2, ["trigeo: " + broken + ":3"], "broken B")
refused([broken, flat, "-o", never], 2, ["trigeo: " + broken + ":3"], "broken A")
refused([flat, os.path.join(tmp, "missing.obj"), "-o", never], 2, ["missing.obj"], "missing B")
refused([nofaces, flat, "-o", never], 2, [nofaces, "no faces"], "A without faces")
refused([flat, nofaces, "-o", never], 2, [nofaces, "no faces"], "B without faces")
for t in ("nan", "-1", "0", "abc", "inf", "1e999"):
    refused([flat, moved, "--tolerance", t, "-o", never], 1, ["--tolerance"], "--tolerance " + t)
refused([flat, moved, "--threads", "-1"], 1, ["--threads"], "--threads -1")
refused([flat], 1, ["two meshes"], "one mesh")
refused([flat, moved, moved], 1, ["unexpected"], "three meshes")
refused([flat, moved, "-o", os.path.join(tmp, "x.obj")], 1, [".ply or .csv"], "-o .obj")
before = open(flat, "rb").read(), open(moved, "rb").read()
refused([flat, moved, "-o", flat], 1, ["-o"], "-o naming A")
refused([flat, moved, "-o", moved], 1, ["-o"], "-o naming B")
check((open(flat, "rb").read(), open(moved, "rb").read()) == before, "the inputs are unchanged")
cli_common.finish()
PY
