#!/usr/bin/env bash
# make_field_refs.sh FIELD_CGAL [MESHES_DIR]: regenerates the CGAL reference distances that
# tests/test_field_cgal_ref.c compares tg_geodesic_field with (CGAL only as an independent oracle;
# build field_cgal with `make bench` or -DTG_BENCH=ON: build-bench/bench/peers/field_cgal).
# Meshes of several kinds that CGAL's Surface_mesh accepts (manifold, consistently oriented):
# scans, CAD, open surfaces with holes, higher genus, degenerate faces. Left out: meshes CGAL
# refuses (non-manifold: c3d_cow, gc_moebius) or crashes on (tm_capsule, degenerate faces: CGAL
# segfaults), and openfoam_terrain, whose UTM coordinates (4.8e6 from the origin)
# cost CGAL's constructions 4e-12 of the largest distance (trigeo, VTP and the old engine agree
# with each other there; BENCHMARKS.md).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tool=${1:?usage: make_field_refs.sh FIELD_CGAL [MESHES_DIR]}
meshes=${2:-$here/../../../shared/meshes}
for m in nvd_spot.obj igl_bunny.off cgal_fandisk.off cgal_elephant-with-holes.off oded_plane_holes.obj c3d_cow.obj \
         igl_decimated-knight.off cgal_pinion.off igl_3holes.off lpm_blub_triangulated.obj cgal_turbine.off \
         tm_capsule.obj c3d_teapot.obj gc_moebius.obj; do
  if "$tool" "$meshes/$m" --ref "$here/${m%%.*}.ref.tmp"; then
    mv "$here/${m%%.*}.ref.tmp" "$here/${m%%.*}.ref"
  else
    rm -f "$here/${m%%.*}.ref.tmp"
    echo "make_field_refs.sh: $m skipped" >&2
  fi
done
