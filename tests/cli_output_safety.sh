#!/usr/bin/env bash
# cli_output_safety.sh: no run of any command destroys a file it reads or writes two outputs into
# one file, and the outputs of a run are one transaction.
# 1. A table of every command and mode (31 command lines) with every output option: each output is given as each
#    input of the run (the file itself, a symbolic link to it, a hard link to it, and the input
#    read through a link), and as another output of the run (the same name, the same name spelled
#    differently, a link): refused (exit 1) before any work, every input byte-identical, no file or
#    temporary written. Each row runs once with fresh output names first and must succeed, so a
#    refusal is the clash's, not a bad command line's.
# 2. Transactions: when one output cannot be written (its folder does not exist: before any work;
#    a device that fails the write: after the work), the other output of the run keeps its old
#    content, and no temporary is left.
# 3. Every -o refuses an extension whose format the command cannot write (render -o x.jpg).
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

def run(*args):
    return subprocess.run([trigeo, *args], capture_output=True)

def leftovers():
    return sorted(f for f in os.listdir(tmp) if f.startswith(".trigeo-"))

# ---- the inputs of every mode ----
shutil.copy(os.path.join(meshes, "oded_spot_low_resolution.obj"), "mesh.obj")
open("sources.txt", "w").write("v:0\nv:400\n")
open("points.txt", "w").write("v:3\nv:9\n")
open("queries.txt", "w").write("0 0 0\n0.1 0.2 0.3\n")
open("pairs.txt", "w").write("v 0 5\nv 3 9\n")
open("traces.txt", "w").write("v:0 1,0,0 0.1\nv:5 0.5 0.2\n")
made = [run("path", "mesh.obj", "--from", "v:0", "--to", "v:300", "-o", "in_path.obj"),
        run("field", "mesh.obj", "--from", "v:0", "-o", "in_field.ply"),
        run("field", "mesh.obj", "--sources", "sources.txt", "--labels", "-o", "in_labels.ply", "--boundaries", "in_bounds.obj"),
        run("logmap", "mesh.obj", "--from", "v:0", "-o", "in_logmap.ply"),
        run("field", "mesh.obj", "--from", "v:0", "--isoline-count", "3", "-o", "in_iso.obj")]
check(all(r.returncode == 0 for r in made), "the overlay inputs: %r" % [r.stderr for r in made if r.returncode])

# Each row: the command line with {mesh}, {in:NAME} for an input file and {out:SLOT.ext} for an
# output (SLOT names the option in messages); the extension is the one the option writes.
rows = [
    "info {mesh} -o {out:o.json}",
    "closest {mesh} {in:queries.txt} -o {out:o.csv}",
    "closest {mesh} {in:queries.txt} -o {out:o.npy}",
    "path {mesh} --from v:0 --to v:5 -o {out:o.obj}",
    "path {mesh} --from v:0 --to v:5 -o {out:o.json}",
    "path {mesh} --through v:0;v:5;v:9 -o {out:o.obj}",
    "path {mesh} --pairs {in:pairs.txt} -o {out:o.csv}",
    "trace {mesh} --from v:0 --angle 1 --length 0.5 -o {out:o.obj}",
    "trace {mesh} --from v:0 --angle 1 --length 0.5 -o {out:o.json}",
    "trace {mesh} --batch {in:traces.txt} -o {out:o.csv}",
    "logmap {mesh} --from v:0 -o {out:o.ply}",
    "logmap {mesh} --from v:0 -o {out:o.npy}",
    "logmap {mesh} --from v:0 -o {out:o.csv}",
    "field {mesh} --from v:0 -o {out:o.ply}",
    "field {mesh} --from v:0 --csv {out:o.csv}",
    "field {mesh} --from v:0 --at {in:points.txt} -o {out:o.txt}",
    "field {mesh} --sources {in:sources.txt} -o {out:o.npy}",
    "field {mesh} --sources {in:sources.txt} --max-distance 0.2 -o {out:o.npz}",
    "field {mesh} --sources {in:sources.txt} --sparse -o {out:o.csv}",
    "field {mesh} --sources all --max-distance 0.05 -o {out:o.npz}",
    "field {mesh} --sources {in:sources.txt} --to {in:points.txt} -o {out:o.csv}",
    "field {mesh} --sources {in:sources.txt} --labels -o {out:o.ply} --boundaries {out:b.obj}",
    "field {mesh} --from v:0;v:400 --labels -o {out:o.csv} --boundaries {out:b.json}",
    "field {mesh} --from v:0 --isoline-count 3 -o {out:o.obj}",
    "field {mesh} --sources {in:sources.txt} --isolines 0.1,0.2 -o {out:o.json}",
    "sample {mesh} --count 3 -o {out:o.txt} --field {out:f.ply}",
    "sample {mesh} --count 3 -o {out:o.csv} --field {out:f.csv}",
    "render {mesh} --size 48x36 --path {in:in_path.obj} --field {in:in_field.ply} --isolines {in:in_iso.obj} -o {out:o.png}",
    "render {mesh} --size 48x36 --boundaries {in:in_bounds.obj} --labels {in:in_labels.ply} -o {out:o.png}",
    "render {mesh} --size 48x36 --logmap {in:in_logmap.ply} -o {out:o.png}",
    "render {mesh} --size 48x36 --from v:0 -o {out:o.png}",
]

def expand(row, subst_in, subst_out):
    """The argv of a row: {mesh} and {in:X} through subst_in(name), {out:S.ext} through subst_out(S, ext)."""
    argv = []
    for tok in row.split():
        if tok == "{mesh}":
            tok = subst_in("mesh.obj")
        elif tok.startswith("{in:"):
            tok = subst_in(tok[4:-1])
        elif tok.startswith("{out:"):
            slot, ext = tok[5:-1].split(".")
            tok = subst_out(slot, ext)
        argv.append(tok)
    return argv

def snapshot():
    """Every file of the folder (links as links) and its bytes."""
    out = {}
    for f in os.listdir(tmp):
        p = os.path.join(tmp, f)
        out[f] = ("link", os.readlink(p)) if os.path.islink(p) else ("file", open(p, "rb").read())
    return out

def refused(argv, why):
    """Runs argv, which must be refused as a clash: exit 1, 'same file' named, nothing changed."""
    before = snapshot()
    r = run(*argv)
    after = snapshot()
    changed = sorted(f for f in set(before) | set(after) if before.get(f) != after.get(f))
    check(r.returncode == 1 and b"same file" in r.stderr and not changed,
          "%s: trigeo %s: exit %d (want 1, 'same file'), changed %s: %r" % (why, " ".join(argv), r.returncode, changed, r.stderr[-300:]))

def reset_links():
    for f in os.listdir(tmp):
        if f.startswith(("as_", "new_", "via_")):
            os.unlink(os.path.join(tmp, f))

for row in rows:
    inputs = ["mesh.obj"] + [t[4:-1] for t in row.split() if t.startswith("{in:")]
    slots = [t[5:-1].split(".") for t in row.split() if t.startswith("{out:")]
    # the control: fresh names, exit 0, every output written
    argv = expand(row, lambda n: n, lambda s, e: "new_%s.%s" % (s, e))
    r = run(*argv)
    check(r.returncode == 0 and all(os.path.exists("new_%s.%s" % (s, e)) for s, e in slots),
          "control: trigeo %s: exit %d %r" % (" ".join(argv), r.returncode, r.stderr[-300:]))
    reset_links()
    for slot, ext in slots:
        for name in inputs:
            fresh = lambda s, e: "new_%s.%s" % (s, e)
            # the input file itself, under a name with the output's extension (inputs are read by
            # content: a mesh named mesh.png is still read as OBJ)
            same = "as_%s.%s" % (name.replace(".", "_"), ext)
            shutil.copy(name, same)
            argv = expand(row, lambda n: same if n == name else n, lambda s, e: same if s == slot else fresh(s, e))
            refused(argv, "output %s = input %s" % (slot, name))
            os.unlink(same)
            # a symbolic link and a hard link to the input as the output
            for kind, make in (("symlink", os.symlink), ("hardlink", os.link)):
                link = "as_%s_%s.%s" % (kind, name.replace(".", "_"), ext)
                make(name, link)
                argv = expand(row, lambda n: n, lambda s, e: link if s == slot else fresh(s, e))
                refused(argv, "output %s = %s to input %s" % (slot, kind, name))
                os.unlink(link)
            # the input read through a symbolic link, the output its target
            target = "as_target_%s.%s" % (name.replace(".", "_"), ext)
            shutil.copy(name, target)
            via = "via_%s" % name
            os.symlink(target, via)
            argv = expand(row, lambda n: via if n == name else n, lambda s, e: target if s == slot else fresh(s, e))
            refused(argv, "output %s = input %s read through a link" % (slot, name))
            os.unlink(via), os.unlink(target)
    # two outputs of the run into one file
    if len(slots) == 2:
        (s0, e0), (s1, e1) = slots
        cases = []
        if e0 == e1:
            cases.append(("the same new name", "as_both.%s" % e0, "as_both.%s" % e1, None))
            cases.append(("the same new name spelled ./", "as_both.%s" % e0, "./as_both.%s" % e1, None))
            cases.append(("the same new name through its folder", "as_both.%s" % e0, "../%s/as_both.%s" % (os.path.basename(tmp), e1), None))
        cases.append(("a symbolic link to the first", "as_first.%s" % e0, "as_link.%s" % e1, os.symlink))
        cases.append(("a hard link to the first", "as_first.%s" % e0, "as_link.%s" % e1, os.link))
        for why, first, second, make in cases:
            if make:
                open(first, "w").write("keep\n")
                make(first, second)
            argv = expand(row, lambda n: n, lambda s, e: first if s == s0 else second)
            refused(argv, "outputs %s and %s: %s" % (s0, s1, why))
            reset_links()
check(not leftovers(), "no temporaries left: %s" % leftovers())

# ---- 2. one transaction per run ----
for old in ("keep.ply", "keep.txt", "keep.csv"):
    open(old, "w").write("keep\n")
transactions = [
    ("field", "mesh.obj", "--sources", "sources.txt", "--labels", "-o", "keep.ply", "--boundaries", "/nonexistent/b.obj"),
    ("field", "mesh.obj", "--sources", "sources.txt", "--labels", "-o", "keep.csv", "--boundaries", "/nonexistent/b.json"),
    ("sample", "mesh.obj", "--count", "3", "-o", "keep.txt", "--field", "/nonexistent/x.ply"),
    ("sample", "mesh.obj", "--count", "3", "-o", "/nonexistent/s.txt", "--field", "keep.ply"),
]
for argv in transactions:
    r = run(*argv)
    check(r.returncode == 2 and b"/nonexistent" in r.stderr and b"nothing written" in r.stderr,
          "trigeo %s: exit %d (want 2) %r" % (" ".join(argv), r.returncode, r.stderr))
# an output that fails as it is written (a full device), after the work: the other is not renamed
if os.path.exists("/dev/full"):
    os.symlink("/dev/full", "full.obj"), os.symlink("/dev/full", "full.ply"), os.symlink("/dev/full", "full.txt")
    for argv in (("field", "mesh.obj", "--sources", "sources.txt", "--labels", "-o", "keep.ply", "--boundaries", "full.obj"),
                 ("sample", "mesh.obj", "--count", "3", "-o", "keep.txt", "--field", "full.ply"),
                 ("sample", "mesh.obj", "--count", "3", "-o", "full.txt", "--field", "keep.ply")):
        r = run(*argv)
        check(r.returncode == 2 and b"full" in r.stderr, "trigeo %s: exit %d (want 2) %r" % (" ".join(argv), r.returncode, r.stderr))
    for f in ("full.obj", "full.ply", "full.txt"):
        os.unlink(f)
for old in ("keep.ply", "keep.txt", "keep.csv"):
    got = open(old, "rb").read()
    check(got == b"keep\n", "%s after the failed runs: %r (want 'keep')" % (old, got[:60]))
# and when both can be written, both are
r = run("sample", "mesh.obj", "--count", "3", "-o", "keep.txt", "--field", "keep.ply")
check(r.returncode == 0 and open("keep.txt").read().startswith("v:") and open("keep.ply", "rb").read(3) == b"ply",
      "sample with two outputs: %d %r" % (r.returncode, r.stderr))
check(not leftovers(), "no temporaries left: %s" % leftovers())

# ---- 3. an extension the command cannot write is refused, nothing written ----
bad_ext = [
    ("render", "mesh.obj", "-o", "x.jpg"),
    ("render", "mesh.obj", "-o", "x"),
    ("info", "mesh.obj", "-o", "x.ply"),
    ("closest", "mesh.obj", "queries.txt", "-o", "x.json"),
    ("path", "mesh.obj", "--pairs", "pairs.txt", "-o", "x.json"),
    ("path", "mesh.obj", "--from", "v:0", "--to", "v:5", "-o", "x.csv"),
    ("trace", "mesh.obj", "--from", "v:0", "--angle", "1", "--length", "0.5", "-o", "x.csv"),
    ("trace", "mesh.obj", "--batch", "traces.txt", "-o", "x.json"),
    ("logmap", "mesh.obj", "--from", "v:0", "-o", "x.obj"),
    ("field", "mesh.obj", "--from", "v:0", "-o", "x.xyz"),
    ("field", "mesh.obj", "--from", "v:0", "--isoline-count", "2", "-o", "x.ply"),
    ("field", "mesh.obj", "--sources", "sources.txt", "--labels", "-o", "x.ply", "--boundaries", "x.csv"),
    ("sample", "mesh.obj", "--count", "3", "-o", "x.ply"),
    ("sample", "mesh.obj", "--count", "3", "--field", "x.txt"),
]
for argv in bad_ext:
    before = set(os.listdir(tmp))
    r = run(*argv)
    new = sorted(set(os.listdir(tmp)) - before)
    check(r.returncode == 1 and not new, "trigeo %s: exit %d (want 1), new files %s %r" % (" ".join(argv), r.returncode, new, r.stderr))
    for f in new:
        os.unlink(f)
shutil.rmtree(tmp)
cli_common.finish()
PY
