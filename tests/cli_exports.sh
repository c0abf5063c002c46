#!/usr/bin/env bash
# cli_exports.sh: libtrigeo.so (beside the trigeo binary) exports exactly the functions
# include/trigeo.h declares with TG_API, every one of them, and nothing else (no tg__ internals,
# no OpenMP critical-section names); its soname carries the version's major.minor, which
# `trigeo --version` and tg_version() report.
set -u
trigeo=${TG_TRIGEO:?}
src=${TG_SOURCE_DIR:?}
lib=$(dirname "$trigeo")/libtrigeo.so
fail=0; pass=0
ok() { if eval "$1"; then pass=$((pass + 1)); else echo "FAIL: $2"; fail=$((fail + 1)); fi; }
exported=$(nm -D --defined-only "$lib" | awk '{print $3}' | sort)
declared=$(grep -o '^TG_API [^(]*(' "$src/include/trigeo.h" | sed 's/($//; s/.*[ *]//' | sort)
ok '[ -n "$declared" ] && [ "$exported" = "$declared" ]' "exports differ from the header: $(diff <(echo "$exported") <(echo "$declared") | head -5 | tr '\n' ' ')"
ok '! grep -q "^tg__" <<<"$exported"' "internal tg__ symbols exported"
version=$("$trigeo" --version | awk '{print $2}')
soname=$(readelf -d "$lib" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
ok '[ "$soname" = "libtrigeo.so.${version%.*}" ]' "soname $soname does not follow version $version"
hdr=$(awk '/#define TG_VERSION_MAJOR/{a=$3} /#define TG_VERSION_MINOR/{b=$3} /#define TG_VERSION_PATCH/{c=$3} END{print a"."b"."c}' "$src/include/trigeo.h")
ok '[ "$version" = "$hdr" ]' "trigeo --version $version, header $hdr"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
