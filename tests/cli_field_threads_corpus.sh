#!/usr/bin/env bash
# cli_field_threads_corpus.sh (make check): one field on several threads through the CLI, on every
# corpus mesh, from vertex 0 and from a point inside face 0: `trigeo field MESH --from SPEC
# --threads T --csv F` on 1 thread, then on 2, 3 and 7 threads twice each. Every run on more than
# one thread must give the same bytes (run to run and whatever the thread count, the header's
# promise), and each distance must be within 1e-14 relative of the one-thread field's, every vertex
# reached by both or by neither. Sanitized builds take every sixth mesh, from vertex 0 only.
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" "${TG_SANITIZED:-0}" <<'PY'
import math, os, subprocess, sys, tempfile
trigeo, meshes, sanitized = sys.argv[1], sys.argv[2], sys.argv[3] in ("1", "ON", "TRUE", "true")
files = [l.split("\t")[0] for l in open(meshes + "/MANIFEST.tsv")][1:]
specs = ["v:0", "f:0:0.2,0.3,0.5"]
if sanitized:
    files, specs = files[::6], specs[:1]
tmp = tempfile.mkdtemp()
failed, fields, differ, worst = 0, 0, 0, (0.0, "")

def field(path, spec, threads, out):
    try:
        p = subprocess.run([trigeo, "field", path, "--from", spec, "--threads", str(threads), "--csv", out, "--quiet"],
                           capture_output=True, text=True, timeout=300)
    except subprocess.TimeoutExpired:
        return None, "no end after 300 s"
    if p.returncode != 0:
        return None, "exit %d: %s" % (p.returncode, p.stderr.strip())
    with open(out, "rb") as f:
        return f.read(), ""

def distances(data):
    return [float(l.split(b",")[-1]) for l in data.splitlines()[1:]]

for name in files:
    for spec in specs:
        path = os.path.join(meshes, name)
        one, err = field(path, spec, 1, os.path.join(tmp, "t1.csv"))
        if one is None:
            print("FAIL %s --from %s, 1 thread: %s" % (name, spec, err)); failed += 1; continue
        runs = {}
        for t in (2, 3, 7):
            for k in (0, 1):
                runs[(t, k)], err = field(path, spec, t, os.path.join(tmp, "t%d%d.csv" % (t, k)))
                if runs[(t, k)] is None:
                    print("FAIL %s --from %s, %d threads: %s" % (name, spec, t, err)); failed += 1
        first = runs[(2, 0)]
        if first is None:
            continue
        other = [key for key, data in runs.items() if data is not None and data != first]
        if other:
            print("FAIL %s --from %s: not the same bytes on (threads, run) %s as on 2 threads" % (name, spec, other))
            failed += 1
            continue
        a, b = distances(one), distances(first)
        if len(a) != len(b):
            print("FAIL %s --from %s: %d rows against %d" % (name, spec, len(b), len(a))); failed += 1; continue
        fields += 1
        for i, (x, y) in enumerate(zip(a, b)):
            if math.isinf(x) != math.isinf(y):
                print("FAIL %s --from %s: vertex %d reached on one of 1 and 2 threads (%r, %r)" % (name, spec, i, x, y))
                failed += 1; break
            if x == y or math.isinf(x):
                continue
            differ += 1
            rel = abs(x - y) / max(abs(x), abs(y))
            if rel > worst[0]:
                worst = (rel, "%s --from %s, vertex %d" % (name, spec, i))
            if rel > 1e-14:
                print("FAIL %s --from %s: vertex %d %.17g on 1 thread, %.17g on 2 (%.3g relative)" % (name, spec, i, x, y, rel))
                failed += 1; break
print("%d fields on 1, 2, 3 and 7 threads (each twice): every run on several threads the same bytes; %d distances "
      "differ from one thread's, at most %.3g relative (%s); %d failed" % (fields, differ, worst[0], worst[1], failed))
sys.exit(1 if failed or fields == 0 else 0)
PY
