#!/usr/bin/env bash
# cli_numbers.sh: the CLI's one rule for numbers (README.md "Numbers"), in every place that reads
# one: a number is its decimal text's nearest double, subnormals included (4.9e-324 is the
# smallest double, not an error), text that underflows is 0, text beyond the largest double is
# refused as not finite, then the option's range. Options (--max-distance, --length, --angle,
# --dir, --ref, --isolines levels), SPEC coordinates and barycentrics, and the batch, pairs,
# sources, points and queries files. Known answers on the jittered flat square of cli_common.
# And every number the CLI writes (CSV, JSON, OBJ, summaries, messages) is the shortest decimal
# that reads back to the same double (Python's repr; integers without ".0"), checked on every
# output of every command; only the fixed-precision displays (seconds, the summary's max angle
# defect %.3g, MiB, microseconds) are rounded on purpose. closest reads .npy queries written by
# NumPy as float64 or float32, little- or big-endian, C or Fortran order, each converted exactly:
# the answers are those of the same points as float64 C order, byte for byte.
set -u
trigeo=${TG_TRIGEO:?}
exec /usr/bin/env python3 - "$trigeo" <<'PY'
import os, re, shutil, subprocess, sys, tempfile
trigeo = sys.argv[1]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check

def run(cmd, *args, stdin=None):
    return subprocess.run([trigeo, cmd, *args], capture_output=True, text=True, input=stdin)
tmp = tempfile.mkdtemp()
flat, vs, fs = cli_common.flat_square(tmp, 11, 8)
def write(name, text):
    p = os.path.join(tmp, name)
    with open(p, "w") as f: f.write(text)
    return p
def ok(args, what, cmd=None):
    r = run(*args)
    check(r.returncode == 0, "%s: exit %d (want 0), stderr %r" % (what, r.returncode, r.stderr.strip()))
    return r
def refused(args, code, needle, what):
    r = run(*args)
    check(r.returncode == code and needle in r.stderr,
          "%s: exit %d (want %d), stderr %r (want %r in it)" % (what, r.returncode, code, r.stderr.strip(), needle))

tiny, sub, under, over = "4.9e-324", "1e-320", "1e-400", "1e999"
# ---- options ----
for d in (tiny, sub, under, "-0"):
    ok(["field", flat, "--from", "v:40", "--max-distance", d, "-o", os.path.join(tmp, "f.csv")], "field --max-distance %s" % d)
    ok(["logmap", flat, "--from", "v:40", "--max-distance", d, "-o", os.path.join(tmp, "l.csv")], "logmap --max-distance %s" % d)
    ok(["field", flat, "--sources", write("s.txt", "v:40\n"), "--max-distance", d, "-o", os.path.join(tmp, "m.npz")],
       "field --sources --max-distance %s" % d)
    ok(["trace", flat, "--from", "v:40", "--angle", "0.5", "--length", d], "trace --length %s" % d)
    ok(["trace", flat, "--from", "v:40", "--angle", d, "--length", "0.1"], "trace --angle %s" % d)
    ok(["field", flat, "--from", "v:40", "--isolines", "0.5,%s" % d, "-o", os.path.join(tmp, "i.obj")], "--isolines 0.5,%s" % d)
# the max distance 4.9e-324: the source alone is reached
r = run("field", flat, "--from", "v:40", "--max-distance", tiny, "-o", os.path.join(tmp, "f.csv"))
rows = open(os.path.join(tmp, "f.csv")).read().split()[1:] if r.returncode == 0 else []
check(sum(1 for row in rows if row.split(",")[1] != "inf") == 1, "--max-distance %s: reached %s" % (tiny, rows[:3]))
# a direction or reference with subnormal components is passed on (its length does not matter:
# the library's business); the CLI's "not all zero" is only for a vector that is 0
for v in ("%s,0,0" % sub, "%s,%s,0" % (tiny, tiny), "1e-300,0,0"):
    r = run("trace", flat, "--from", "v:40", "--dir", v, "--length", "0.1")
    check("bad --dir" not in r.stderr, "--dir %s refused by the CLI: %r" % (v, r.stderr.strip()))
    r = run("logmap", flat, "--from", "v:40", "--ref", v, "-o", os.path.join(tmp, "l.csv"))
    check("bad --ref" not in r.stderr, "--ref %s refused by the CLI: %r" % (v, r.stderr.strip()))
# beyond the largest double: not finite; underflow to 0 and not decimal text: as the option says
for d in (over, "-1e999", "inf", "nan", "0x1p-3", "-5e-324", "1e", "1.5x"):
    refused(["field", flat, "--from", "v:40", "--max-distance", d], 1, "--max-distance", "field --max-distance %s" % d)
    refused(["logmap", flat, "--from", "v:40", "--max-distance", d, "-o", os.path.join(tmp, "l.csv")], 1, "--max-distance",
            "logmap --max-distance %s" % d)
    refused(["trace", flat, "--from", "v:40", "--angle", "0.5", "--length", d], 1, "--length", "--length %s" % d)
for v in ("%s,0,0" % under, "0,-1e-400,0", "1e999,0,0"):
    refused(["trace", flat, "--from", "v:40", "--dir", v, "--length", "0.1"], 1, "--dir", "--dir %s" % v)
refused(["render", flat, "--logmap", "x.ply", "--checker", "0", "-o", os.path.join(tmp, "x.png")], 1, "--checker",
        "--checker 0")

# ---- SPEC coordinates and barycentrics ----
for spec in ("f:10:1,%s,0" % tiny, "f:10:%s,1,%s" % (sub, under), "e:30:%s" % tiny, "p:%s,0.5,%s" % (sub, tiny)):
    ok(["path", flat, "--from", spec, "--to", "v:40"], "path --from %s" % spec)
    ok(["field", flat, "--from", spec, "-o", os.path.join(tmp, "f.csv")], "field --from %s" % spec)
ok(["path", flat, "--through", "v:40;f:10:1,%s,0;v:3" % tiny], "--through with a subnormal barycentric")
refused(["path", flat, "--from", "f:10:1,1e999,0", "--to", "v:40"], 1, "--from", "f: with 1e999")

# ---- files ----
ok(["trace", flat, "--batch", write("b.txt", "v:40 %s,0,0 0.1\nf:10:1,%s,0 0.5 %s\n" % (sub, tiny, tiny))], "batch with subnormals")
refused(["trace", flat, "--batch", write("b.txt", "v:40 1,0,0 0.1\nv:40 1,0,0 1e999\n")], 2, "b.txt:2:", "batch length 1e999")
refused(["trace", flat, "--batch", write("b.txt", "v:40 1e-400,0,0 0.1\n")], 2, "b.txt:1:", "batch direction 1e-400,0,0 (0)")
ok(["path", flat, "--pairs", write("p.txt", "f 10 1 %s 0 20 %s 1 0\np 0.5 0.5 %s 0.2 0.2 0\n" % (tiny, sub, tiny))],
   "pairs with subnormals")
refused(["path", flat, "--pairs", write("p.txt", "v 0 1\np 0.5 0.5 1e999 0.2 0.2 0\n")], 2, "p.txt:2:", "pairs 1e999")
ok(["field", flat, "--sources", write("s.txt", "f:10:1,%s,0\nv:3\n" % tiny), "-o", os.path.join(tmp, "m.npy")],
   "sources with a subnormal")
r = ok(["field", flat, "--from", "v:40", "--at", write("a.txt", "%s 0.5 0\n0.5,%s,%s\np:%s,0,0\n" % (tiny, sub, under, sub))],
       "--at points with subnormals")
check(len(r.stdout.split()) == 3, "--at: 3 distances, got %r" % r.stdout)
refused(["field", flat, "--from", "v:40", "--at", write("a.txt", "0 0 0\n1e999 0 0\n")], 2, "a.txt:2:", "--at 1e999")
ok(["closest", flat, write("q.txt", "%s 0.5 %s\n" % (tiny, under))], "closest queries with subnormals")
refused(["closest", flat, write("q.txt", "0 0 0\n0x1p-2 0 0\n")], 2, "q.txt:2:", "closest hexadecimal query")

# ---- every number written is the shortest that reads back ----
NUM = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[+-]?\d+)?(?![\w.])")
def shortest(t):
    r = repr(float(t))
    return t == r or t + ".0" == r
def numbers_shortest(what, text, skip=("seconds ", "max angle defect ", "entries ")):
    bad = []
    for line in text.splitlines():
        if line.startswith(skip): continue
        bad += [t for t in NUM.findall(line) if not shortest(t)]
    check(text.strip() != "" and not bad, "%s: %d numbers not the shortest that reads back, e.g. %s" % (what, len(bad), bad[:4]))
def o(name): return os.path.join(tmp, name)
def out_of(args, path=None):
    r = run(*args)
    check(r.returncode == 0, "%s: exit %d, %r" % (args, r.returncode, r.stderr.strip()))
    return (open(path).read() if path and os.path.exists(path) else "") if path else r.stdout
tri = write("tri.obj", "v 0.1 -0.331878 0.3\nv 1.1 0.2 0.3\nv 0.1 1.3 0.7\nf 1 2 3\n")
srcs, pts = write("s.txt", "v:0\nf:10:0.2,0.3,0.5\n"), write("pt.txt", "0.3 0.7 0\nf:20:0.1,0.1,0.8\n")
batch = write("b.txt", "v:40 1,0.3,0 0.7\nf:10:0.2,0.3,0.5 0.3 0.45\n")
pairs = write("p.txt", "v 0 40\nf 10 0.2 0.3 0.5 20 0.1 0.1 0.8\np 0.1 0.2 0 0.7 0.6 0\nv 0 81\n")
outputs = [
    ("info", out_of(["info", tri])), ("info --json", out_of(["info", tri, "--json"])),
    ("closest", out_of(["closest", flat, write("q.txt", "0.1 0.2 0.3\n0.7 0.1 -0.2\n"), "--signed"])),
    ("path summary", out_of(["path", flat, "--from", "f:10:0.2,0.3,0.5", "--to", "f:20:0.1,0.1,0.8"])),
    ("path -o OBJ", out_of(["path", flat, "--from", "f:10:0.2,0.3,0.5", "--to", "f:20:0.1,0.1,0.8", "-o", o("p.obj")], o("p.obj"))),
    ("path --json", out_of(["path", flat, "--from", "f:10:0.2,0.3,0.5", "--to", "f:20:0.1,0.1,0.8", "--json"])),
    ("path --through --json", out_of(["path", flat, "--through", "v:0;f:10:0.2,0.3,0.5;v:44", "--json"])),
    ("path --pairs", "\n".join(",".join(c for k, c in enumerate(l.split(",")) if k != 5)
                               for l in out_of(["path", flat, "--pairs", pairs, "--method", "straighten"]).splitlines())),
    ("trace summary", out_of(["trace", flat, "--from", "v:40", "--dir", "1,0.3,0", "--length", "0.7"])),
    ("trace --json", out_of(["trace", flat, "--from", "v:40", "--dir", "1,0.3,0", "--length", "0.7", "--json"])),
    ("trace -o OBJ", out_of(["trace", flat, "--from", "v:40", "--dir", "1,0.3,0", "--length", "0.7", "-o", o("t.obj")], o("t.obj"))),
    ("trace --batch", out_of(["trace", flat, "--batch", batch])),
    ("field summary", out_of(["field", flat, "--from", "f:10:0.2,0.3,0.5"])),
    ("field -o CSV", out_of(["field", flat, "--from", "f:10:0.2,0.3,0.5", "-o", "-"])),
    ("field --at", out_of(["field", flat, "--from", "f:10:0.2,0.3,0.5", "--at", pts])),
    ("field --sources CSV", out_of(["field", flat, "--sources", srcs, "-o", o("m.csv")], o("m.csv"))),
    ("field --sources --to", out_of(["field", flat, "--sources", srcs, "--to", pts, "-o", o("t.csv")], o("t.csv"))),
    ("field --sparse", out_of(["field", flat, "--sources", srcs, "--sparse", "--max-distance", "0.3", "-o", o("sp.csv")], o("sp.csv"))),
    ("field --sparse summary", out_of(["field", flat, "--sources", srcs, "--max-distance", "0.3", "-o", o("sp.npz")])),
    ("field --labels", out_of(["field", flat, "--sources", srcs, "--labels", "-o", o("l.csv"), "--boundaries", o("b.obj")], o("l.csv"))),
    ("field --boundaries OBJ", open(o("b.obj")).read() if os.path.exists(o("b.obj")) else ""),
    ("field --boundaries JSON", out_of(["field", flat, "--sources", srcs, "--labels", "--boundaries", o("b.json")], o("b.json"))),
    ("field --isolines OBJ", out_of(["field", flat, "--from", "f:10:0.2,0.3,0.5", "--isolines", "0.3,0.55", "-o", o("i.obj")], o("i.obj"))),
    ("field --isolines JSON", out_of(["field", flat, "--from", "f:10:0.2,0.3,0.5", "--isoline-count", "3", "-o", o("i.json")], o("i.json"))),
    ("field --isolines summary", out_of(["field", flat, "--from", "f:10:0.2,0.3,0.5", "--isoline-count", "3", "-o", o("i.json")])),
    ("logmap CSV", out_of(["logmap", flat, "--from", "f:10:0.2,0.3,0.5", "-o", "-"])),
    ("logmap summary", out_of(["logmap", flat, "--from", "f:10:0.2,0.3,0.5", "-o", o("lm.npy")])),
    ("sample -o CSV", out_of(["sample", flat, "--count", "4", "-o", o("s.csv")], o("s.csv"))),
    ("sample --field", out_of(["sample", flat, "--count", "4", "--field", o("sf.csv")], o("sf.csv"))),
    ("sample summary", out_of(["sample", flat, "--count", "4"])),
]
for what, text in outputs: numbers_shortest(what, text)
# messages quote numbers the same way
r = run("path", flat, "--pairs", write("p.txt", "v 0 1\np 0.1 0.2 0 0.7 0.6 1.0000000000000001e200\n"))
check("1e+200" in r.stderr, "a coordinate quoted in a message: %r" % r.stderr.strip())

# ---- .npy queries in every float layout NumPy writes ----
# NumPy writes them (np.save); an interpreter with NumPy: this one, else Debian's (make deps)
writer = r"""
import sys, numpy as np
out = sys.argv[1]
rng = np.random.default_rng(7)
q = rng.uniform(-0.5, 1.5, (257, 3))
q[:, 2] = rng.uniform(-0.2, 0.2, 257)
q[0] = (1e-40, 0.5, 0)  # a float32 subnormal
q32 = q.astype(np.float32)
np.save(out + "/ref64.npy", q32.astype(np.float64))
for name, a in [("le4", q32), ("be4", q32.astype(">f4")), ("f4F", np.asfortranarray(q32)),
                ("be4F", np.asfortranarray(q32.astype(">f4"))), ("le8", q32.astype(np.float64)),
                ("be8", q32.astype(">f8")), ("f8F", np.asfortranarray(q32.astype(np.float64))),
                ("be8F", np.asfortranarray(q32.astype(">f8")))]:
    np.save(out + "/" + name + ".npy", a)
bad = q32.copy(); bad[5, 1] = np.nan
np.save(out + "/nan4.npy", bad)
"""
pythons = [sys.executable, "/usr/bin/python3"]
made = False
for py in pythons:
    if os.path.exists(py) and subprocess.run([py, "-c", writer, tmp], capture_output=True).returncode == 0:
        made = True
        break
check(made, "no Python with NumPy to write .npy files (python3-numpy: make deps)")
if made:
    want = run("closest", flat, os.path.join(tmp, "ref64.npy"), "--signed")
    check(want.returncode == 0 and len(want.stdout.splitlines()) == 258, "float64 reference: exit %d %r" % (want.returncode, want.stderr))
    for name in ("le4", "be4", "f4F", "be4F", "le8", "be8", "f8F", "be8F"):
        got = run("closest", flat, os.path.join(tmp, name + ".npy"), "--signed")
        check(got.returncode == 0 and got.stdout == want.stdout,
              "closest %s.npy: exit %d %r, %s" % (name, got.returncode, got.stderr.strip(),
                                                   "same answers" if got.stdout == want.stdout else "answers differ from float64"))
    r = run("closest", flat, os.path.join(tmp, "nan4.npy"), "-o", o("never.csv"))
    check(r.returncode == 2 and "row 5 (from 0), y is nan" in r.stderr and not os.path.exists(o("never.csv")),
          "float32 nan: exit %d %r" % (r.returncode, r.stderr.strip()))

shutil.rmtree(tmp)
cli_common.finish()
PY
