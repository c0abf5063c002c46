#!/usr/bin/env bash
# cli_input_lines.sh: every line-oriented input of the CLI refuses what it does not read, with
# FILE:LINE and the reason, exit 2 and no output: a field after the last one (a trace batch's
# fourth, a pairs line's tenth, text after a source, a point or a query) was dropped silently by
# the batch and pairs readers. And every ';' list (field/render --from, path --through) takes
# blanks around its items: "v:0; v:5" is the list "v:0;v:5", the same output byte for byte. An
# option's value is read whole too (render --size 100x100abc was 100x100).
set -u
trigeo=${TG_TRIGEO:?}
exec /usr/bin/env python3 - "$trigeo" <<'PY'
import os, shutil, subprocess, sys, tempfile
trigeo = sys.argv[1]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check

def run(cmd, *args):
    return subprocess.run([trigeo, cmd, *args], capture_output=True, text=True)
tmp = tempfile.mkdtemp()
flat, vs, fs = cli_common.flat_square(tmp, 11, 8)
out = os.path.join(tmp, "never.csv")
def refused(what, args, name, text, line, code=2):
    p = os.path.join(tmp, name)
    with open(p, "w") as f: f.write(text)
    r = run(*[p if a == "@" else a for a in args])
    where = "%s:%d: " % (p, line)
    check(r.returncode == code and where in r.stderr and not os.path.exists(out),
          "%s %r: exit %d (want %d), stderr %r (want %r), output %s" % (what, text, r.returncode, code, r.stderr.strip(),
                                                                        where, os.path.exists(out)))
    if os.path.exists(out): os.remove(out)

# ---- a field too many ----
good_trace = "v:22 1,0,0 0.1\n"
for junk in ("v:22 1,0,0 0.1 0.5", "v:22 0.5 0.1 0.5", "v:22 1,0,0 0.1 #", "f:10:0.2,0.3,0.5 1,0,0 0.1 x"):
    refused("trace --batch", ["trace", flat, "--batch", "@", "-o", out], "b.txt", good_trace + junk + "\n", 2)
good_pair = "v 0 40\n"
for junk in ("v 0 40 7", "f 10 0.2 0.3 0.5 20 0.3 0.3 0.4 1", "p 10 0.2 0.3 0.5 20 0.3 0.3 0.4 x", "p 0.1 0.1 0 0.6 0.6 0 1"):
    refused("path --pairs", ["path", flat, "--pairs", "@", "-o", out], "p.txt", good_pair + junk + "\n", 2)
for junk in ("v:3 v:4", "v:3 junk", "f:10:0.2,0.3,0.5,0.1", "e:30:0.5 0.5"):
    refused("field --sources", ["field", flat, "--sources", "@", "-o", out], "s.txt", "v:40\n" + junk + "\n", 2)
src = os.path.join(tmp, "s0.txt")
with open(src, "w") as f: f.write("v:40\n")
for junk in ("0.5 0.5 0 1", "0.5 0.5 0,", "0.5,,0.5,0", "0.5 0.5", "v:3 1", "0.5-0.5 0"):
    refused("field --at", ["field", flat, "--from", "v:40", "--at", "@", "-o", out], "a.txt", "0.1 0.1 0\n" + junk + "\n", 2)
    refused("field --to", ["field", flat, "--sources", src, "--to", "@", "-o", out], "a.txt", "0.1 0.1 0\n" + junk + "\n", 2)
for junk in ("0.5 0.5 0 1", "0.5 0.5 0 x"):
    refused("closest", ["closest", flat, "@", "-o", out], "q.txt", "0 0 0\n" + junk + "\n", 2)
for levels in ("0.1,0.2 x", "0.1 0.2", "0.1,0.2,"):
    r = run("field", flat, "--from", "v:40", "--isolines", levels, "-o", os.path.join(tmp, "never.obj"))
    check(r.returncode == 2 and "--isolines" in r.stderr and not os.path.exists(os.path.join(tmp, "never.obj")),
          "--isolines %r: exit %d, %r" % (levels, r.returncode, r.stderr.strip()))

# ---- ';' lists: blanks around items ----
def same(cmd, args, spaced, tight, outname):
    outs = []
    for lst in (tight, spaced):
        o = os.path.join(tmp, outname)
        r = run(cmd, flat, *[lst if a == "@" else a for a in args], "-o", o)
        outs.append(open(o, "rb").read() if r.returncode == 0 and os.path.exists(o) else None)
        check(r.returncode == 0, "%s %r: exit %d, %r" % (cmd, lst, r.returncode, r.stderr.strip()))
        if os.path.exists(o): os.remove(o)
    check(outs[0] is not None and outs[0] == outs[1], "%s %r and %r: different outputs" % (cmd, spaced, tight))
same("field", ["--from", "@"], "v:0; v:5", "v:0;v:5", "f.csv")
same("field", ["--from", "@"], " v:0 ;\tf:10:0.2,0.3,0.5 ; p:0.5,0.5,0 ", "v:0;f:10:0.2,0.3,0.5;p:0.5,0.5,0", "f.csv")
same("field", ["--from", "@", "--labels"], "v:0; v:5", "v:0;v:5", "l.csv")
same("path", ["--through", "@"], "v:0; v:40 ; v:3", "v:0;v:40;v:3", "t.obj")
same("render", ["--from", "@", "--size", "32x24"], "v:0; v:5", "v:0;v:5", "r.png")
same("path", ["--to", "v:40", "--from", "@"], " f:10:0.2,0.3,0.5 ", "f:10:0.2,0.3,0.5", "p.obj")
for bad in ("v:0;;v:5", "v:0; ;v:5", "v:0;", " ; "):
    r = run("field", flat, "--from", bad)
    check(r.returncode == 1 and "--from" in r.stderr, "field --from %r: exit %d, %r" % (bad, r.returncode, r.stderr.strip()))
    r = run("path", flat, "--through", bad)
    check(r.returncode == 1 and "--through" in r.stderr, "path --through %r: exit %d, %r" % (bad, r.returncode, r.stderr.strip()))

# ---- option values: the whole value or nothing ----
png = os.path.join(tmp, "never.png")
for opt, args in (("--size", ["render", flat, "--size", "100x100abc", "-o", png]),
                  ("--size", ["render", flat, "--size", "64x48.5", "-o", png]),
                  ("--size", ["render", flat, "--size", "16x16x16", "-o", png]),
                  ("--threads", ["field", flat, "--sources", src, "--threads", "2x", "-o", out]),
                  ("--count", ["sample", flat, "--count", "3x"]), ("--seed", ["sample", flat, "--count", "2", "--seed", " -5"]),
                  ("--max-steps", ["trace", flat, "--from", "v:40", "--angle", "1", "--length", "0.1", "--max-steps", "1.5"])):
    r = run(*args)
    check(r.returncode == 1 and opt in r.stderr and not os.path.exists(png) and not os.path.exists(out),
          "%s: exit %d (want 1), %r" % (args[2:], r.returncode, r.stderr.strip()))
    for p in (png, out):
        if os.path.exists(p): os.remove(p)
r = run("render", flat, "--size", "32x24", "-o", png)
check(r.returncode == 0 and os.path.exists(png), "--size 32x24: exit %d %r" % (r.returncode, r.stderr))

shutil.rmtree(tmp)
cli_common.finish()
PY
