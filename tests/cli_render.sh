#!/usr/bin/env bash
# cli_render.sh: `trigeo render` writes a PNG of the bundled mesh with a path overlay; usage and
# input errors give exit codes 1 and 2 with a `trigeo:` message.
set -u
trigeo=${TG_TRIGEO:?} src=${TG_SOURCE_DIR:?}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
printf 'v 0.1 0.2 0.3\nv 0.2 0.3 0.1\nv 0.3 0.1 0.2\nl 1 2 3\n' > "$tmp/p.obj"
"$trigeo" render "$src/data/nvd_spot.obj" --path "$tmp/p.obj" --size 64x48 -o "$tmp/a.png" && ok || bad "render exit $?"
[ "$(head -c 8 "$tmp/a.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] && ok || bad "not a PNG"
"$trigeo" render "$src/data/nvd_spot.obj" 2>"$tmp/err"; rc=$?
[ $rc -eq 1 ] && grep -q "^trigeo: .*-o" "$tmp/err" && ok || bad "missing -o: exit $rc"
printf 'v 0 0 0\nl 1 7\n' > "$tmp/bad.obj"
"$trigeo" render "$src/data/nvd_spot.obj" --path "$tmp/bad.obj" -o "$tmp/b.png" 2>"$tmp/err"; rc=$?
[ $rc -eq 2 ] && grep -q "bad.obj:2: line index 7 out of range" "$tmp/err" && ok || bad "bad path file: exit $rc: $(cat "$tmp/err")"
[ ! -e "$tmp/b.png" ] && ok || bad "wrote an image after an input error"
"$trigeo" render "$tmp/missing.obj" -o "$tmp/c.png" 2>"$tmp/err"; rc=$?
[ $rc -eq 2 ] && grep -q "^trigeo: $tmp/missing.obj: cannot open" "$tmp/err" && ok || bad "missing mesh: exit $rc: $(cat "$tmp/err")"
"$trigeo" render "$src/data/nvd_spot.obj" --size 9x9 -o "$tmp/d.png" 2>/dev/null; rc=$?
[ $rc -eq 1 ] && ok || bad "tiny size: exit $rc"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
