#!/usr/bin/env bash
# cli_logmap.sh: `trigeo logmap` (-o CSV, .npy, .ply, '-'), `trigeo render --logmap`, exit codes
# 0/1/2 and no output file on error. Known answer: on the flat top of a closed plate from
# ../shared/tools/plate.py (no holes), every top vertex's (u, v) are its plane coordinates about
# the source (1e-12 of the diagonal), angle 0 along --ref; distances equal `trigeo field`'s. On
# corpus meshes: `trigeo trace` along each sampled vertex's (theta, r) ends at that vertex.
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 "$meshes/../tools/plate.py" "$tmp/plate.obj" 20 1000 2.0 > /dev/null || { echo "FAIL plate.py"; exit 1; }
exec /usr/bin/env python3 - "$trigeo" "$tmp" <<'PY'
import csv, math, os, struct, subprocess, sys
trigeo, tmp = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(cmd, *args):
    return subprocess.run([trigeo, cmd, *args], capture_output=True, text=True)
plate = os.path.join(tmp, "plate.obj")
verts = [tuple(map(float, l.split()[1:4])) for l in open(plate) if l.startswith("v ")]
top = max(v[2] for v in verts)
diag = math.dist((0, 0, 0), (400, 400, top))

# the top is flat and convex: every top vertex is reached straight, so (u, v) = (x - sx, y - sy)
src = (123.0, 211.0, top)
out = os.path.join(tmp, "lm.csv")
r = run("logmap", plate, "--from", "p:%r,%r,%r" % src, "--ref", "1,0,0", "-o", out)
check(r.returncode == 0, "logmap exit %d %s" % (r.returncode, r.stderr))
rows = list(csv.DictReader(open(out))) if os.path.exists(out) else []
check(len(rows) == len(verts) and list(rows[0].keys()) == ["vertex", "r", "theta", "u", "v"] if rows else False,
      "CSV header vertex,r,theta,u,v and one row a vertex")
worst = 0.0
for row, v in zip(rows, verts):
    if v[2] != top: continue
    dx, dy = v[0] - src[0], v[1] - src[1]
    u, w, rr, th = float(row["u"]), float(row["v"]), float(row["r"]), float(row["theta"])
    worst = max(worst, abs(u - dx), abs(w - dy), abs(rr - math.hypot(dx, dy)))
    check(0.0 <= th < 2 * math.pi, "theta %r in [0, 2 pi)" % th)
check(worst <= 1e-12 * diag, "flat top: (u, v) off the plane coordinates by %.3g of the diagonal" % (worst / diag))

# r is the field's, bit for bit
fout = os.path.join(tmp, "f.csv")
r = run("field", plate, "--from", "p:%r,%r,%r" % src, "-o", fout)
check(r.returncode == 0, "field exit %d" % r.returncode)
fd = [float(l.split(",")[1]) for l in open(fout).read().split("\n")[1:] if l] if os.path.exists(fout) else []
check(fd == [float(row["r"]) for row in rows], "logmap r equals field's distances")

# .npy: (n, 4) float64 r, theta, u, v; .ply for render --logmap; '-' writes CSV to stdout
npy = os.path.join(tmp, "lm.npy")
check(run("logmap", plate, "--from", "v:5", "-o", npy).returncode == 0, "logmap -o .npy")
data = open(npy, "rb").read() if os.path.exists(npy) else b""
check(data[:6] == b"\x93NUMPY" and b"'shape': (%d, 4)" % len(verts) in data[:128] and b"<f8" in data[:128],
      ".npy header: (n, 4) float64")
r = run("logmap", plate, "--from", "v:5", "-o", "-")
check(r.returncode == 0 and r.stdout.startswith("vertex,r,theta,u,v\n") and r.stdout.count("\n") == len(verts) + 1,
      "-o - prints the CSV")
ply, png = os.path.join(tmp, "lm.ply"), os.path.join(tmp, "lm.png")
check(run("logmap", plate, "--from", "v:5", "-o", ply).returncode == 0, "logmap -o .ply")
r = run("render", plate, "--logmap", ply, "--checker", "20", "--size", "64x48", "-o", png)
check(r.returncode == 0 and os.path.getsize(png) > 0, "render --logmap: exit %d %s" % (r.returncode, r.stderr))
r = run("render", plate, "--logmap", npy, "-o", os.path.join(tmp, "bad.png"))
check(r.returncode == 2 and not os.path.exists(os.path.join(tmp, "bad.png")), "render --logmap of a non-PLY: exit 2")

# bad input: exit 1 (usage: unparsable values) or 2 (refused by the mesh), never a file
bad = os.path.join(tmp, "bad.csv")
for args, code, word in [(["--from", "v:5", "--ref", "0,0,0"], 1, "ref"),
                         (["--from", "v:5", "--ref", "nan,0,1"], 1, "ref"),
                         (["--from", "f:3:0.2,0.3,0.5", "--ref", "0,0,1"], 2, "perpendicular"),
                         (["--from", "v:99999"], 2, "out of range"),
                         (["--from", "e:999999:0.5"], 2, "999999"),
                         (["--from", "v:5", "--max-distance", "-1"], 1, "max-distance"),
                         (["--from", "v:5", "--transport", "0,0,0"], 1, "transport"),
                         (["--from", "v:5", "--transport", "1,2"], 1, "transport"),
                         (["--from", "f:3:0.2,0.3,0.5", "--transport", "0,0,1"], 2, "perpendicular")]:
    r = run("logmap", plate, *args, "-o", bad)
    check(r.returncode == code and word in r.stderr and r.stderr.startswith("trigeo: ") and not os.path.exists(bad),
          "%s: exit %d (want %d), stderr %r" % (args, r.returncode, code, r.stderr))
r = run("logmap", plate, "--from", "v:5", "-o", os.path.join(tmp, "x.txt"))
check(r.returncode == 1 and "extension" in r.stderr, "-o .txt refused")
link = os.path.join(tmp, "link.csv")
os.symlink(plate, link)
r = run("logmap", plate, "--from", "v:5", "-o", link)
check(r.returncode == 1 and "same file" in r.stderr and open(plate).read(5) == open(link).read(5),
      "-o the mesh itself (through a link) refused")
# beyond --max-distance: r inf, theta 0, u and v inf
r = run("logmap", plate, "--from", "v:5", "--max-distance", "50", "-o", "-")
far = [l.split(",") for l in r.stdout.split("\n")[1:] if l and l.split(",")[1] == "inf"]
check(len(far) > 0 and all(f[2] == "0" and f[3] == "inf" and f[4] == "inf" for f in far), "unreached rows: inf,0,inf,inf")

# corpus meshes, end to end through the CLI and independent of the log map's code: where the exact
# path (`trigeo path --json`) from the source to a vertex bends at no vertex, `trigeo trace` from
# the source at the log map's angle theta for its distance r ends at that vertex (1e-9 of the
# diagonal); theta and r are read back from the CSV (shortest round-trip decimals)
import json, random
rng = random.Random(5)
checked = 0
for name, srcv in [("nvd_spot.obj", 11), ("igl_decimated-knight.off", 40), ("cgal_pinion.off", 7)]:
    mesh = os.path.join(os.environ["TG_MESHES_DIR"], name)
    out = os.path.join(tmp, "c.csv")
    r = run("logmap", mesh, "--from", "v:%d" % srcv, "-o", out)
    check(r.returncode == 0, "%s: logmap exit %d %s" % (name, r.returncode, r.stderr))
    rows = [row for row in csv.DictReader(open(out))] if os.path.exists(out) else []
    info = json.loads(run("info", mesh, "--json").stdout)
    d = math.dist(info["bbox_min"], info["bbox_max"])
    cand = [row for row in rows if row["r"] != "inf" and float(row["r"]) > 0]
    for row in rng.sample(cand, min(30, len(cand))):
        k = int(row["vertex"])
        pj = json.loads(run("path", mesh, "--from", "v:%d" % srcv, "--to", "v:%d" % k, "--json").stdout)
        if any(pt["kind"] == "vertex" for pt in pj["points"][1:-1]):
            continue  # bends at a vertex: the trace would have to pass through it exactly
        tr = run("trace", mesh, "--from", "v:%d" % srcv, "--angle", row["theta"], "--length", row["r"], "--json")
        tj = json.loads(tr.stdout) if tr.returncode == 0 else None
        want = pj["xyz"][-1]
        got = tj["end"]["xyz"] if tj else None
        check(got is not None and math.dist(got, want) <= 1e-9 * d,
              "%s v:%d -> v:%d: trace(theta %s, r %s) ends %.3g of the diagonal away" %
              (name, srcv, k, row["theta"], row["r"], math.dist(got, want) / d if got else float("inf")))
        checked += 1
check(checked >= 15, "traced %d straight log map directions on the corpus (want >= 15)" % checked)

# spot scaled by 1e100 and 1e-100 (refused before: "zero area"), --ref of any length
spot_lines = open(os.path.join(os.environ["TG_MESHES_DIR"], "oded_spot_low_resolution.obj")).read().splitlines()
base = {}
for scale in (1.0, 1e100, 1e-100):
    path = os.path.join(tmp, "spot_%g.obj" % scale)
    with open(path, "w") as f:
        for l in spot_lines:
            f.write("v " + " ".join(repr(float(x) * scale) for x in l.split()[1:4]) + "\n" if l.startswith("v ") else l + "\n")
    for start in ("v:0", "e:301:0.37", "f:77:0.2,0.3,0.5"):
        for ref in ([], ["--ref", "1,0,0"], ["--ref", "1e200,0,0"], ["--ref", "1e-200,0,0"]):
            out = os.path.join(tmp, "s.csv")
            r = run("logmap", path, "--from", start, *ref, "-o", out, "--quiet")
            rows = [(float(row["r"]) / scale, float(row["theta"])) for row in csv.DictReader(open(out))] if r.returncode == 0 else None
            key = (start, "none" if not ref else "x")  # every --ref is (1, 0, 0) times something
            if scale == 1.0 and ref[1:] in ([], ["1,0,0"]): base[key] = rows
            want = base.get(key)
            worst = max((abs(a[0] - b[0]) / max(b[0], 1e-300) + min(abs(a[1] - b[1]), 2 * math.pi - abs(a[1] - b[1]))
                         for a, b in zip(rows, want) if b[0] != math.inf), default=0.0) if rows and want else math.inf
            check(rows is not None and want is not None and len(rows) == len(want) and worst <= 1e-9,
                  "spot x%g logmap --from %s %s: %s, %.3g from the unscaled map (%s)" %
                  (scale, start, " ".join(ref), "exit %d" % r.returncode, worst, r.stderr.strip()))
# --threads N: the same bytes for every N > 1 (0 = all cores), within 1e-12 of one thread's
spot = os.path.join(os.environ["TG_MESHES_DIR"], "nvd_spot.obj")
outs = {}
for t in ("1", "2", "3", "0"):
    o = os.path.join(tmp, "thr%s.csv" % t)
    r = run("logmap", spot, "--from", "f:40:0.2,0.3,0.5", "--threads", t, "-o", o, "--quiet")
    outs[t] = open(o).read() if r.returncode == 0 else r.stderr
check(outs["2"] == outs["3"] == outs["0"], "logmap --threads 2, 3 and 0 give different files")
l1 = [l.split(",") for l in outs["1"].split()[1:]]
l2 = [l.split(",") for l in outs["2"].split()[1:]]
check(len(l1) == len(l2) == 2930 and all(abs(float(a[1]) - float(b[1])) <= 1e-12 * float(a[1]) and
                                         abs(float(a[2]) - float(b[2])) <= 1e-9 for a, b in zip(l1, l2)),
      "logmap --threads 2 vs 1: %d, %d rows" % (len(l1), len(l2)))
for bad_t in ("x", "-1", "257"):
    r = run("logmap", spot, "--from", "v:0", "--threads", bad_t, "-o", os.path.join(tmp, "no.csv"))
    check(r.returncode == 1 and "--threads" in r.stderr and not os.path.exists(os.path.join(tmp, "no.csv")),
          "logmap --threads %s: exit %d %r" % (bad_t, r.returncode, r.stderr))

cli_common.finish()
PY
