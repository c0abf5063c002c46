#!/usr/bin/env bash
# cli_corpus.sh: every mesh of the shared corpus loads through `trigeo info --json` and its counts
# equal MANIFEST.tsv (vertices, faces, components, boundary_edges, nonmanifold_edges,
# degenerate_faces, genus_if_closed_manifold).
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
exec /usr/bin/env python3 - "$trigeo" "$meshes" <<'PY'
import json, subprocess, sys
trigeo, meshes = sys.argv[1], sys.argv[2]
rows = [l.rstrip("\n").split("\t") for l in open(meshes + "/MANIFEST.tsv")]
hdr, rows = rows[0], rows[1:]
keys = ["vertices", "faces", "components", "boundary_edges", "nonmanifold_edges", "degenerate_faces"]
passed = failed = 0
for r in rows:
    m = dict(zip(hdr, r))
    p = subprocess.run([trigeo, "info", "--json", meshes + "/" + m["file"]], capture_output=True, text=True)
    if p.returncode != 0:
        print("FAIL %s: exit %d: %s" % (m["file"], p.returncode, p.stderr.strip())); failed += 1; continue
    j = json.loads(p.stdout)
    bad = [(k, j[k], m[k]) for k in keys if str(j[k]) != m[k]]
    g = "NA" if j["genus"] is None else str(j["genus"])
    if g != m["genus_if_closed_manifold"]: bad.append(("genus", g, m["genus_if_closed_manifold"]))
    if bad:
        print("FAIL %s: %s" % (m["file"], ", ".join("%s=%s (manifest %s)" % b for b in bad))); failed += 1
    else:
        passed += 1
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
PY
