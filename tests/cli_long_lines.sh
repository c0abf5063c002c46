#!/usr/bin/env bash
# cli_long_lines.sh: the CLI's readers take lines (and names) of any length, and a cut or corrupt
# record is refused with FILE:LINE, never read silently as something else.
# - trigeo writes `l` records longer than any fixed buffer (a trace of length 400 on nvd_spot: one
#   record of about 100,000 characters): render --path draws it exactly as the same polyline
#   split into short records (concatenated: --path), and --isolines / --boundaries exactly as
#   the same polyline split into short overlapping records (each record one part); the PNG bytes
#   are compared. A long record with a bad token or an index out of range far past 65,536
#   characters is refused naming its line.
# - pairs (path --pairs) and traces (trace --batch) files with lines past 4096 characters (a long
#   comment, a padded line) read like the same files without them; files of exactly 256 lines
#   (the readers' first capacity) read whole.
# - a points file (field --at) with a coordinate of 300 digits; a mesh whose path is longer than
#   1024 characters, its format told only by its extension (a headerless OFF).
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" <<'PY'
import os, shutil, subprocess, sys, tempfile
trigeo, meshes = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check
tmp = tempfile.mkdtemp()
os.chdir(tmp)
spot = os.path.join(meshes, "nvd_spot.obj")

def run(*args, stdin=None):
    return subprocess.run([trigeo, *args], input=stdin, capture_output=True)

# ---- render: one long `l` record against the same polyline in short records ----
r = run("trace", spot, "--from", "v:0", "--angle", "0.3", "--length", "400", "-o", "t.obj")
lines = open("t.obj").read().splitlines()
vs = [l for l in lines if l.startswith("v ")]
ls = [l for l in lines if l.startswith("l ")]
longest = max(len(l) for l in lines)
check(r.returncode == 0 and len(ls) == 1 and longest > 65536, "trace: exit %d, %d l records, longest line %d (want > 65536)"
      % (r.returncode, len(ls), longest))
idx = ls[0].split()[1:]
def write(name, chunks, extra=""):
    with open(name, "w") as f:
        f.write("\n".join(vs) + "\n" + "".join("l " + " ".join(c) + "\n" for c in chunks) + extra)
write("cat.obj", [idx[i:i + 500] for i in range(0, len(idx), 500)])              # --path joins every record
write("overlap.obj", [idx[i:i + 501] for i in range(0, len(idx) - 1, 500)])      # parts share their ends
def png(*args):
    out = "img%d.png" % png.n
    png.n += 1
    r = run("render", spot, "--size", "240x180", *args, "-o", out)
    return r.returncode, open(out, "rb").read() if r.returncode == 0 else r.stderr
png.n = 0
plain = png()
for opt, split in (("--path", "cat.obj"), ("--isolines", "overlap.obj"), ("--boundaries", "overlap.obj")):
    a, b = png(opt, "t.obj"), png(opt, split)
    check(a[0] == 0 and b[0] == 0 and a[1] == b[1] and a[1] != plain[1],
          "render %s: the long record (exit %d, %d bytes) draws as the split one (exit %d, %d bytes): %s, differs from no "
          "overlay: %s" % (opt, a[0], len(a[1]), b[0], len(b[1]), a[1] == b[1], a[1] != plain[1]))
# a corrupt token and an index out of range far into the long record: refused with the line
lline = len(lines)  # the `l` record is the last line
toks = ls[0].split()
bad = toks[:]
bad[len(bad) * 3 // 4] = "12x"
col = len(" ".join(bad[:len(bad) * 3 // 4])) + 2
check(col > 65536, "the bad token sits at column %d (want > 65536)" % col)
for name, record, why in (("bad_token.obj", " ".join(bad), b"12x"),
                          ("bad_index.obj", ls[0] + " %d" % (len(vs) + 1), b"out of range"),
                          ("cut.obj", ls[0][:70001] + "/", b"bad index"),
                          ("zero.obj", " ".join(toks[:len(toks) // 2] + ["0"] + toks[len(toks) // 2:]), b"out of range")):
    open(name, "w").write("\n".join(lines[:-1]) + "\n" + record + "\n")
    for opt in ("--path", "--isolines", "--boundaries"):
        r = run("render", spot, opt, name, "-o", "x.png")
        check(r.returncode == 2 and ("%s:%d:" % (name, lline)).encode() in r.stderr and why in r.stderr
              and not os.path.exists("x.png"), "render %s %s: exit %d (want 2, %s:%d: %s) %r"
              % (opt, name, r.returncode, name, lline, why.decode(), r.stderr[:300]))
open("bad_v.obj", "w").write("v 0 0 0\nv 1 0 0 junk\nl 1 2\n")
r = run("render", spot, "--path", "bad_v.obj", "-o", "x.png")
check(r.returncode == 2 and b"bad_v.obj:2:" in r.stderr, "a 'v' record with junk: exit %d %r" % (r.returncode, r.stderr))

# ---- pairs and traces files: long lines, and exactly 256 lines ----
def rows(out):  # the CSV without the timing column of path --pairs
    return [l.split(b",")[:5] + l.split(b",")[6:] for l in out.splitlines()]
pairs = "v 0 100\nv 5 2000\n"
long_pairs = "#" + "x" * 5000 + "\n" + "v 0 100" + " " * 5000 + "\nv 5 2000\n"
a = run("path", spot, "--pairs", "-", "--method", "edge", stdin=pairs.encode())
b = run("path", spot, "--pairs", "-", "--method", "edge", stdin=long_pairs.encode())
check(a.returncode == 0 and b.returncode == 0 and rows(a.stdout) == rows(b.stdout),
      "pairs with 5000-character lines: exit %d %r, %r vs %r" % (b.returncode, b.stderr, rows(b.stdout), rows(a.stdout)))
traces = "v:0 1,0,0 0.1\nv:5 0.5 0.2\n"
long_traces = "#" + "x" * 5000 + "\n" + "v:0 1,0,0 0.1" + " " * 5000 + "\nv:5 0.5 0.2\n"
a = run("trace", spot, "--batch", "-", stdin=traces.encode())
b = run("trace", spot, "--batch", "-", stdin=long_traces.encode())
check(a.returncode == 0 and b.returncode == 0 and a.stdout == b.stdout,
      "traces with 5000-character lines: exit %d %r" % (b.returncode, b.stderr))
for n in (255, 256, 257):
    r = run("path", spot, "--pairs", "-", "--method", "edge", stdin=("v 0 1\n" * n).encode())
    check(r.returncode == 0 and len(r.stdout.splitlines()) == n + 1, "%d pairs: exit %d, %d rows %r"
          % (n, r.returncode, len(r.stdout.splitlines()) - 1, r.stderr))
    r = run("trace", spot, "--batch", "-", stdin=("v:0 1,0,0 0.01\n" * n).encode())
    check(r.returncode == 0 and len(r.stdout.splitlines()) == n + 1, "%d traces: exit %d, %d rows %r"
          % (n, r.returncode, len(r.stdout.splitlines()) - 1, r.stderr))

# ---- a points file with long numbers; a long mesh path ----
open("short.txt", "w").write("0.1 0.2 0.3\n")
open("long.txt", "w").write("0.1" + "0" * 300 + " 0.2 0.3" + "0" * 300 + "\n")
a = run("field", spot, "--from", "v:0", "--at", "short.txt")
b = run("field", spot, "--from", "v:0", "--at", "long.txt")
check(a.returncode == 0 and b.returncode == 0 and a.stdout == b.stdout,
      "--at with 300-digit numbers: exit %d %r, %r vs %r" % (b.returncode, b.stderr, b.stdout, a.stdout))
deep = os.path.join(tmp, *["d" * 200] * 5)
os.makedirs(deep)
name = os.path.join(deep, "x" * 200 + ".off")
open(name, "w").write("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")  # OFF without its header: only the name says OFF
r = run("info", name, "--json")
check(len(name) > 1024 and r.returncode == 0 and b'"faces": 1' in r.stdout,
      "a mesh path of %d characters: exit %d %r" % (len(name), r.returncode, r.stderr[-200:]))
shutil.rmtree(tmp)
cli_common.finish()
PY
