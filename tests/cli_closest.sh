#!/usr/bin/env bash
# cli_closest.sh: `trigeo closest` - the CSV format (header, columns, numbers as the shortest
# decimals that read back to the same doubles, 0-based face ids), --signed and --sign, .npy query
# input and .npy output (a structured array with the CSV's columns), the error paths (a malformed
# or non-finite query line is reported as QUERIES:LINE, a malformed .npy as QUERIES: .npy: reason,
# with exit 2 and nothing written; usage errors exit 1), and on every corpus mesh answers
# identical to a brute-force linear scan (tests/test_bvh_corpus --brute, the kernel on every face)
# for 60 mixed queries, with 1 and 2 threads, the values compared as doubles. The full suite
# (TG_FULL=1) takes every mesh of the manifest (under the sanitizers, TG_SANITIZED=1, every third);
# the fast suite the meshes of tests/corpus_fast.txt.
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
    for x in f[2:9]:  # the shortest decimal that reads back: as many significant digits as repr
        digits = lambda t: t.lstrip("-").split("e")[0].replace(".", "").lstrip("0").rstrip("0") or "0"
        assert digits(x) == digits(repr(float(x))), (x, repr(float(x)))
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

# --- .npy: queries in, records out ---
# a (k, 3) '<f8' C-order array; npy_file PATH DESCR FORTRAN SHAPE [DATA_BYTES] [VERSION] writes one
# (the data are the first points of q.txt, or DATA_BYTES bytes of them)
npy_file() {
    python3 - "$tmp/q.txt" "$@" <<'PY'
import struct, sys
src, path, descr, fortran, shape = sys.argv[1:6]
nbytes = int(sys.argv[6]) if len(sys.argv) > 6 and sys.argv[6] != "-" else None
version = int(sys.argv[7]) if len(sys.argv) > 7 else 1
pts = [float(v) for line in open(src) for v in line.split("#")[0].split()]
data = struct.pack("<%dd" % len(pts), *pts)
if nbytes is not None:
    data = (data * 4)[:nbytes]
head = "{'descr': %s, 'fortran_order': %s, 'shape': %s, }" % (descr, fortran, shape)
head += " " * ((64 - (len(head) + 11 + (2 if version > 1 else 0)) % 64) % 64) + "\n"
pre = b"\x93NUMPY" + bytes([version, 0]) + (struct.pack("<H", len(head)) if version == 1 else struct.pack("<I", len(head)))
open(path, "wb").write(pre + head.encode() + data)
PY
}
npy_file "$tmp/q.npy" "'<f8'" False "(4, 3)"
if "$trigeo" closest "$mesh" "$tmp/q.npy" -o "$tmp/npyin.csv" 2> "$tmp/err" && cmp -s "$tmp/npyin.csv" "$tmp/out.csv"; then ok
else fail ".npy queries give other answers than the same text queries: $(cat "$tmp/err")"; fi
npy_file "$tmp/q2.npy" "'<f8'" False "(4, 3)" - 2
if "$trigeo" closest "$mesh" "$tmp/q2.npy" -o "$tmp/npyin2.csv" 2> "$tmp/err" && cmp -s "$tmp/npyin2.csv" "$tmp/out.csv"; then ok
else fail ".npy version 2.0 queries: $(cat "$tmp/err")"; fi
for signed in "" --signed; do
    if "$trigeo" closest "$mesh" "$tmp/q.npy" $signed -o "$tmp/out.npy" 2> "$tmp/err" &&
        "$trigeo" closest "$mesh" "$tmp/q.txt" $signed -o "$tmp/ref.csv" 2>/dev/null &&
        python3 - "$tmp/out.npy" "$tmp/ref.csv" "$signed" <<'PY'
import ast, struct, sys
raw = open(sys.argv[1], "rb").read()
assert raw[:8] == b"\x93NUMPY\x01\x00", raw[:8]
hlen = struct.unpack("<H", raw[8:10])[0]
assert (10 + hlen) % 64 == 0
head = ast.literal_eval(raw[10:10 + hlen].decode())
names = ["face", "sqdist", "cx", "cy", "cz", "b0", "b1", "b2"] + (["sign"] if sys.argv[3] else [])
assert [d[0] for d in head["descr"]] == names, head
assert head["fortran_order"] is False
rows = [l.split(",") for l in open(sys.argv[2]).read().split("\n")[1:-1]]
assert head["shape"] == (len(rows),), head
fmt = "<I7d" + ("b" if sys.argv[3] else "")
size = struct.calcsize(fmt)
body = raw[10 + hlen:]
assert len(body) == size * len(rows)
for i, r in enumerate(rows):
    rec = struct.unpack(fmt, body[i * size:(i + 1) * size])
    assert rec[0] == int(r[1]) and list(rec[1:8]) == [float(x) for x in r[2:9]], (rec, r)
    if sys.argv[3]:
        assert rec[8] == int(r[9])
PY
    then ok; else fail ".npy output${signed:+ (signed)} differs from the CSV: $(cat "$tmp/err")"; fi
done
# malformed .npy queries: exit 2, "QUERIES: .npy: reason", no output file
expect_npy_error() { # $1 = the reason expected in the message about $tmp/bad.npy (a grep pattern)
    rm -f "$tmp/bad.csv"
    "$trigeo" closest "$mesh" "$tmp/bad.npy" -o "$tmp/bad.csv" > "$tmp/bad.out" 2> "$tmp/bad.err"
    local rc=$?
    if [ $rc -eq 2 ] && grep -q "^trigeo: $tmp/bad.npy: .npy: $1" "$tmp/bad.err" && [ ! -e "$tmp/bad.csv" ] && [ ! -s "$tmp/bad.out" ]; then ok
    else fail "malformed .npy ($1): exit $rc, stderr '$(cat "$tmp/bad.err")', output $( [ -e "$tmp/bad.csv" ] && echo written || echo absent)"; fi
}
check_bad_npy() { # $1 = expected words in the message, then npy_file arguments
    local want=$1
    shift
    npy_file "$tmp/bad.npy" "$@"
    expect_npy_error ".*$want"
}
check_bad_npy "dtype '<i8'" "'<i8'" False "(4, 3)"
check_bad_npy "dtype '<f2'" "'<f2'" False "(4, 3)"
check_bad_npy "dtype \[('x'" "[('x', '<f8'), ('y', '<f8'), ('z', '<f8')]" False "(4,)"
check_bad_npy "shape (6, 2)" "'<f8'" False "(6, 2)"
check_bad_npy "shape (12,)" "'<f8'" False "(12,)"
check_bad_npy "fortran_order is neither" "'<f8'" 1 "(4, 3)"
check_bad_npy "48 bytes after the data" "'<f4'" False "(4, 3)"
check_bad_npy "truncated data: 40 bytes" "'>f4'" True "(4, 3)" 40
check_bad_npy "truncated data: 90 bytes" "'<f8'" False "(4, 3)" 90
check_bad_npy "8 bytes after the data" "'<f8'" False "(4, 3)" 104
check_bad_npy "truncated data" "'<f8'" False "(5, 3)"
python3 -c "
h=\"{'descr': '<f8', 'fortran_order': False, }\"; h+=' '*((64-(len(h)+11)%64)%64)+'\n'
open('$tmp/bad.npy','wb').write(b'\x93NUMPY\x01\x00'+bytes([len(h),0])+h.encode())"
expect_npy_error "the header lacks 'shape'"
printf '\x93NUMPY\x01\x00\x40\x00{not a dict' > "$tmp/bad.npy"
expect_npy_error "truncated header"
printf '\x93NUMPY\x01\x00\x08\x00[1, 2]  ' > "$tmp/bad.npy"
expect_npy_error "the header is not a dictionary"
printf '\x93NUMPY\x07\x00\x08\x00{}      ' > "$tmp/bad.npy"
expect_npy_error "unsupported format version 7.0"
# a non-finite coordinate in a .npy
python3 -c "
import struct; h=\"{'descr': '<f8', 'fortran_order': False, 'shape': (1, 3), }\"; h+=' '*((64-(len(h)+11)%64)%64)+'\n'
open('$tmp/bad.npy','wb').write(b'\x93NUMPY\x01\x00'+struct.pack('<H',len(h))+h.encode()+struct.pack('<3d',0.0,float('nan'),0.0))"
expect_npy_error "row 0 (from 0), y is nan"
# nor is a partial .npy written, nor anything to stdout without -o
npy_file "$tmp/bad.npy" "'<f8'" False "(4, 3)" 90
rm -f "$tmp/bad_out.npy"
"$trigeo" closest "$mesh" "$tmp/bad.npy" -o "$tmp/bad_out.npy" > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$tmp/bad_out.npy" ] && ok || fail "a malformed .npy left a partial .npy output"
"$trigeo" closest "$mesh" "$tmp/bad.npy" > "$tmp/bad.out" 2>/dev/null
[ $? -eq 2 ] && [ ! -s "$tmp/bad.out" ] && ok || fail "a malformed .npy wrote to stdout"

# --- every corpus mesh: identical to the brute-force scan ---
# same_csv GOT WANT: same header, same faces, the same doubles (the brute force prints %.17g)
same_csv() {
    python3 - "$1" "$2" <<'PY'
import sys
a = open(sys.argv[1]).read().split("\n")
b = open(sys.argv[2]).read().split("\n")
assert a[0] == b[0] and len(a) == len(b)
for x, y in zip(a[1:], b[1:]):
    fx, fy = x.split(","), y.split(",")
    assert fx[:2] == fy[:2] and [float(v) for v in fx[2:]] == [float(v) for v in fy[2:]], (x, y)
PY
}
# the full suite: every mesh (under the sanitizers every third); the fast suite: corpus_fast.txt
step=1
[ "${TG_SANITIZED:-0}" = 1 ] && step=3
full=0
case "${TG_FULL:-0}" in ""|0) ;; *) full=1 ;; esac
fast_list=$(grep -v '^#' "${TG_SOURCE_DIR:?}/tests/corpus_fast.txt" | awk '{print $1}')
row=0
while IFS=$'\t' read -r file rest; do
    [ "$file" = file ] && continue
    row=$((row + 1))
    if [ $full = 1 ]; then
        [ $((row % step)) -eq 0 ] || continue
    else
        grep -qxF "$file" <<< "$fast_list" || continue
    fi
    m=$meshes/$file
    if ! "$helper" --queries "$m" 60 17 > "$tmp/cq.txt"; then fail "$file: cannot make queries"; continue; fi
    "$helper" --brute "$m" "$tmp/cq.txt" > "$tmp/want.csv"
    if "$trigeo" closest "$m" "$tmp/cq.txt" --threads 1 -o "$tmp/got.csv" 2> "$tmp/err" && same_csv "$tmp/got.csv" "$tmp/want.csv"; then ok
    else fail "$file (threads 1): differs from brute force: $(diff "$tmp/got.csv" "$tmp/want.csv" | head -3) $(cat "$tmp/err")"; fi
    # two threads: byte for byte the one-thread answer (one Python start a mesh, not two)
    if "$trigeo" closest "$m" "$tmp/cq.txt" --threads 2 -o "$tmp/got2.csv" 2> "$tmp/err" && cmp -s "$tmp/got2.csv" "$tmp/got.csv"; then ok
    else fail "$file (threads 2): differs from one thread: $(diff "$tmp/got2.csv" "$tmp/got.csv" | head -3) $(cat "$tmp/err")"; fi
done < "$meshes/MANIFEST.tsv"

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
