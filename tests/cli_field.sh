#!/usr/bin/env bash
# cli_field.sh: `trigeo field` per the CLI contract - CSV (to a file and to stdout) and PLY output
# (a per-vertex double property 'distance' that `trigeo render --field` draws), every source spec
# (v:, f:, e:, p: snapped to the surface), several sources, unreachable vertices (inf), the
# distance limit, exit codes 0/1/2 and the error format. Known answers come from a flat
# triangulated square written here (geodesic distance = Euclidean distance).
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" <<'PY'
import math, os, random, struct, subprocess, sys, tempfile
trigeo, meshes = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(*args, cmd="field"):
    return subprocess.run([trigeo, cmd, *args], capture_output=True, text=True)

tmp = tempfile.mkdtemp()
# a flat square [0,1]^2, jittered 8x8 grid, plus a far second component (a lone triangle)
n = 8
flat, vs, fs = cli_common.flat_square(tmp, 5, n)
base = len(vs) - 3  # the far triangle's first vertex
def pos_face(fi, b): return cli_common.pos_face(vs, fs, fi, b)
def pos_edge(h, t):
    f, k = divmod(h, 3)
    a, b = vs[fs[f][k]], vs[fs[f][(k + 1) % 3]]
    return [(1 - t) * a[c] + t * b[c] for c in range(3)]
def dist(p, q): return math.sqrt(sum((p[c] - q[c]) ** 2 for c in range(3)))
def parse_csv(text):
    rows = [l.split(",") for l in text.strip().splitlines()]
    if not rows or rows[0] != ["vertex", "distance"]: return None
    return [float(r[1]) for r in rows[1:]]

def expect_field(spec, points, out=None):
    args = [flat, "--from", spec, "--csv", out or "-"]
    r = run(*args)
    check(r.returncode == 0, "%s: exit %d %s" % (spec, r.returncode, r.stderr))
    d = parse_csv(open(out).read() if out else r.stdout)
    check(d is not None and len(d) == len(vs), "%s: CSV header and %d rows" % (spec, len(d) if d else -1))
    if not d: return None
    worst = 0
    for v in range(len(vs)):
        if v >= base:
            check(d[v] == math.inf, "%s: vertex %d of the other component: %s" % (spec, v, d[v]))
            continue
        want = min(dist(vs[v], p) for p in points)
        worst = max(worst, abs(d[v] - want))
    check(worst <= 1e-12, "%s: max |field - euclidean| %.3g" % (spec, worst))
    return d

expect_field("v:0", [vs[0]])
expect_field("f:10:0.2,0.3,0.5", [pos_face(10, (0.2, 0.3, 0.5))], os.path.join(tmp, "f.csv"))
expect_field("e:31:0.25", [pos_edge(31, 0.25)])
expect_field("p:0.3,0.4,0.7", [(0.3, 0.4, 0.0)])
expect_field("v:3;f:100:0.6,0.2,0.2;e:7:0.5", [vs[3], pos_face(100, (0.6, 0.2, 0.2)), pos_edge(7, 0.5)])

# the summary without --csv; the distance limit
r = run(flat, "--from", "v:0")
check(r.returncode == 0 and "vertices" in r.stdout and "(%d reached)" % base in r.stdout, "summary: %r" % r.stdout)
r = run(flat, "--from", "v:0", "--csv", "-", "--max-distance", "0.5")
d = parse_csv(r.stdout) if r.returncode == 0 else None
check(d is not None and all((x == math.inf) == (dist(vs[v], vs[0]) > 0.5) for v, x in enumerate(d) if v < base),
      "--max-distance 0.5: inf exactly beyond")

# PLY output: the mesh plus a double property 'distance'; render draws it
ply = os.path.join(tmp, "field.ply")
r = run(flat, "--from", "v:12", "-o", ply)
check(r.returncode == 0 and os.path.exists(ply), "-o PLY: exit %d %s" % (r.returncode, r.stderr))
if os.path.exists(ply):
    data = open(ply, "rb").read()
    end = data.find(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    props = [l.split()[-1] for l in header.splitlines() if l.startswith("property double")]
    check("format binary_little_endian" in header and props == ["x", "y", "z", "distance"], "PLY header: %r" % header)
    nvtx = int([l for l in header.splitlines() if l.startswith("element vertex")][0].split()[-1])
    check(nvtx == len(vs), "PLY vertex count %d" % nvtx)
    vals = struct.unpack_from("<%dd" % (4 * nvtx), data, end)
    dd = vals[3::4]
    check(all(abs(dd[v] - dist(vs[v], vs[12])) <= 1e-12 for v in range(base)) and all(x == math.inf for x in dd[base:]),
          "PLY distances")
    png = os.path.join(tmp, "field.png")
    r = run(flat, "--field", ply, "-o", png, cmd="render")
    check(r.returncode == 0 and os.path.getsize(png) > 1000, "render --field: exit %d %s" % (r.returncode, r.stderr))


# --max-distance 0 means distance 0 (not "no limit"): only the source
r = run(flat, "--from", "v:0", "--csv", "-", "--max-distance", "0")
d = parse_csv(r.stdout) if r.returncode == 0 else None
check(d is not None and d[0] == 0 and all(x == math.inf for x in d[1:]), "--max-distance 0: only the source")

# --sources FILE: one field per source, a matrix in .npy (float64, rows = sources) and .csv
def read_npy(path):
    data = open(path, "rb").read()
    check(data[:6] == b"\x93NUMPY" and data[6] == 1, "npy magic and version")
    hlen = struct.unpack_from("<H", data, 8)[0]
    header = data[10:10 + hlen].decode()
    check((10 + hlen) % 64 == 0 and header.endswith("\n") and "'descr': '<f8'" in header, "npy header %r" % header)
    shape = tuple(int(x) for x in header.split("(")[1].split(")")[0].split(",") if x.strip())
    count = 1
    for x in shape: count *= x
    return shape, list(struct.unpack_from("<%dd" % count, data, 10 + hlen))
srcs = os.path.join(tmp, "sources.txt")
with open(srcs, "wb") as fh:
    fh.write(b"\xef\xbb\xbf# a comment, a BOM, CRLF and blank lines\r\nv:0\r\n\n  f:10:0.2,0.3,0.5  \ne:31:0.25\n")
pts = [vs[0], pos_face(10, (0.2, 0.3, 0.5)), pos_edge(31, 0.25)]
npy = os.path.join(tmp, "m.npy")
r = run(flat, "--sources", srcs, "-o", npy, "--threads", "2")
check(r.returncode == 0, "--sources .npy: exit %d %s" % (r.returncode, r.stderr))
if r.returncode == 0:
    shape, vals = read_npy(npy)
    check(shape == (3, len(vs)), "matrix shape %s" % (shape,))
    worst = max(abs(vals[i * len(vs) + v] - dist(vs[v], pts[i])) for i in range(3) for v in range(base))
    check(worst <= 1e-12 and all(vals[i * len(vs) + v] == math.inf for i in range(3) for v in range(base, len(vs))),
          "matrix rows = fields of each source (worst %.3g)" % worst)
    r2 = run(flat, "--from", "f:10:0.2,0.3,0.5", "-o", os.path.join(tmp, "one.npy"))
    shape1, one = read_npy(os.path.join(tmp, "one.npy"))
    check(r2.returncode == 0 and shape1 == (len(vs),) and one == vals[len(vs):2 * len(vs)], "row 1 == the single field")
mcsv = os.path.join(tmp, "m.csv")
r = run(flat, "--sources", srcs, "-o", mcsv)
rows = [l.split(",") for l in open(mcsv).read().splitlines()] if r.returncode == 0 else []
check(len(rows) == 3 and all(len(x) == len(vs) for x in rows) and float(rows[2][5]) == vals[2 * len(vs) + 5],
      "--sources .csv: 3 rows of %d" % len(vs))
# a bad line names file and line; no output file, not even a temporary one
bad = os.path.join(tmp, "bad.txt")
open(bad, "w").write("v:0\nv:1\nv:99999\n")
out = os.path.join(tmp, "bad.npy")
err_r = run(flat, "--sources", bad, "-o", out)
check(err_r.returncode == 2 and (bad + ":3:") in err_r.stderr, "bad source line: %d %r" % (err_r.returncode, err_r.stderr))
check(not [f for f in os.listdir(tmp) if f.startswith("bad.npy")], "no partial output: %s" % os.listdir(tmp))

# --at POINTS: the distance at surface points (SPEC or "x y z" a line), one a line
atf = os.path.join(tmp, "points.txt")
open(atf, "w").write("f:10:0.2,0.3,0.5\n# a comment\n0.3 0.4 0.7\ne:31:0.25\nv:5\n")
want = [dist(vs[12], p) for p in (pos_face(10, (0.2, 0.3, 0.5)), (0.3, 0.4, 0.0), pos_edge(31, 0.25), vs[5])]
r = run(flat, "--from", "v:12", "--at", atf)
got = [float(x) for x in r.stdout.split()] if r.returncode == 0 else []
check(len(got) == 4 and all(abs(a - b) <= 1e-12 for a, b in zip(got, want)), "--at: %s vs %s (%s)" % (got, want, r.stderr))
r = run(flat, "--from", "v:12", "--at", atf, "-o", os.path.join(tmp, "at.npy"))
if r.returncode == 0:
    shape, vals = read_npy(os.path.join(tmp, "at.npy"))
    check(shape == (4,) and vals == got, "--at .npy: %s %s" % (shape, vals))
else:
    check(False, "--at -o .npy: exit %d %s" % (r.returncode, r.stderr))
open(atf, "w").write("v:1\n1 2\n")
err_r = run(flat, "--from", "v:12", "--at", atf)
check(err_r.returncode == 2 and (atf + ":2:") in err_r.stderr, "--at bad line: %d %r" % (err_r.returncode, err_r.stderr))

# a terminal on stderr: a progress line once the work passes about a second; Ctrl-C (SIGINT) stops
# it with exit 130 and leaves no file, not even the temporary one
import pty, signal, time, select
kitten = os.path.join(meshes, "fcpw_kitten.obj")
many = os.path.join(tmp, "many.txt")
open(many, "w").write("".join("v:%d\n" % (997 * i) for i in range(40)))
outm = os.path.join(tmp, "stopped.npy")
master, slave = pty.openpty()
proc = subprocess.Popen([trigeo, "field", kitten, "--sources", many, "-o", outm, "--threads", "1"],
                        stdout=subprocess.DEVNULL, stderr=slave)
os.close(slave)
seen, t0 = b"", time.time()
while b"%" not in seen and time.time() - t0 < 120 and proc.poll() is None:
    r, _, _ = select.select([master], [], [], 0.5)
    if r:
        try: seen += os.read(master, 4096)
        except OSError: break
check(b"field:" in seen and b"fields" in seen, "progress line on a terminal: %r" % seen[-200:])
proc.send_signal(signal.SIGINT)
try: rc = proc.wait(timeout=60)
except subprocess.TimeoutExpired: proc.kill(); rc = None
try:
    while True:
        r, _, _ = select.select([master], [], [], 0.2)
        if not r: break
        chunk = os.read(master, 4096)
        if not chunk: break
        seen += chunk
except OSError: pass
os.close(master)
check(rc == 130 and b"interrupted" in seen, "Ctrl-C: exit %s, stderr %r" % (rc, seen[-200:]))
check(not [f for f in os.listdir(tmp) if f.startswith("stopped.npy")], "Ctrl-C: no partial output: %s" % os.listdir(tmp))
# --quiet, or stderr not a terminal: no progress line
r = run(flat, "--sources", srcs, "-o", npy)
check("%" not in r.stderr, "no progress line when stderr is not a terminal: %r" % r.stderr)

# errors: usage (1), input (2), message format
def err(args, code, needle):
    r = run(*args)
    check(r.returncode == code and r.stderr.startswith("trigeo: ") and needle in r.stderr,
          "%s: exit %d (want %d), stderr %r" % (args, r.returncode, code, r.stderr))
err([flat], 1, "--from")
err([flat, "--from", "x:1"], 1, "x:1")
err([flat, "--from", "v:1;"], 1, "--from")
err([flat, "--from", "v:1", "-o", os.path.join(tmp, "a.ply"), "--csv", "-"], 1, "exclude")
err([flat, "--from", "v:1", "--max-distance", "-2"], 1, "--max-distance")
err([flat, "--from", "v:1", "--bogus"], 1, "--bogus")
err([flat, "--from", "v:99999"], 2, "out of range")
err([flat, "--from", "v:1;f:1:0.5,0.6,0.5"], 2, "sum")
err([os.path.join(tmp, "missing.obj"), "--from", "v:1"], 2, "missing.obj")
err([flat, "--sources", srcs], 1, "-o")
err([flat, "--sources", srcs, "--from", "v:1", "-o", npy], 1, "either")
err([flat, "--from", "v:1", "-o", os.path.join(tmp, "x.txt")], 1, "extension")
err([flat, "--sources", os.path.join(tmp, "none.txt"), "-o", npy], 2, "none.txt")
err([flat, "--from", "v:1", "-o", os.path.join(tmp, "no", "such", "dir.ply")], 2, "dir.ply")

# a corpus mesh, the default demo mesh: every vertex reached, finite, 0 at the source
spot = os.path.join(meshes, "nvd_spot.obj")
r = run(spot, "--from", "v:0;p:0,0,0", "--csv", "-")
d = parse_csv(r.stdout) if r.returncode == 0 else None
check(d is not None and len(d) == 2930 and all(math.isfinite(x) and x >= 0 for x in d) and d[0] == 0,
      "spot: exit %d, %s rows" % (r.returncode, len(d) if d else None))

# --threads N on one field (--from, --at, --labels, --isolines): the same bytes for every N > 1,
# within 1e-12 relative of one thread's
outs = {}
for t in ("1", "2", "3", "0"):
    o = os.path.join(tmp, "t%s.csv" % t)
    r = run(spot, "--from", "v:0;f:100:0.2,0.3,0.5", "--threads", t, "-o", o, "--quiet")
    outs[t] = open(o).read() if r.returncode == 0 else r.stderr
check(outs["2"] == outs["3"] == outs["0"], "--threads 2, 3 and 0 give different files")
one, two = parse_csv(outs["1"]), parse_csv(outs["2"])
check(one and two and len(one) == len(two) and all(abs(a - b) <= 1e-12 * a for a, b in zip(one, two)),
      "--threads 2 vs 1: %s" % (max(abs(a - b) / a for a, b in zip(one, two) if a) if one and two else outs["2"]))
atf = os.path.join(tmp, "at1.txt")
open(atf, "w").write("v:3\nf:7:0.2,0.3,0.5\n0.1 0.2 0.3\n")
def numbers(text): return [float(x) for x in text.split()]
at = {t: run(spot, "--from", "v:0", "--threads", t, "--at", atf) for t in ("1", "2", "3")}
check(all(r.returncode == 0 for r in at.values()) and at["2"].stdout == at["3"].stdout,
      "--at with --threads: %s" % [(r.returncode, r.stderr) for r in at.values()])
a1, a2 = numbers(at["1"].stdout), numbers(at["2"].stdout)
check(len(a1) == len(a2) == 3 and all(abs(x - y) <= 1e-12 * x for x, y in zip(a1, a2)),
      "--at, 2 threads vs 1: %s vs %s" % (a2, a1))
lab = {}
for t in ("1", "2", "3"):
    o = os.path.join(tmp, "lab%s.csv" % t)
    r = run(spot, "--from", "v:0;v:1500", "--labels", "--threads", t, "-o", o, "--quiet")
    lab[t] = open(o).read() if r.returncode == 0 else r.stderr
check(lab["2"] == lab["3"], "--labels: 2 and 3 threads give different files")
rows1, rows2 = [l.split(",") for l in lab["1"].split()[1:]], [l.split(",") for l in lab["2"].split()[1:]]
check(len(rows1) == len(rows2) == 2930 and all(p[:2] == q[:2] and abs(float(p[2]) - float(q[2])) <= 1e-12 *
                                                  float(p[2]) for p, q in zip(rows1, rows2)),
      "--labels, 2 threads vs 1: %d and %d rows (%s)" % (len(rows1), len(rows2), lab["2"][:200]))
iso = {}
for t in ("1", "2", "3"):
    o = os.path.join(tmp, "iso%s.obj" % t)
    r = run(spot, "--from", "v:0", "--isolines", "0.2,0.5", "--threads", t, "-o", o, "--quiet")
    iso[t] = open(o).read() if r.returncode == 0 else r.stderr
check(iso["2"] == iso["3"], "--isolines: 2 and 3 threads give different files")
count = lambda text: sum(1 for l in text.splitlines() if l.startswith("v "))
check(count(iso["1"]) == count(iso["2"]) > 0, "--isolines: %d points on 2 threads, %d on one" % (count(iso["2"]), count(iso["1"])))
err([spot, "--from", "v:0", "--threads", "x"], 1, "--threads")
# a front wide enough for rounds whose vertices are processed on every thread (propagate.c,
# vertex_round): fcpw_kitten, one field on 1, 2 and 3 threads
big = {}
for t in ("1", "2", "3"):
    o = os.path.join(tmp, "k%s.npy" % t)
    r = run(kitten, "--from", "v:0", "--threads", t, "-o", o, "--quiet")
    big[t] = open(o, "rb").read() if r.returncode == 0 else r.stderr.encode()
check(big["2"] == big["3"], "kitten: 2 and 3 threads give different files")
k1, k2 = (struct.unpack("<%dd" % ((len(big[t]) - 128) // 8), big[t][128:]) for t in ("1", "2"))
check(len(k1) == len(k2) == 53123 and all(abs(a - b) <= 1e-12 * a for a, b in zip(k1, k2)),
      "kitten, 2 threads vs 1: %s" % (max(abs(a - b) / a for a, b in zip(k1, k2) if a) if len(k1) == len(k2) else
                                     (len(k1), len(k2))))

# --gradient: the CSV and the PLY hold the same numbers; --face-gradient beside it; usage errors
g_csv, g_ply, g_face = (os.path.join(tmp, n) for n in ("g.csv", "g.ply", "gf.csv"))
r = run(spot, "--from", "v:0;f:100:0.2,0.3,0.5", "--gradient", "-o", g_csv, "--face-gradient", g_face, "--quiet")
rows = [l.split(",") for l in open(g_csv).read().split()[1:]] if r.returncode == 0 else []
check(len(rows) == 2930 and rows[0][5] == "1" and all(abs(sum(float(x) ** 2 for x in row[2:5]) - 1) < 1e-12
                                                     for row in rows[1:] if row[5] == "0"),
      "--gradient CSV: exit %d %s, %d rows" % (r.returncode, r.stderr, len(rows)))
frows = open(g_face).read().split()[1:] if r.returncode == 0 else []
check(len(frows) == 5856, "--face-gradient: %d rows" % len(frows))
err([spot, "--from", "v:0", "--face-gradient", g_face, "-o", g_csv], 1, "--face-gradient")
err([spot, "--from", "v:0", "--gradient", "-o", os.path.join(tmp, "g.txt")], 1, "--gradient")
err([spot, "--from", "v:0", "--gradient", "--labels", "-o", g_csv], 1, "--gradient")
err([spot, "--from", "v:0", "--gradient", "-o", g_csv, "--face-gradient", g_csv], 1, "same")

cli_common.finish()
PY
