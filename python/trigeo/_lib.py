"""The C side: finding libtrigeo.so and declaring its structs and functions for ctypes.

Every declaration mirrors include/trigeo.h (the API reference); nothing here computes.
ctypes releases the GIL for the duration of every call through a CDLL, so Python threads run
trigeo queries in parallel.
"""
from __future__ import annotations

import ctypes
import os
from ctypes import POINTER, c_char, c_char_p, c_double, c_int, c_int64, c_size_t, c_uint32, c_uint64, c_void_p

__all__ = ["lib", "lib_path"]

_HERE = os.path.dirname(os.path.realpath(__file__))  # the package's real folder, through links
INSTALLED_MARK = "_installed_beside_lib"  # written by `make install` only (CMakeLists.txt)


def _checkout_root() -> str | None:
    """The checkout this package is the python/trigeo folder of, or None: identified positively
    (CMakeLists.txt and include/trigeo.h beside python/), so that an installed package never
    takes a folder above it for a checkout."""
    root = os.path.dirname(os.path.dirname(_HERE))
    if os.path.basename(_HERE) != "trigeo" or os.path.basename(os.path.dirname(_HERE)) != "python":
        return None
    marks = (os.path.join(root, "CMakeLists.txt"), os.path.join(root, "include", "trigeo.h"))
    if all(os.path.isfile(m) for m in marks):
        return root
    return None


def _candidates() -> list[tuple[str, str | None, str]]:
    """(description, path or None when not tried, why not) in the order they are tried. Only
    three places: an explicit TRIGEO_LIB; the checkout's own build/ (when this package is the
    python/trigeo of a checkout); the library shipped with the package: inside it (`pip install
    .`) or, when `make install` marked the package so, PREFIX/LIBDIR/libtrigeo.so beside
    PREFIX/LIBDIR/python3/dist-packages/trigeo. No folder above a checkout or an installed
    package and no system search path: a libtrigeo.so someone else can put there is never run."""
    env = os.environ.get("TRIGEO_LIB")
    if env:
        # an explicit choice is never silently replaced by another library
        return [("TRIGEO_LIB", os.path.abspath(env), "")]
    out: list[tuple[str, str | None, str]] = []
    root = _checkout_root()
    if root is not None:
        out.append(("the checkout's build", os.path.join(root, "build", "libtrigeo.so"), ""))
    else:
        out.append(("the checkout's build", None,
                    f"{_HERE} is not python/trigeo of a checkout (CMakeLists.txt and include/trigeo.h beside python/)"))
    # `pip install .`: setup.py puts the library inside the package
    out.append(("the library inside the package", os.path.join(_HERE, "libtrigeo.so"), ""))
    # `make install`: PREFIX/LIBDIR/python3/dist-packages/trigeo beside PREFIX/LIBDIR/libtrigeo.so
    if os.path.isfile(os.path.join(_HERE, INSTALLED_MARK)):
        out.append(("the library installed with the package",
                    os.path.normpath(os.path.join(_HERE, "..", "..", "..", "libtrigeo.so")), ""))
    else:
        out.append(("the library installed with the package", None,
                    f"no {INSTALLED_MARK} in {_HERE} (not `make install`)"))
    return out


def _load() -> tuple[ctypes.CDLL, str]:
    tried = []
    for what, path, why in _candidates():
        if path is None:
            tried.append(f"{what}: not tried ({why})")
            continue
        if not os.path.exists(path):
            tried.append(f"{what}: {path} (no such file)")
            continue
        try:
            return ctypes.CDLL(path), path
        except OSError as e:
            tried.append(f"{what}: {path} ({e})")
    raise ImportError(
        "trigeo: cannot load libtrigeo.so; looked at\n  " + "\n  ".join(tried) +
        "\nBuild it with `make` in the checkout, install the package (`pip install .` or `make install`), or set "
        "TRIGEO_LIB to the library's path.")


lib, lib_path = _load()

NONE = 0xFFFFFFFF


class Diag(ctypes.Structure):
    _fields_ = [("file", c_char * 256), ("line", c_uint64), ("column", c_uint64), ("byte_offset", c_uint64),
                ("message", c_char * 256)]


class Allocator(ctypes.Structure):
    _fields_ = [("alloc", c_void_p), ("realloc", c_void_p), ("free", c_void_p), ("user", c_void_p)]


class MeshReport(ctypes.Structure):
    _fields_ = [(name, c_uint64) for name in (
        "vertices", "faces", "edges", "components", "boundary_edges", "boundary_loops", "nonmanifold_edges",
        "nonmanifold_vertices", "misoriented_edges", "degenerate_faces", "duplicate_faces",
        "unreferenced_vertices")] + [
        ("euler_characteristic", c_int64), ("genus", c_int64), ("closed_manifold", c_int),
        ("bbox_min", c_double * 3), ("bbox_max", c_double * 3)]


class SurfacePointC(ctypes.Structure):
    _fields_ = [("kind", c_int), ("index", c_uint32), ("t", c_double), ("bary", c_double * 3)]


class SurfaceSegmentC(ctypes.Structure):
    _fields_ = [("a", SurfacePointC), ("b", SurfacePointC)]


class ClosestHit(ctypes.Structure):
    _fields_ = [("face", c_uint32), ("feature", c_int), ("sqdist", c_double), ("point", c_double * 3),
                ("bary", c_double * 3)]


class SignedHit(ctypes.Structure):
    _fields_ = [("hit", ClosestHit), ("distance", c_double), ("sign", c_int), ("method", c_int),
                ("winding_number", c_double)]


class BvhOptions(ctypes.Structure):
    _fields_ = [("allocator", c_void_p), ("max_leaf_size", c_uint32), ("winding_data", c_int), ("threads", c_int)]


class KernelOptions(ctypes.Structure):
    _fields_ = [("digits", c_int), ("max_iterations", c_int), ("strategy", c_int), ("root_method", c_int)]


class PathView(ctypes.Structure):
    _fields_ = [("point_count", c_size_t), ("points", POINTER(SurfacePointC)), ("xyz", POINTER(c_double)),
                ("faces", POINTER(c_uint32)), ("length", c_double), ("initial_length", c_double),
                ("max_angle_defect", c_double), ("status", c_int), ("global_", c_int), ("iterations", c_uint32),
                ("edge_path_vertices", c_uint32)]


class TraceDirection(ctypes.Structure):
    _fields_ = [("kind", c_int), ("vector", c_double * 3), ("angle", c_double)]




class TraceEnd(ctypes.Structure):
    _fields_ = [("point", SurfacePointC), ("xyz", c_double * 3), ("direction", c_double * 3), ("face", c_uint32),
                ("status", c_int), ("length", c_double), ("crossings", c_uint64), ("vertices", c_uint32),
                ("branches", c_uint32)]


class TraceView(ctypes.Structure):
    _fields_ = [("point_count", c_size_t), ("points", POINTER(SurfacePointC)), ("xyz", POINTER(c_double)),
                ("faces", POINTER(c_uint32)), ("branch_count", c_size_t), ("branch_points", POINTER(c_size_t)),
                ("end", TraceEnd)]


class VertexScalar(ctypes.Structure):
    _fields_ = [("name", c_char_p), ("values", POINTER(c_double))]


class FieldProgress(ctypes.Structure):
    _fields_ = [("front_distance", c_double), ("settled_fraction", c_double), ("rows_done", c_size_t),
                ("row_count", c_size_t)]


PROGRESS_FN = ctypes.CFUNCTYPE(c_int, c_void_p, POINTER(FieldProgress))


class MeanOptions(ctypes.Structure):
    _fields_ = [("tolerance", c_double), ("max_iterations", c_uint32), ("start", POINTER(SurfacePointC)),
                ("skip_uniqueness", c_int), ("allocator", c_void_p), ("progress", PROGRESS_FN),
                ("progress_user", c_void_p)]


class MeanResult(ctypes.Structure):
    _fields_ = [("point", SurfacePointC), ("xyz", c_double * 3), ("energy", c_double), ("gradient_norm", c_double),
                ("radius", c_double), ("iterations", c_uint32), ("halvings", c_uint32), ("fields", c_uint32),
                ("status", c_int), ("uniqueness", c_int)]


class CentroidalOptions(ctypes.Structure):
    _fields_ = [("iterations", c_uint32), ("tolerance", c_double), ("allocator", c_void_p), ("progress", PROGRESS_FN),
                ("progress_user", c_void_p)]


class TraceOptions(ctypes.Structure):
    _fields_ = [("max_steps", c_uint64), ("progress", PROGRESS_FN), ("progress_user", c_void_p)]


class PathOptions(ctypes.Structure):
    _fields_ = [("method", c_int), ("max_iterations", c_uint32), ("tolerance", c_double),
                ("kernel", POINTER(KernelOptions)), ("certify", c_int), ("progress", PROGRESS_FN),
                ("progress_user", c_void_p)]


class FieldOptions(ctypes.Structure):
    _fields_ = [("allocator", c_void_p), ("limit", c_int), ("max_distance", c_double),
                ("progress", PROGRESS_FN), ("progress_user", c_void_p), ("threads", c_int)]


RENDER_PROGRESS_FN = ctypes.CFUNCTYPE(c_int, c_void_p, c_double)


class MeshDistanceProgress(ctypes.Structure):
    _fields_ = [("fraction", c_double), ("lower", c_double), ("upper", c_double)]


MESH_DISTANCE_PROGRESS_FN = ctypes.CFUNCTYPE(c_int, c_void_p, POINTER(MeshDistanceProgress))


class MeshDistanceOptions(ctypes.Structure):
    _fields_ = [("allocator", c_void_p), ("tolerance", c_double), ("mean_tolerance", c_double),
                ("max_pieces", c_size_t), ("threads", c_int), ("progress", MESH_DISTANCE_PROGRESS_FN),
                ("progress_user", c_void_p)]


class MeshDistanceResult(ctypes.Structure):
    _fields_ = [("lower", c_double), ("upper", c_double), ("tolerance", c_double), ("converged", c_int),
                ("distance", c_double), ("face", c_uint32), ("bary", c_double * 3), ("point", c_double * 3),
                ("closest_face", c_uint32), ("closest_bary", c_double * 3), ("closest_point", c_double * 3),
                ("area", c_double), ("mean_lower", c_double), ("mean_upper", c_double), ("rms_lower", c_double),
                ("rms_upper", c_double), ("pieces", c_uint64), ("queries", c_uint64)]


class SparseMatrixView(ctypes.Structure):
    _fields_ = [("row_count", c_size_t), ("col_count", c_size_t), ("entry_count", c_size_t),
                ("row_start", POINTER(c_uint64)), ("col", POINTER(c_uint32)), ("value", POINTER(c_double))]


class RenderOptions(ctypes.Structure):
    _fields_ = [("width", c_int), ("height", c_int), ("view_dir", c_double * 3), ("up", c_double * 3),
                ("vertex_scalar", POINTER(c_double)), ("isolines", c_int), ("polyline", POINTER(c_double)),
                ("polyline_count", c_size_t), ("supersample", c_int), ("progress", RENDER_PROGRESS_FN),
                ("progress_user", c_void_p), ("vertex_label", POINTER(c_uint32)),
                ("polyline_start", POINTER(c_size_t)), ("polyline_parts", c_size_t),
                ("vertex_uv", POINTER(c_double)), ("checker_size", c_double),
                ("isoline_xyz", POINTER(c_double)), ("isoline_start", POINTER(c_size_t)),
                ("isoline_level", POINTER(c_double)), ("isoline_parts", c_size_t)]


class IsolinesView(ctypes.Structure):
    _fields_ = [("level_count", c_size_t), ("levels", POINTER(c_double)), ("level_start", POINTER(c_size_t)),
                ("polyline_count", c_size_t), ("polyline_start", POINTER(c_size_t)),
                ("polyline_closed", POINTER(ctypes.c_uint8)), ("point_count", c_size_t),
                ("points", POINTER(SurfacePointC)), ("faces", POINTER(c_uint32)), ("xyz", POINTER(c_double))]


class BoundariesView(ctypes.Structure):
    _fields_ = [("polyline_count", c_size_t), ("polyline_start", POINTER(c_size_t)),
                ("polyline_cells", POINTER(c_uint32)), ("point_count", c_size_t),
                ("points", POINTER(SurfacePointC)), ("xyz", POINTER(c_double))]


_vp = c_void_p
_pvp = POINTER(c_void_p)
_pd = POINTER(c_double)
_pu32 = POINTER(c_uint32)
_psp = POINTER(SurfacePointC)
_pdiag = POINTER(Diag)

_SIGNATURES = {
    "tg_version": (c_char_p, []),
    "tg_status_name": (c_char_p, [c_int]),
    "tg_status_string": (c_char_p, [c_int]),
    "tg_mesh_create": (c_int, [_pd, c_size_t, _pu32, c_size_t, _vp, _pdiag, _pvp]),
    "tg_mesh_load": (c_int, [c_char_p, c_int, _vp, _pdiag, _pvp]),
    "tg_mesh_load_memory": (c_int, [c_char_p, c_size_t, c_char_p, c_int, _vp, _pdiag, _pvp]),
    "tg_mesh_destroy": (None, [_vp]),
    "tg_mesh_vertex_count": (c_size_t, [_vp]),
    "tg_mesh_face_count": (c_size_t, [_vp]),
    "tg_mesh_positions": (_pd, [_vp]),
    "tg_mesh_triangles": (_pu32, [_vp]),
    "tg_mesh_get_report": (POINTER(MeshReport), [_vp]),
    "tg_mesh_write_obj": (c_int, [_vp, c_char_p, _pdiag]),
    "tg_mesh_write_ply": (c_int, [_vp, c_char_p, POINTER(VertexScalar), c_size_t, _pdiag]),
    "tg_mesh_memory_bytes": (c_size_t, [_vp]),
    "tg_mesh_halfedge_from": (c_uint32, [_vp, c_uint32]),
    "tg_mesh_halfedge_to": (c_uint32, [_vp, c_uint32]),
    "tg_surface_point_validate": (c_int, [_vp, _psp, _pdiag]),
    "tg_surface_point_position": (None, [_vp, _psp, _pd]),
    "tg_bvh_create": (c_int, [_vp, POINTER(BvhOptions), _pvp]),
    "tg_bvh_destroy": (None, [_vp]),
    "tg_bvh_memory_bytes": (c_size_t, [_vp]),
    "tg_bvh_workspace_create": (c_int, [_vp, _pvp]),
    "tg_bvh_workspace_destroy": (None, [_vp]),
    "tg_bvh_closest_batch": (c_int, [_vp, _pd, c_size_t, c_double, c_int, POINTER(ClosestHit)]),
    "tg_bvh_signed_distance_batch": (c_int, [_vp, _pd, c_size_t, c_int, c_int, POINTER(SignedHit)]),
    "tg_bvh_winding_number_batch": (c_int, [_vp, _pd, c_size_t, c_int, _pd]),
    "tg_bvh_sign_method": (c_int, [_vp, c_int]),
    "tg_bvh_locate": (c_int, [_vp, _vp, _pd, _psp, POINTER(ClosestHit)]),
    "tg_mesh_distance": (c_int, [_vp, _vp, POINTER(MeshDistanceOptions), _pd, POINTER(MeshDistanceResult)]),
    "tg_geodesic_create": (c_int, [_vp, _vp, _pvp]),
    "tg_geodesic_destroy": (None, [_vp]),
    "tg_geodesic_memory_bytes": (c_size_t, [_vp]),
    "tg_geodesic_workspace_create": (c_int, [_vp, _pvp]),
    "tg_geodesic_workspace_destroy": (None, [_vp]),
    "tg_path_create": (c_int, [_vp, _pvp]),
    "tg_path_destroy": (None, [_vp]),
    "tg_path_get_view": (None, [_vp, POINTER(PathView)]),
    "tg_path_status_name": (c_char_p, [c_int]),
    "tg_path_global_name": (c_char_p, [c_int]),
    "tg_geodesic_path": (c_int, [_vp, _vp, _psp, _psp, POINTER(PathOptions), _vp]),
    "tg_path_write_obj": (c_int, [_vp, c_char_p, _pdiag]),
    "tg_geodesic_path_through": (c_int, [_vp, _vp, _psp, c_size_t, c_int, POINTER(PathOptions), _vp,
                                         POINTER(c_size_t)]),
    "tg_trace_create": (c_int, [_vp, _pvp]),
    "tg_trace_destroy": (None, [_vp]),
    "tg_trace_get_view": (None, [_vp, POINTER(TraceView)]),
    "tg_trace_status_name": (c_char_p, [c_int]),
    "tg_geodesic_trace": (c_int, [_vp, _psp, POINTER(TraceDirection), c_double, POINTER(TraceOptions), _vp]),
    "tg_geodesic_trace_batch": (c_int, [_vp, _psp, POINTER(TraceDirection), _pd, c_size_t, POINTER(TraceOptions),
                                        c_int, POINTER(TraceEnd)]),
    "tg_geodesic_field": (c_int, [_vp, _vp, _psp, c_size_t, POINTER(FieldOptions), _pd, _vp]),
    "tg_geodesic_log_map": (c_int, [_vp, _vp, _psp, _pd, POINTER(FieldOptions), _pd, _pd, _vp]),
    "tg_geodesic_transport_field": (c_int, [_vp, _vp, _psp, _pd, POINTER(FieldOptions), _pd, _vp, _pd, _vp]),
    "tg_polyline_transport": (c_int, [_vp, c_size_t, _pd, _pu32, _pd, _pd]),
    "tg_geodesic_field_gradient": (c_int, [_vp, _vp, _psp, c_size_t, POINTER(FieldOptions), _pd, _vp, _pu32, _pd, _pd,
                                           _vp, _vp]),
    "tg_geodesic_field_at": (c_int, [_vp, _vp, _psp, c_size_t, _psp, c_size_t, POINTER(FieldOptions), _pd, _pd, _vp]),
    "tg_geodesic_curve_field": (c_int, [_vp, _vp, _psp, c_size_t, POINTER(SurfaceSegmentC), c_size_t, _psp, c_size_t,
                                        POINTER(FieldOptions), _pd, _pd, _vp]),
    "tg_geodesic_boundary_segments": (c_int, [_vp, POINTER(SurfaceSegmentC), c_size_t, POINTER(c_size_t)]),
    "tg_geodesic_curve_voronoi": (c_int, [_vp, _vp, _psp, c_size_t, _pu32, POINTER(SurfaceSegmentC), c_size_t, _pu32,
                                          c_size_t, POINTER(FieldOptions), _pd, _pu32, _vp]),
    "tg_geodesic_curve_distance_matrix": (c_int, [_vp, _psp, c_size_t, _pu32, POINTER(SurfaceSegmentC), c_size_t,
                                                  _pu32, c_size_t, _psp, c_size_t, POINTER(FieldOptions), c_int, _pd,
                                                  _vp]),
    "tg_geodesic_curve_path": (c_int, [_vp, _vp, _psp, c_size_t, POINTER(SurfaceSegmentC), c_size_t, _psp,
                                       POINTER(PathOptions), _vp]),
    "tg_surface_segment_validate": (c_int, [_vp, POINTER(SurfaceSegmentC), _pdiag]),
    "tg_surface_point_snap": (SurfacePointC, [_vp, _psp, c_double]),
    "tg_geodesic_distance_matrix": (c_int, [_vp, _psp, c_size_t, POINTER(FieldOptions), c_int, _pd, _vp]),
    "tg_geodesic_distance_matrix_at": (c_int, [_vp, _psp, c_size_t, _psp, c_size_t, POINTER(FieldOptions), c_int,
                                               _pd, _vp]),
    "tg_geodesic_local_matrix": (c_int, [_vp, _psp, c_size_t, c_double, POINTER(FieldOptions), c_int, _vp, _vp]),
    "tg_sparse_matrix_create": (c_int, [_vp, _pvp]),
    "tg_sparse_matrix_get_view": (None, [_vp, POINTER(SparseMatrixView)]),
    "tg_sparse_matrix_destroy": (None, [_vp]),
    "tg_render_png": (c_int, [_vp, POINTER(RenderOptions), c_char_p, _pdiag]),
    "tg_geodesic_voronoi": (c_int, [_vp, _vp, _psp, c_size_t, POINTER(FieldOptions), _vp, _pd, _pu32, _vp]),
    "tg_voronoi_boundaries_create": (c_int, [_vp, _pvp]),
    "tg_voronoi_boundaries_get_view": (None, [_vp, POINTER(BoundariesView)]),
    "tg_voronoi_boundaries_destroy": (None, [_vp]),
    "tg_geodesic_isolines": (c_int, [_vp, _vp, _psp, c_size_t, _pd, c_size_t, POINTER(FieldOptions), _vp, _pd,
                                     _vp]),
    "tg_geodesic_curve_isolines": (c_int, [_vp, _vp, _psp, c_size_t, POINTER(SurfaceSegmentC), c_size_t, _pd,
                                           c_size_t, POINTER(FieldOptions), _vp, _pd, _vp]),
    "tg_isolines_create": (c_int, [_vp, _pvp]),
    "tg_isolines_get_view": (None, [_vp, POINTER(IsolinesView)]),
    "tg_isolines_destroy": (None, [_vp]),
    "tg_mean_status_name": (c_char_p, [c_int]),
    "tg_mean_uniqueness_name": (c_char_p, [c_int]),
    "tg_geodesic_mean": (c_int, [_vp, _vp, _psp, _pd, c_size_t, POINTER(MeanOptions), POINTER(MeanResult)]),
    "tg_geodesic_bezier_with": (c_int, [_vp, _vp, _psp, c_size_t, c_size_t, c_int, POINTER(PathOptions), _psp, _pd]),
    "tg_geodesic_centroidal_voronoi": (c_int, [_vp, _vp, _psp, c_uint64, c_size_t, POINTER(CentroidalOptions), _psp,
                                               _pu32, _pd, POINTER(c_size_t)]),
    "tg_geodesic_farthest_point_sampling": (c_int, [_vp, _vp, c_uint32, c_uint64, c_size_t, POINTER(FieldOptions),
                                                    _pu32, _pd, _pu32, _vp]),
}

for _name, (_res, _args) in _SIGNATURES.items():
    _f = getattr(lib, _name)
    _f.restype = _res
    _f.argtypes = _args
