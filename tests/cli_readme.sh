#!/usr/bin/env bash
# cli_readme.sh: the README's hand-run demo ("What `make demo` does, by hand") as a reader runs it:
# every "$ " command of that block, run from the repository with this build's trigeo first on
# PATH (build/ outputs sent to a temporary directory), prints what the README shows below it
# ("..." stands for any text; a "# N vertices, N faces, closed, genus G" comment is checked
# against the report), and the straightened length the README quotes for the demo pair is the
# one `path --method straighten` prints. The max angle defect is compared in the release build
# only (the sanitizer build's compiler may round the last bits differently). And the README's
# table of src/geodesic lists exactly the files there. scripts/demo.sh (make demo) runs the same
# trigeo commands as that block, and the README says where the CLI is (build/trigeo) before its
# first example.
set -u
trigeo=${TG_TRIGEO:?}
exec /usr/bin/env python3 - "$trigeo" <<'PY'
import os, re, shlex, shutil, subprocess, sys, tempfile
trigeo = sys.argv[1]
src = os.environ["TG_SOURCE_DIR"]
sanitized = os.environ.get("TG_SANITIZED", "0") not in ("0", "", "FALSE", "false")
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(src, "tests"))
import cli_common
from cli_common import check

readme = open(os.path.join(src, "README.md")).read()
m = re.search(r"What `make demo` does(?:(?!```).)*?by hand(?:(?!```).)*?:\n\n```\n(.*?)```", readme, re.S)
check(m is not None, "README: the demo block")
tmp = tempfile.mkdtemp()
env = dict(os.environ, PATH=os.path.dirname(os.path.abspath(trigeo)) + os.pathsep + os.environ["PATH"])

blocks = []  # (command, comment, expected lines)
for line in (m.group(1) if m else "").splitlines():
    if line.startswith("$ "):
        cmd, _, comment = line[2:].partition(" # ")
        blocks.append((cmd.strip(), comment.strip(), []))
    elif blocks:
        blocks[-1][2].append(line)
check(len(blocks) >= 4, "README demo: %d commands" % len(blocks))

def run(cmd):
    cmd = re.sub(r"(?<![\w/])build/", tmp + "/", cmd)
    return subprocess.run(["bash", "-c", cmd], cwd=src, env=env, capture_output=True, text=True)

for cmd, comment, want in blocks:
    r = run(cmd)
    check(r.returncode == 0, "README demo '%s': exit %d %s" % (cmd, r.returncode, r.stderr))
    got = r.stdout.splitlines()
    if comment:  # "2930 vertices, 5856 faces, closed, genus 0"
        report = r.stdout
        for n, what in re.findall(r"(\d+) (vertices|faces)", comment):
            check(re.search(r"^\s*%s\s+%s$" % (what, n), report, re.M), "README demo: '%s' (%s)" % (comment, what))
        g = re.search(r"genus (\d+)", comment)
        if g:
            check(re.search(r"^\s*genus\s+%s \(closed manifold\)" % g.group(1), report, re.M),
                  "README demo: '%s' (genus): %s" % (comment, report))
    if not want:
        continue
    if want[-1] == "...":  # more rows follow in the README's eyes: compare the ones shown
        want = want[:-1]
        got = got[:len(want)]
    check(len(got) == len(want), "README demo '%s': %d lines, README shows %d" % (cmd, len(got), len(want)))
    for w, g in zip(want, got):
        if sanitized and w.startswith("max angle defect"):
            w = "max angle defect ..."
        pattern = ".*".join(re.escape(part) for part in w.split("..."))
        check(re.fullmatch(pattern, g) is not None, "README demo '%s': README shows %r, trigeo prints %r" % (cmd, w, g))

# the README's demo is what `make demo` runs: scripts/demo.sh through a trigeo that logs its
# arguments runs the same trigeo commands in the same order (its files go beside the trigeo
# binary, the README's build/)
wrap = os.path.join(tmp, "wrap")
os.makedirs(wrap)
log = os.path.join(tmp, "demo.log")
with open(os.path.join(wrap, "trigeo"), "w") as f:
    f.write('#!/usr/bin/env bash\nfor a in "$@"; do printf "%%s\\t" "$a"; done >> %s\necho >> %s\nexec %s "$@"\n'
            % (shlex.quote(log), shlex.quote(log), shlex.quote(os.path.abspath(trigeo))))
os.chmod(os.path.join(wrap, "trigeo"), 0o755)
r = subprocess.run(["bash", os.path.join(src, "scripts", "demo.sh"), os.path.join(wrap, "trigeo")], capture_output=True, text=True)
check(r.returncode == 0, "scripts/demo.sh: exit %d %s" % (r.returncode, r.stderr))
def normal(arg):
    return arg.replace(os.path.join(src, "data") + "/", "data/").replace(wrap + "/", "build/")
ran = [[normal(a) for a in l.rstrip("\n").split("\t")[:-1]] for l in open(log)] if os.path.exists(log) else []
shown = [shlex.split(cmd.split("|")[-1])[1:] for cmd, _, _ in blocks]
check(ran == shown, "README demo and scripts/demo.sh run different commands:\n  README: %s\n  demo.sh: %s" % (shown, ran))
# the CLI's place after the build, said before the first example that calls it trigeo
first_example = readme.find("\ntrigeo info MESH")  # the CLI tour's first line
check("build/trigeo" in readme[:first_example] and "PATH" in readme[:first_example] and "make install" in readme[:first_example],
      "README: where the CLI is (build/trigeo, PATH, make install) before the first `trigeo` example")

# the straightened path of the demo pair, as the README's prose quotes it
q = re.search(r"On the demo pair\s+above it stops at ([0-9.]+)", readme)
path_cmd = next((c for c, _, _ in blocks if " path " in " " + c), None)
check(q is not None and path_cmd is not None, "README: the straightened length of the demo pair")
if q and path_cmd:
    r = run(path_cmd + " --method straighten")
    length = re.search(r"^length\s+(\S+)$", r.stdout, re.M)
    check(length is not None and length.group(1) == q.group(1),
          "README: straighten stops at %s, trigeo prints %s" % (q.group(1), length and length.group(1)))
# the README's table of src/geodesic names every file there, and only those
geo = os.path.join(src, "src", "geodesic")
actual = sorted(os.path.relpath(os.path.join(d, f), geo) for d, _, fs in os.walk(geo) for f in fs)
section = readme.split("`src/geodesic`, the solver core", 1)[-1].split("\n## ", 1)[0]
listed = sorted(n for row in section.splitlines() if row.startswith("| `")
                for n in re.findall(r"`([^`]+)`", row.split("|")[1]))
check(listed == actual, "README's src/geodesic table: missing %s, not there %s"
      % (sorted(set(actual) - set(listed)), sorted(set(listed) - set(actual))))
shutil.rmtree(tmp)
cli_common.finish()
PY
