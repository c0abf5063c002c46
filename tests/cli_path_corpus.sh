#!/usr/bin/env bash
# cli_path_corpus.sh: `trigeo path --pairs` on every mesh of the shared corpus, end to end through
# the CLI: three face-point pairs per mesh (first, middle and last faces, centroids). Each
# straightened row must be converged with a certificate <= 1e-10 rad and a finite length, or
# unreachable with length inf
# exactly when the two faces lie in different components (checked against the vertex-connected
# components of the mesh, computed here from `trigeo info`'s counts: a mesh with one component
# must never report unreachable). Straightening with --certify and the default method (exact)
# must then prove every converged path, never longer than the straightened one. The full suite
# (TG_FULL=1) takes every mesh of the manifest, the fast suite those of tests/corpus_fast.txt.
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" "${TG_SOURCE_DIR:?}/tests/corpus_fast.txt" <<'PY'
import json, math, os, subprocess, sys
trigeo, meshes, fast_list = sys.argv[1], sys.argv[2], sys.argv[3]
rows = [l.rstrip("\n").split("\t") for l in open(meshes + "/MANIFEST.tsv")][1:]
if os.environ.get("TG_FULL", "0") in ("", "0"):
    fast = {l.split()[0] for l in open(fast_list) if l.strip() and not l.startswith("#")}
    rows = [r for r in rows if r[0] in fast]
    assert len(rows) == len(fast), "meshes of corpus_fast.txt missing from the manifest"
    print("fast suite: %d corpus meshes (tests/corpus_fast.txt; TG_FULL=1 for all)" % len(rows))
passed = failed = 0
def fail(msg):
    global failed
    failed += 1
    print("FAIL " + msg)
for r in rows:
    path = meshes + "/" + r[0]
    info = json.loads(subprocess.run([trigeo, "info", "--json", path], capture_output=True, text=True).stdout)
    F, comps = info["faces"], info["components"]
    c = "0.3333333333333333 0.3333333333333333 0.33333333333333337"
    pairs = "p 0 %s %d %s\np %d %s %d %s\np 0 %s 0 %s\n" % (c, F - 1, c, F // 2, c, F - 1, c, c, c)
    p = subprocess.run([trigeo, "path", path, "--pairs", "-", "--method", "straighten"], input=pairs,
                       capture_output=True, text=True)
    if p.returncode != 0:
        fail("%s: exit %d: %s" % (r[0], p.returncode, p.stderr.strip())); continue
    out = [l.split(",") for l in p.stdout.strip().splitlines()]
    if out[0] != ["i", "length", "points", "status", "max_angle_defect", "microseconds", "global"] or len(out) != 4:
        fail("%s: bad CSV %r" % (r[0], out[:2])); continue
    ok = True
    for row in out[1:]:
        length, status, defect = float(row[1]), row[3], float(row[4]) if row[4] not in ("", "nan") else 0.0
        if status == "converged":
            ok &= math.isfinite(length) and defect <= 1e-10
        elif status == "unreachable":
            ok &= comps > 1 and math.isinf(length)
        else:
            ok = False
        if not ok:
            fail("%s: row %s" % (r[0], row)); break
    # a face to itself: length 0
    if ok and float(out[3][1]) != 0.0:
        fail("%s: same point, length %s" % (r[0], out[3][1])); ok = False
    # straightening with --certify (an exact propagation bounded by its length), and the default
    # method (exact): every converged path proven globally shortest, never longer than the
    # straightened one, and certified straight, except on meshes with zero-area faces: an exact
    # path through them (tm_capsule.obj's poles) is the shortest by its length, while the angles
    # the certificate measures inside such faces mean nothing
    flat_ok = info.get("degenerate_faces", 0) > 0
    for extra in (["--method", "straighten", "--certify"], []):
        if not ok:
            break
        what = " ".join(extra) or "default"
        pc = subprocess.run([trigeo, "path", path, "--pairs", "-", *extra], input=pairs, capture_output=True, text=True)
        cert = [l.split(",") for l in pc.stdout.strip().splitlines()]
        if pc.returncode != 0 or len(cert) != 4:
            fail("%s: %s exit %d %s" % (r[0], what, pc.returncode, pc.stderr.strip())); ok = False
        else:
            for a, b in zip(out[1:], cert[1:]):
                if b[3] == "converged" and not (b[6] == "proven" and float(b[1]) <= float(a[1]) * (1 + 1e-12)
                                                and (float(b[4]) <= 1e-10 or flat_ok)):
                    fail("%s: %s row %s (straightened %s)" % (r[0], what, b, a)); ok = False; break
                if b[3] != "converged" and b[3] != a[3]:
                    fail("%s: %s status %s vs %s" % (r[0], what, b, a)); ok = False; break
    if ok:
        passed += 1
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
PY
