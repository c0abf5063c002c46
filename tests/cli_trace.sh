#!/usr/bin/env bash
# cli_trace.sh: `trigeo trace` (single traces: summary, -o OBJ/JSON, --json; --batch: CSV to
# stdout and -o, every line checked first) and `trigeo path --through` (open and closed routes),
# exit codes 0/1/2 and error format. Known answers come from a flat triangulated square written
# here: a trace is the straight segment, a route through waypoints the sum of Euclidean distances.
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" <<'PY'
import csv, io, json, math, os, subprocess, sys, tempfile
trigeo, meshes = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(cmd, *args, stdin=None):
    return subprocess.run([trigeo, cmd, *args], capture_output=True, text=True, input=stdin)
def dist(p, q): return math.sqrt(sum((p[c] - q[c]) ** 2 for c in range(3)))

tmp = tempfile.mkdtemp()
n = 8
flat, vs, fs = cli_common.flat_square(tmp, 11, n)
def pos_face(fi, b): return cli_common.pos_face(vs, fs, fi, b)
def jload(text):
    try: return json.loads(text)
    except Exception: check(False, "JSON parse: %r" % text[:200]); return None

# single traces on the flat square: the end is start + L * unit(dir), to 1e-12
cases = [("f:10:0.2,0.3,0.5", (1, 0.5, 0), 0.2), ("f:70:0.6,0.2,0.2", (-0.3, 1, 7), 0.25), ("v:40", (0.2, -1, 0), 0.4)]
for spec, d, L in cases:
    out = os.path.join(tmp, "t.json")
    r = run("trace", flat, "--from", spec, "--dir", "%.17g,%.17g,%.17g" % d, "--length", repr(L), "-o", out, "--json")
    check(r.returncode == 0, "%s: exit %d %s" % (spec, r.returncode, r.stderr))
    j, jf = jload(r.stdout), jload(open(out).read()) if os.path.exists(out) else None
    if not j: continue
    check(j == jf, "-o OUT.json holds the --json document")
    p0 = j["xyz"][0]
    u = [d[0], d[1], 0.0]; s = math.hypot(u[0], u[1]); u = [x / s for x in u]
    want = [p0[c] + L * u[c] for c in range(3)]
    check(j["status"] == "complete" and j["length"] == L, "%s: status %s length %r" % (spec, j["status"], j["length"]))
    check(dist(j["end"]["xyz"], want) <= 1e-12, "%s: end %s, straight line %s" % (spec, j["end"]["xyz"], want))
    check(dist(j["end"]["direction"], u) <= 1e-12, "%s: end direction %s" % (spec, j["end"]["direction"]))
    check(j["point_count"] == len(j["points"]) == len(j["xyz"]) == len(j["faces"]) + 1, "JSON array sizes")
    check(all(abs(dist(j["xyz"][i], j["xyz"][i + 1]) + dist(j["xyz"][i + 1], want) - dist(j["xyz"][i], want)) <= 1e-12
              for i in range(len(j["xyz"]) - 1)), "%s: every point on the segment" % spec)
    if spec.startswith("f:10:"):
        check(j["points"][0] == {"kind": "face", "face": 10, "bary": [0.2, 0.3, 0.5]}, "start kept: %s" % j["points"][0])
# the summary, and the OBJ polyline
obj = os.path.join(tmp, "t.obj")
r = run("trace", flat, "--from", "v:40", "--angle", "0.5", "--length", "0.2", "-o", obj)
check(r.returncode == 0 and "status             complete" in r.stdout and "length             0.2" in r.stdout,
      "summary: %d %s %s" % (r.returncode, r.stdout, r.stderr))
lines = open(obj).read().splitlines() if os.path.exists(obj) else []
vrec = [l for l in lines if l.startswith("v ")]
lrec = [l for l in lines if l.startswith("l ")]
check(len(vrec) >= 2 and lrec == ["l " + " ".join(str(i + 1) for i in range(len(vrec)))], "OBJ polyline %s" % lrec)
check(vrec and dist([float(x) for x in vrec[0].split()[1:]], vs[40]) == 0, "OBJ starts at v:40")
# leaving the square: status boundary, the length walked is the distance to the edge x = 1
r = run("trace", flat, "--from", "f:10:0.2,0.3,0.5", "--dir", "1,0,0", "--length", "5", "--json")
j = jload(r.stdout)
if j:
    x0 = j["xyz"][0][0]
    check(j["status"] == "boundary" and abs(j["length"] - (1 - x0)) <= 1e-12 and abs(j["end"]["xyz"][0] - 1) <= 1e-12,
          "boundary: %s %r" % (j["status"], j["length"]))

# --batch: the same ends as single traces, CSV to stdout and to -o, in input order
batch = os.path.join(tmp, "traces.txt")
with open(batch, "w") as f:
    f.write("# start direction length\n\n")
    for spec, d, L in cases: f.write("%s %.17g,%.17g,%.17g %r\n" % (spec, d[0], d[1], d[2], L))
    f.write("v:40 0.5 0.2\n")
singles = []
for spec, d, L in cases:
    singles.append(jload(run("trace", flat, "--from", spec, "--dir", "%.17g,%.17g,%.17g" % d, "--length", repr(L), "--json").stdout))
singles.append(jload(run("trace", flat, "--from", "v:40", "--angle", "0.5", "--length", "0.2", "--json").stdout))
for out, threads in ((None, "1"), (os.path.join(tmp, "ends.csv"), "0")):
    r = run("trace", flat, "--batch", batch, "--threads", threads, *(["-o", out] if out else []))
    check(r.returncode == 0, "batch exit %d %s" % (r.returncode, r.stderr))
    rows = list(csv.reader(io.StringIO(open(out).read() if out else r.stdout)))
    check(rows and rows[0] == "i,status,length,crossings,vertices,branches,face,x,y,z,dx,dy,dz,end".split(","), "header %s" % rows[:1])
    check(len(rows) == 5, "batch rows %d" % len(rows))
    for row, s in zip(rows[1:], singles):
        if not s: continue
        check(row[1] == s["status"] and float(row[2]) == s["length"] and int(row[3]) == s["crossings"]
              and int(row[6]) == s["end"]["face"] and [float(x) for x in row[7:10]] == s["end"]["xyz"]
              and [float(x) for x in row[10:13]] == s["end"]["direction"], "batch row %s = single %s" % (row, s["end"]))
        sp = s["end"]["point"]
        check(row[13].startswith({"face": "f:%d:", "edge": "e:%d:", "vertex": "v:%d"}[sp["kind"]] %
                                  sp.get("face", sp.get("halfedge", sp.get("vertex")))), "end spec %s" % row[13])

# path --through: the sum of the Euclidean distances on the flat square, the waypoints' indices
pts = ["f:10:0.2,0.3,0.5", "v:40", "f:100:0.1,0.1,0.8", "v:3"]
xyz = [pos_face(10, (0.2, 0.3, 0.5)), vs[40], pos_face(100, (0.1, 0.1, 0.8)), vs[3]]
for closed in (False, True):
    r = run("path", flat, "--through", ";".join(pts), "--json", *(["--closed"] if closed else []))
    check(r.returncode == 0, "--through exit %d %s" % (r.returncode, r.stderr))
    j = jload(r.stdout)
    if not j: continue
    route = xyz + ([xyz[0]] if closed else [])
    want = sum(dist(route[i], route[i + 1]) for i in range(len(route) - 1))
    check(abs(j["length"] - want) <= 1e-12 and j["global"] == "proven", "--through length %r vs %r" % (j["length"], want))
    wp = j["waypoint_points"]
    check(j["closed"] == closed and len(wp) == len(route) and wp[0] == 0 and wp[-1] == j["point_count"] - 1,
          "waypoint_points %s" % wp)
    check(all(dist(j["xyz"][wp[i]], route[i]) <= 1e-15 for i in range(len(wp))), "waypoints are on the path")
r = run("path", flat, "--through", "v:0;v:80", "--closed")
check(r.returncode == 0 and "waypoints          2, closed" in r.stdout, "--through summary: %s" % r.stdout)
obj = os.path.join(tmp, "route.obj")
r = run("path", flat, "--through", "v:0;v:80;v:8", "-o", obj)
check(r.returncode == 0 and os.path.exists(obj), "--through -o OBJ")

# errors: usage (1), input (2), message format, no output file
def err(cmd, args, code, needle, stdin=None, out=None):
    r = run(cmd, *args, stdin=stdin)
    check(r.returncode == code and r.stderr.startswith("trigeo: ") and needle in r.stderr,
          "%s %s: exit %d (want %d), stderr %r" % (cmd, args, r.returncode, code, r.stderr))
    if out: check(not os.path.exists(out), "%s: no output file after an error" % args)
gone = os.path.join(tmp, "never.json")
err("trace", [flat, "--from", "v:1", "--dir", "0,0,0", "--length", "1", "-o", gone], 1, "--dir", out=gone)
err("trace", [flat, "--from", "v:1", "--dir", "nan,0,0", "--length", "1"], 1, "--dir")
err("trace", [flat, "--from", "f:3:0.2,0.3,0.5", "--dir", "0,0,1", "--length", "1", "-o", gone], 1, "perpendicular", out=gone)
err("trace", [flat, "--from", "v:1", "--dir", "1,0,0", "--length", "-1"], 1, "--length")
err("trace", [flat, "--from", "v:1", "--dir", "1,0,0", "--length", "inf"], 1, "--length")
err("trace", [flat, "--from", "v:1", "--dir", "1,0,0"], 1, "--length")
err("trace", [flat, "--from", "v:1", "--dir", "1,0,0", "--angle", "1", "--length", "1"], 1, "one of them")
err("trace", [flat, "--from", "v:99999", "--dir", "1,0,0", "--length", "1"], 2, "out of range")
err("trace", [flat, "--batch", batch, "--from", "v:1"], 1, "--batch")
bad = os.path.join(tmp, "bad.txt")
gone = os.path.join(tmp, "never.csv")
for text, needle in (("v:1 1,0,0 1\nv:2 1,0 1\n", "bad.txt:2:"), ("v:1 1,0,0 -2\n", "bad.txt:1:"),
                     ("v:1 1,0,0\n", "bad.txt:1:"), ("v:1 1,0,0 1\n# c\nv:99999 1,0,0 1\n", "bad.txt:3: 'v:99999'"),
                     ("v:1 1,0,0 1\n\nf:3:0.2,0.3,0.5 0,0,2 1\n", "bad.txt:3: the direction is perpendicular")):
    with open(bad, "w") as f: f.write(text)
    err("trace", [flat, "--batch", bad, "-o", gone], 2, needle, out=gone)
err("path", [flat, "--through", "v:1;;v:2"], 1, "--through")
err("path", [flat, "--through", "v:1;x:2"], 1, "item 2")
err("path", [flat, "--through", "v:1;v:2", "--from", "v:1"], 1, "--through")
err("path", [flat, "--from", "v:1", "--to", "v:2", "--closed"], 1, "--closed")
err("path", [flat, "--through", "v:1;v:99999"], 2, "out of range")

# a corpus mesh: a batch from stdin on every thread count gives the same rows
spot = os.path.join(meshes, "nvd_spot.obj")
lines = "".join("f:%d:0.2,0.3,0.5 %d,%d,1 0.7\n" % (37 * i, i % 3 - 1, i % 5 - 2) for i in range(40))
outs = [run("trace", spot, "--batch", "-", "--threads", t, stdin=lines) for t in ("1", "2")]
check(all(o.returncode == 0 for o in outs) and outs[0].stdout == outs[1].stdout and len(outs[0].stdout.splitlines()) == 41,
      "spot batch, 1 and 2 threads: %s" % [o.stderr for o in outs])

# a --dir of any length, the tangent plane at a vertex, any scale of the mesh
r = run("trace", os.path.join(meshes, "cgal_mpi.off"), "--from", "v:81", "--dir", "1.387,-1.317,-2.283", "--length", "0.1")
check(r.returncode == 0 and "status             complete" in r.stdout,
      "cgal_mpi v:81 --dir 1.387,-1.317,-2.283 (92-107 degrees from the surface there): %d %s" % (r.returncode, r.stderr))
ends = {}
for dd in ("1,0,0", "1e-165,0,0", "1e-160,0,0", "1e160,0,0", "1e300,0,0"):
    r = run("trace", flat, "--from", "v:40", "--dir", dd, "--length", "0.3", "--json")
    ends[dd] = jload(r.stdout)["end"]["xyz"] if r.returncode == 0 else None
    check(ends[dd] is not None and ends["1,0,0"] is not None and dist(ends[dd], ends["1,0,0"]) <= 1e-12,
          "flat v:40 --dir %s: end %s, --dir 1,0,0: %s (%s)" % (dd, ends[dd], ends["1,0,0"], r.stderr.strip()))
spot_lines = open(os.path.join(meshes, "oded_spot_low_resolution.obj")).read().splitlines()
base = {}
for scale in (1.0, 1e100, 1e-100):
    path = os.path.join(tmp, "spot_%g.obj" % scale)
    with open(path, "w") as f:
        for l in spot_lines:
            f.write("v " + " ".join(repr(float(x) * scale) for x in l.split()[1:4]) + "\n" if l.startswith("v ") else l + "\n")
    for how in (["--angle", "1"], ["--dir", "0.3,-1,0.5"]):
        for start in ("v:0", "e:301:0.37", "f:77:0.2,0.3,0.5"):
            r = run("trace", path, "--from", start, *how, "--length", repr(0.5 * scale), "--json")
            end = [x / scale for x in jload(r.stdout)["end"]["xyz"]] if r.returncode == 0 else None
            key = (how[0], start)
            if scale == 1.0: base[key] = end
            check(end is not None and base[key] is not None and dist(end, base[key]) <= 1e-12,
                  "spot x%g --from %s %s: end %s (/ scale), unscaled %s (%s)" % (scale, start, " ".join(how), end, base[key],
                                                                                r.stderr.strip()))

cli_common.finish()
PY
