#!/usr/bin/env bash
# cli_mean.sh: `trigeo mean`, `trigeo path --bezier` and `trigeo sample --cvt` (its errors; its
# numbers are python/tests/test_mean.py's), exit codes 0/1/2 and nothing written on
# error. Known answers on the flat top of a closed plate from ../shared/tools/plate.py (no holes):
# the mean of top points is their weighted average, the Bezier curve of top control points the
# planar one (Bernstein form, by both --bezier-method), both to 1e-12 of the diagonal; the JSON and the summary agree.
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 "$meshes/../tools/plate.py" "$tmp/plate.obj" 20 1000 2.0 > /dev/null || { echo "FAIL plate.py"; exit 1; }
exec /usr/bin/env python3 - "$trigeo" "$tmp" <<'PY'
import json, math, os, random, subprocess, sys
trigeo, tmp = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(cmd, *args, stdin=None):
    return subprocess.run([trigeo, cmd, *args], capture_output=True, text=True, input=stdin)
def write(name, text):
    p = os.path.join(tmp, name)
    open(p, "w").write(text)
    return p
plate = os.path.join(tmp, "plate.obj")
verts = [tuple(map(float, l.split()[1:4])) for l in open(plate) if l.startswith("v ")]
faces = [tuple(int(x) - 1 for x in l.split()[1:4]) for l in open(plate) if l.startswith("f ")]
top = max(v[2] for v in verts)
diag = math.dist((0, 0, 0), (400, 400, top))
top_faces = [i for i, f in enumerate(faces) if all(verts[k][2] == top for k in f)]
rnd = random.Random(4)
def top_point():
    f = rnd.choice(top_faces)
    a = rnd.random(); b = rnd.random() * (1 - a)
    bary = (a, b, 1 - a - b)
    xyz = [sum(bary[k] * verts[faces[f][k]][c] for k in range(3)) for c in range(3)]
    return "f:%d:%r,%r,%r" % (f, *bary), xyz

# the mean: the weighted average; JSON (-o and --json) and the summary agree
specs, xyzs = zip(*[top_point() for _ in range(7)])
weights = [rnd.uniform(0.2, 3.0) for _ in specs]
pts = write("pts.txt", "# seven points of the top\n" + "\n".join(specs) + "\n\n")
wts = write("w.txt", "\n".join(repr(w) for w in weights) + "\n")
avg = [sum(w * x[c] for w, x in zip(weights, xyzs)) / sum(weights) for c in range(3)]
out = os.path.join(tmp, "mean.json")
r = run("mean", plate, "--points", pts, "--weights", wts, "-o", out)
check(r.returncode == 0, "mean exit %d %s" % (r.returncode, r.stderr))
doc = json.load(open(out)) if os.path.exists(out) else {}
got = doc.get("xyz", [math.inf] * 3)
check(math.dist(got, avg) <= 1e-12 * diag, "mean %s vs weighted average %s" % (got, avg))
check(doc.get("status") == "converged" and doc.get("points") == 7, "status converged, 7 points: %s" % doc)
summary = dict(l.split(None, 1) for l in r.stdout.splitlines() if l.strip() and not l.startswith("gradient") and
               not l.startswith("windows"))
check(summary.get("xyz", "").split() == [repr(x) if x != int(x) else repr(x) for x in got] or
      [float(x) for x in summary.get("xyz", "0 0 0").split()] == got, "summary xyz equals the JSON's")
r2 = run("mean", plate, "--points", pts, "--weights", wts, "--json")
check(r2.returncode == 0 and json.loads(r2.stdout)["xyz"] == got, "--json prints the same document")
# unit weights: the plain average; positions ("x y z") read as p: specs
xyz_pts = write("xyz.txt", "\n".join("%r %r %r" % tuple(x) for x in xyzs) + "\n")
r = run("mean", plate, "--points", xyz_pts, "--json")
plain = [sum(x[c] for x in xyzs) / len(xyzs) for c in range(3)]
check(r.returncode == 0 and math.dist(json.loads(r.stdout)["xyz"], plain) <= 1e-12 * diag,
      "x y z points, unit weights: the average (%s)" % r.stderr.strip())
r = run("mean", plate, "--points", "-", "--json", stdin="\n".join(specs) + "\n")
check(r.returncode == 0 and math.dist(json.loads(r.stdout)["xyz"], plain) <= 1e-12 * diag, "--points - reads stdin")

# usage errors (exit 1) and input errors (exit 2, the file and line named), nothing written
two = write("two.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf 1 2 3\nf 4 5 6\n")
cases = [
    (["mean", plate], 1, "missing --points"),
    (["mean", plate, "--points", pts, "--tolerance", "-1"], 1, "--tolerance"),
    (["mean", plate, "--points", pts, "--max-iterations", "0"], 1, "--max-iterations"),
    (["mean", plate, "--points", pts, "--start", "q:1"], 1, "bad --start"),
    (["mean", plate, "--points", pts, "--bogus"], 1, "unknown option"),
    (["mean", plate, "--points", pts, "-o", os.path.join(tmp, "m.txt")], 1, "-o writes the JSON"),
    (["mean", plate, "--points", write("bad.txt", "v:0\nnot a point\n")], 2, "bad.txt:2: bad point"),
    (["mean", plate, "--points", write("empty.txt", "# nothing\n\n")], 2, "no points"),
    (["mean", plate, "--points", write("far.txt", "v:0\nv:99999999\n")], 2, "far.txt:2"),
    (["mean", plate, "--points", pts, "--weights", write("w3.txt", "1\n2\n")], 2, "2 weights for 7 points"),
    (["mean", plate, "--points", pts, "--weights", write("wneg.txt", "1\n-1\n1\n1\n1\n1\n1\n")], 2, "wneg.txt:2: bad weight"),
    (["mean", plate, "--points", pts, "--weights", write("w0.txt", "0\n" * 7)], 2, "every weight is 0"),
    (["mean", plate, "--points", pts, "--weights", write("wnan.txt", "1\n1\nnan\n1\n1\n1\n1\n")], 2, "wnan.txt:3"),
    (["mean", two, "--points", write("comp.txt", "v:0\nv:4\n")], 2, "different components"),
    (["mean", two, "--points", write("one.txt", "v:0\n"), "--start", "v:4"], 2, "different components"),
    (["sample", plate, "--count", "3", "--iterations", "4"], 1, "--iterations applies to --cvt"),
    (["sample", plate, "--count", "3", "--cvt", "--iterations", "0"], 1, "--iterations needs"),
    (["sample", plate, "--count", "99999999", "--cvt"], 2, "--count 99999999"),
    (["path", plate, "--bezier", "v:0;v:1", "--samples", "1"], 1, "--samples"),
    (["path", plate, "--from", "v:0", "--to", "v:1", "--samples", "5"], 1, "--samples applies to --bezier"),
    (["path", plate, "--bezier", "v:0;v:1", "--from", "v:2"], 1, "--bezier excludes"),
    (["path", plate, "--bezier", "v:0;v:1", "--method", "straighten"], 1, "--method"),
    (["path", plate, "--bezier", "v:0;;v:1"], 1, "--bezier"),
    (["path", plate, "--bezier", "v:0;v:1", "--bezier-method", "exact"], 1, "--bezier-method takes paths or logmap"),
    (["path", plate, "--from", "v:0", "--to", "v:1", "--bezier-method", "logmap"], 1, "--bezier-method applies to --bezier"),
    (["path", plate, "--bezier", "v:0;v:1", "-o", os.path.join(tmp, "b.txt")], 1, "-o takes B.obj"),
    (["path", two, "--bezier", "v:0;v:1;v:4"], 2, "different components"),
    (["path", plate, "--bezier", "v:0;v:99999999"], 2, "v:99999999"),
]
for args, code, text in cases:
    target = os.path.join(tmp, {"mean": "never.json", "sample": "never.txt"}.get(args[0], "never.obj"))
    extra = [] if "-o" in args else ["-o", target]
    r = subprocess.run([trigeo, *args, *extra], capture_output=True, text=True)
    check(r.returncode == code and text in r.stderr and not os.path.exists(target),
          "%s: exit %d (want %d), stderr %r should name %r, nothing written" % (" ".join(args[:1] + args[2:]), r.returncode,
                                                                            code, r.stderr.strip(), text))

# the Bezier curve of top control points: the planar one, at t = j / (N - 1)
for degree, how in [(d, m) for d in (1, 2, 3, 4) for m in ("paths", "logmap")]:
    cs, cx = zip(*[top_point() for _ in range(degree + 1)])
    n = 13
    out = os.path.join(tmp, "b%d.obj" % degree)
    r = run("path", plate, "--bezier", ";".join(cs), "--samples", str(n), "-o", out, "--bezier-method", how)
    check(r.returncode == 0, "bezier exit %d %s" % (r.returncode, r.stderr))
    got = [tuple(map(float, l.split()[1:4])) for l in open(out) if l.startswith("v ")] if os.path.exists(out) else []
    line = [l for l in open(out) if l.startswith("l ")] if os.path.exists(out) else []
    worst = math.inf if len(got) != n else 0.0
    for j, p in enumerate(got):
        t = j / (n - 1)
        want = [sum(math.comb(degree, i) * t ** i * (1 - t) ** (degree - i) * cx[i][c] for i in range(degree + 1))
                for c in range(3)]
        worst = max(worst, math.dist(p, want))
    check(worst <= 1e-12 * diag and line == ["l " + " ".join(str(i + 1) for i in range(n)) + "\n"],
          "degree %d (%s): %d samples, %.3g from the planar curve" % (degree, how, len(got), worst))
    r = run("path", plate, "--bezier", ";".join(cs), "--samples", str(n), "--json", "--bezier-method", how)
    doc = json.loads(r.stdout) if r.returncode == 0 else {}
    check([tuple(x) for x in doc.get("xyz", [])] == got and len(doc.get("points", [])) == n and
          len(doc.get("controls", [])) == degree + 1, "degree %d: --json holds the OBJ's points" % degree)
# sample --cvt on the plate: the summary's energies never increase; -o .txt one SPEC a line
out = os.path.join(tmp, "sites.txt")
r = run("sample", plate, "--count", "12", "--cvt", "--iterations", "3", "-o", out)
line = [l for l in r.stdout.splitlines() if l.startswith("energies")]
e = [float(x) for x in line[0].split()[1:]] if line else []
check(r.returncode == 0 and len(e) >= 2 and all(b <= a * (1 + 1e-12) for a, b in zip(e, e[1:])),
      "sample --cvt: exit %d, energies %s (%s)" % (r.returncode, e, r.stderr.strip()))
specs_out = open(out).read().split() if os.path.exists(out) else []
check(len(specs_out) == 12 and all(s.split(":")[0] in ("v", "e", "f") for s in specs_out), "sites file: 12 SPECs")
cli_common.finish()
PY
