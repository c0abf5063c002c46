#!/usr/bin/env bash
# cli_outputs.sh: what the CLI writes and reads at the edges:
# text inputs that start with a UTF-8 byte-order mark (mesh, queries, pairs, sources) read like
# the same text without it; a directory given as a mesh is named as one; output that cannot be
# written (/dev/full) is exit 2, not a silent success; a bad pairs or queries line leaves no output
# file at all (inputs are checked before anything is written; outputs go to a temporary name).
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" <<'PY'
import os, subprocess, sys, tempfile
trigeo, meshes = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
def run(*args, stdin=None, stdout=subprocess.PIPE):
    return subprocess.run([trigeo, *args], input=stdin, stdout=stdout, stderr=subprocess.PIPE)
tmp = tempfile.mkdtemp()
BOM = b"\xef\xbb\xbf"
spot = os.path.join(meshes, "nvd_spot.obj")

# a BOM before a mesh: the issue's example has 5 vertices, not 4
obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 9 9 9\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
for name, data in (("plain.obj", obj), ("bom.obj", BOM + obj)):
    open(os.path.join(tmp, name), "wb").write(data)
a = run("info", os.path.join(tmp, "plain.obj"), "--json").stdout
b = run("info", os.path.join(tmp, "bom.obj"), "--json").stdout
check(b'"vertices": 5' in b and a.replace(b"plain.obj", b"X") == b.replace(b"bom.obj", b"X"),
      "BOM mesh reads like the plain one: %r" % b[:120])

# a BOM before queries, pairs and sources
q = b"0 0 0\n0.2 0.1 0.5\n"
r0, r1 = run("closest", spot, "-", stdin=q), run("closest", spot, "-", stdin=BOM + q)
check(r1.returncode == 0 and r0.stdout == r1.stdout, "BOM queries: %r" % r1.stderr)
p = b"v 0 100\nv 5 2000\n"
r0, r1 = run("path", spot, "--pairs", "-", stdin=p), run("path", spot, "--pairs", "-", stdin=BOM + p)
strip = lambda out: [l.split(b",")[:5] for l in out.splitlines()]  # without the timing column
check(r1.returncode == 0 and strip(r0.stdout) == strip(r1.stdout), "BOM pairs: %r" % r1.stderr)
src = os.path.join(tmp, "src.txt")
open(src, "wb").write(BOM + b"v:0\nv:7\n")
r = run("field", spot, "--sources", src, "-o", os.path.join(tmp, "m.csv"))
check(r.returncode == 0, "BOM sources: %r" % r.stderr)

# a gzip bomb (256 MiB of zeros in a .stl.gz of 250 KB): refused as it is read, long before the
# 8 GiB input limit
import gzip
bomb = os.path.join(tmp, "bomb.stl.gz")
with gzip.open(bomb, "wb", compresslevel=1) as g:
    chunk = bytes(1 << 20)
    for _ in range(256):
        g.write(chunk)
r = run("info", bomb)
check(r.returncode == 2 and b"gzip bomb" in r.stderr, "gzip bomb: %d %r" % (r.returncode, r.stderr))

# threads: under a tight address-space limit one thread still works (--threads
# reaches the BVH build too), and more threads than can be started is a clean error, exit 2,
# not libgomp ending the process (not under AddressSanitizer, which reserves terabytes)
import resource
asan = b"__asan_init" in subprocess.run(["nm", trigeo], capture_output=True).stdout
def limited(kb, *args, stdin=b"0 0 0\n"):
    lim = lambda: resource.setrlimit(resource.RLIMIT_AS, (kb * 1024, kb * 1024))
    return subprocess.run([trigeo, *args], input=stdin, capture_output=True, preexec_fn=lim)
if not asan:
    done = False
    for kb in (12000, 14000, 16000, 20000, 10000):
        one = limited(kb, "closest", spot, "-", "--threads", "1")
        many = limited(kb, "closest", spot, "-", "--threads", "64")
        if one.returncode == 0 and many.returncode != 0:
            check(many.returncode == 2 and b"cannot start" in many.stderr and b"libgomp" not in many.stderr,
                  "64 threads under %d KB: %d %r" % (kb, many.returncode, many.stderr))
            done = True
            break
    check(done, "no address-space limit where one thread works and 64 do not")

# coordinates beyond the range where squared distances stay finite: refused with
# the limit named, for meshes and for query points, never a wrong answer (sqdist 0 or inf)
huge = os.path.join(tmp, "huge.obj")
open(huge, "w").write("v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n")
for args in (["closest", huge, "-"], ["path", huge, "--from", "v:0", "--to", "v:2"], ["field", huge, "--from", "v:0"]):
    r = run(*args, stdin=b"0 0 0\n")
    check(r.returncode == 2 and b"1e150" in r.stderr and b"1e+300" in r.stderr, "huge mesh %s: %d %r" % (args[0], r.returncode, r.stderr))
check(run("info", huge).returncode == 0, "info still reads a huge mesh")
# a mesh near 1e-300: its angles cannot be measured, and a straightened path there is "stalled",
# not "converged"
tiny = os.path.join(tmp, "tiny.obj")
open(tiny, "w").write("v 0 0 0\nv 1e-300 0 0\nv 0 1e-300 0\nv 1e-300 1e-300 0\nf 1 2 3\nf 2 4 3\n")
# the solver computes in a frame scaled to the data: at 1e-300 the paths are those of the unit
# square, scaled (straightened and exact alike, the exact one proven)
unit = os.path.join(tmp, "unit.obj")
open(unit, "w").write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
def length_of(out):
    return float([l for l in out.decode().splitlines() if l.startswith("length ")][0].split()[1])
for method in ("straighten", "exact"):
    r = run("path", tiny, "--from", "f:0:0.6,0.2,0.2", "--to", "f:1:0.2,0.6,0.2", "--method", method)
    u = run("path", unit, "--from", "f:0:0.6,0.2,0.2", "--to", "f:1:0.2,0.6,0.2", "--method", method)
    ok = r.returncode == 0 and u.returncode == 0 and b"status             converged" in r.stdout
    ok = ok and (method != "exact" or b"global             proven" in r.stdout)
    ok = ok and abs(length_of(r.stdout) - 1e-300 * length_of(u.stdout)) <= 1e-12 * 1e-300 * length_of(u.stdout)
    check(ok, "tiny mesh path (%s): %d %r" % (method, r.returncode, r.stdout[:300]))
r = run("closest", spot, "-", stdin=b"0 0 0\n1e300 0 0\n")
check(r.returncode == 2 and b"-:2:" in r.stderr and b"1e150" in r.stderr and not r.stdout,
      "huge query: %d %r" % (r.returncode, r.stderr))

# a directory as a mesh
r = run("info", tmp + "/")
check(r.returncode == 2 and b"directory" in r.stderr, "directory: %d %r" % (r.returncode, r.stderr))

# output that cannot be written
with open("/dev/full", "wb") as full:
    for args in (["info", spot, "--json"], ["info", spot], ["closest", spot, "-"], ["path", spot, "--from", "v:0", "--to", "v:9"]):
        r = run(*args, stdin=q, stdout=full)
        check(r.returncode == 2 and b"No space" in r.stderr, "%s > /dev/full: exit %d %r" % (args[0], r.returncode, r.stderr))

# a bad line late in the input: no output file, not even a temporary one
pairs = os.path.join(tmp, "pairs.txt")
open(pairs, "w").write("".join("v %d %d\n" % (i, i + 1) for i in range(1001)) + "v 0 99999\n")
out = os.path.join(tmp, "paths.csv")
r = run("path", spot, "--pairs", pairs, "-o", out)
check(r.returncode == 2 and (pairs + ":1002:").encode() in r.stderr, "bad pair row 1002: %d %r" % (r.returncode, r.stderr))
queries = os.path.join(tmp, "q.txt")
open(queries, "w").write("0 0 0\n" * 500 + "0 0 nan\n")
out2 = os.path.join(tmp, "closest.csv")
r = run("closest", spot, queries, "-o", out2)
check(r.returncode == 2 and (queries + ":501:").encode() in r.stderr, "bad query row 501: %d %r" % (r.returncode, r.stderr))
left = [f for f in os.listdir(tmp) if f.startswith(("paths.csv", "closest.csv"))]
check(not left, "no partial outputs: %s" % left)
# and the good runs do write their files
r = run("path", spot, "--pairs", "-", "-o", out, stdin=b"v 0 1\n")
r2 = run("closest", spot, "-", "-o", out2, stdin=q)
check(r.returncode == 0 and r2.returncode == 0 and os.path.exists(out) and os.path.exists(out2), "good runs write")
check(not [f for f in os.listdir(tmp) if ".tmp-" in f or f.startswith(".trigeo-")], "no temporary files left: %s" % os.listdir(tmp))

# one CLI language
r = run("help", "help")
check(r.returncode == 0 and b"usage: trigeo help" in r.stdout, "trigeo help help: %r" % r.stdout[:80])
r = run("help", "nonsense")
check(r.returncode == 1 and b"unknown command" in r.stderr, "trigeo help nonsense is a usage error")
# the command lists of 'help help' and 'help nonsense' name every command of the overview,
# and point to 'trigeo help', not to 'trigeo help ' with nothing after it
overview = run("--help").stdout.decode()
names = sorted({l.split()[1] for l in overview.splitlines() if l.startswith("  trigeo ") and l.split()[1][0] != "-"})
for args, stream in ((("help", "help"), "stdout"), (("help", "nonsense"), "stderr"), (("help", "--help"), "stdout")):
    text = getattr(run(*args), stream).decode()
    listed = text.split("ommands: ")[-1].split(")")[0].split(".")[0].replace("\n", " ")
    check(sorted(n.strip() for n in listed.split(",")) == names, "trigeo %s lists %r, the overview %r" % (" ".join(args), listed, names))
check(b"'trigeo help '" not in run("help", "nonsense").stderr, "trigeo help nonsense: no empty 'trigeo help '")
spot_bytes = open(spot, "rb").read()
want = run("info", spot, "--json").stdout.replace(spot.encode(), b"X")
for args in (("info", "-", "--json", "--format", "obj"), ("info", "--format", "obj", "-", "--json"), ("info", "-", "--json")):
    r = run(*args, stdin=spot_bytes)
    check(r.returncode == 0 and r.stdout.replace(b'"-"', b'"X"') == want, "mesh from stdin %s: %r" % (args, r.stderr))
r = run("info", "-", "--format", "3ds", stdin=spot_bytes)
check(r.returncode == 1 and b"--format" in r.stderr, "bad --format is a usage error")
r = run("info", "-", "--format", "ply", stdin=spot_bytes)
check(r.returncode == 2 and r.stderr.startswith(b"trigeo: -"), "a forced wrong format names '-': %r" % r.stderr)
r = run("closest", "-", "-", stdin=spot_bytes)
check(r.returncode == 1 and b"standard input" in r.stderr, "two inputs from stdin refused: %r" % r.stderr)
# barycentrics within 1e-6 of summing to 1 are rescaled; farther off refused (exit 2)
a = run("path", spot, "--from", "f:3832:0.2,0.3,0.5", "--to", "v:0", "--json").stdout
b = run("path", spot, "--from", "f:3832:0.2000001,0.3,0.5", "--to", "v:0", "--json")
c = run("path", spot, "--from", "f:3832:0.21,0.3,0.5", "--to", "v:0", "--json")
check(b.returncode == 0 and b'"length"' in b.stdout and c.returncode == 2, "bary rescaled within 1e-6: %r %r" % (b.stderr, c.stderr))
# pairs: "f" face points, the older "p" with nine fields, "p" positions; the same lengths
pf = os.path.join(tmp, "forms.txt")
open(pf, "w").write("f 3832 0.2 0.3 0.5 4380 0.3 0.3 0.4\np 3832 0.2 0.3 0.5 4380 0.3 0.3 0.4\n"
                     "f 3832 0.2 0.3 0.5000004 4380 0.3 0.3 0.4\n")
r = run("path", spot, "--pairs", pf)
rows = [l.split(b",") for l in r.stdout.splitlines()[1:]]
check(r.returncode == 0 and len(rows) == 3 and rows[0][1] == rows[1][1] and abs(float(rows[2][1]) - float(rows[0][1])) < 1e-6,
      "f and old p pair forms agree: %r %r" % (r.stdout[:200], r.stderr))
js = run("path", spot, "--from", "f:3832:0.2,0.3,0.5", "--to", "f:4380:0.3,0.3,0.4", "--json").stdout.decode()
import json
pts = json.loads(js)["xyz"] if "xyz" in json.loads(js) else None
if pts:
    p0, p1 = pts[0], pts[-1]
    open(pf, "w").write("p %.17g %.17g %.17g %.17g %.17g %.17g\n" % (*p0, *p1))
    r = run("path", spot, "--pairs", pf)
    got = r.stdout.splitlines()[1].split(b",") if r.returncode == 0 else None
    check(got is not None and abs(float(got[1]) - float(rows[0][1])) < 1e-9, "p position pairs: %r %r" % (r.stdout, r.stderr))
else:
    check(False, "path --json has no xyz key: %r" % js[:200])
# -o everywhere, the extension picks the format
ij, it = os.path.join(tmp, "info.json"), os.path.join(tmp, "info.txt")
r1, r2 = run("info", spot, "-o", ij), run("info", spot, "-o", it)
check(r1.returncode == 0 and json.load(open(ij))["vertices"] == 2930 and open(it).read().startswith(spot),
      "info -o OUT.json / OUT.txt: %r %r" % (r1.stderr, r2.stderr))
pj = os.path.join(tmp, "p.json")
r = run("path", spot, "--from", "v:0", "--to", "v:9", "-o", pj)
want = json.loads(run("path", spot, "--from", "v:0", "--to", "v:9", "--json").stdout)
check(r.returncode == 0 and json.load(open(pj)) == want, "path -o PATH.json is the --json document")
r = run("path", spot, "--from", "v:0", "--to", "v:9", "-o", os.path.join(tmp, "p.txt"))
check(r.returncode == 1 and not os.path.exists(os.path.join(tmp, "p.txt")), "path -o with an unknown extension is a usage error")
cli_common.finish()
PY
