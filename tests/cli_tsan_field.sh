#!/usr/bin/env bash
# cli_tsan_field.sh (make check): one field on several threads under ThreadSanitizer. The
# library's sources and tests/tsan_field.c are built with clang -fsanitize=thread -fopenmp into
# the build directory, and the driver runs fields on 2, 3 and 7 threads on two corpus meshes;
# any report ("WARNING: ThreadSanitizer") fails the test, as do thread counts that disagree.
# The crew's synchronisation is C11 atomics and threads.h, which TSan sees; libomp is only the
# team's launcher here (ignore_noninstrumented_modules keeps its uninstrumented internals out).
set -u
src=${TG_SOURCE_DIR:?}
out=${TG_BUILD_DIR:?}/tsan
meshes=${TG_MESHES_DIR:?}
command -v clang >/dev/null || { echo "clang not found: skipped"; exit 77; }
mkdir -p "$out"
if ! clang -O1 -g -fsanitize=thread -fopenmp -std=c11 -D_GNU_SOURCE -I"$src/include" -I"$src/src" \
     "$src"/src/*/*.c "$src"/src/geodesic/*/*.c "$src/tests/tsan_field.c" -o "$out/tsan_field" -lm -lz -lpng; then
    echo "FAIL: the ThreadSanitizer build"
    exit 1
fi
log="$out/tsan_field.log"
TSAN_OPTIONS="ignore_noninstrumented_modules=1 halt_on_error=0 exitcode=0" OMP_WAIT_POLICY=PASSIVE \
    "$out/tsan_field" "$meshes/nvd_spot.obj" "$meshes/igl_armadillo.obj" >"$log" 2>&1
rc=$?
cat "$log"
if [ $rc -ne 0 ] || grep -q "WARNING: ThreadSanitizer" "$log"; then
    echo "FAIL: exit $rc, $(grep -c 'WARNING: ThreadSanitizer' "$log") ThreadSanitizer reports"
    exit 1
fi
echo "ThreadSanitizer: no report"
