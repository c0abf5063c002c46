"""The ctypes mirrors of the C structs (python/trigeo/_lib.py) against the C layout itself: a small
C program compiled now with the system compiler against include/trigeo.h prints sizeof and
offsetof of every field of every mirrored struct; the mirrors must have the same size, the same
fields in the same order (read from the header's struct definitions), the same offsets and the
same field sizes. A wrong offset would make the library read or write the wrong bytes silently."""
import ctypes
import inspect
import os
import re
import shutil
import subprocess

import pytest

from conftest import REPO
from trigeo import _lib

HEADER = os.path.join(REPO, "include", "trigeo.h")

# the Python mirror of each C struct
C_NAME = {
    "Diag": "tg_diag",
    "Allocator": "tg_allocator",
    "MeshReport": "tg_mesh_report",
    "SurfacePointC": "tg_surface_point",
    "SurfaceSegmentC": "tg_surface_segment",
    "ClosestHit": "tg_closest_hit",
    "SignedHit": "tg_signed_hit",
    "BvhOptions": "tg_bvh_options",
    "KernelOptions": "tg_geodesic_kernel_options",
    "PathOptions": "tg_path_options",
    "PathView": "tg_path_view",
    "TraceDirection": "tg_trace_direction",
    "TraceOptions": "tg_trace_options",
    "MeanOptions": "tg_mean_options",
    "MeanResult": "tg_mean_result",
    "CentroidalOptions": "tg_centroidal_options",
    "TraceEnd": "tg_trace_end",
    "TraceView": "tg_trace_view",
    "VertexScalar": "tg_vertex_scalar",
    "FieldProgress": "tg_field_progress",
    "FieldOptions": "tg_field_options",
    "SparseMatrixView": "tg_sparse_matrix_view",
    "RenderOptions": "tg_render_options",
    "BoundariesView": "tg_voronoi_boundaries_view",
    "IsolinesView": "tg_isolines_view",
    "MeshDistanceProgress": "tg_mesh_distance_progress",
    "MeshDistanceOptions": "tg_mesh_distance_options",
    "MeshDistanceResult": "tg_mesh_distance_result",
}
# Python field names that differ from C's (keywords)
C_FIELD = {"global_": "global"}


def mirrors():
    return {name: cls for name, cls in vars(_lib).items()
            if inspect.isclass(cls) and issubclass(cls, ctypes.Structure) and cls.__module__ == _lib.__name__}


def header_fields(struct):
    """The field names of `typedef struct NAME {...} NAME;` in trigeo.h, in order."""
    text = open(HEADER).read()
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    m = re.search(r"typedef struct %s \{(.*?)\} %s;" % (struct, struct), text, flags=re.S)
    assert m, f"{struct} not found in {HEADER}"
    names = []
    for decl in m.group(1).split(";"):
        decl = " ".join(decl.split())
        if not decl:
            continue
        fp = re.search(r"\(\s*\*\s*(\w+)\s*\)", decl)  # a function pointer
        if fp:
            names.append(fp.group(1))
            continue
        decl = re.sub(r"\[[^\]]*\]", "", decl)  # arrays
        first, *rest = decl.split(",")
        names.append(re.findall(r"\w+", first)[-1])
        names += [re.findall(r"\w+", r)[-1] for r in rest]
    return names


@pytest.fixture(scope="module")
def c_layout(tmp_path_factory):
    """{struct: (size, {field: (offset, size)})} from the C compiler."""
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if not cc:
        pytest.skip("no C compiler to measure the C layout with")
    lines = ["#include <stddef.h>", "#include <stdio.h>", "#include <trigeo.h>", "int main(void) {"]
    for py, c in C_NAME.items():
        lines.append(f'    printf("S {c} %zu\\n", sizeof({c}));')
        for field in header_fields(c):
            lines.append(f'    printf("F {c} {field} %zu %zu\\n", offsetof({c}, {field}), sizeof((({c}*)0)->{field}));')
    lines += ["    return 0;", "}"]
    d = tmp_path_factory.mktemp("abi")
    src, exe = d / "layout.c", d / "layout"
    src.write_text("\n".join(lines) + "\n")
    r = subprocess.run([cc, "-std=c11", "-I", os.path.join(REPO, "include"), str(src), "-o", str(exe)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    out = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout
    layout = {}
    for line in out.splitlines():
        kind, name, *rest = line.split()
        if kind == "S":
            layout[name] = (int(rest[0]), {})
        else:
            layout[name][1][rest[0]] = (int(rest[1]), int(rest[2]))
    return layout


def test_every_mirror_is_checked():
    assert set(mirrors()) == set(C_NAME), "a ctypes Structure in _lib.py without its C struct in C_NAME (or gone)"


@pytest.mark.parametrize("py", sorted(C_NAME))
def test_struct_layout(py, c_layout):
    cls = mirrors()[py]
    c = C_NAME[py]
    size, fields = c_layout[c]
    py_fields = [C_FIELD.get(f[0], f[0]) for f in cls._fields_]
    assert py_fields == header_fields(c), f"{py}: fields {py_fields}, trigeo.h's {c}: {header_fields(c)}"
    for f in cls._fields_:
        name = C_FIELD.get(f[0], f[0])
        desc = getattr(cls, f[0])
        assert (desc.offset, desc.size) == fields[name], \
            f"{py}.{f[0]}: ctypes offset {desc.offset} size {desc.size}, C ({c}.{name}) offset and size {fields[name]}"
    assert ctypes.sizeof(cls) == size, f"{py}: ctypes size {ctypes.sizeof(cls)}, sizeof({c}) {size}"
