#!/usr/bin/env bash
# cli_messages.sh: what the CLI says besides its data. --quiet means one thing in every command
# that has it (field in all its forms, logmap, sample): no progress line and no summary, while
# errors are still printed and data sent to stdout still is. Every summary words the same thing
# the same way: "largest distance", "windows N created, M propagated", labels in one column. A path
# between components says that no path exists (summary; JSON and CSV: status unreachable, the CSV
# columns unchanged), with every method and through waypoints. Messages name the option the user
# gave (--to, not --at), print no doubled word ("the the mesh") and no "-0".
set -u
trigeo=${TG_TRIGEO:?}
exec /usr/bin/env python3 - "$trigeo" <<'PY'
import csv, io, json, os, re, shutil, subprocess, sys, tempfile
trigeo = sys.argv[1]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.environ["TG_SOURCE_DIR"], "tests"))
import cli_common
from cli_common import check

def run(cmd, *args):
    return subprocess.run([trigeo, cmd, *args], capture_output=True, text=True)
tmp = tempfile.mkdtemp()
flat, vs, fs = cli_common.flat_square(tmp, 11, 8)
def write(name, text):
    p = os.path.join(tmp, name)
    with open(p, "w") as f: f.write(text)
    return p
def o(name): return os.path.join(tmp, name)
src, pts = write("s.txt", "v:0\nv:40\n"), write("a.txt", "0.5 0.5 0\nv:3\n")

# ---- --quiet: nothing but the data ----
runs = [("field", ["--from", "v:0", "-o", o("f.csv")]), ("field", ["--from", "v:0"]),
        ("field", ["--from", "v:0", "-o", o("f.ply")]), ("field", ["--from", "v:0;v:40", "--labels", "-o", o("l.csv")]),
        ("field", ["--sources", src, "--labels", "-o", o("l.ply"), "--boundaries", o("b.obj")]),
        ("field", ["--from", "v:0", "--isoline-count", "3", "-o", o("i.obj")]),
        ("field", ["--sources", src, "--max-distance", "0.3", "-o", o("m.npz")]),
        ("field", ["--sources", src, "-o", o("m.npy")]), ("field", ["--sources", src, "--to", pts, "-o", o("t.csv")]),
        ("field", ["--from", "v:0", "--at", pts, "-o", o("at.txt")]),
        ("logmap", ["--from", "v:40", "-o", o("lm.csv")]), ("logmap", ["--from", "v:40", "-o", o("lm.npy")]),
        ("sample", ["--count", "3", "-o", o("s3.txt")]), ("sample", ["--count", "3", "--field", o("sf.csv")]),
        ("sample", ["--count", "3"])]
for cmd, args in runs:
    loud, quiet = run(cmd, flat, *args), run(cmd, flat, *args, "--quiet")
    check(loud.returncode == 0 and loud.stdout.strip() != "", "%s %s: a summary without --quiet (exit %d, %r)"
          % (cmd, args, loud.returncode, loud.stdout[:80]))
    check(quiet.returncode == 0 and quiet.stdout == "" and quiet.stderr == "",
          "%s %s --quiet: exit %d, stdout %r, stderr %r (want both empty)" % (cmd, args, quiet.returncode, quiet.stdout[:200],
                                                                              quiet.stderr[:200]))
# data sent to stdout is still written, and errors still printed
for cmd, args in [("field", ["--from", "v:0", "-o", "-"]), ("field", ["--from", "v:0", "--at", pts]),
                  ("logmap", ["--from", "v:40", "-o", "-"]), ("sample", ["--count", "3", "-o", "-"])]:
    loud, quiet = run(cmd, flat, *args), run(cmd, flat, *args, "--quiet")
    check(quiet.returncode == 0 and quiet.stdout != "" and quiet.stdout == loud.stdout and quiet.stderr == "",
          "%s %s --quiet: the data %r, without --quiet %r" % (cmd, args, quiet.stdout[:60], loud.stdout[:60]))
for cmd, args in [("field", ["--from", "v:9999"]), ("logmap", ["--from", "v:9999", "-o", o("x.csv")]),
                  ("sample", ["--count", "999"])]:
    r = run(cmd, flat, *args, "--quiet")
    check(r.returncode == 2 and r.stderr.startswith("trigeo: "), "%s %s --quiet: the error (exit %d, %r)"
          % (cmd, args, r.returncode, r.stderr))
for cmd in ("field", "logmap", "sample"):
    h = run(cmd, "--help").stdout
    check("--quiet" in h and "no summary" in h, "%s --help: --quiet says 'no summary'" % cmd)

# ---- one wording in every summary ----
summaries = {}
for cmd, args in runs:
    r = run(cmd, flat, *args)
    summaries["%s %s" % (cmd, " ".join(a for a in args if not a.startswith(tmp)))] = r.stdout
for what, text in summaries.items():
    lines = text.splitlines()
    windows = [l for l in lines if l.startswith("windows")]
    check(len(windows) == 1 and re.fullmatch(r"windows {12}\d+ created, \d+ propagated", windows[0]),
          "%s: windows line %r (want 'windows            N created, M propagated')" % (what, windows))
    check(not any(l.startswith(("max distance", "maximum distance", "farthest")) for l in lines),
          "%s: the largest distance worded otherwise: %r" % (what, lines))
    check(all(re.fullmatch(r"[a-z][a-z -]{0,17} {1,}\S.*", l) and l[18] == " " and l[19] != " " for l in lines),
          "%s: labels not in one 19-column field: %r" % (what, lines))
for what in ("field --from v:0 -o", "logmap --from v:40 -o"):
    text = summaries.get(what, "")
    check(any(l.startswith("largest distance   ") for l in text.splitlines()), "%s: 'largest distance' in %r" % (what, text))

# ---- no path between components ----
far = "v:%d" % (len(vs) - 2)  # the lone far triangle
for args in (["--from", "v:0", "--to", far], ["--from", "f:10:0.2,0.3,0.5", "--to", far, "--method", "straighten"],
             ["--from", "v:0", "--to", far, "--method", "relax"], ["--from", "v:0", "--to", far, "--method", "edge"],
             ["--from", "v:0", "--to", far, "--method", "straighten", "--certify"], ["--through", "v:0;v:40;%s" % far],
             ["--through", "v:0;%s" % far, "--closed"]):
    r = run("path", flat, *args)
    glob = [l for l in r.stdout.splitlines() if l.startswith("global")]
    check(r.returncode == 0 and "status             unreachable" in r.stdout and len(glob) == 1 and
          "no path exists" in glob[0] and "different components" in glob[0] and "unproven" not in glob[0],
          "path %s: the global line %r (want 'no path exists ... different components')" % (args, glob))
    check("edge path length   none (no path exists)" in r.stdout, "path %s: edge path length line in %r" % (args, r.stdout))
    j = json.loads(run("path", flat, *args, "--json").stdout or "null")
    check(j and j["status"] == "unreachable" and j["length"] is None and j["points"] == [], "path %s --json: %s" % (args, j))
pairs = write("pairs.txt", "v 0 40\nv 0 %s\n" % far[2:])
for method in ("exact", "straighten"):
    rows = list(csv.reader(io.StringIO(run("path", flat, "--pairs", pairs, "--method", method).stdout)))
    check(rows and rows[0] == "i,length,points,status,max_angle_defect,microseconds,global".split(",") and len(rows) == 3
          and rows[2][3] == "unreachable" and rows[2][1] == "inf" and rows[1][3] == "converged",
          "--pairs %s: header and the unreachable row %s" % (method, rows))

# ---- messages ----
def stderr_of(*args): return run(*args).stderr
doubled = re.compile(r"\b([A-Za-z]+)\s+\1\b")
m_csv = os.path.join(tmp, "m.csv")
shutil.copy(flat, m_csv)
p_csv = write("p.csv", "0.5 0.5 0\n")
msgs = {"logmap -o MESH": stderr_of("logmap", m_csv, "--format", "obj", "--from", "v:0", "-o", m_csv),
        "field --to -o POINTS": stderr_of("field", flat, "--sources", src, "--to", p_csv, "-o", p_csv),
        "field --at -o POINTS": stderr_of("field", flat, "--from", "v:0", "--at", p_csv, "-o", p_csv),
        "field --to empty": stderr_of("field", flat, "--sources", src, "--to", write("e.txt", "# none\n"), "-o", o("x.npy")),
        "trace --threads 300": stderr_of("trace", flat, "--batch", write("t.txt", "v:0 1,0,0 0.1\n"), "--threads", "300")}
for what, text in msgs.items():
    check(text.startswith("trigeo: ") and not doubled.search(text), "%s: %r (a doubled word?)" % (what, text))
check("the mesh " in msgs["logmap -o MESH"], "logmap -o MESH names the mesh: %r" % msgs["logmap -o MESH"])
check("(--to)" in msgs["field --to -o POINTS"] and "--at" not in msgs["field --to -o POINTS"],
      "field --to: the message names --to: %r" % msgs["field --to -o POINTS"])
check("(--at)" in msgs["field --at -o POINTS"], "field --at: the message names --at: %r" % msgs["field --at -o POINTS"])
check("x y z" in msgs["field --to empty"], "an empty points file: the forms it takes: %r" % msgs["field --to empty"])
check("0..256" in msgs["trace --threads 300"], "trace --threads 300: %r" % msgs["trace --threads 300"])
r = run("field", flat, "--sources", src, "--max-distance", "-0", "-o", o("m.npz"))
check("radius             0\n" in r.stdout, "--max-distance -0: %r (want radius 0)" % r.stdout)
r = run("trace", flat, "--from", "v:40", "--angle", "0", "--length", "-0", "--json")
check('"requested_length": 0,' in r.stdout, "--length -0: %r" % r.stdout[:160])
for cmd in ("info", "closest", "path", "field", "trace", "logmap", "sample", "render", "help"):
    h = run("help", cmd).stdout
    check(h and not doubled.search(h.replace("\n", " ")), "help %s: doubled word %r" % (cmd, doubled.search(h.replace("\n", " "))))

shutil.rmtree(tmp)
cli_common.finish()
PY
