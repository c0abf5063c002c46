#!/usr/bin/env bash
# cli_closest.sh: `trigeo closest` - the CSV format (header, columns, %.17g numbers, 0-based face
# ids), --signed and --sign, the error paths (a malformed or non-finite query line is reported as
# QUERIES:LINE with exit 2 and nothing is written; usage errors exit 1), and on every corpus mesh
# answers identical to a brute-force linear scan (tests/test_bvh_corpus --brute, the kernel on
# every face) for 60 mixed queries, with 1 and 2 threads.
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
helper=${TG_BUILD_DIR:?}/tests/test_bvh_corpus
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0 failed=0
ok() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

mesh=$meshes/nvd_spot.obj

# --- format ---
printf '# a comment\n0 0 0\n\n  1 2 3   # trailing comment\n0.1 -0.2 0.3\r\n-1e-3 5 2.5\n' > "$tmp/q.txt"
if "$trigeo" closest "$mesh" "$tmp/q.txt" -o "$tmp/out.csv" 2> "$tmp/err"; then ok; else fail "closest exit $?: $(cat "$tmp/err")"; fi
python3 - "$tmp/out.csv" "$($trigeo info --json "$mesh" | python3 -c 'import json,sys; print(json.load(sys.stdin)["faces"])')" 9 <<'PY' && ok || fail "CSV format"
import sys
path, faces, cols = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
lines = open(path).read().split("\n")
assert lines[-1] == "", "no final newline"
lines = lines[:-1]
hdr = "i,face,sqdist,cx,cy,cz,b0,b1,b2" + (",sign" if cols == 10 else "")
assert lines[0] == hdr, "header %r" % lines[0]
assert len(lines) == 5, "%d rows" % (len(lines) - 1)
for i, l in enumerate(lines[1:]):
    f = l.split(",")
    assert len(f) == cols, l
    assert int(f[0]) == i and 0 <= int(f[1]) < faces, l
    v = [float(x) for x in f[2:9]]
    assert v[0] >= 0 and abs(sum(v[4:7]) - 1) < 1e-12 and all(0 <= b <= 1 for b in v[4:7]), l
    for x in f[2:9]:  # %.17g round-trips: printing the parsed value again gives the same text
        assert "%.17g" % float(x) == x, x
    if cols == 10:
        assert f[9] in ("-1", "0", "1"), l
PY
# stdout when no -o, identical to the file
if "$trigeo" closest "$mesh" "$tmp/q.txt" > "$tmp/stdout.csv" 2>/dev/null && cmp -s "$tmp/stdout.csv" "$tmp/out.csv"; then ok; else fail "stdout differs from -o"; fi
# '-' reads stdin
if "$trigeo" closest "$mesh" - < "$tmp/q.txt" 2>/dev/null | cmp -s - "$tmp/out.csv"; then ok; else fail "stdin differs"; fi
# --signed adds a sign column and reports the method; --sign forces one
if "$trigeo" closest "$mesh" "$tmp/q.txt" --signed -o "$tmp/s.csv" 2> "$tmp/err" && grep -q "pseudonormal" "$tmp/err"; then ok; else fail "--signed: $(cat "$tmp/err")"; fi
python3 - "$tmp/s.csv" 5000000 10 <<'PY' && ok || fail "signed CSV format"
import sys
lines = open(sys.argv[1]).read().split("\n")[:-1]
assert lines[0] == "i,face,sqdist,cx,cy,cz,b0,b1,b2,sign", lines[0]
assert all(len(l.split(",")) == 10 and l.split(",")[9] in ("-1", "0", "1") for l in lines[1:])
PY
if "$trigeo" closest "$mesh" "$tmp/q.txt" --sign winding -o "$tmp/w.csv" 2> "$tmp/err" && grep -q "winding" "$tmp/err"; then ok; else fail "--sign winding: $(cat "$tmp/err")"; fi
if [ "$(cut -d, -f10 "$tmp/s.csv")" = "$(cut -d, -f10 "$tmp/w.csv")" ]; then ok; else fail "pseudonormal and winding signs differ on a closed mesh"; fi
if [ "$(cut -d, -f1-9 "$tmp/s.csv")" = "$(cut -d, -f1-9 "$tmp/out.csv")" ]; then ok; else fail "--signed changes the closest points"; fi

# --- errors: exit 2, QUERIES:LINE, nothing written ---
check_bad() { # $1 = query text, $2 = line number expected in the message
    printf "$1" > "$tmp/bad.txt"
    rm -f "$tmp/bad.csv"
    "$trigeo" closest "$mesh" "$tmp/bad.txt" -o "$tmp/bad.csv" > "$tmp/bad.out" 2> "$tmp/bad.err"
    local rc=$?
    if [ $rc -eq 2 ] && grep -q "^trigeo: $tmp/bad.txt:$2: " "$tmp/bad.err" && [ ! -e "$tmp/bad.csv" ] && [ ! -s "$tmp/bad.out" ]; then ok
    else fail "bad query '$1': exit $rc, stderr '$(cat "$tmp/bad.err")', output file $( [ -e "$tmp/bad.csv" ] && echo written || echo absent)"; fi
}
check_bad '0 0 0\n1 2\n' 2
check_bad '0 0 0\n\n# c\n1 2 x\n' 4
check_bad '1 2 3 4\n' 1
check_bad '0 0 0\n0 nan 0\n' 2
check_bad '0 0 inf\n' 1
check_bad '1e400 0 0\n' 1
check_bad '0 0 0\n0,0,0\n' 2
# without -o nothing reaches stdout either
printf '0 0 0\n1 2\n' | "$trigeo" closest "$mesh" - > "$tmp/bad.out" 2> "$tmp/bad.err"
if [ $? -eq 2 ] && [ ! -s "$tmp/bad.out" ] && grep -q '^trigeo: -:2: ' "$tmp/bad.err"; then ok; else fail "stdin error path"; fi
# usage errors exit 1, a missing mesh or queries file exits 2
"$trigeo" closest "$mesh" > /dev/null 2>&1; [ $? -eq 1 ] && ok || fail "missing QUERIES should exit 1"
"$trigeo" closest "$mesh" "$tmp/q.txt" --sign sideways > /dev/null 2>&1; [ $? -eq 1 ] && ok || fail "bad --sign should exit 1"
"$trigeo" closest "$mesh" "$tmp/q.txt" --threads x > /dev/null 2>&1; [ $? -eq 1 ] && ok || fail "bad --threads should exit 1"
"$trigeo" closest "$tmp/none.obj" "$tmp/q.txt" > /dev/null 2>&1; [ $? -eq 2 ] && ok || fail "missing mesh should exit 2"
"$trigeo" closest "$mesh" "$tmp/none.txt" > /dev/null 2>&1; [ $? -eq 2 ] && ok || fail "missing queries should exit 2"

# --- every corpus mesh: identical to the brute-force scan ---
while IFS=$'\t' read -r file rest; do
    [ "$file" = file ] && continue
    m=$meshes/$file
    if ! "$helper" --queries "$m" 60 17 > "$tmp/cq.txt"; then fail "$file: cannot make queries"; continue; fi
    "$helper" --brute "$m" "$tmp/cq.txt" > "$tmp/want.csv"
    for t in 1 2; do
        if "$trigeo" closest "$m" "$tmp/cq.txt" --threads $t -o "$tmp/got.csv" 2> "$tmp/err" && cmp -s "$tmp/got.csv" "$tmp/want.csv"; then ok
        else fail "$file (threads $t): differs from brute force: $(diff "$tmp/got.csv" "$tmp/want.csv" | head -3) $(cat "$tmp/err")"; fi
    done
done < "$meshes/MANIFEST.tsv"

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
