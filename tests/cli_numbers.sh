#!/usr/bin/env bash
# cli_numbers.sh: the CLI's one rule for numbers (README.md "Numbers"), in every place that reads
# one: a number is its decimal text's nearest double, subnormals included (4.9e-324 is the
# smallest double, not an error), text that underflows is 0, text beyond the largest double is
# refused as not finite, then the option's range. Options (--max-distance, --length, --angle,
# --dir, --ref, --isolines levels), SPEC coordinates and barycentrics, and the batch, pairs,
# sources, points and queries files. Known answers on the jittered flat square of cli_common.
set -u
trigeo=${TG_TRIGEO:?}
exec /usr/bin/env python3 - "$trigeo" <<'PY'
import os, shutil, subprocess, sys, tempfile
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

shutil.rmtree(tmp)
cli_common.finish()
PY
