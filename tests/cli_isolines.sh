#!/usr/bin/env bash
# cli_isolines.sh: `trigeo field --isolines` (levels as a list or a count; -o OBJ groups and JSON),
# the points checked independently by `trigeo field --at` at the written surface points (the
# level, 1e-9 relative), circles about a source on a flat square, `trigeo render --from` drawing
# them, and bad input (negative, NaN, empty levels; wrong output): exit 2 or 1, no file.
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" <<'PY'
import json, math, os, subprocess, sys, tempfile
trigeo, meshes = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(cmd, *args):
    return subprocess.run([trigeo, cmd, *args], capture_output=True, text=True)

tmp = tempfile.mkdtemp()
flat, vs, fs = cli_common.flat_square(tmp, 5, 10)
src = "f:97:0.2,0.3,0.5"
s = cli_common.pos_face(vs, fs, 97, (0.2, 0.3, 0.5))

# JSON: every point at its level by the field's own point query, and on the circle (1e-12)
out = os.path.join(tmp, "iso.json")
levels = [0.05, 0.15, 0.2]
r = run("field", flat, "--from", src, "--isolines", ",".join(repr(l) for l in levels), "-o", out, "--quiet")
check(r.returncode == 0, "json: exit %d %s" % (r.returncode, r.stderr))
doc = json.load(open(out))
check(doc["levels"] == levels, "levels %r" % doc["levels"])
pts = os.path.join(tmp, "pts.txt")
want = []
with open(pts, "w") as f:
    for pl in doc["polylines"]:
        check(len(pl["points"]) == len(pl["surface"]) == len(pl["faces"]) >= 2, "polyline arrays")
        for p, sp in zip(pl["points"], pl["surface"]):
            f.write(sp + "\n")
            want.append(pl["value"])
            r0 = math.hypot(p[0] - s[0], p[1] - s[1])
            check(abs(r0 - pl["value"]) <= 1e-12, "flat: a point %.3g off its circle" % abs(r0 - pl["value"]))
r = run("field", flat, "--from", src, "--at", pts)
got = [float(x) for x in r.stdout.split()]
check(r.returncode == 0 and len(got) == len(want), "field --at: exit %d, %d values" % (r.returncode, len(got)))
bad = [(g, w) for g, w in zip(got, want) if not abs(g - w) <= 1e-9 * w]
check(not bad, "%d points off their level: %r" % (len(bad), bad[:3]))
check(sum(1 for pl in doc["polylines"] if pl["closed"]) >= 1, "a closed circle")

# OBJ with a count: N groups, 'l' records indexing 'v' records; on a corpus mesh
mesh = os.path.join(meshes, "cgal_nefertiti.off")
obj = os.path.join(tmp, "iso.obj")
r = run("field", mesh, "--from", "v:3", "--isoline-count", "8", "-o", obj, "--quiet")
check(r.returncode == 0, "obj: exit %d %s" % (r.returncode, r.stderr))
lines = open(obj).read().splitlines()
nv = sum(1 for l in lines if l.startswith("v "))
groups = [l for l in lines if l.startswith("g level_")]
ls = [l for l in lines if l.startswith("l ")]
check(len(groups) == 8 and len(ls) >= 8, "%d groups, %d polylines" % (len(groups), len(ls)))
check(all(1 <= int(i) <= nv for l in ls for i in l.split()[1:]), "'l' indices in range")

# a number is always a level, as in Python's Mesh.isolines (the help and the README say so): "1"
# and "1.0" are the level 1; a count of levels below the max is asked for by name
js = os.path.join(tmp, "one.json")
got = {}
for opt, text in (("--isolines", "1"), ("--isolines", "1.0"), ("--isoline-count", "1")):
    r = run("field", mesh, "--from", "v:3", opt, text, "-o", js, "--quiet")
    got[opt + " " + text] = json.load(open(js))["levels"] if r.returncode == 0 else r.stderr
check(got["--isolines 1"] == [1.0] and got["--isolines 1.0"] == [1.0] and len(got["--isoline-count 1"]) == 1
      and got["--isoline-count 1"][0] > 1.0, "--isolines 1, 1.0 and --isoline-count 1: %r" % got)
r = run("field", mesh, "--from", "v:3", "--isolines", "1", "--isoline-count", "2", "-o", js)
check(r.returncode == 1 and "not both" in r.stderr, "levels and a count: exit %d %r" % (r.returncode, r.stderr))
for bad in ("0", "4097", "2.5", "x"):
    r = run("field", mesh, "--from", "v:3", "--isoline-count", bad, "-o", os.path.join(tmp, "never.json"))
    check(r.returncode == 2 and "--isoline-count" in r.stderr and not os.path.exists(os.path.join(tmp, "never.json")),
          "--isoline-count %s: exit %d %r" % (bad, r.returncode, r.stderr.strip()))

# render draws the exact isolines of --from
png = os.path.join(tmp, "iso.png")
r = run("render", mesh, "--from", "v:3", "-o", png, "--size", "160x120")
check(r.returncode == 0 and os.path.getsize(png) > 0, "render --from: exit %d %s" % (r.returncode, r.stderr))
r = run("render", mesh, "--field", os.path.join(tmp, "nope.ply"), "--isolines", obj, "-o", png + "2.png")
check(r.returncode == 2 and not os.path.exists(png + "2.png"), "render: a missing field file: exit %d" % r.returncode)

# levels equal to vertex distances on a closed mesh (the curves pass through those vertices): every
# polyline closed, every point on its level by `trigeo field --at` at the written surface points
mesh = os.path.join(meshes, "nvd_bob_tri.obj")
csv = os.path.join(tmp, "bob.csv")
r = run("field", mesh, "--from", "v:1556", "-o", csv, "--quiet")
check(r.returncode == 0, "bob field: exit %d" % r.returncode)
dist = [float(l.split(",")[1]) for l in open(csv).read().split()[1:]]
levels = [dist[i] for i in (17, 2023, 4099)]
out = os.path.join(tmp, "bob.json")
r = run("field", mesh, "--from", "v:1556", "--isolines", ",".join(repr(l) for l in levels), "-o", out, "--quiet")
check(r.returncode == 0, "bob isolines: exit %d %s" % (r.returncode, r.stderr))
doc = json.load(open(out))
opened = [pl for pl in doc["polylines"] if not pl["closed"]]
check(doc["polylines"] and not opened, "levels at vertices: %d of %d polylines open" % (len(opened), len(doc["polylines"])))
with open(pts, "w") as f:
    want = []
    for pl in doc["polylines"]:
        for sp in pl["surface"]:
            f.write(sp + "\n")
            want.append(pl["value"])
r = run("field", mesh, "--from", "v:1556", "--at", pts)
got = [float(x) for x in r.stdout.split()]
bad = [(g, w) for g, w in zip(got, want) if not abs(g - w) <= 1e-9 * w]
check(r.returncode == 0 and len(got) == len(want) and not bad,
      "levels at vertices: %d of %d points off their level: %r" % (len(bad), len(want), bad[:3]))

# bad input: exit 2 (levels) or 1 (usage), no file, the reason named
for bad, code, why in [("-0.1", 2, "level"), ("0.1,nan", 2, "level"), ("", 2, "level"), ("0.1,,0.2", 2, "level"),
                       ("inf", 2, "level"), ("3,x", 2, "level")]:
    o = os.path.join(tmp, "bad.obj")
    r = run("field", flat, "--from", src, "--isolines", bad, "-o", o)
    check(r.returncode == code and not os.path.exists(o) and why in r.stderr,
          "--isolines %r: exit %d, %s" % (bad, r.returncode, r.stderr.strip()))
for args, code in [(["--isolines", "3", "-o", os.path.join(tmp, "x.ply")], 1), (["--isolines", "3"], 1),
                   (["--isolines", "3", "--labels", "-o", os.path.join(tmp, "x.obj")], 1)]:
    r = run("field", flat, "--from", src, *args)
    check(r.returncode == code and not os.path.exists(os.path.join(tmp, "x.obj")), "%r: exit %d" % (args, r.returncode))
cli_common.finish()
PY
