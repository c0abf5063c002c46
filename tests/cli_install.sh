#!/usr/bin/env bash
# cli_install.sh: a staged install (cmake --install into a temporary prefix) is consumed as a C
# user would: a tiny program built with `pkg-config --cflags --libs trigeo`, and the same program
# built by a CMake project with find_package(trigeo) and the target trigeo::trigeo; both run
# against the installed libtrigeo.so and compute a field on the installed header's API; and the
# README's C example, built the same way, prints what the CLI computes
# Needs pkg-config and cmake (installed by the Makefile's deps).
set -u
trigeo=${TG_TRIGEO:?}
meshes=${TG_MESHES_DIR:?}
build=$(dirname "$trigeo")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0; pass=0
ok() { if eval "$1"; then pass=$((pass + 1)); else echo "FAIL: $2"; fail=$((fail + 1)); fi; }
cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" 2>&1
ok '[ -f "$tmp/prefix/include/trigeo.h" ] && [ -e "$tmp/prefix/lib/libtrigeo.so" ] && [ -x "$tmp/prefix/bin/trigeo" ]' "staged install: $(tail -n 3 "$tmp/install.log")"
ok '! grep -q "\.\./shared\|TG-SECTION" "$tmp/prefix/include/trigeo.h"' "the installed header refers to the source tree"
cat >"$tmp/consumer.c" <<'C'
#include <stdio.h>
#include <trigeo.h>
int main(int argc, char** argv)
{
    tg_mesh* m = NULL;
    tg_geodesic* g = NULL;
    tg_diag d;
    if (argc < 2 || tg_mesh_load(argv[1], TG_FORMAT_AUTO, NULL, &d, &m) != TG_OK) return 2;
    if (tg_geodesic_create(m, NULL, &g) != TG_OK) return 3;
    static double dist[1 << 16];
    tg_surface_point s = tg_surface_vertex(0);
    if (tg_mesh_vertex_count(m) > (1 << 16) || tg_geodesic_field(g, NULL, &s, 1, NULL, dist, NULL) != TG_OK) return 4;
    printf("trigeo %s %.6f\n", tg_version(), dist[1]);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return 0;
}
C
if nm -D "$tmp/prefix/lib/libtrigeo.so" | grep -q __asan_init; then
  # a sanitizer build: its library needs the sanitizer runtime first in any program; the consumers
  # are built and run by the plain (gcc) build's run of this test
  echo "$pass passed, $fail failed"
  [ "$fail" -eq 0 ]; exit
fi
want=$("$trigeo" field "$meshes/nvd_spot.obj" --from v:0 --csv - | awk -F, '$1 == 1 {printf "%.6f", $2}')
export PKG_CONFIG_PATH="$tmp/prefix/lib/pkgconfig"
cc "$tmp/consumer.c" -o "$tmp/by_pkgconfig" $(pkg-config --cflags --libs trigeo) -Wl,-rpath,"$tmp/prefix/lib" 2>"$tmp/cc.log"
out=$("$tmp/by_pkgconfig" "$meshes/nvd_spot.obj" 2>&1)
ok '[ "$out" = "trigeo $("$trigeo" --version | cut -d" " -f2) $want" ]' "pkg-config consumer: '$out' (want $want) $(head -n 3 "$tmp/cc.log")"
# the README's C example, as printed there, is a complete program: built strictly against the
# installed package and run from the repository (it loads data/nvd_spot.obj), it prints the
# vertex count and the same last-vertex distance as the CLI
src=${TG_SOURCE_DIR:?}
awk '/^```c$/ {on = 1; next} /^```$/ {on = 0} on' "$src/README.md" >"$tmp/readme.c"
cc -std=c11 -Wall -Wextra -Werror -pedantic "$tmp/readme.c" -o "$tmp/readme" $(pkg-config --cflags --libs trigeo) \
  -Wl,-rpath,"$tmp/prefix/lib" 2>"$tmp/readme.log"
last=$("$trigeo" field "$src/data/nvd_spot.obj" --from v:0 --csv - | tail -n 1)
out=$(cd "$src" && "$tmp/readme" 2>&1)
ok '[ "$out" = "2930 vertices, genus 0
distance to vertex ${last%%,*}: ${last#*,}" ]' "README's C example: '$out' (last vertex $last) $(head -n 5 "$tmp/readme.log")"
mkdir -p "$tmp/cm"
cat >"$tmp/cm/CMakeLists.txt" <<'CM'
cmake_minimum_required(VERSION 3.16)
project(consumer C)
find_package(trigeo 0.6 REQUIRED)
add_executable(consumer ../consumer.c)
target_link_libraries(consumer PRIVATE trigeo::trigeo)
CM
cmake -S "$tmp/cm" -B "$tmp/cm/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" >"$tmp/cm.log" 2>&1 &&
  cmake --build "$tmp/cm/build" >>"$tmp/cm.log" 2>&1
out=$("$tmp/cm/build/consumer" "$meshes/nvd_spot.obj" 2>&1)
ok '[ "$out" = "trigeo $("$trigeo" --version | cut -d" " -f2) $want" ]' "CMake consumer: '$out' $(tail -n 5 "$tmp/cm.log" | tr '\n' ' ')"
# the Python package installed beside the library, used from elsewhere, finds that library
if /usr/bin/python3 -c "import numpy" 2>/dev/null; then
  out=$(cd "$tmp" && env -u TRIGEO_LIB PYTHONPATH="$tmp/prefix/lib/python3/dist-packages" /usr/bin/python3 -c \
    "import trigeo; print(trigeo._lib.lib_path); print('%.6f' % trigeo.load('$meshes/nvd_spot.obj').field(0)[1])" 2>&1)
  ok '[ "$(sed -n 1p <<<"$out")" = "$tmp/prefix/lib/libtrigeo.so" ] && [ "$(sed -n 2p <<<"$out")" = "$want" ]' "installed Python package: '$out' (want $want)"
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
