"""trigeo: exact distances and shortest paths on triangle meshes, with NumPy arrays in and out.

A pure-Python package over the C library libtrigeo.so (ctypes; no compiled extension). The
library is found through the TRIGEO_LIB environment variable if set, else the checkout's
build/libtrigeo.so (after `make`; only for the python/trigeo folder of a checkout), else the
library inside the package (`pip install .` puts it there), else the library `make install` put
beside the package (both under PREFIX/lib); nowhere else.

    import trigeo
    mesh = trigeo.load("data/nvd_spot.obj")          # OBJ, OFF, PLY, STL, optionally .gz
    d, face, p = mesh.closest(points)                # closest surface points, exact in double
    path = mesh.path(0, 1200)                        # globally shortest path, proven
    print(path.length, path.points.shape, path.global_)
    dist = mesh.field([0])                           # exact geodesic distance to every vertex
    mesh.render("spot.png", path=path, field=dist)

Surface points are given as a vertex index (int), a trigeo.SurfacePoint (a face point with
barycentric coordinates, an edge point on a halfedge, or a vertex), or an (x, y, z) position,
which is snapped to the closest surface point.

Every C call releases the GIL, so Python threads run queries in parallel; batch calls also take
a `threads` argument (0: all cores) and run on C threads. Errors raise trigeo.Error subclasses
carrying the file, line and reason. Objects: Mesh, Path, Trace, SurfacePoint; functions: load.
For batches over many machines, see trigeo.dask.
"""
from __future__ import annotations

import atexit
import ctypes
import math
import os
import threading
import time
import warnings
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from typing import Any, Callable, Iterator, Optional, Sequence, Union

import numpy as np

from . import _lib as _c
from ._lib import lib as _L

__all__ = [
    "load", "load_bytes", "Mesh", "Path", "Trace", "GeodesicMean", "SurfacePoint", "version", "Error", "InvalidArgumentError",
    "OutOfMemoryError", "FileError", "ParseError", "InvalidMeshError", "UnsupportedError", "CapacityError",
    "CancelledError", "LoadWarning", "MAX_THREADS", "MeshDistance",
]

__version__ = _L.tg_version().decode()


def version() -> str:
    """The version of the loaded libtrigeo.so, e.g. "0.5.0"."""
    return _L.tg_version().decode()


# ---------------------------------------------------------------------------------------------
# Errors
# ---------------------------------------------------------------------------------------------

class Error(Exception):
    """A trigeo failure. Attributes: status (the library's short name, e.g. "parse"), file, line,
    column (1-based; 0 when not a text position) and reason (the sentence without location)."""

    status = "error"

    def __init__(self, message: str, file: str = "", line: int = 0, column: int = 0, reason: str = ""):
        super().__init__(message)
        self.file, self.line, self.column = file, line, column
        self.reason = reason or message

    def __reduce__(self):  # picklable, so a Dask worker's error reaches the client as it is
        return (type(self), (str(self), self.file, self.line, self.column, self.reason))


class InvalidArgumentError(Error, ValueError):
    """An argument is out of range or inconsistent (wrong shape, NaN, bad index, bad surface point)."""
    status = "invalid_argument"


class OutOfMemoryError(Error, MemoryError):
    """Memory allocation failed or a size overflowed."""
    status = "out_of_memory"


class FileError(Error, OSError):
    """A file could not be opened, read or written."""
    status = "io"


class ParseError(Error, ValueError):
    """The input file is malformed; .file, .line and .column say where."""
    status = "parse"


class InvalidMeshError(Error, ValueError):
    """The data cannot describe a mesh (bad index, NaN or infinite coordinate)."""
    status = "invalid_mesh"


class UnsupportedError(Error):
    """The format or feature is not supported (e.g. coordinates beyond +-1e150)."""
    status = "unsupported"


class CapacityError(Error):
    """An output buffer is too small."""
    status = "capacity"


class CancelledError(Error):
    """A progress callback asked to stop."""
    status = "cancelled"


_ERRORS = [None, InvalidArgumentError, OutOfMemoryError, FileError, ParseError, InvalidMeshError,
           UnsupportedError, CapacityError, CancelledError]


def _raise(status: int, what: str, diag: Optional[_c.Diag] = None) -> None:
    """Raises the Error subclass of a non-zero status, with the diag's location and reason."""
    cls = _ERRORS[status] if 0 < status < len(_ERRORS) else Error
    reason = _L.tg_status_string(status).decode()
    file, line, column = "", 0, 0
    if diag is not None:
        file = diag.file.decode(errors="replace")
        line, column = int(diag.line), int(diag.column)
        if diag.message:
            reason = diag.message.decode(errors="replace")
    where = file + (f":{line}" if line else "") + (f":{column}" if line and column else "")
    message = f"{where}: {reason}" if where else f"{what}: {reason}"
    raise cls(message, file, line, column, reason)


def _check(status: int, what: str, diag: Optional[_c.Diag] = None) -> None:
    if status:
        _raise(status, what, diag)


# A curve's points given in coordinates lie on the edges they cross up to rounding: within this share
# of an edge (a barycentric, or t along an edge) they are taken on it (the CLI's ON_EDGE_REL).
_ON_EDGE_REL = 1e-9


def _bad(message: str) -> InvalidArgumentError:
    return InvalidArgumentError(message)


# ---------------------------------------------------------------------------------------------
# Surface points
# ---------------------------------------------------------------------------------------------

class SurfacePoint:
    """A location on a mesh surface.

    SurfacePoint(face, (b0, b1, b2))   a point in a face, by barycentric coordinates of its
                                       corners 0, 1, 2 (each in [0, 1], summing to 1)
    SurfacePoint.vertex(v)             mesh vertex v
    SurfacePoint.edge(h, t)            (1 - t) * from(h) + t * to(h) on halfedge h = 3 * face + i,
                                       which runs from corner i to corner (i + 1) % 3 of face

    Attributes: kind ("vertex", "edge" or "face"), index, t, bary. Equal points compare equal.
    """

    __slots__ = ("kind", "index", "t", "bary")
    _KINDS = ("vertex", "edge", "face")

    def __init__(self, face: int, bary: Sequence[float] = (1 / 3, 1 / 3, 1 / 3), *, kind: str = "face",
                 t: float = 0.0):
        if not isinstance(kind, str) or kind not in self._KINDS:
            raise _bad(f"SurfacePoint kind must be one of {self._KINDS}, not {kind!r}")
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "index", _index(face, "SurfacePoint index"))
        object.__setattr__(self, "t", _real(t, "SurfacePoint t"))
        if kind == "face":
            try:
                items = list(bary)
            except TypeError:
                raise _bad(f"SurfacePoint needs 3 barycentric coordinates, not {_show(bary)}") from None
            b = tuple(_real(x, "SurfacePoint barycentric coordinate") for x in items)
        else:
            b = (0.0, 0.0, 0.0)
        if len(b) != 3:
            raise _bad(f"SurfacePoint needs 3 barycentric coordinates, got {len(b)}")
        object.__setattr__(self, "bary", b)

    def __setattr__(self, name, value):
        raise AttributeError("SurfacePoint is immutable")

    @classmethod
    def vertex(cls, v: int) -> "SurfacePoint":
        """Mesh vertex v."""
        return cls(v, kind="vertex")

    @classmethod
    def edge(cls, halfedge: int, t: float) -> "SurfacePoint":
        """The point at parameter t in [0, 1] along halfedge (3 * face + i)."""
        return cls(halfedge, kind="edge", t=t)

    @classmethod
    def face(cls, face: int, bary: Sequence[float]) -> "SurfacePoint":
        """A point in a face by barycentric coordinates."""
        return cls(face, bary)

    def __repr__(self) -> str:
        if self.kind == "vertex":
            return f"SurfacePoint.vertex({self.index})"
        if self.kind == "edge":
            return f"SurfacePoint.edge({self.index}, {self.t!r})"
        return f"SurfacePoint({self.index}, {self.bary!r})"

    def __eq__(self, other) -> bool:
        return isinstance(other, SurfacePoint) and (self.kind, self.index, self.t, self.bary) == (
            other.kind, other.index, other.t, other.bary)

    def __hash__(self) -> int:
        return hash((self.kind, self.index, self.t, self.bary))

    def __reduce__(self):
        return (_make_surface_point, (self.kind, self.index, self.t, self.bary))

    def _to_c(self) -> _c.SurfacePointC:
        return _c.SurfacePointC(self._KINDS.index(self.kind), self.index, self.t,
                                (ctypes.c_double * 3)(*self.bary))

    @classmethod
    def _from_c(cls, p: _c.SurfacePointC) -> "SurfacePoint":
        kind = cls._KINDS[p.kind]
        return cls(p.index, tuple(p.bary), kind=kind, t=p.t)


def _make_surface_point(kind, index, t, bary):
    return SurfacePoint(index, bary, kind=kind, t=t)


def _index(x: Any, what: str) -> int:
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, np.integer)):
        raise _bad(f"{what} must be an integer, not {type(x).__name__}")
    i = int(x)
    if not 0 <= i < 0xFFFFFFFF:
        raise _bad(f"{what} {i} is out of range: an index from 0 to 4294967294")
    return i


def _u64(x: Any, what: str) -> int:
    """An integer in 0 .. 2**64 - 1 (a seed: the range `trigeo sample --seed` takes)."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, np.integer)):
        raise _bad(f"{what} must be an integer, not {type(x).__name__}")
    i = int(x)
    if not 0 <= i <= 0xFFFFFFFFFFFFFFFF:
        raise _bad(f"{what} {i} is out of range: an integer from 0 to 2**64 - 1")
    return i


def _show(x: Any) -> str:
    """x for a message: its repr, cut to 60 characters."""
    r = repr(x)
    return r if len(r) <= 60 else r[:57] + "..."


# The ranges of numeric arguments; one rule with the CLI's numbers (tools/: a number is the double
# it is, subnormals included, then checked against its argument's range).
_RANGES = {"finite": ("a finite number", lambda v: math.isfinite(v)),
           ">=0": ("a finite number >= 0", lambda v: math.isfinite(v) and v >= 0.0),
           ">0": ("a finite number > 0", lambda v: math.isfinite(v) and v > 0.0)}


def _real(x: Any, what: str) -> float:
    """A Python or NumPy number (not a bool or a string) as the double it is, unchecked: for
    values the library validates against the mesh (barycentric coordinates, edge parameters)."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.integer, np.floating)):
        raise _bad(f"{what} must be a number, not {type(x).__name__} {_show(x)}")
    try:
        return float(x)
    except OverflowError:
        raise _bad(f"{what} = {_show(x)} is beyond the range of a double") from None


def _number(x: Any, what: str, allowed: str = "finite", hint: str = "") -> float:
    """One numeric argument: the double it is (subnormals included), then its range: "finite",
    ">=0" or ">0"."""
    v = _real(x, what)
    words, ok = _RANGES[allowed]
    if not ok(v):
        raise _bad(f"{what} must be {words}{hint}, not {_show(x)}")
    return v


def _floats(x: Any, what: str, shape: str) -> np.ndarray:
    """An array of numbers (any integer or float dtype) as float64, unchecked in range; shape
    names what is expected, for the message."""
    try:
        a = np.asarray(x)
    except (TypeError, ValueError):  # ragged nesting
        raise _bad(f"{what} must be {shape} of numbers, not {_show(x)}") from None
    if a.dtype.kind not in "fiu":
        raise _bad(f"{what} must be {shape} of numbers, not {_show(x)} (dtype {a.dtype})")
    return a.astype(np.float64)


def _check_values(a: np.ndarray, what: str, allowed: str) -> None:
    """Every element of a (any shape) in the range of _number; the first outside is named."""
    words, ok = _RANGES[allowed]
    flat = a.reshape(-1)
    good = np.isfinite(flat) if allowed == "finite" else (
        np.isfinite(flat) & ((flat >= 0.0) if allowed == ">=0" else (flat > 0.0)))
    if not good.all():
        i = int(np.argmin(good))
        where = np.unravel_index(i, a.shape) if a.ndim > 1 else (i,)
        index = ", ".join(str(int(k)) for k in where)
        raise _bad(f"{what}[{index}] = {flat[i]!r} must be {words}")


def _flag(x: Any, what: str) -> bool:
    """A yes/no argument: a bool (or the integer 0 or 1), never an array whose truth is ambiguous."""
    if isinstance(x, (bool, np.bool_)) or (isinstance(x, (int, np.integer)) and x in (0, 1)):
        return bool(x)
    raise _bad(f"{what} must be True or False, not {_show(x)}")


def _choice(x: Any, what: str, table: dict) -> Any:
    """A keyword argument from a fixed set of names."""
    if not isinstance(x, str) or x not in table:
        raise _bad(f"{what} must be one of {sorted(table)}, not {_show(x)}")
    return table[x]


# ---------------------------------------------------------------------------------------------
# Array helpers
# ---------------------------------------------------------------------------------------------

def _points(points: Any, what: str = "points") -> np.ndarray:
    """(k, 3) C-contiguous float64, finite; a C-contiguous float64 input is returned as it is."""
    try:
        a = np.asarray(points)
    except (TypeError, ValueError):  # ragged nesting
        raise _bad(f"{what} must be a (k, 3) array of numbers, not {_show(points)}") from None
    if a.dtype.kind not in "fiu" or a.dtype == np.float16:
        raise _bad(f"{what} must be numbers (float64 preferred), not dtype {a.dtype}")
    if a.ndim == 1 and a.shape[0] == 3:
        a = a.reshape(1, 3)
    if a.ndim != 2 or a.shape[1] != 3:
        raise _bad(f"{what} must have shape (k, 3), not {a.shape}")
    a = np.ascontiguousarray(a, dtype=np.float64)
    finite = np.isfinite(a).all(axis=1)
    if not finite.all():
        i = int(np.argmin(finite))
        raise _bad(f"{what}[{i}] is not finite: {a[i].tolist()}")
    inside = (np.abs(a) <= MAX_COORDINATE).all(axis=1)
    if not inside.all():
        i = int(np.argmin(inside))
        raise _bad(f"{what}[{i}] = {a[i].tolist()} is beyond the supported range of +-1e150 "
                   "(squared distances would overflow)")
    return a


def _shape(x: Any) -> Optional[tuple]:
    """np.shape(x), or None for a ragged sequence (which has none)."""
    try:
        return np.shape(x)
    except ValueError:
        return None


def _polyline(points: Any, what: str) -> np.ndarray:
    """A polyline: (k, 3) as _points, k >= 0 (an empty sequence is no point)."""
    if isinstance(points, (list, tuple, np.ndarray)) and len(points) == 0:
        return np.empty((0, 3))
    return _points(points, what)


MAX_THREADS = 256  # TG_MAX_THREADS of include/trigeo.h
MAX_COORDINATE = 1e150  # the library's range for distances (tg_bvh_create, tg_geodesic_create)


def _threads(threads: int) -> int:
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 0:
        raise _bad(f"threads must be an integer >= 0 (0: all cores), not {threads!r}")
    if threads > MAX_THREADS:
        raise _bad(f"threads must be at most {MAX_THREADS} (trigeo.MAX_THREADS), not {int(threads)}")
    return int(threads)


def _ptr(a: np.ndarray, ctype=ctypes.c_double):
    return a.ctypes.data_as(ctypes.POINTER(ctype))


class _ArrayView:
    """Exposes library memory to NumPy while keeping its owner alive (the array's base)."""

    def __init__(self, owner: Any, address: int, shape: tuple, typestr: str):
        self._owner = owner
        self.__array_interface__ = {"data": (address, True), "shape": shape, "typestr": typestr, "version": 3}


def _view(owner: Any, pointer, shape: tuple, typestr: str) -> np.ndarray:
    address = ctypes.cast(pointer, ctypes.c_void_p).value or 0
    if address == 0 or 0 in shape:
        return np.empty(shape, dtype=np.dtype(typestr))
    a = np.asarray(_ArrayView(owner, address, shape, typestr))
    a.flags.writeable = False
    return a


class _Pool:
    """Per-call scratch objects (workspaces, path objects), created on demand and reused, one per
    concurrent caller."""

    def __init__(self, create: Callable[[], int], destroy: Callable[[int], None]):
        self._create, self._destroy = create, destroy
        self._free: list = []
        self._lock = threading.Lock()

    @contextmanager
    def take(self) -> Iterator[int]:
        with self._lock:
            h = self._free.pop() if self._free else None
        if h is None:
            h = self._create()
        try:
            yield h
        finally:
            with self._lock:
                self._free.append(h)

    def close(self) -> None:
        with self._lock:
            for h in self._free:
                self._destroy(h)
            self._free = []


def _new(create: Callable, *args) -> int:
    out = ctypes.c_void_p()
    _check(create(*args, ctypes.byref(out)), create.__name__)
    return out.value


# ---------------------------------------------------------------------------------------------
# Calls: Ctrl-C, progress callbacks, and close() while calls run
# ---------------------------------------------------------------------------------------------

TG_ERR_CANCELLED_ = 8
_local = threading.local()  # .callbacks: depth of user progress callbacks on this thread


class _Call:
    """One public call: its cancellation flag and the C callbacks that report it to the library.

    From the main thread the C work runs on a helper thread while the main thread waits, so
    that Ctrl-C raises KeyboardInterrupt at once: the flag is set, the library stops at its
    next look (fields, paths and renders every few milliseconds, batches of points between
    chunks), and the main thread re-raises. Work that cannot stop (building a BVH or a solver,
    writing a file, loading one) is left to finish on its own after a short grace period; the
    Mesh counts it as running until it ends, so close() still waits for it."""

    GRACE_S = 0.5  # how long Ctrl-C waits for work to stop before leaving it to finish alone

    def __init__(self, user: Optional[Callable[[float], Any]] = None):
        self.user, self.error, self.cancel = user, None, False
        self.field_fn = _c.PROGRESS_FN(self._field)
        self.render_fn = _c.RENDER_PROGRESS_FN(self._render)
        self.mesh_distance_fn = _c.MESH_DISTANCE_PROGRESS_FN(self._mesh_distance)

    def _report(self, fraction: float) -> int:
        if self.cancel or self.error is not None:
            return 1
        if self.user is None:
            return 0
        _local.callbacks = getattr(_local, "callbacks", 0) + 1
        try:
            return 1 if self.user(fraction) is False else 0
        except BaseException as e:  # stop the C call; re-raised by finish()
            self.error = e
            return 1
        finally:
            _local.callbacks -= 1

    def _field(self, _user, progress) -> int:
        return self._report(float(progress.contents.settled_fraction))

    def _render(self, _user, fraction) -> int:
        return self._report(float(fraction))

    def _mesh_distance(self, _user, progress) -> int:
        return self._report(float(progress.contents.fraction))

    def run(self, work: Callable[[], Any], uses: Optional["_Uses"] = None) -> Any:
        """work() on this thread, or from the main thread on a helper thread (see the class)."""
        if threading.current_thread() is not threading.main_thread():
            return work()
        box: dict = {}

        def target():
            try:
                if uses is not None:
                    with uses.inside():  # nested calls on the Mesh are part of this one
                        box["result"] = work()
                else:
                    box["result"] = work()
            except BaseException as e:
                box["error"] = e
            finally:
                if uses is not None:
                    uses.release()

        if uses is not None:
            uses.hold()  # the helper's own claim: released when it ends, even if left alone
        t = threading.Thread(target=target, name="trigeo-call", daemon=True)
        try:
            t.start()
        except BaseException:
            if uses is not None:
                uses.release()
            raise
        try:
            while t.is_alive():
                t.join(0.05)
        except BaseException:
            self.cancel = True
            t.join(self.GRACE_S)
            raise
        if "error" in box:
            raise box["error"]
        return box["result"]

    def finish(self, status: int, what: str, diag: Optional[_c.Diag] = None) -> None:
        """Raises the user callback's exception, else the status's Error."""
        if self.error is not None:
            raise self.error
        _check(status, what, diag)


class _Uses:
    """The calls running on a Mesh, so that close() frees nothing while one of them uses it:
    close() waits for them (and refuses from inside one: a progress callback); calls started
    after close() are refused, but not a call made inside a running one (a running call reading
    .vertex_count, a progress callback asking for .faces), which close() is waiting for anyway."""

    def __init__(self):
        self._cond = threading.Condition()
        self._count = 0
        self._closed = False
        self._waiting = False  # close() is waiting for the calls to end
        self._free: Optional[Callable[[], None]] = None
        self._depth = threading.local()  # .n: running calls of this Mesh on this thread

    def enter(self) -> None:
        with self._cond:
            if self._closed and not getattr(self._depth, "n", 0):
                raise _bad("this Mesh was closed")
            self._count += 1

    def hold(self) -> None:
        with self._cond:
            self._count += 1

    def release(self) -> None:
        free = None
        with self._cond:
            self._count -= 1
            if self._count == 0:
                self._cond.notify_all()
                if self._closed and not self._waiting:  # close() was interrupted: the last call frees
                    free, self._free = self._free, None
        if free is not None:
            free()

    @contextmanager
    def inside(self) -> Iterator[None]:
        """This thread runs a call of the Mesh (counted elsewhere: enter() or hold())."""
        self._depth.n = getattr(self._depth, "n", 0) + 1
        try:
            yield
        finally:
            self._depth.n -= 1

    @contextmanager
    def use(self) -> Iterator[None]:
        self.enter()
        try:
            with self.inside():
                yield
        finally:
            self.release()

    def close(self, free: Callable[[], None]) -> None:
        if getattr(_local, "callbacks", 0):
            raise _bad("close() from inside a progress callback would wait for its own call; close the Mesh "
                       "after the call returns")
        with self._cond:
            if self._closed:
                return
            self._closed = True
            self._free = free
            self._waiting = True
            try:
                while self._count:
                    self._cond.wait()
            finally:
                self._waiting = False
            free, self._free = self._free, None
        if free is not None:
            free()


# ---- files written whole: a private temporary directory beside the target, then a rename ----

_TEMP_DIRS: set = set()  # in-flight temporaries, removed at exit (work left running by Ctrl-C)
_TEMP_LOCK = threading.Lock()


def _remove_temporaries() -> None:
    import shutil
    with _TEMP_LOCK:
        dirs = list(_TEMP_DIRS)
    for d in dirs:
        shutil.rmtree(d, ignore_errors=True)


atexit.register(_remove_temporaries)


def _fs_path(path: Any, what: str) -> str:
    try:
        p = os.fspath(path)
    except TypeError:
        raise _bad(f"{what} must be a file name (str, bytes or os.PathLike), not {type(path).__name__} "
                   f"{_show(path)}") from None
    if isinstance(p, bytes):
        p = os.fsdecode(p)
    if "\0" in p:
        raise _bad(f"{what} {p!r} contains a NUL character (the file name would end there)")
    return p


def _write_whole(path: str, call: _Call, write: Callable[[bytes, _c.Diag], int]) -> None:
    """Writes a file through a library writer so that it appears only complete: into a private
    directory made by mkdtemp beside the target (no predictable name, no link followed), then
    renamed over it. A character device or FIFO is written directly; a directory is refused.
    A cancelled call (Ctrl-C) removes its temporary instead of renaming it."""
    import stat
    import tempfile
    try:
        st = os.stat(path)
    except OSError:
        st = None
    if st is not None and (stat.S_ISDIR(st.st_mode) or stat.S_ISBLK(st.st_mode) or stat.S_ISSOCK(st.st_mode)):
        kind = "a directory" if stat.S_ISDIR(st.st_mode) else "a block device or socket"
        raise FileError(f"{path}: is {kind}: give a file name", path, 0, 0, f"is {kind}")
    diag = _c.Diag()
    if st is not None and (stat.S_ISCHR(st.st_mode) or stat.S_ISFIFO(st.st_mode)):
        _check(write(os.fsencode(path), diag), path, diag)
        return
    try:
        tmpdir = tempfile.mkdtemp(prefix=".trigeo-", dir=os.path.dirname(os.path.abspath(path)))
    except OSError as e:
        raise FileError(f"{path}: cannot create a temporary directory beside it: {e.strerror}", path, 0, 0,
                        f"cannot create a temporary directory beside it: {e.strerror}") from None
    with _TEMP_LOCK:
        _TEMP_DIRS.add(tmpdir)
    tmp = os.path.join(tmpdir, os.path.basename(path))
    try:
        status = write(os.fsencode(tmp), diag)
        if status == 0 and not call.cancel:
            try:
                os.replace(tmp, path)
            except OSError as e:
                raise FileError(f"{path}: cannot rename the finished file into place: {e.strerror}", path, 0, 0,
                                e.strerror) from None
    finally:
        for f in (lambda: os.unlink(tmp), lambda: os.rmdir(tmpdir)):
            try:
                f()
            except OSError:
                pass
        with _TEMP_LOCK:
            _TEMP_DIRS.discard(tmpdir)
    if status:
        # the library named the temporary file: name the one asked for
        diag.file = os.fsencode(path)[:255]
        diag.message = diag.message.replace(os.fsencode(tmp)[:255], os.fsencode(path)[:200])
        call.finish(status, path, diag)


# ---------------------------------------------------------------------------------------------
# Mesh
# ---------------------------------------------------------------------------------------------

_FORMATS = {"auto": 0, "obj": 1, "off": 2, "ply": 3, "stl": 4}
_SIGN = {"auto": 0, "pseudonormal": 1, "winding": 2}
_METHODS = {"exact": 0, "straighten": 1, "relax": 2, "edge": 3}  # tg_path_method; "exact" is the C default
_BEZIER_METHODS = {"paths": 0, "logmap": 1}  # tg_bezier_method
_HIT = np.dtype(_c.ClosestHit)
_SIGNED = np.dtype(_c.SignedHit)


class LoadWarning(UserWarning):
    """A mesh file loaded, but its reader tolerated something (e.g. padding bytes after the last
    record of a binary STL or PLY). .file and .reason as for Error."""

    def __init__(self, message: str, file: str = "", reason: str = ""):
        super().__init__(message)
        self.file, self.reason = file, reason or message


def _warn_diag(diag: _c.Diag, stacklevel: int = 3) -> None:
    """A warning a successful load left in diag ("warning: ..."), as a LoadWarning."""
    if diag.message:
        file = diag.file.decode(errors="replace")
        reason = diag.message.decode(errors="replace")
        where = f"byte {int(diag.byte_offset)}: " if not diag.line and diag.byte_offset else ""
        if diag.line:
            where = f"line {int(diag.line)}: "
        warnings.warn(LoadWarning(f"{file}: {where}{reason}", file, reason), stacklevel=stacklevel)


def _mesh_from_handle(handle: int, source: Optional[str]) -> "Mesh":
    m = Mesh.__new__(Mesh)
    m._init(handle, source)
    return m


def load(path: Union[str, os.PathLike], format: str = "auto") -> "Mesh":
    """Loads a mesh file: OBJ, OFF, PLY (ascii or binary), STL (ascii or binary), optionally
    gzip-compressed (.gz). format: "auto" (by extension, then content), "obj", "off", "ply" or
    "stl". Polygons are fan-triangulated; vertices keep file order. Counts in the file are
    checked against its data. Raises FileError, ParseError (with .file and .line),
    InvalidMeshError or UnsupportedError (InvalidArgumentError for a path with a NUL
    character); something the reader tolerated (padding after a binary STL) is a LoadWarning.
    Ctrl-C interrupts it."""
    fmt = _choice(format, "format", _FORMATS)
    name = _fs_path(path, "path")
    p = os.fsencode(name)
    call = _Call()
    diag = _c.Diag()

    def work() -> Optional[int]:
        h = ctypes.c_void_p()
        st = _L.tg_mesh_load(p, fmt, None, ctypes.byref(diag), ctypes.byref(h))
        if st == 0 and call.cancel:  # Ctrl-C came first: nobody will take this mesh
            _L.tg_mesh_destroy(h.value)
            return None
        _check(st, name, diag)
        return h.value

    handle = call.run(work)
    _warn_diag(diag)
    return _mesh_from_handle(handle, os.path.abspath(name))


def load_bytes(data: bytes, name: str = "", format: str = "auto") -> "Mesh":
    """A mesh from the bytes of a mesh file (gzip data is inflated); name is used in messages and,
    with format "auto", for its extension. Errors and warnings as load()."""
    fmt = _choice(format, "format", _FORMATS)
    if not isinstance(data, (bytes, bytearray, memoryview)):
        raise _bad(f"data must be bytes (a mesh file's content), not {type(data).__name__}")
    if not isinstance(name, str):
        raise _bad(f"name must be a str, not {type(name).__name__}")
    data = bytes(data)
    diag = _c.Diag()
    h = ctypes.c_void_p()
    st = _L.tg_mesh_load_memory(data, len(data), os.fsencode(name), fmt, None, ctypes.byref(diag),
                                ctypes.byref(h))
    _check(st, name or "load_bytes", diag)
    _warn_diag(diag)
    return _mesh_from_handle(h.value, None)


class MeshDistance:
    """The certified distance from mesh A to mesh B (Mesh.distance_to; tg_mesh_distance in C):

    lower, upper: the one-sided Hausdorff distance h(A, B) (the largest distance from a point of
        A's surface to B's surface) lies in [lower, upper]; upper - lower <= tolerance when
        converged.
    tolerance: the absolute tolerance used; converged: False only when max_pieces stopped the
        refinement (the interval is then still valid, only wider).
    distance, face, bary, point: the point of A realising the lower bound (A's face, its
        barycentrics, xyz) and its distance to B; closest_face, closest_bary, closest_point: its
        closest point on B.
    area: A's area; mean, rms: (lower, upper) intervals of the mean and the root mean square
        of the distance over A's area.
    pieces, queries: the work (triangle pieces made, closest-point queries on B).
    vertex_distance: (n,) float64, every vertex of A's exact distance to B.
    reverse: with symmetric=True the same for B to A, else None; symmetric: with symmetric=True
        the symmetric Hausdorff interval (max of the lowers, max of the uppers), else None.
    as_dict(): the numbers as `trigeo compare --json` prints one direction."""

    _FIELDS = ("lower", "upper", "tolerance", "converged", "distance", "face", "bary", "point", "closest_face",
               "closest_bary", "closest_point", "area", "mean", "rms", "pieces", "queries")

    def __init__(self, r: "_c.MeshDistanceResult", vertex_distance: np.ndarray):
        self.lower, self.upper, self.tolerance = float(r.lower), float(r.upper), float(r.tolerance)
        self.converged = bool(r.converged)
        self.distance, self.face = float(r.distance), int(r.face)
        self.bary, self.point = tuple(r.bary), tuple(r.point)
        self.closest_face, self.closest_bary, self.closest_point = int(r.closest_face), tuple(r.closest_bary), \
            tuple(r.closest_point)
        self.area = float(r.area)
        self.mean, self.rms = (float(r.mean_lower), float(r.mean_upper)), (float(r.rms_lower), float(r.rms_upper))
        self.pieces, self.queries = int(r.pieces), int(r.queries)
        self.vertex_distance = vertex_distance
        self.reverse: Optional[MeshDistance] = None
        self.symmetric: Optional[tuple] = None

    def as_dict(self) -> dict:
        return {k: list(v) if isinstance(v, tuple) else v for k, v in ((k, getattr(self, k)) for k in self._FIELDS)}

    def __repr__(self) -> str:
        sym = f", symmetric [{self.symmetric[0]!r}, {self.symmetric[1]!r}]" if self.symmetric else ""
        return (f"<trigeo.MeshDistance hausdorff [{self.lower!r}, {self.upper!r}], mean [{self.mean[0]!r}, "
                f"{self.mean[1]!r}], rms [{self.rms[0]!r}, {self.rms[1]!r}]{sym}>")


class Mesh:
    """An immutable triangle mesh and its lazily built query structures (a BVH for closest
    points, a geodesic solver for paths and fields), kept for the mesh's lifetime.

    Mesh(vertices, faces): vertices an (n, 3) array of finite numbers, faces an (m, 3) array of
    vertex indices (any integer dtype; C-contiguous float64 and uint32 arrays are passed to the
    library without an intermediate copy; the library keeps its own copy). Meshes from files
    come from trigeo.load. Any mesh real files contain is accepted: boundaries, several
    components, non-manifold edges, degenerate and duplicate faces (see .report).

    Thread-safe: any number of threads may query one Mesh at once, and close() waits for the
    calls running on it. Ctrl-C interrupts every call (KeyboardInterrupt within about a second).
    """

    def __init__(self, vertices: Any, faces: Any):
        try:
            v = np.asarray(vertices)
            f = np.asarray(faces)
        except (TypeError, ValueError):  # ragged nesting
            raise _bad("vertices and faces must be (n, 3) and (m, 3) arrays, not ragged sequences") from None
        if v.ndim != 2 or v.shape[1] != 3 or v.dtype.kind not in "fiu":
            raise _bad(f"vertices must be an (n, 3) array of numbers, not shape {v.shape} dtype {v.dtype}")
        if f.ndim != 2 or f.shape[1] != 3 or f.dtype.kind not in "iu":
            raise _bad(f"faces must be an (m, 3) integer array, not shape {f.shape} dtype {f.dtype}")
        if f.size:
            lo, hi = int(f.min()), int(f.max())
            if lo < 0 or hi >= v.shape[0]:
                bad = int(np.argmax(((f < 0) | (f >= v.shape[0])).any(axis=1)))
                raise _bad(f"faces[{bad}] = {f[bad].tolist()} has an index outside [0, {v.shape[0]})")
        v = np.ascontiguousarray(v, dtype=np.float64)
        f = np.ascontiguousarray(f, dtype=np.uint32)
        finite = np.isfinite(v).all(axis=1)
        if not finite.all():
            i = int(np.argmin(finite))
            raise InvalidMeshError(f"vertices[{i}] is not finite: {v[i].tolist()}")
        diag = _c.Diag()
        h = ctypes.c_void_p()
        st = _L.tg_mesh_create(_ptr(v), v.shape[0], _ptr(f, ctypes.c_uint32), f.shape[0], None,
                               ctypes.byref(diag), ctypes.byref(h))
        _check(st, "Mesh", diag)
        self._init(h.value, source=None)

    def _init(self, handle: int, source: Optional[str]) -> None:
        self._dask_arrays = None  # trigeo.dask: (client, future) of the scattered arrays
        self._content_hash = None  # trigeo.dask: the hash of vertices and faces, made once
        self._uses = _Uses()
        self._owner = _MeshHandle(handle)
        self._h = handle
        self._source = source
        self._source_ids: tuple = ()  # (device, inode) of the file loaded: outputs never replace it
        if source is not None:
            try:
                st = os.stat(source)
                self._source_ids = ((st.st_dev, st.st_ino),)
            except OSError:
                pass
        self._lock = threading.Lock()
        self._bvh = None
        self._geo = None
        self._bvh_ws = _Pool(lambda: _new(_L.tg_bvh_workspace_create, self._bvh),
                             _L.tg_bvh_workspace_destroy)
        self._geo_ws = _Pool(lambda: _new(_L.tg_geodesic_workspace_create, self._geo),
                             _L.tg_geodesic_workspace_destroy)
        self._paths = _Pool(lambda: _new(_L.tg_path_create, None), _L.tg_path_destroy)
        self._traces = _Pool(lambda: _new(_L.tg_trace_create, None), _L.tg_trace_destroy)

    # -- lifetime ---------------------------------------------------------------------------

    def close(self) -> None:
        """Frees the library's objects (also done when the Mesh is garbage-collected). Calls
        running on the Mesh in other threads finish first: close() waits for them, and calls
        made after it raise InvalidArgumentError. From a progress callback of a call on this
        Mesh it raises (it would wait for itself). Arrays previously returned by .vertices and
        .faces stay valid."""
        uses = getattr(self, "_uses", None)
        if uses is not None and getattr(self, "_h", None):
            uses.close(self._free)

    def _free(self) -> None:
        if not self._h:
            return
        for pool in (self._bvh_ws, self._geo_ws, self._paths, self._traces):
            pool.close()
        if self._geo:
            _L.tg_geodesic_destroy(self._geo)
        if self._bvh:
            _L.tg_bvh_destroy(self._bvh)
        self._geo = self._bvh = None
        self._h = None
        self._owner = None  # the C mesh goes with the last view of its arrays

    def _run(self, work: Callable[[_Call], Any], progress: Optional[Callable[[float], Any]] = None) -> Any:
        """A public call: the Mesh in use for its duration (close() waits), work(call) run so
        that Ctrl-C interrupts it (see _Call)."""
        if progress is not None and not callable(progress):
            raise _bad(f"progress must be a function of the settled fraction (or None), not {_show(progress)}")
        call = _Call(progress)
        with self._uses.use():
            return call.run(lambda: work(call), self._uses)

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def __enter__(self) -> "Mesh":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __reduce__(self):  # pickling copies the arrays (trigeo.dask sends paths or scatters once)
        return (Mesh, (np.array(self.vertices), np.array(self.faces)))

    def _handle(self) -> int:
        if not self._h:
            raise _bad("this Mesh was closed")
        return self._h

    def _get_bvh(self, threads: int = 0) -> int:
        with self._lock:
            if self._bvh is None:
                o = _c.BvhOptions()
                o.threads = threads
                self._bvh = _new(_L.tg_bvh_create, self._handle(), ctypes.byref(o))
            return self._bvh

    def _get_geo(self) -> int:
        with self._lock:
            if self._geo is None:
                self._geo = _new(_L.tg_geodesic_create, self._handle(), None)
            return self._geo

    # -- data -------------------------------------------------------------------------------

    @property
    def vertex_count(self) -> int:
        """Number of vertices."""
        with self._uses.use():
            return int(_L.tg_mesh_vertex_count(self._handle()))

    @property
    def face_count(self) -> int:
        """Number of triangles."""
        with self._uses.use():
            return int(_L.tg_mesh_face_count(self._handle()))

    @property
    def vertices(self) -> np.ndarray:
        """(n, 3) float64, a read-only view of the library's positions (no copy)."""
        with self._uses.use():
            return _view(self._owner, _L.tg_mesh_positions(self._handle()), (self.vertex_count, 3), "<f8")

    @property
    def faces(self) -> np.ndarray:
        """(m, 3) uint32, a read-only view of the library's triangles (no copy)."""
        with self._uses.use():
            return _view(self._owner, _L.tg_mesh_triangles(self._handle()), (self.face_count, 3), "<u4")

    @property
    def source(self) -> Optional[str]:
        """The absolute path the mesh was loaded from, or None for a mesh made from arrays."""
        return self._source

    @property
    def report(self) -> dict:
        """The validation report computed at load: counts of vertices, faces, edges, components,
        boundary edges and loops, non-manifold edges and vertices, misoriented edges, degenerate,
        duplicate faces, unreferenced vertices, Euler characteristic, genus (-1 unless a closed
        manifold), closed_manifold (bool), bbox_min and bbox_max."""
        with self._uses.use():
            r = _L.tg_mesh_get_report(self._handle()).contents
            out = {name: int(getattr(r, name)) for name, _ in _c.MeshReport._fields_[:14]}
            out["closed_manifold"] = bool(r.closed_manifold)
            out["bbox_min"] = tuple(r.bbox_min)
            out["bbox_max"] = tuple(r.bbox_max)
            return out

    def __repr__(self) -> str:
        if not getattr(self, "_h", None):
            return "<trigeo.Mesh (closed)>"
        where = f" from {self._source!r}" if self._source else ""
        return f"<trigeo.Mesh {self.vertex_count} vertices, {self.face_count} faces{where}>"

    # -- point queries ------------------------------------------------------------------------

    def _batch(self, call: _Call, n: int, threads: int, run_chunk: Callable[[int, int], int]) -> int:
        """Runs a batch of n point queries in chunks (answers are per point, so chunking changes
        none), sized to about 0.2 s each so that Ctrl-C is seen between them: from 16 points up,
        since one point can cost milliseconds (an exact winding number over a million faces)."""
        lo, size = 0, 16
        while lo < n:
            if call.cancel:
                return TG_ERR_CANCELLED_
            hi = min(n, lo + size)
            t0 = time.perf_counter()
            st = run_chunk(lo, hi)
            if st:
                return st
            dt = time.perf_counter() - t0
            size = int(min(max(size * (0.2 / dt if dt > 0 else 4.0), 1024), 4 * size, 1 << 22))
            lo = hi
        return 0

    def closest(self, points: Any, threads: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The closest surface point to each of k query points (exact in double, equal to a linear
        scan over all faces; the lowest face index wins ties).

        points: (k, 3) or (3,), within +-1e150. threads: 0 all cores, n at most n (at most
        MAX_THREADS). Returns (distance (k,) float64, face (k,) int64, point (k, 3) float64);
        face is -1 and distance inf on an empty mesh. Ctrl-C interrupts it."""
        p = _points(points)
        threads = _threads(threads)
        hits = np.empty(p.shape[0], dtype=_HIT)

        def work(call: _Call) -> int:
            bvh = self._get_bvh(threads)
            return self._batch(call, p.shape[0], threads, lambda lo, hi: _L.tg_bvh_closest_batch(
                bvh, _ptr(p[lo:hi]), hi - lo, math.inf, threads,
                hits[lo:hi].ctypes.data_as(ctypes.POINTER(_c.ClosestHit))))

        _check(self._run(work), "closest")
        return _hits(hits)

    def distance_to(self, other: "Mesh", tolerance: Optional[float] = None, symmetric: bool = False,
                    threads: int = 0, mean_tolerance: Optional[float] = None, max_pieces: int = 0,
                    progress: Optional[Callable[[float], Any]] = None) -> MeshDistance:
        """The certified distance from this mesh (A) to `other` (B): the one-sided Hausdorff
        distance as an interval [lower, upper] no wider than the tolerance, the point realising
        the lower bound, the mean and RMS distance over A's area as intervals, and every vertex's
        distance (see MeshDistance; the same numbers as `trigeo compare A B`).

        tolerance: the Hausdorff interval's width (> 0; None: 1e-9 of the larger bounding-box
        diagonal). symmetric: also B to A (result.reverse) and the symmetric interval
        (result.symmetric). threads: the first pass's threads (0 all cores; the numbers are the
        same for every count). mean_tolerance: refine the mean's and the RMS's intervals to this
        width too (> 0; None: no more than the Hausdorff interval needs). max_pieces: the most
        triangle pieces kept, A's faces included (0: A's faces + 2**21). progress(fraction): return False to stop
        (CancelledError); Ctrl-C interrupts it. Both meshes need faces (InvalidArgumentError)."""
        if not isinstance(other, Mesh):
            raise _bad(f"other must be a trigeo.Mesh, not {_show(other)}")
        tol = 0.0 if tolerance is None else _number(tolerance, "tolerance", ">0", " (None: 1e-9 of the diagonal)")
        mtol = 0.0 if mean_tolerance is None else _number(mean_tolerance, "mean_tolerance", ">0", " (None: none)")
        symmetric = _flag(symmetric, "symmetric")
        threads = _threads(threads)
        pieces = _u64(max_pieces, "max_pieces")
        for m, name in ((self, "this mesh"), (other, "other")):
            if m.face_count == 0:
                raise _bad(f"{name} has no faces: no surface to measure a distance from or to")
        pairs = [(self, other)] + ([(other, self)] if symmetric else [])
        out = []
        for a, b in pairs:
            r = _c.MeshDistanceResult()
            vd = np.empty(a.vertex_count, dtype=np.float64)

            def work(call: _Call, a=a, b=b, r=r, vd=vd) -> int:
                o = _c.MeshDistanceOptions()
                o.tolerance, o.mean_tolerance, o.max_pieces, o.threads = tol, mtol, pieces, threads
                o.progress = call.mesh_distance_fn
                with b._uses.use():
                    bvh = b._get_bvh(threads)
                    st = _L.tg_mesh_distance(a._handle(), bvh, ctypes.byref(o), _ptr(vd), ctypes.byref(r))
                call.finish(st, "distance_to")
                return st

            self._run(work, progress)
            out.append(MeshDistance(r, vd))
        res = out[0]
        if symmetric:
            res.reverse = out[1]
            res.symmetric = (max(res.lower, out[1].lower), max(res.upper, out[1].upper))
        return res

    def signed_distance(self, points: Any, method: str = "auto",
                        threads: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Signed distance to the surface: negative inside (faces counter-clockwise seen from
        outside). method: "pseudonormal" (angle-weighted pseudonormal at the closest feature;
        exact on closed manifolds), "winding" (generalized winding number >= 1/2 is inside; robust
        on open or broken meshes) or "auto" (pseudonormal on a consistently oriented closed
        manifold without degenerate faces, else winding). The sign does not depend on the scale
        or position of the mesh. Returns (signed distance (k,), face (k,), closest point (k, 3));
        0 exactly on the surface. threads as closest(); Ctrl-C interrupts it."""
        sign = _choice(method, "method", _SIGN)
        p = _points(points)
        threads = _threads(threads)
        hits = np.empty(p.shape[0], dtype=_SIGNED)

        def work(call: _Call) -> int:
            bvh = self._get_bvh(threads)
            return self._batch(call, p.shape[0], threads, lambda lo, hi: _L.tg_bvh_signed_distance_batch(
                bvh, _ptr(p[lo:hi]), hi - lo, sign, threads,
                hits[lo:hi].ctypes.data_as(ctypes.POINTER(_c.SignedHit))))

        _check(self._run(work), "signed_distance")
        _, face, point = _hits(hits["hit"])
        return hits["distance"].copy(), face, point

    def winding_number(self, points: Any, threads: int = 0) -> np.ndarray:
        """The generalized winding number at each point: 1 inside and 0 outside a closed,
        consistently oriented mesh, fractional near holes (hierarchical evaluation, typically
        within 1e-2 of the exact sum; independent of the mesh's scale). Returns (k,) float64.
        threads as closest(); Ctrl-C interrupts it."""
        p = _points(points)
        threads = _threads(threads)
        out = np.empty(p.shape[0])

        def work(call: _Call) -> int:
            bvh = self._get_bvh(threads)
            return self._batch(call, p.shape[0], threads, lambda lo, hi: _L.tg_bvh_winding_number_batch(
                bvh, _ptr(p[lo:hi]), hi - lo, threads, _ptr(out[lo:hi])))

        _check(self._run(work), "winding_number")
        return out

    def locate(self, xyz: Any) -> SurfacePoint:
        """The surface point closest to position xyz (a face, edge or vertex point)."""
        p = _points(xyz, "xyz")
        if p.shape[0] != 1:
            raise _bad(f"locate takes one position, not {p.shape[0]}")
        return SurfacePoint._from_c(self._run(lambda call: self._locate(p[0])))

    def _locate(self, p: np.ndarray) -> _c.SurfacePointC:
        if _L.tg_mesh_face_count(self._handle()) == 0:
            raise _bad("the mesh has no faces: there is no surface point to snap a position to")
        out = _c.SurfacePointC()
        bvh = self._get_bvh()
        with self._bvh_ws.take() as ws:
            st = _L.tg_bvh_locate(bvh, ws, _ptr(p), ctypes.byref(out), None)
        _check(st, "locate")
        return out

    # -- surface points -----------------------------------------------------------------------

    def _surface_point(self, x: Any, what: str) -> _c.SurfacePointC:
        """Converts a vertex index, SurfacePoint or (x, y, z) and validates it on this mesh."""
        if isinstance(x, SurfacePoint):
            sp = x._to_c()
        elif isinstance(x, (int, np.integer)) and not isinstance(x, (bool, np.bool_)):
            sp = _c.SurfacePointC(0, _index(x, what), 0.0)
        else:
            try:
                p = np.asarray(x, dtype=np.float64)
            except (TypeError, ValueError):
                raise _bad(f"{what} must be a vertex index, a SurfacePoint or (x, y, z), not {x!r}") from None
            if p.shape != (3,):
                raise _bad(f"{what} must be a vertex index, a SurfacePoint or (x, y, z), not {x!r}")
            return self._locate(_points(p, what)[0])
        diag = _c.Diag()
        if _L.tg_surface_point_validate(self._handle(), ctypes.byref(sp), ctypes.byref(diag)):
            raise _bad(f"{what}: {diag.message.decode(errors='replace') or 'invalid surface point'}")
        return sp

    def _surface_points(self, xs: Any, what: str) -> ctypes.Array:
        """A list of sources or points: an int or integer array (vertices), a float (k, 3) array
        or one (x, y, z) (positions), a SurfacePoint, or a sequence of any of those."""
        if isinstance(xs, (SurfacePoint, int, np.integer)):
            xs = [xs]
        elif not isinstance(xs, (list, tuple)) or (xs and not any(isinstance(x, SurfacePoint) for x in xs)):
            try:
                a = np.asarray(xs)
            except (TypeError, ValueError):  # ragged: vertex indices mixed with (x, y, z)
                a = np.empty(0, dtype=object)
            if a.dtype == object and isinstance(xs, (list, tuple)):
                pass  # a mixed sequence: element by element, below
            elif a.dtype.kind in "iu" and a.ndim <= 1:
                xs = [int(i) for i in a.reshape(-1)]
                if xs and (min(xs) < 0 or max(xs) >= self.vertex_count):
                    i = next(k for k, v in enumerate(xs) if not 0 <= v < self.vertex_count)
                    raise _bad(f"{what}[{i}] = {xs[i]} is not a vertex (the mesh has {self.vertex_count})")
            elif a.dtype.kind in "fiu" and a.size:
                p = _points(a, what)
                out = (_c.SurfacePointC * p.shape[0])()
                for i in range(p.shape[0]):
                    out[i] = self._locate(p[i])
                return out
            elif a.size == 0 and a.dtype != object:
                xs = []
            else:
                raise _bad(f"{what}: cannot read {type(xs).__name__} of dtype {a.dtype} as surface points")
        out = (_c.SurfacePointC * len(xs))()
        for i, x in enumerate(xs):
            out[i] = self._surface_point(x, f"{what}[{i}]")
        return out

    # -- paths --------------------------------------------------------------------------------

    def path(self, a: Any, b: Any, method: str = "exact", certify: bool = False) -> "Path":
        """The geodesic (shortest on-surface) path from a to b.

        a, b: a vertex index, a SurfacePoint, or an (x, y, z) snapped to the closest surface
        point. method: "exact" (default: the globally shortest path, proven, global_ "proven":
        an exact window propagation from a ordered toward b and bounded by the best distance to
        b found so far, traced back; no edge path, so initial_length == length and iterations
        == 0; timings in BENCHMARKS.md), "straighten" (faster on far pairs: the shortest edge
        path straightened into a locally shortest path, certified straight but "unproven"), "relax" (the seed's relaxation) or "edge" (the
        shortest edge path only). certify=True checks a straighten/relax/edge result against the
        exact distance and replaces it with the exact path if a shorter one exists, so the path
        comes out proven (redundant with "exact").
        Endpoints in different components give a Path with status "unreachable" and length inf.
        Ctrl-C interrupts it (KeyboardInterrupt within a few milliseconds of work)."""
        _choice(method, "method", _METHODS)
        certify = _flag(certify, "certify")

        def work(call: _Call) -> "Path":
            spa = self._surface_point(a, "a")
            spb = self._surface_point(b, "b")
            opts = _c.PathOptions(_METHODS[method], 0, 0.0, None, 1 if certify else 0, call.field_fn, None)
            return self._path_call(call, "path", lambda geo, ws, ph: _L.tg_geodesic_path(
                geo, ws, ctypes.byref(spa), ctypes.byref(spb), ctypes.byref(opts), ph))

        return self._run(work)

    def _path_call(self, call: _Call, name: str, fn: Callable[[Any, Any, Any], int]) -> "Path":
        """Runs fn(geo, workspace, path handle) (a tg_geodesic_*path call) and reads its Path."""
        geo = self._get_geo()
        with self._geo_ws.take() as ws, self._paths.take() as ph:
            call.finish(fn(geo, ws, ph), name)
            view = _c.PathView()
            _L.tg_path_get_view(ph, ctypes.byref(view))
            p = Path._from_view(view)
        p._mesh = self
        return p

    def _pair_points(self, pairs: Any, froms: Any, tos: Any) -> tuple:
        """The endpoints of path_lengths' pairs, as two C arrays."""
        if (pairs is None) == (froms is None and tos is None):
            raise _bad("give either pairs (a (k, 2) array of vertices) or both froms= and tos=")
        if pairs is None:
            if froms is None or tos is None:
                raise _bad("froms= and tos= go together")
            a, b = self._surface_points(froms, "froms"), self._surface_points(tos, "tos")
            if len(a) != len(b):
                raise _bad(f"froms and tos differ in length ({len(a)} and {len(b)})")
            return a, b
        try:
            pa = np.asarray(pairs)
        except (TypeError, ValueError):  # ragged nesting
            raise _bad(f"pairs must be a (k, 2) integer array of vertices, not {_show(pairs)}") from None
        if pa.ndim != 2 or pa.shape[1] != 2 or (pa.size and pa.dtype.kind not in "iu"):
            raise _bad(f"pairs must be a (k, 2) integer array of vertices, not shape {pa.shape} dtype {pa.dtype}")
        return (self._surface_points(pa[:, 0].astype(np.int64), "pairs[:, 0]"),
                self._surface_points(pa[:, 1].astype(np.int64), "pairs[:, 1]"))

    def path_lengths(self, pairs: Any = None, method: str = "exact", threads: int = 0,
                     certify: bool = False, *, froms: Any = None, tos: Any = None) -> np.ndarray:
        """Lengths of many geodesic paths (inf where the endpoints are not connected).

        pairs: a (k, 2) integer array of vertex pairs; or, instead, froms= and tos=: two equally
        long sequences of endpoints as path() takes them (SurfacePoints, vertex indices, (x, y, z)
        positions). Every endpoint is checked before any path is computed. method, certify: as
        path() (default "exact": globally shortest). threads: 0 all cores; the pairs are shared
        out among that many threads, each with its own workspace. Returns (k,) float64, the same
        numbers as k calls of path(). Ctrl-C interrupts it."""
        _choice(method, "method", _METHODS)
        certify = _flag(certify, "certify")
        threads = _threads(threads)

        def work(call: _Call) -> np.ndarray:
            a, b = self._pair_points(pairs, froms, tos)
            k = len(a)
            out = np.empty(k)
            if k == 0:
                return out
            geo = self._get_geo()
            opts = _c.PathOptions(_METHODS[method], 0, 0.0, None, 1 if certify else 0, call.field_fn, None)
            nt = (os.cpu_count() or 1) if threads == 0 else threads
            nt = max(1, min(nt, k, MAX_THREADS))

            def run(lo: int, hi: int) -> None:
                view = _c.PathView()
                with self._geo_ws.take() as ws, self._paths.take() as ph:
                    for i in range(lo, hi):
                        if call.cancel:  # Ctrl-C, or another chunk failed
                            return
                        st = _L.tg_geodesic_path(geo, ws, ctypes.byref(a[i]), ctypes.byref(b[i]), ctypes.byref(opts),
                                                 ph)
                        if st == TG_ERR_CANCELLED_ and call.cancel:
                            return
                        _check(st, f"path_lengths: pair {i}")
                        _L.tg_path_get_view(ph, ctypes.byref(view))
                        out[i] = view.length

            if nt == 1:
                run(0, k)
            else:
                step = max(1, min(64, k // (4 * nt)))
                with ThreadPoolExecutor(nt) as ex:
                    futures = [ex.submit(run, lo, min(k, lo + step)) for lo in range(0, k, step)]
                    try:
                        for f in futures:
                            f.result()
                    except BaseException:
                        call.cancel = True  # the other chunks stop at their next pair
                        raise
            if call.cancel:
                raise CancelledError("path_lengths: cancelled")
            return out

        return self._run(work)

    def path_through(self, points: Any, closed: bool = False) -> "Path":
        """The shortest route visiting `points` in this order (and back to the first with
        closed=True): the exact shortest path between each pair of consecutive points, each
        proven, joined into one Path (global_ "proven"; its length is the sum of the pieces').

        points: a sequence of surface points as path() takes them (vertex indices, SurfacePoints,
        (x, y, z) positions), at least one. The Path's waypoint_points ((m,) int64, m = the number
        of points, + 1 when closed) gives the index in path.points of each waypoint in visiting
        order. Consecutive points in different components give status "unreachable", length inf.
        Ctrl-C interrupts it."""
        closed = _flag(closed, "closed")

        def work(call: _Call) -> "Path":
            pts = self._surface_points(points, "points")
            if len(pts) == 0:
                raise _bad("path_through needs at least one point")
            m = len(pts) + (1 if closed else 0)
            at = (ctypes.c_size_t * m)()
            opts = _c.PathOptions(0, 0, 0.0, None, 0, call.field_fn, None)  # exact, Ctrl-C as cancellation
            geo = self._get_geo()
            with self._geo_ws.take() as ws, self._paths.take() as ph:
                st = _L.tg_geodesic_path_through(geo, ws, pts, len(pts), 1 if closed else 0, ctypes.byref(opts), ph, at)
                call.finish(st, "path_through")
                view = _c.PathView()
                _L.tg_path_get_view(ph, ctypes.byref(view))
                p = Path._from_view(view)
            p._mesh = self
            p.waypoint_points = np.array(at[:], dtype=np.int64) if view.point_count else np.empty(0, np.int64)
            return p

        return self._run(work)

    # -- geometry on the exact maps ------------------------------------------------------------

    def geodesic_mean(self, points: Any, weights: Any = None, start: Any = None, tolerance: Optional[float] = None,
                      max_iterations: Optional[int] = None, uniqueness: bool = True,
                      progress: Optional[Callable[[float], Any]] = None) -> "GeodesicMean":
        """The weighted geodesic (Karcher / Frechet) mean: the surface point minimising
        sum w_i d(m, x_i)^2 with exact geodesic distances, by the iteration
        p <- exp_p(sum w_i log_p(x_i) / sum w_i) on exact paths and the exact trace (the same
        numbers as `trigeo mean` and tg_geodesic_mean).

        points: surface points as path() takes them (vertex indices, SurfacePoints, (k, 3)
        positions), at least one, all in one component. weights: None (all 1) or k numbers >= 0,
        not all 0. start: None (the point of largest weight) or a surface point where the
        iteration starts (it finds a mean near it). tolerance: stop when a step is below this
        share of the bounding box's diagonal (default 1e-10). max_iterations: at most this many
        steps (default 100). uniqueness: False skips the uniqueness test (one bounded field).
        Returns a GeodesicMean (point, xyz, status, iterations, halvings, gradient_norm, energy,
        radius, uniqueness, fields). Ctrl-C and progress (the share of the step cap done)
        interrupt it."""
        check_unique = _flag(uniqueness, "uniqueness")
        tol = 0.0 if tolerance is None else _number(tolerance, "tolerance", ">0")
        cap = 0 if max_iterations is None else _index(max_iterations, "max_iterations")
        if max_iterations is not None and not 1 <= cap <= 0xFFFFFFFF:
            raise _bad(f"max_iterations must be at least 1, not {_show(max_iterations)}")

        def work(call: _Call) -> "GeodesicMean":
            pts = self._surface_points(points, "points")
            k = len(pts)
            if k == 0:
                raise _bad("points: geodesic_mean needs at least one point")
            wp = None
            if weights is not None:
                w = _floats(weights, "weights", f"a sequence of {k}")
                if w.shape != (k,):
                    raise _bad(f"weights must hold one number per point ({k}), not shape {w.shape}")
                _check_values(w, "weights", ">=0")
                if not w.sum() > 0.0:
                    raise _bad("weights: every weight is 0 (at least one must be positive)")
                w = np.ascontiguousarray(w)
                wp = _ptr(w)
            st_ = None
            if start is not None:
                st_ = (_c.SurfacePointC * 1)(self._surface_point(start, "start"))
            o = _c.MeanOptions(tol, cap, st_, 0 if check_unique else 1, None, call.field_fn, None)
            r = _c.MeanResult()
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_mean(geo, ws, pts, wp, k, ctypes.byref(o), ctypes.byref(r))
            if st == 1 and call.error is None:
                raise _bad("geodesic_mean: the points%s lie in different components of the mesh (no path joins "
                           "them)" % (" (and start)" if start is not None else ""))
            call.finish(st, "geodesic_mean")
            return GeodesicMean._from_c(r)

        return self._run(work, progress)

    def bezier(self, points: Any, samples: int = 101, method: str = "paths",
               progress: Optional[Callable[[float], Any]] = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The geodesic Bezier curve of the control points: de Casteljau's construction on the
        surface (on a flat region the planar Bezier curve; the same numbers as `trigeo path
        --bezier` and tg_geodesic_bezier_with). method: "paths" (default: each interpolation at
        fraction t of the exact shortest path between two points) or "logmap" (exp_a(t log_a(b))
        on the exact maps: the trace from a along the log map's direction to b; the same where
        the path passes no vertex). points: the n + 1 control points (as path() takes them;
        degree n), all in one component. samples: the curve at t = 0, 1 / (samples - 1), ..., 1 (>= 2).
        Returns (xyz, faces, bary): (samples, 3) float64 positions, (samples,) int64 faces and
        (samples, 3) float64 barycentric coordinates in them (a point on an edge or at a vertex
        named in one face holding it); the first is the first control point, the last the last.
        Ctrl-C and progress (the share of the samples done) interrupt it."""
        n = _index(samples, "samples")
        if n < 2:
            raise _bad(f"samples must be at least 2, not {_show(samples)}")
        how = _choice(method, "method", _BEZIER_METHODS)

        def work(call: _Call) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            ctrl = self._surface_points(points, "points")
            if len(ctrl) == 0:
                raise _bad("points: bezier needs at least one control point")
            out = (_c.SurfacePointC * n)()
            xyz = np.empty((n, 3))
            opts = _c.PathOptions(0, 0, 0.0, None, 0, call.field_fn, None)  # exact, Ctrl-C as cancellation
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_bezier_with(geo, ws, ctrl, len(ctrl), n, how, ctypes.byref(opts), out, _ptr(xyz))
            if st == 1 and call.error is None:
                raise _bad("bezier: the control points lie in different components of the mesh (no path joins them)")
            call.finish(st, "bezier")
            faces, bary = self._face_points(out)
            return xyz, faces, bary

        return self._run(work, progress)

    def centroidal_voronoi(self, count: int, iterations: int = 10, start: Any = None, seed: int = 0,
                           tolerance: Optional[float] = None, progress: Optional[Callable[[float], Any]] = None
                           ) -> tuple[list, np.ndarray, np.ndarray]:
        """A geodesic centroidal Voronoi tessellation (geodesic Lloyd, tg_geodesic_centroidal_voronoi,
        the numbers of `trigeo sample --cvt`): `count` sites, each moved to the geodesic mean of
        its exact Voronoi cell (the cells clipped inside the faces at their boundaries, each
        vertex weighing the integral of its hat function over the cell: the quadrature in
        trigeo.h), the cells made again, at most `iterations` times or until no site moves more
        than tolerance (default 1e-7) times the bounding box's diagonal. start: None
        (farthest-point sampling with `seed`) or `count` surface points. Returns (sites, labels,
        energies): a list of SurfacePoints, (n,) int64 vertex labels (-1: unreached or
        unreferenced), and the energies (the integral over the cells of the squared distance to
        their site) before and after each iteration, never increasing."""
        k = _index(count, "count")
        its = _index(iterations, "iterations")
        if not 1 <= its <= 0xFFFFFFFF:
            raise _bad(f"iterations must be at least 1, not {_show(iterations)}")
        sd = _u64(seed, "seed")
        tol = 0.0 if tolerance is None else _number(tolerance, "tolerance", ">0")
        if k < 1:
            raise _bad(f"count must be at least 1, not {_show(count)}")

        def work(call: _Call) -> tuple[list, np.ndarray, np.ndarray]:
            sp = None
            if start is not None:
                sp = self._surface_points(start, "start")
                if len(sp) != k:
                    raise _bad(f"start must hold count = {k} surface points, not {len(sp)}")
            elif k > self.report["vertices"] - self.report["unreferenced_vertices"]:
                raise _bad(f"count = {k} exceeds the vertices used by faces")
            o = _c.CentroidalOptions(its, tol, None, call.field_fn, None)
            sites = (_c.SurfacePointC * k)()
            labels = np.empty(self.vertex_count, np.uint32)
            energies = np.empty(its + 1)
            done = ctypes.c_size_t(0)
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_centroidal_voronoi(geo, ws, sp, sd, k, ctypes.byref(o), sites,
                                                        labels.ctypes.data_as(ctypes.POINTER(ctypes.c_uint32)),
                                                        _ptr(energies), ctypes.byref(done))
            call.finish(st, "centroidal_voronoi")
            lab = labels.astype(np.int64)
            lab[labels == 0xFFFFFFFF] = -1
            return [SurfacePoint._from_c(p) for p in sites], lab, energies[:done.value + 1].copy()

        return self._run(work, progress)

    def _face_points(self, pts) -> tuple[np.ndarray, np.ndarray]:
        """Surface points as (face, barycentrics): a vertex in the first face using it, an edge
        point in its halfedge's face."""
        tri = self.faces
        k = len(pts)
        faces, bary = np.empty(k, np.int64), np.zeros((k, 3))
        first = None
        for i, p in enumerate(pts):
            if p.kind == 2:
                faces[i], bary[i] = p.index, p.bary[:]
            elif p.kind == 1:
                faces[i] = p.index // 3
                bary[i, p.index % 3], bary[i, (p.index + 1) % 3] = 1.0 - p.t, p.t
            else:
                if first is None:
                    flat = tri.reshape(-1)
                    first = np.full(self.vertex_count, -1, np.int64)
                    first[flat[::-1]] = np.arange(flat.size - 1, -1, -1) // 3
                faces[i] = first[p.index]
                bary[i, int(np.nonzero(tri[faces[i]] == p.index)[0][0])] = 1.0
        return faces, bary

    # -- tracing ------------------------------------------------------------------------------

    @staticmethod
    def _trace_options(max_steps: int, call: Optional[_Call] = None) -> _c.TraceOptions:
        """The walk's options; with a call, its cancel flag as the progress callback (Ctrl-C)."""
        ms = _index(max_steps, "max_steps")
        return _c.TraceOptions(ms, call.field_fn if call is not None else _c.PROGRESS_FN(), None)

    @staticmethod
    def _directions(directions: Any, k: int, angles: bool) -> ctypes.Array:
        """k directions: (k, 3) or one (3,) vector (TG_TRACE_VECTOR); with angles, k or one angle
        in radians (TG_TRACE_ANGLE)."""
        angles = _flag(angles, "angles")
        a = _floats(directions, "direction", "angles in radians" if angles else "3D vectors")
        vectors = not angles
        if vectors and a.ndim in (1, 2) and a.shape[-1] == 3:
            a = a.reshape(-1, 3)
        elif angles and a.ndim <= 1:
            a = a.reshape(-1)
        else:
            raise _bad(f"direction must be {'angles (a number or (k,) array)' if angles else 'a (3,) or (k, 3) array'}, "
                       f"not shape {a.shape}")
        if a.shape[0] not in (1, k):
            raise _bad(f"{a.shape[0]} directions for {k} starts")
        out = (_c.TraceDirection * k)()
        for i in range(k):
            d = a[i if a.shape[0] == k else 0]
            if vectors:
                if not np.all(np.isfinite(d)) or not np.any(d):
                    raise _bad(f"direction[{i}] = {d.tolist()} must be three finite numbers, not all zero")
                out[i] = _c.TraceDirection(0, tuple(d), 0.0)
            else:
                if not math.isfinite(d):
                    raise _bad(f"angle[{i}] = {float(d)!r} must be finite (radians)")
                out[i] = _c.TraceDirection(1, (0.0, 0.0, 0.0), float(d))
        return out

    @staticmethod
    def _lengths(lengths: Any, k: int) -> np.ndarray:
        a = _floats(lengths, "length", "a length or lengths").reshape(-1)
        if a.shape[0] not in (1, k):
            raise _bad(f"{a.shape[0]} lengths for {k} starts")
        _check_values(a, "length", ">=0")
        return np.ascontiguousarray(np.broadcast_to(a, (k,)))

    def _refused(self, what: str, geo: int, starts, dirs, lengths, opts) -> None:
        """The library refused directions that passed the checks above: say which and why."""
        for i in range(len(starts)):
            end = _c.TraceEnd()
            if _L.tg_geodesic_trace_batch(geo, ctypes.byref(starts[i]), ctypes.byref(dirs[i]),
                                          _ptr(lengths[i:i + 1]), 1, ctypes.byref(opts), 1, ctypes.byref(end)) == 1:
                why = ("is perpendicular to the surface at the start" if dirs[i].kind == 0 else
                       "is measured in the start's reference face, which has zero area (give a 3D vector)")
                raise _bad(f"{what}: direction[{i}] {why}")

    def trace(self, start: Any, direction: Any, length: float, max_steps: int = 0) -> "Trace":
        """The exponential map: the geodesic walked straight from `start` in `direction` for
        `length`, across the faces as they unfold, through a vertex as the straightest geodesic
        (Polthier and Schmies), stopping at the boundary (status "boundary").

        start: a vertex index, SurfacePoint or (x, y, z) (snapped). direction: a 3D vector of any
        length (its projection onto the start face; at an edge or vertex onto the tangent plane
        there, include/trigeo.h TG_TRACE_VECTOR) or an angle in radians from the start's reference direction (include/trigeo.h,
        TG_TRACE_ANGLE). length: finite, >= 0. max_steps: the most faces to enter (0: default).
        Zero, NaN or perpendicular directions and negative lengths raise InvalidArgumentError.
        Returns a Trace (points, faces, surface points, the end and its direction, the status).
        Ctrl-C interrupts it."""
        is_angle = isinstance(direction, (int, float, np.integer, np.floating)) and not isinstance(direction, (bool, np.bool_))
        if not is_angle and _shape(direction) != (3,):
            raise _bad(f"direction must be a 3D vector or an angle in radians, not {direction!r}")
        d = self._directions(direction, 1, is_angle)
        lengths = self._lengths(length, 1)

        def work(call: _Call) -> "Trace":
            sp = (_c.SurfacePointC * 1)(self._surface_point(start, "start"))
            opts = self._trace_options(max_steps, call)
            geo = self._get_geo()
            with self._traces.take() as th:
                st = _L.tg_geodesic_trace(geo, sp, d, float(lengths[0]), ctypes.byref(opts), th)
                if st == 1:
                    self._refused("trace", geo, sp, d, lengths, opts)
                call.finish(st, "trace")
                view = _c.TraceView()
                _L.tg_trace_get_view(th, ctypes.byref(view))
                return Trace._from_view(view)

        return self._run(work)

    def trace_batch(self, starts: Any, directions: Any, lengths: Any, threads: int = 0,
                    max_steps: int = 0, angles: bool = False) -> dict:
        """Many traces at once (the vectorised trace(), on `threads` C threads, 0: all cores):
        the end of each, bit for bit trace()'s. starts: k surface points as field() takes them
        (vertex indices, SurfacePoints, (k, 3) positions). directions: (k, 3) vectors, or one for
        all; with angles=True, k angles in radians (or one). lengths: k lengths or one. Every
        entry is checked before any walk.

        Returns a dict of arrays: "xyz" (k, 3) end positions, "direction" (k, 3) unit end
        directions, "face" (k,) the last segment's face, "length" (k,) the length walked,
        "status" (k,) str ("complete", "boundary", "singular", "step_limit", "stalled"),
        "crossings" (k,) edges crossed, "points" the k end SurfacePoints. Ctrl-C interrupts it."""
        threads = _threads(threads)

        def work(call: _Call) -> tuple:
            sps = self._surface_points(starts, "starts")
            k = len(sps)
            dirs = self._directions(directions, k, angles) if k else (_c.TraceDirection * 0)()
            lens = self._lengths(lengths, k) if k else np.empty(0)
            opts = self._trace_options(max_steps, call)
            ends = (_c.TraceEnd * k)()
            geo = self._get_geo()
            st = _L.tg_geodesic_trace_batch(geo, sps, dirs, _ptr(lens), k, ctypes.byref(opts), threads, ends)
            if st == 1:
                self._refused("trace_batch", geo, sps, dirs, lens, opts)
            call.finish(st, "trace_batch")
            return k, ends

        k, ends = self._run(work)
        names = {}
        status = np.empty(k, dtype=object)
        for i in range(k):
            s = ends[i].status
            status[i] = names.get(s) or names.setdefault(s, _L.tg_trace_status_name(s).decode())
        return {
            "xyz": np.array([e.xyz[:] for e in ends], dtype=np.float64).reshape(k, 3),
            "direction": np.array([e.direction[:] for e in ends], dtype=np.float64).reshape(k, 3),
            "face": np.array([e.face for e in ends], dtype=np.int64),
            "length": np.array([e.length for e in ends], dtype=np.float64),
            "status": status.astype(str) if k else np.empty(0, dtype=str),
            "crossings": np.array([e.crossings for e in ends], dtype=np.int64),
            "points": [SurfacePoint._from_c(e.point) for e in ends],
        }

    # -- fields -------------------------------------------------------------------------------

    def _field_options(self, max_distance: Optional[float], call: _Call, threads: int = 1) -> _c.FieldOptions:
        """The C options; threads (checked by _threads): one field's, 0 every core."""
        o = _c.FieldOptions()
        if max_distance is not None:
            o.limit, o.max_distance = 1, _number(max_distance, "max_distance", ">=0", " (None: no limit)")
        o.progress = call.field_fn
        o.threads = -1 if threads == 0 else threads
        return o

    def _segments(self, curve: Any, curves: Any, boundary: Any) -> Optional[ctypes.Array]:
        """The curve sources of field() and field_at() as C segments (None: none given)."""
        boundary = _flag(boundary, "boundary")
        lines = []
        if curve is not None:
            lines.append(("curve", curve))
        if curves is not None:
            if isinstance(curves, (str, bytes)) or not isinstance(curves, (list, tuple)):
                raise _bad("curves must be a list of polylines (each as curve= takes one)")
            lines += [(f"curves[{i}]", c) for i, c in enumerate(curves)]
        if not lines and not boundary:
            return None
        geo = self._get_geo()
        segs = []
        if boundary:
            n = ctypes.c_size_t(0)
            _L.tg_geodesic_boundary_segments(geo, None, 0, ctypes.byref(n))
            if n.value == 0:
                raise _bad("boundary=True: the mesh has no boundary (every edge has two faces or more)")
            arr = (_c.SurfaceSegmentC * n.value)()
            _check(_L.tg_geodesic_boundary_segments(geo, arr, n.value, ctypes.byref(n)), "boundary")
            segs += list(arr)
        for what, line in lines:
            pts = self._surface_points(line, what)
            if len(pts) == 0:
                raise _bad(f"{what}: an empty polyline")
            # points from coordinates lie on the edges they cross up to rounding: named by that edge
            snapped = [_L.tg_surface_point_snap(self._handle(), ctypes.byref(p), _ON_EDGE_REL) for p in pts]
            pairs = [(snapped[0], snapped[0])] if len(snapped) == 1 else list(zip(snapped, snapped[1:]))
            for i, (a, b) in enumerate(pairs):
                sg = _c.SurfaceSegmentC(a, b)
                diag = _c.Diag()
                if _L.tg_surface_segment_validate(geo, ctypes.byref(sg), ctypes.byref(diag)):
                    msg = diag.message.decode(errors="replace") or "invalid segment"
                    raise _bad(f"{what}: points {i} and {i + 1}: {msg}")
                segs.append(sg)
        return (_c.SurfaceSegmentC * len(segs))(*segs)

    def _curve_field(self, name: str, sources: Any, segs: ctypes.Array, points: Any, max_distance: Optional[float],
                     progress: Optional[Callable[[float], Any]], nthreads: int) -> np.ndarray:
        """tg_geodesic_curve_field: the vertices' distances, or (points given) the points'."""
        def work(call: _Call) -> np.ndarray:
            src = self._surface_points(sources if sources is not None else [], "sources")
            pts = self._surface_points(points, "points") if points is not None else None
            o = self._field_options(max_distance, call, nthreads)
            out = np.empty(self.vertex_count if pts is None else len(pts))
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                if pts is None:
                    st = _L.tg_geodesic_curve_field(geo, ws, src, len(src), segs, len(segs), None, 0,
                                                    ctypes.byref(o), None, _ptr(out), None)
                else:
                    st = _L.tg_geodesic_curve_field(geo, ws, src, len(src), segs, len(segs), pts, len(pts),
                                                    ctypes.byref(o), _ptr(out), None, None)
            call.finish(st, name)
            return out

        return self._run(work, progress)

    def curve_path(self, to: Any, *, curve: Any = None, curves: Any = None, boundary: bool = False,
                   sources: Any = None, progress: Optional[Callable[[float], Any]] = None) -> "Path":
        """The exact shortest path from the nearest point of the curves (and sources) to `to`:
        it starts where it leaves them (a source, a polyline's end, or at right angles from a
        segment's inside) and its length is field_at()'s distance at `to` (global "proven"; the
        CLI's path --from curve:FILE|boundary). curve, curves, boundary as field()'s; sources:
        point sources beside them (as field()'s). Returns a Path (unreachable: no points)."""
        segs = self._segments(curve, curves, boundary)
        if segs is None and sources is None:
            raise _bad("curve_path() needs curve=, curves=, boundary=True or sources=")
        if segs is None:
            segs = (_c.SurfaceSegmentC * 0)()

        def work(call: _Call) -> "Path":
            src = self._surface_points(sources if sources is not None else [], "sources")
            t = self._surface_point(to, "to")
            opts = _c.PathOptions(_METHODS["exact"], 0, 0.0, None, 0, call.field_fn, None)
            return self._path_call(call, "curve_path", lambda geo, ws, ph: _L.tg_geodesic_curve_path(
                geo, ws, src, len(src), segs, len(segs), ctypes.byref(t), ctypes.byref(opts), ph))

        return self._run(work, progress)

    def boundary_segments(self) -> np.ndarray:
        """The mesh's boundary edges, (m, 2) vertex indices (each edge of exactly one kept face,
        in the order of the faces and their corners): the segments field(boundary=True) uses."""
        geo = self._get_geo()
        n = ctypes.c_size_t(0)
        _L.tg_geodesic_boundary_segments(geo, None, 0, ctypes.byref(n))
        arr = (_c.SurfaceSegmentC * max(n.value, 1))()
        _check(_L.tg_geodesic_boundary_segments(geo, arr, n.value, ctypes.byref(n)), "boundary_segments")
        return np.array([[arr[i].a.index, arr[i].b.index] for i in range(n.value)], dtype=np.int64).reshape(-1, 2)

    def field(self, sources: Any = None, max_distance: Optional[float] = None,
              progress: Optional[Callable[[float], Any]] = None, threads: int = 1, *, curve: Any = None,
              curves: Any = None, boundary: bool = False) -> np.ndarray:
        """The exact geodesic distance from the nearest source to every vertex, by window
        propagation (Chen-Han / VTP), exact up to rounding.

        Curves are sources too, exact (every point of them, the insides of their segments
        included, as the CLI's --from curve:FILE and boundary): curve= one polyline (an integer
        array of vertices, a (k, 3) array of positions snapped to the surface, or SurfacePoints;
        consecutive points in one face or on one edge: a path's points are a curve; points within
        1e-9 of an edge or corner are taken on it), curves= a list of polylines, boundary=True
        every boundary edge of the mesh. They mix with point sources.

        sources: a vertex index, a list or integer array of vertices, SurfacePoints (on faces or
        edges too), or (k, 3) positions snapped to the surface. max_distance: stop there (vertices
        beyond get inf): a finite number >= 0 (subnormals included, as the CLI's --max-distance),
        None for no limit. progress: called with the settled fraction in [0, 1] every few ms; return
        False to cancel (CancelledError). Ctrl-C stops the computation too. Returns (n,) float64;
        inf where no path reaches (other components, unused vertices). An empty source list is
        accepted, as by every call taking sources: nothing is reached (all inf).
        threads: 1 (the default) the serial engine; N > 1 (0: every core) one field's
        propagation on N threads: every N > 1 gives the same bits, within 1e-12 relative of one
        thread's (the CLI's field --from --threads N)."""
        nthreads = _threads(threads)
        segs = self._segments(curve, curves, boundary)
        if segs is not None:
            return self._curve_field("field", sources, segs, None, max_distance, progress, nthreads)
        if sources is None:
            raise _bad("field() needs sources, curve=, curves= or boundary=True")

        def work(call: _Call) -> np.ndarray:
            src = self._surface_points(sources, "sources")
            o = self._field_options(max_distance, call, nthreads)
            out = np.empty(self.vertex_count)
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_field(geo, ws, src, len(src), ctypes.byref(o), _ptr(out), None)
            call.finish(st, "field")
            return out

        return self._run(work, progress)

    def log_map(self, source: Any, ref: Any = None, max_distance: Optional[float] = None,
                progress: Optional[Callable[[float], Any]] = None,
                threads: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The exact logarithmic map about one surface point: per vertex the exact geodesic
        distance r (bit for bit field()'s), the angle theta in radians at which its shortest path
        leaves the source, and the 2D coordinates (r cos theta, r sin theta).

        source: a vertex index, SurfacePoint or (x, y, z) (snapped). ref: None, or a 3D vector of
        any length whose direction on the surface, as trace() takes it, is angle 0 (zero, NaN or
        perpendicular vectors raise InvalidArgumentError). Angles are counterclockwise in [0, 2 pi), measured as
        trace()'s angles: from corner 0 towards corner 1 of a face point's face, along an edge
        point's halfedge, from a vertex's first halfedge with the turn around it scaled to 2 pi
        (pi at a boundary vertex, angles in [0, pi]); so trace(source, theta[v], r[v]) ends at v
        wherever its shortest path is unique and meets no vertex. Vertices not reached: r inf,
        theta 0, coordinates inf. Returns (r, theta, uv): (n,), (n,) and (n, 2) float64.
        threads: as field()'s (an angle where two paths tie within rounding may be the other
        path's on more than one thread)."""
        nthreads = _threads(threads)

        def work(call: _Call) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            sp = (_c.SurfacePointC * 1)(self._surface_point(source, "source"))
            rp = None
            if ref is not None:
                rv = _floats(ref, "ref", "a 3D vector")
                if rv.shape != (3,) or not np.all(np.isfinite(rv)) or not np.any(rv):
                    raise _bad(f"ref must be a 3D vector of finite numbers, not all zero, not {_show(ref)}")
                rv = np.ascontiguousarray(rv)
                rp = _ptr(rv)
            o = self._field_options(max_distance, call, nthreads)
            r, theta = np.empty(self.vertex_count), np.empty(self.vertex_count)
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_log_map(geo, ws, sp, rp, ctypes.byref(o), _ptr(r), _ptr(theta), None)
            if st == 1:
                raise _bad("log_map: the reference vector is perpendicular to the surface at the source (or the "
                           "reference face has zero area)" if ref is not None else
                           "log_map: the reference face at the source has zero area: give ref")
            call.finish(st, "log_map")
            far = ~(r < math.inf)
            rr = np.where(far, 0.0, r)
            uv = np.stack([rr * np.cos(theta), rr * np.sin(theta)], axis=1)
            uv[far] = math.inf
            return r, theta, uv

        return self._run(work, progress)

    def transport_field(self, source: Any, vector: Any, max_distance: Optional[float] = None,
                        progress: Optional[Callable[[float], Any]] = None,
                        threads: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Parallel transport from one surface point to every vertex: the tangent vector `vector`
        at the source (3 numbers, not zero, taken as a direction of the surface there as
        log_map's ref, with its length) carried along each vertex's exact shortest path, keeping
        its angle to the path. Returns (vectors (n, 3), distance (n,), flag (n,)): the vector at
        each vertex in the plane of the face holding its path's last segment, 0 where not reached
        (distance inf); the log map's distances; flag as field_gradient's (0 transported, 1 the
        source, 2 unreached, 3 the cut locus: a second path as short arrives from another
        direction, transport undefined; the vector there follows the log map's path). max_distance, progress, threads as log_map's. The same
        numbers as tg_geodesic_transport_field and `trigeo logmap --transport X,Y,Z`."""
        nthreads = _threads(threads)
        vec = _floats(vector, "vector", "a 3D vector")
        if vec.shape != (3,) or not np.all(np.isfinite(vec)) or not np.any(vec):
            raise _bad(f"vector must be a 3D vector of finite numbers, not all zero, not {_show(vector)}")
        vec = np.ascontiguousarray(vec)

        def work(call: _Call) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            sp = (_c.SurfacePointC * 1)(self._surface_point(source, "source"))
            o = self._field_options(max_distance, call, nthreads)
            out, dist = np.empty((self.vertex_count, 3)), np.empty(self.vertex_count)
            flag = np.empty(self.vertex_count, dtype=np.uint8)
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_transport_field(geo, ws, sp, _ptr(vec), ctypes.byref(o), _ptr(out),
                                                    _ptr(flag, ctypes.c_uint8), _ptr(dist), None)
            if st == 1:
                raise _bad("transport_field: the vector is perpendicular to the surface at the source (or the "
                           "reference face has zero area)")
            call.finish(st, "transport_field")
            return out, dist, flag.astype(np.int64)

        return self._run(work, progress)

    def field_gradient(self, sources: Any, max_distance: Optional[float] = None, faces: bool = False,
                       progress: Optional[Callable[[float], Any]] = None, threads: int = 1) -> dict:
        """The exact gradient of the distance field from the sources: per vertex the unit
        direction in which its shortest path arrives (steepest ascent, never averaged), the
        nearest source and the distance; with faces=True also per face at its centroid (where the
        field is sigma + |p - s| for the window of source image s reaching it, so the gradient is
        (p - s) / |p - s| exactly). sources as field(). Returns a dict: "gradient" (n, 3),
        "flag" (n,) int64 (0 defined, 1 a source, 2 unreached, 3 two sources tie within 1e-12:
        no gradient there), "label" (n,) int64 (-1 none), "distance" (n,); with faces=True
        "face_gradient" (F, 3) and "face_flag" (F,). Directions at a vertex where two paths from
        one source tie (its cut locus) follow the path found first, not flagged. The same
        numbers as tg_geodesic_field_gradient and `trigeo field --gradient`."""
        faces = _flag(faces, "faces")
        nthreads = _threads(threads)

        def work(call: _Call) -> dict:
            src = self._surface_points(sources, "sources")
            o = self._field_options(max_distance, call, nthreads)
            n, nf = self.vertex_count, self.face_count
            g, d = np.empty((n, 3)), np.empty(n)
            fl, lab = np.empty(n, dtype=np.uint8), np.empty(n, dtype=np.uint32)
            fg, ff = (np.empty((nf, 3)), np.empty(nf, dtype=np.uint8)) if faces else (None, None)
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_field_gradient(geo, ws, src, len(src), ctypes.byref(o), _ptr(g), _ptr(fl, ctypes.c_uint8),
                                                   _ptr(lab, ctypes.c_uint32), _ptr(d),
                                                   _ptr(fg) if faces else None,
                                                   _ptr(ff, ctypes.c_uint8) if faces else None, None)
            call.finish(st, "field_gradient")
            out = {"gradient": g, "flag": fl.astype(np.int64), "label": _labels(lab), "distance": d}
            if faces:
                out["face_gradient"], out["face_flag"] = fg, ff.astype(np.int64)
            return out

        return self._run(work, progress)

    def _polyline_transport(self, points: np.ndarray, faces: np.ndarray, vector: Any, what: str) -> np.ndarray:
        """tg_polyline_transport over a path's or trace's points and faces."""
        vec = _floats(vector, "vector", "a 3D vector")
        if vec.shape != (3,) or not np.all(np.isfinite(vec)) or not np.any(vec):
            raise _bad(f"vector must be a 3D vector of finite numbers, not all zero, not {_show(vector)}")
        vec = np.ascontiguousarray(vec)
        pts = np.ascontiguousarray(points, dtype=np.float64)
        fc = np.ascontiguousarray(faces, dtype=np.uint32)
        if pts.shape[0] < 2:
            raise _bad(f"{what}: the path has fewer than two points")

        def work(call: _Call) -> np.ndarray:
            out = np.empty((pts.shape[0], 3))
            st = _L.tg_polyline_transport(self._handle(), pts.shape[0], _ptr(pts), _ptr(fc, ctypes.c_uint32),
                                          _ptr(vec), _ptr(out))
            if st == 1:
                raise _bad(f"{what}: the vector is perpendicular to the path's first face, or the path has length 0")
            call.finish(st, what)
            return out

        return self._run(work)

    def field_at(self, sources: Any, points: Any, max_distance: Optional[float] = None, threads: int = 1, *,
                 curve: Any = None, curves: Any = None, boundary: bool = False) -> np.ndarray:
        """The exact geodesic distance from the sources to arbitrary surface points (in faces, on
        edges, vertices) in one propagation. sources as field() (None with curves only); points:
        SurfacePoints, vertex indices or (k, 3) positions; threads, curve, curves, boundary as
        field()'s. Returns (k,) float64."""
        nthreads = _threads(threads)
        segs = self._segments(curve, curves, boundary)
        if segs is not None:
            return self._curve_field("field_at", sources, segs, points, max_distance, None, nthreads)

        def work(call: _Call) -> np.ndarray:
            src = self._surface_points(sources, "sources")
            pts = self._surface_points(points, "points")
            o = self._field_options(max_distance, call, nthreads)
            out = np.empty(len(pts))
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_field_at(geo, ws, src, len(src), pts, len(pts), ctypes.byref(o), _ptr(out),
                                             None, None)
            call.finish(st, "field_at")
            return out

        return self._run(work)

    def distance_matrix(self, sources: Any = None, max_distance: Optional[float] = None, threads: int = 0,
                        progress: Optional[Callable[[float], Any]] = None, *, targets: Any = None,
                        sparse: bool = False, curves: Any = None, boundary: bool = False) -> Any:
        """One exact field per source: row i is field([sources[i]]) exactly (bit-identical).
        Rows run in parallel on `threads` C threads (0: all cores). Returns (K, n) float64.

        targets: surface points (as field_at's points): the (K, T) matrix of the distances from
        each source to them, each field stopped as soon as its targets are settled (see
        _matrix_at). sparse=True: the local matrix, a scipy.sparse.csr_matrix of every vertex
        within max_distance of each source (see _local_matrix); sources may then be "all".
        Curve rows (tg_geodesic_curve_distance_matrix, the CLI's curve:FILE and boundary lines in
        --sources): curves= a list of polylines (each as field()'s curve=), boundary=True the
        mesh's boundary; the rows are the sources, then each curve, then the boundary, each row
        field(curve=...) of its own bit for bit (dense only, targets allowed)."""
        sparse = _flag(sparse, "sparse")
        if curves is not None or _flag(boundary, "boundary"):
            if sparse:
                raise _bad("curve rows give a dense matrix: sparse=True does not apply")
            return self._curve_matrix(sources, curves, boundary, targets, max_distance, threads, progress)
        if sources is None:
            raise _bad("distance_matrix() needs sources, curves= or boundary=True")
        if targets is not None:
            if sparse:
                raise _bad("targets gives a dense (K, T) matrix: sparse=True does not apply")
            return self._matrix_at(sources, targets, max_distance, threads, progress)
        if sparse:
            return self._local_matrix(sources, max_distance, threads, progress)
        if isinstance(sources, str) and sources == "all":
            raise _bad('sources="all" goes with sparse=True (and max_distance=D): the dense matrix of every '
                       "vertex holds n x n doubles")
        threads = _threads(threads)

        def work(call: _Call) -> np.ndarray:
            src = self._surface_points(sources, "sources")
            o = self._field_options(max_distance, call)
            out = np.empty((len(src), self.vertex_count))
            geo = self._get_geo()
            st = _L.tg_geodesic_distance_matrix(geo, src, len(src), ctypes.byref(o), threads, _ptr(out), None)
            call.finish(st, "distance_matrix")
            return out

        return self._run(work, progress)

    def _curve_matrix(self, sources: Any, curves: Any, boundary: bool, targets: Any, max_distance: Optional[float],
                      threads: int, progress: Optional[Callable[[float], Any]]) -> np.ndarray:
        """distance_matrix with curve rows: the sources' rows, each curve's, the boundary's."""
        if curves is not None and (isinstance(curves, (str, bytes)) or not isinstance(curves, (list, tuple))):
            raise _bad("curves must be a list of polylines (each as field()'s curve= takes one)")
        parts = [self._segments(c, None, False) for c in (curves or [])]
        if boundary:
            parts.append(self._segments(None, None, True))
        threads = _threads(threads)

        def work(call: _Call) -> np.ndarray:
            src = self._surface_points(sources if sources is not None else [], "sources")
            tgt = self._surface_points(targets, "targets") if targets is not None else None
            segs = [sg for part in parts for sg in part]
            rows = [len(src) + k for k, part in enumerate(parts) for _ in part]
            arr = (_c.SurfaceSegmentC * len(segs))(*segs)
            seg_row = (ctypes.c_uint32 * max(len(rows), 1))(*rows)
            nrows = len(src) + len(parts)
            o = self._field_options(max_distance, call)
            out = np.empty((nrows, self.vertex_count if tgt is None else len(tgt)))
            st = _L.tg_geodesic_curve_distance_matrix(self._get_geo(), src, len(src), None, arr, len(segs), seg_row,
                                                      nrows, tgt, 0 if tgt is None else len(tgt), ctypes.byref(o),
                                                      threads, _ptr(out), None)
            call.finish(st, "distance_matrix")
            return out

        return self._run(work, progress)

    def _matrix_at(self, sources: Any, targets: Any, max_distance: Optional[float], threads: int,
                   progress: Optional[Callable[[float], Any]]) -> np.ndarray:
        """distance_matrix(sources, targets=...): row i holds the distances from sources[i] to
        the targets, exactly field_at([sources[i]], targets) (bit-identical), inf where
        unreachable or beyond max_distance. Each row's field stops once every target has a
        finite bound and the front has passed the largest, so near targets cost a disc around
        the source, not the mesh. Returns (K, T) float64."""
        threads = _threads(threads)

        def work(call: _Call) -> np.ndarray:
            src = self._surface_points(sources, "sources")
            tgt = self._surface_points(targets, "targets")
            o = self._field_options(max_distance, call)
            out = np.empty((len(src), len(tgt)))
            geo = self._get_geo()
            st = _L.tg_geodesic_distance_matrix_at(geo, src, len(src), tgt, len(tgt), ctypes.byref(o), threads,
                                                   _ptr(out), None)
            call.finish(st, "distance_matrix")
            return out

        return self._run(work, progress)

    def _local_matrix(self, sources: Any, max_distance: Optional[float], threads: int,
                      progress: Optional[Callable[[float], Any]]) -> Any:
        """distance_matrix(sources, max_distance=D, sparse=True): the local distance matrix as a
        scipy.sparse.csr_matrix of shape (K, n): row i stores every vertex within D of
        sources[i] (geodesic distance along the surface) with that distance, bit-identical to
        the finite entries of field([sources[i]], max_distance=D); absent entries are farther
        (or unreachable), a stored 0.0 is the source vertex itself. sources="all" (or None):
        every vertex, row i = vertex i (an unused vertex gets an empty row). max_distance=None:
        every reachable vertex (the full matrix, stored sparse). Memory: 12 bytes per entry.

        Symmetry: d(a, b) and d(b, a) come from two propagations and agree to rounding only
        (measured on fcpw_kitten within 5% of the diagonal: at most 1.4e-16 absolute, 2.6e-15
        relative; BENCHMARKS.md), so the matrix of every
        vertex is symmetric to rounding, and a pair at distance D to rounding may be stored one
        way only. For an exactly symmetric matrix take M.maximum(M.T) (keeps a pair stored either
        way; SciPy drops the stored zeros of the diagonal, which M.setdiag(0) puts back)."""
        import scipy.sparse

        radius = math.inf if max_distance is None else _number(max_distance, "max_distance", ">=0", " (None: no limit)")
        everything = sources is None or (isinstance(sources, str) and sources == "all")
        if isinstance(sources, str) and not everything:
            raise _bad(f"sources must be surface points or \"all\", not {sources!r}")
        threads = _threads(threads)

        def work(call: _Call) -> ctypes.c_void_p:
            src = None if everything else self._surface_points(sources, "sources")
            rows = self.vertex_count if everything else len(src)
            o = self._field_options(None, call)
            geo = self._get_geo()
            st = _L.tg_geodesic_local_matrix(geo, src, rows, radius, ctypes.byref(o), threads, mat, None)
            call.finish(st, "distance_matrix")

        mat = _new(_L.tg_sparse_matrix_create, None)
        try:
            self._run(work, progress)
            v = _c.SparseMatrixView()
            _L.tg_sparse_matrix_get_view(mat, ctypes.byref(v))
            n, k = v.entry_count, v.row_count
            indptr = np.array(_view(None, v.row_start, (k + 1,), "<u8"), dtype=np.int64)
            index = np.int32 if v.col_count <= np.iinfo(np.int32).max and n <= np.iinfo(np.int32).max else np.int64
            if index == np.int32:
                indptr = indptr.astype(np.int32)
            indices = np.array(_view(None, v.col, (n,), "<u4"), dtype=index)
            data = np.array(_view(None, v.value, (n,), "<f8"))
        finally:
            _L.tg_sparse_matrix_destroy(mat)
        return scipy.sparse.csr_matrix((data, indices, indptr), shape=(k, v.col_count), copy=False)

    # -- files ------------------------------------------------------------------------------

    def save(self, path: Union[str, os.PathLike], fields: Optional[dict] = None) -> None:
        """Writes the mesh: PATH.obj (Wavefront OBJ) or PATH.ply (binary PLY, with one double
        vertex property per entry of `fields`, a dict of name -> (n,) array, e.g.
        {"distance": mesh.field(0)}, readable by ParaView, MeshLab, trimesh and `trigeo render
        --field`). Names: 1-64 letters, digits and '_', not x, y or z. The file appears only when
        complete (written into a private temporary directory beside it, then renamed over it: a
        full disk or Ctrl-C leaves the previous file as it was); a character device or FIFO is
        written directly. A path that is the mesh's own file (the same file through any name or
        link) is refused (InvalidArgumentError), as any output that is an input. Raises FileError
        when the file cannot be written."""
        p = _fs_path(path, "path")
        low = p.lower()
        if not (low.endswith(".obj") or low.endswith(".ply")):
            raise _bad(f"save writes .obj or .ply files, not {p!r}")
        self._check_output(p, "path")
        if fields is not None and not isinstance(fields, dict):
            raise _bad(f"fields must be a dict of name -> (n,) array, not {_show(fields)}")
        fields = fields or {}
        if fields and not low.endswith(".ply"):
            raise _bad("per-vertex fields are written to PLY files (PATH.ply)")
        keep, arr = [], (_c.VertexScalar * max(1, len(fields)))()
        for i, (name, values) in enumerate(fields.items()):
            if not isinstance(name, str):
                raise _bad(f"field name {name!r} must be a string")  # its characters: the library checks
            a = np.ascontiguousarray(_floats(values, f"field {name!r}", "one value per vertex"))
            if a.shape != (self.vertex_count,):
                raise _bad(f"field {name!r} must have one value per vertex ({self.vertex_count}), not shape {a.shape}")
            b = name.encode()
            keep += [a, b]
            arr[i].name, arr[i].values = b, _ptr(a)
        def write(name: bytes, diag: _c.Diag) -> int:
            if low.endswith(".ply"):
                return _L.tg_mesh_write_ply(self._handle(), name, arr, len(fields), ctypes.byref(diag))
            return _L.tg_mesh_write_obj(self._handle(), name, ctypes.byref(diag))

        self._run(lambda call: _write_whole(p, call, write))

    # -- Voronoi cells and sampling --------------------------------------------------------

    def voronoi(self, sources: Any = None, max_distance: Optional[float] = None, boundaries: bool = False,
                progress: Optional[Callable[[float], Any]] = None, threads: int = 1, *, curves: Any = None,
                boundary: bool = False) -> tuple:
        """Geodesic Voronoi cells: per vertex the index of the nearest source (in the order
        given; ties to the lowest index) and the exact distance to it. sources as field().
        Equal to the argmin over each source's own field (distance_matrix(sources).argmin(0)
        where reached). Returns (labels (n,) int64, -1 where no source reaches;
        distance (n,) float64, inf there). With boundaries=True also a list of the cells'
        boundary polylines, each a dict: "cells" (a, b) the labels on its two sides (a < b),
        "points" (k, 3) float64, "surface_points" k SurfacePoints (edge crossings, where the two
        sources' exact distances are equal to 1e-10 relative, and junctions inside faces of
        three cells); closed loops repeat their first point. threads: each source's field on that
        many threads, as field()'s (a label where two sources tie within rounding may differ
        from one thread's).
        Curve sites (tg_geodesic_curve_voronoi, the CLI's --labels with curve:FILE and boundary):
        curves= a list of polylines (each as field()'s curve=), boundary=True the mesh's
        boundary: the sites are the sources (0 .. S-1), then each curve, then the boundary, each
        vertex labelled with the nearest (exact distance to its nearest point); boundaries=True
        is for point sources only."""
        boundaries = _flag(boundaries, "boundaries")
        nthreads = _threads(threads)
        n = self.vertex_count
        labels = np.empty(n, dtype=np.uint32)
        dist = np.empty(n)
        if curves is not None or _flag(boundary, "boundary"):
            if boundaries:
                raise _bad("boundaries=True draws the cells of point sources only, not of curves")
            if curves is not None and (isinstance(curves, (str, bytes)) or not isinstance(curves, (list, tuple))):
                raise _bad("curves must be a list of polylines (each as field()'s curve= takes one)")
            parts = [self._segments(c, None, False) for c in (curves or [])]
            if boundary:
                parts.append(self._segments(None, None, True))

            def work_curves(call: _Call) -> None:
                src = self._surface_points(sources if sources is not None else [], "sources")
                segs = [sg for part in parts for sg in part]
                site = [len(src) + k for k, part in enumerate(parts) for _ in part]
                arr = (_c.SurfaceSegmentC * len(segs))(*segs)
                sites = (ctypes.c_uint32 * max(len(site), 1))(*site)
                o = self._field_options(max_distance, call, nthreads)
                with self._geo_ws.take() as ws:
                    st = _L.tg_geodesic_curve_voronoi(self._get_geo(), ws, src, len(src), None, arr, len(segs), sites,
                                                      len(src) + len(parts), ctypes.byref(o), _ptr(dist),
                                                      _ptr(labels, ctypes.c_uint32), None)
                call.finish(st, "voronoi")

            self._run(work_curves, progress)
            return _labels(labels), dist
        if sources is None:
            raise _bad("voronoi() needs sources, curves= or boundary=True")

        def work(call: _Call) -> None:
            src = self._surface_points(sources, "sources")
            o = self._field_options(max_distance, call, nthreads)
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_voronoi(geo, ws, src, len(src), ctypes.byref(o), bounds, _ptr(dist),
                                            _ptr(labels, ctypes.c_uint32), None)
            call.finish(st, "voronoi")

        if not boundaries:
            bounds = None
            self._run(work, progress)
            return _labels(labels), dist
        bounds = _new(_L.tg_voronoi_boundaries_create, None)
        try:
            self._run(work, progress)
            v = _c.BoundariesView()
            _L.tg_voronoi_boundaries_get_view(bounds, ctypes.byref(v))
            xyz = np.ctypeslib.as_array(v.xyz, shape=(v.point_count, 3)).copy() if v.point_count else np.empty((0, 3))
            lines = []
            for p in range(v.polyline_count):
                a, b = v.polyline_start[p], v.polyline_start[p + 1]
                lines.append({"cells": (int(v.polyline_cells[2 * p]), int(v.polyline_cells[2 * p + 1])),
                              "points": xyz[a:b].copy(),
                              "surface_points": [SurfacePoint._from_c(v.points[i]) for i in range(a, b)]})
        finally:
            _L.tg_voronoi_boundaries_destroy(bounds)
        return _labels(labels), dist, lines

    def isolines(self, sources: Any = None, levels: Any = None, max_distance: Optional[float] = None,
                 details: bool = False, progress: Optional[Callable[[float], Any]] = None, *,
                 count: Optional[int] = None, threads: int = 1, curve: Any = None, curves: Any = None,
                 boundary: bool = False) -> list:
        """Exact isolines: for each level, the curves where the exact geodesic distance from the
        nearest source equals it. sources as field() (none: no curves); curve=, curves=,
        boundary=True: curves as sources, as field() takes them (then the isolines are their
        exact offset curves on the surface: straight where the distance comes from a segment's
        inside, arcs about its ends and about the vertices the paths bend at, the CLI's field
        --from curve:FILE|boundary --isolines); levels: a number or a
        sequence of finite levels >= 0 (any order; a number is always a level, as the CLI's
        --isolines). count=N instead of levels: N levels equally spaced below the largest
        distance, max * k / (N + 1) for k = 1..N (the CLI's --isoline-count N; the field is
        computed first for its largest distance). Edge crossings are placed on the exact distance function (not
        interpolated between vertices) and the curves follow the exact circular arcs inside faces
        (within 1e-3 of the face's size); every point's field_at() is its level to ~1e-15.
        Returns one list per level (in the order given) of polylines, each a (k, 3) float64
        array; a closed curve repeats its first point at its end. With details=True each
        polyline is a dict: "points" (k, 3), "closed" bool, "faces" (k,) int64 (a face holding
        each point), "surface_points" k SurfacePoints (edge points at crossings, face points
        inside faces). max_distance: as field() (levels beyond it give no polylines). threads: as
        field()'s (the curves' points where windows meet inside a face may differ from one
        thread's, each on its level)."""
        details = _flag(details, "details")
        nthreads = _threads(threads)
        segs = self._segments(curve, curves, boundary)
        if sources is None and segs is None:
            raise _bad("isolines() needs sources, curve=, curves= or boundary=True")
        if (levels is None) == (count is None):
            raise _bad("give the levels or count=N (how many levels below the largest distance), one of them")
        if count is not None:
            if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or not 1 <= count <= 4096:
                raise _bad(f"count must be an integer from 1 to 4096, not {_show(count)}")
            lv = np.zeros(int(count))
        else:
            lv = np.ascontiguousarray(np.atleast_1d(_floats(levels, "levels", "a level or a sequence")).ravel())
            if lv.size == 0:
                raise _bad(f"levels must be one or more finite numbers >= 0, not {_show(levels)}")
            _check_values(lv, "levels", ">=0")

        def work(call: _Call) -> None:
            src = self._surface_points(sources if sources is not None else [], "sources")
            sg, ns = (segs, len(segs)) if segs is not None else (None, 0)
            o = self._field_options(max_distance, call, nthreads)
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                if count is not None:  # the levels below the field's largest finite distance, as the CLI's
                    d = np.empty(self.vertex_count)
                    st = _L.tg_geodesic_curve_field(geo, ws, src, len(src), sg, ns, None, 0, ctypes.byref(o), None,
                                                    _ptr(d), None)
                    if st != 0:
                        call.finish(st, "isolines")
                    fin = d[np.isfinite(d)]
                    far = float(fin.max()) if fin.size and fin.max() > 0 else 0.0
                    for k in range(lv.size):
                        lv[k] = far * float(k + 1) / float(lv.size + 1)
                st = _L.tg_geodesic_curve_isolines(geo, ws, src, len(src), sg, ns, _ptr(lv), lv.size,
                                                   ctypes.byref(o), handle, None, None)
            call.finish(st, "isolines")

        handle = _new(_L.tg_isolines_create, None)
        try:
            self._run(work, progress)
            v = _c.IsolinesView()
            _L.tg_isolines_get_view(handle, ctypes.byref(v))
            n = v.point_count
            xyz = np.ctypeslib.as_array(v.xyz, shape=(n, 3)).copy() if n else np.empty((0, 3))
            faces = np.ctypeslib.as_array(v.faces, shape=(n,)).astype(np.int64) if n else np.empty(0, np.int64)
            out = []
            for li in range(v.level_count):
                lines = []
                for p in range(v.level_start[li], v.level_start[li + 1]):
                    a, b = v.polyline_start[p], v.polyline_start[p + 1]
                    if not details:
                        lines.append(xyz[a:b].copy())
                        continue
                    lines.append({"points": xyz[a:b].copy(), "closed": bool(v.polyline_closed[p]),
                                  "faces": faces[a:b].copy(),
                                  "surface_points": [SurfacePoint._from_c(v.points[i]) for i in range(a, b)]})
                out.append(lines)
        finally:
            _L.tg_isolines_destroy(handle)
        return out

    def farthest_point_sampling(self, count: int, start: Optional[int] = None, seed: int = 0,
                                progress: Optional[Callable[[float], Any]] = None, threads: int = 1
                                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Farthest-point sampling in exact geodesic distance: sample 0 is `start` (a vertex used
        by a face), or, when None, the vertex `seed` picks (the same as `trigeo sample --seed`);
        each next sample is the vertex farthest from all earlier ones (a component no sample
        reaches yet first; ties to the lowest index); seed: any integer from 0 to 2**64 - 1, as the
        CLI's, giving the CLI's samples. Each new sample's field runs only where it
        gets below the earlier ones. Returns (samples (count,) int64 in order, distance (n,)
        float64 to the nearest sample, labels (n,) int64: its position in samples, -1 where
        none reaches). threads: each sample's field on that many threads, as field()'s (the
        samples are one thread's except where two candidates tie within rounding)."""
        nthreads = _threads(threads)
        k = _index(count, "count")
        if k < 1:
            raise _bad(f"count must be at least 1, not {count!r}")
        first = _c.NONE if start is None else _index(start, "start")
        if start is not None and first >= self.vertex_count:
            raise _bad(f"start {start!r} is not a vertex (the mesh has {self.vertex_count})")
        sd = _u64(seed, "seed")
        n = self.vertex_count
        samples = np.empty(k, dtype=np.uint32)
        labels = np.empty(n, dtype=np.uint32)
        dist = np.empty(n)

        def work(call: _Call) -> None:
            o = self._field_options(None, call, nthreads)
            geo = self._get_geo()
            with self._geo_ws.take() as ws:
                st = _L.tg_geodesic_farthest_point_sampling(geo, ws, first, sd, k, ctypes.byref(o),
                                                            _ptr(samples, ctypes.c_uint32), _ptr(dist),
                                                            _ptr(labels, ctypes.c_uint32), None)
            if st == 1:  # TG_ERR_INVALID_ARGUMENT: the arguments were checked but these two
                if start is not None and not np.any(self.faces == first):
                    raise _bad(f"start {start!r} is used by no face")
                used = self.report["vertices"] - self.report["unreferenced_vertices"]
                raise _bad(f"count {k} exceeds the {used} vertices used by faces")
            call.finish(st, "farthest_point_sampling")

        self._run(work, progress)
        return samples.astype(np.int64), dist, _labels(labels)

    # -- pictures -----------------------------------------------------------------------------

    def render(self, png_path: Union[str, os.PathLike], path: Any = None, field: Any = None, view: Any = None,
               width: int = 960, height: int = 720, isolines: Any = 16, labels: Any = None,
               boundaries: Any = None, logmap: Any = None, checker: float = 0.0, isoline_levels: Any = None) -> None:
        """Writes a PNG picture of the mesh (orthographic, shaded), with an optional path (a Path
        or a (k, 3) polyline, drawn as a red tube) and an optional per-vertex field (n values,
        coloured dark blue to yellow with isolines; non-finite values, e.g. inf, drawn grey).
        png_path: a name ending in .png (any case), never the mesh's own file (InvalidArgumentError,
        before any work). width, height: 1 to 8192 pixels. view: the direction the camera looks
        along, e.g. (0, 0, -1) (finite, not all zero); None: a three-quarter view. isolines: the
        number of colour bands, 0 for none.
        Memory is bounded (the library's TG_RENDER_MAX_BYTES, 2 GiB: large pictures get less
        supersampling). The file appears only when complete, as with save(); Ctrl-C interrupts
        the drawing and leaves no file.
        labels: Voronoi cells (n labels as voronoi() returns, -1 none), one colour per cell,
        drawn instead of field. boundaries: polylines (voronoi(..., boundaries=True)'s list, or
        (k, 3) arrays) drawn as dark tubes, instead of path.
        logmap: (n, 2) coordinates per vertex (log_map()'s uv), drawn as the checkerboard of
        squares of side `checker` (0: the bounding box diagonal / 40), instead of field and
        labels; inf coordinates grey (NaN refused). isolines may also be the exact curves of
        isolines() (its list of lists of (k, 3) arrays or dicts, one list per level;
        isoline_levels: one finite level >= 0 per list, for their colours) drawn as thin lines
        instead of the colour bands. Every argument is checked before any drawing: a wrong type,
        shape, length or value raises InvalidArgumentError naming it."""
        png = _fs_path(png_path, "png_path")
        if not png.lower().endswith(".png"):
            raise _bad(f"render writes PNG files: png_path must end in .png, not {png!r}")
        self._check_output(png, "png_path")
        o = _c.RenderOptions()
        for name, size in (("width", width), ("height", height)):
            if isinstance(size, (bool, np.bool_)) or not isinstance(size, (int, np.integer)) or not 1 <= size <= 8192:
                raise _bad(f"{name} must be an integer from 1 to 8192 (pixels), not {_show(size)}")
        o.width, o.height = int(width), int(height)
        n = self.vertex_count
        keep = []
        if isinstance(isolines, (int, np.integer)) and not isinstance(isolines, (bool, np.bool_)):
            if not 0 <= isolines <= 0x7FFFFFFF:
                raise _bad(f"isolines must be a number of bands from 0 (none) to 2147483647, not {isolines!r}")
            o.isolines = int(isolines) if isolines > 0 else -1
            if isoline_levels is not None:
                raise _bad("isoline_levels goes with isolines=the curves of isolines() (one list per level), "
                           "not with a number of bands")
        else:  # exact curves: one list of polylines per level
            curves = self._render_curves(isolines, isoline_levels)
            keep.append(curves)
            pts, starts, levels_arr = curves
            o.isoline_xyz, o.isoline_start, o.isoline_parts = _ptr(pts), _ptr(starts, ctypes.c_size_t), len(starts) - 1
            if isoline_levels is not None:
                o.isoline_level = _ptr(levels_arr)
        if view is not None:
            v = _floats(view, "view", "a 3D direction")
            if v.shape != (3,) or not np.all(np.isfinite(v)) or not np.any(v):
                raise _bad(f"view must be a 3D direction of finite numbers, not all zero, not {_show(view)}")
            o.view_dir = (ctypes.c_double * 3)(*v)
        if field is not None:
            fa = np.ascontiguousarray(_floats(field, "field", "one value per vertex"))
            if fa.shape != (n,):
                raise _bad(f"field must have one value per vertex ({n}), not shape {fa.shape}")
            keep.append(fa)
            o.vertex_scalar = _ptr(fa)
        if labels is not None:
            try:
                la = np.asarray(labels)
            except (TypeError, ValueError):
                la = np.empty(0, dtype=object)
            if la.shape != (n,) or la.dtype.kind not in "iu" or (la.size and not -1 <= la.min() <= la.max() < _c.NONE):
                raise _bad(f"labels must be {n} integers from -1 (no cell) to 4294967294, "
                           f"not {_show(labels)} (dtype {la.dtype}, shape {la.shape})")
            cells = np.where(la < 0, _c.NONE, la).astype(np.uint32)
            keep.append(cells)
            o.vertex_label = _ptr(cells, ctypes.c_uint32)
        if logmap is not None:
            uv = np.ascontiguousarray(_floats(logmap, "logmap", "(n, 2) coordinates"))
            if uv.shape != (n, 2):
                raise _bad(f"logmap must be ({n}, 2) coordinates, not shape {uv.shape}")
            if np.isnan(uv).any():
                i = int(np.argmax(np.isnan(uv).any(axis=1)))
                raise _bad(f"logmap[{i}] = {uv[i].tolist()} is NaN (inf: a vertex not reached, drawn grey)")
            keep.append(uv)
            o.vertex_uv = _ptr(uv)
        o.checker_size = _number(checker, "checker", ">=0", " (0: the bounding box diagonal / 40)")
        if boundaries is not None:
            if path is not None:
                raise _bad("render takes a path or boundaries, not both")
            parts = [_polyline(b, f"boundaries[{i}]") for i, b in enumerate(self._polylines(boundaries, "boundaries"))]
            pl = np.concatenate(parts) if parts else np.empty((0, 3))
            starts = np.cumsum([0] + [len(q) for q in parts]).astype(np.uintp)
            keep += [pl, starts]
            o.polyline, o.polyline_count = _ptr(pl), pl.shape[0]
            o.polyline_start, o.polyline_parts = _ptr(starts, ctypes.c_size_t), len(parts)
        if path is not None:
            pts = path.points if isinstance(path, Path) else path
            pl = _polyline(pts, "path")
            keep.append(pl)
            o.polyline, o.polyline_count = _ptr(pl), pl.shape[0]
        def work(call: _Call) -> None:
            o.progress = call.render_fn
            _write_whole(png, call, lambda name, diag: _L.tg_render_png(self._handle(), ctypes.byref(o), name,
                                                                        ctypes.byref(diag)))

        self._run(work)


    @staticmethod
    def _polylines(lines: Any, what: str) -> list:
        """A sequence of polylines, each a (k, 3) array or a dict with "points" (voronoi(), isolines(
        details=True)), as the list of their point arrays (not yet checked)."""
        if isinstance(lines, (str, bytes, dict)) or not hasattr(lines, "__iter__"):
            raise _bad(f"{what} must be a list of polylines ((k, 3) arrays or dicts with 'points'), not {_show(lines)}")
        out = []
        for i, pl in enumerate(lines):
            if isinstance(pl, dict):
                if "points" not in pl:
                    raise _bad(f"{what}[{i}] is a dict without 'points'")
                pl = pl["points"]
            out.append(pl)
        return out

    def _render_curves(self, isolines: Any, levels: Any) -> tuple:
        """render(isolines=the curves of isolines()): (points (P, 3), part offsets (parts + 1,),
        each part's level (parts,)), checked: one list of polylines per level and, when levels is
        given, one finite level >= 0 per list."""
        what = "isolines"
        if isinstance(isolines, (str, bytes, dict)) or not isinstance(isolines, (list, tuple)):
            raise _bad(f"{what} must be a number of bands (an integer >= 0) or the curves isolines() returns "
                       f"(a list per level of (k, 3) arrays), not {_show(isolines)}")
        per_level = [self._polylines(lines, f"{what}[{li}]") for li, lines in enumerate(isolines)]
        lv = np.zeros(len(per_level))
        if levels is not None:
            lv = np.atleast_1d(_floats(levels, "isoline_levels", "one level per list of isolines")).ravel()
            if lv.shape[0] != len(per_level):
                raise _bad(f"isoline_levels must give one level per list of curves in isolines ({len(per_level)}), "
                           f"not {lv.shape[0]}")
            _check_values(lv, "isoline_levels", ">=0")
        parts, part_level = [], []
        for li, lines in enumerate(per_level):
            for pi, pl in enumerate(lines):
                parts.append(_polyline(pl, f"{what}[{li}][{pi}]"))
                part_level.append(lv[li])
        pts = np.concatenate(parts) if parts else np.empty((0, 3))
        starts = np.cumsum([0] + [len(q) for q in parts]).astype(np.uintp)
        return np.ascontiguousarray(pts), starts, np.array(part_level, dtype=np.float64)

    def _check_output(self, path: str, what: str) -> None:
        """Refuses an output path that is an input of the call: the mesh's own file (the same
        device and inode, through links; as loaded, and what its path names now)."""
        try:
            st = os.stat(path)
        except OSError:
            return  # nothing there (or unreachable): not an input
        ids = set(self._source_ids)
        if self._source:
            try:
                now = os.stat(self._source)
                ids.add((now.st_dev, now.st_ino))
            except OSError:
                pass
        if (st.st_dev, st.st_ino) in ids:
            raise _bad(f"{what} {path!r} is the mesh's own file ({self._source}): an output never overwrites an input")


def _labels(labels: np.ndarray) -> np.ndarray:
    out = labels.astype(np.int64)
    out[labels == _c.NONE] = -1
    return out


def _hits(hits: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    face = hits["face"].astype(np.int64)
    face[face == _c.NONE] = -1
    return np.sqrt(hits["sqdist"]), face, np.ascontiguousarray(hits["point"])


class _MeshHandle:
    """Owns the C mesh. The Mesh and every NumPy view of the mesh's arrays hold a reference, so
    the arrays stay valid after Mesh.close() until the last view is gone."""

    __slots__ = ("value",)

    def __init__(self, value: int):
        self.value = value

    def __del__(self):
        if self.value:
            _L.tg_mesh_destroy(self.value)
            self.value = None


# ---------------------------------------------------------------------------------------------
# Path
# ---------------------------------------------------------------------------------------------

class GeodesicMean:
    """The result of Mesh.geodesic_mean. Attributes:

    point          SurfacePoint, the mean
    xyz            (3,) float64, its position
    status         "converged", "iteration_cap" (the last point) or "stalled" (a step could not
                   be walked)
    iterations     steps taken (a step walked again at half length counts once more)
    halvings       steps walked again at half length because the energy rose
    gradient_norm  |sum w log_p(x)| / sum w at the mean (0 at an exact critical point)
    energy         sum w d^2 / sum w, the function minimised
    radius         the largest distance from the mean to a point of positive weight
    uniqueness     "unique" (certified: the faces within 4 radii form a disc with no vertex of
                   angle sum below 2 pi inside), "not_certified" (says nothing either way) or
                   "not_checked"
    fields         exact field runs made
    """

    __slots__ = ("point", "xyz", "status", "iterations", "halvings", "gradient_norm", "energy", "radius",
                 "uniqueness", "fields")

    @classmethod
    def _from_c(cls, r: _c.MeanResult) -> "GeodesicMean":
        m = cls.__new__(cls)
        m.point = SurfacePoint._from_c(r.point)
        m.xyz = np.array(r.xyz[:], dtype=np.float64)
        m.status = _L.tg_mean_status_name(r.status).decode()
        m.uniqueness = _L.tg_mean_uniqueness_name(r.uniqueness).decode()
        m.iterations, m.halvings, m.fields = int(r.iterations), int(r.halvings), int(r.fields)
        m.gradient_norm, m.energy, m.radius = float(r.gradient_norm), float(r.energy), float(r.radius)
        return m

    def __repr__(self) -> str:
        return (f"GeodesicMean({self.point!r}, xyz={self.xyz.tolist()}, status={self.status!r}, "
                f"iterations={self.iterations}, gradient_norm={self.gradient_norm:.3g}, uniqueness={self.uniqueness!r})")


class Path:
    """A geodesic path (from Mesh.path). Attributes:

    length            float, the sum of the 3D segment lengths (inf when unreachable)
    points            (k, 3) float64: from, every edge crossing and vertex passage, to
    faces             (k - 1,) int64: the face each segment lies in
    surface_points    list of k SurfacePoints (the same points on the mesh)
    status            "converged", "iteration_cap", "unreachable" or "stalled"
    max_angle_defect  the certificate, radians: the largest deviation from straight over the
                      crossings and vertex passages (0 for a straight path)
    global_           "proven" (an exact computation showed no shorter path exists) or "unproven"
    waypoint_points   Mesh.path_through only: (m,) int64, where each waypoint is in points
                      (None for other paths)
    proven            bool, global_ == "proven"
    initial_length    the length of the initial shortest edge path ("exact" computes none: length)
    iterations        straightening sweeps or relaxation passes performed (0 for "exact")
    """

    __slots__ = ("length", "points", "faces", "surface_points", "status", "max_angle_defect", "global_",
                 "initial_length", "iterations", "waypoint_points", "_mesh")

    @classmethod
    def _from_view(cls, v: _c.PathView) -> "Path":
        p = cls.__new__(cls)
        k = int(v.point_count)
        p.length = float(v.length)
        p.initial_length = float(v.initial_length)
        p.max_angle_defect = float(v.max_angle_defect)
        p.status = _L.tg_path_status_name(v.status).decode()
        p.global_ = _L.tg_path_global_name(v.global_).decode()
        p.iterations = int(v.iterations)
        p.waypoint_points = None
        p._mesh = None
        if k:
            p.points = np.ctypeslib.as_array(v.xyz, shape=(k, 3)).copy()
            p.faces = np.ctypeslib.as_array(v.faces, shape=(k - 1,)).astype(np.int64) if k > 1 else np.empty(0, np.int64)
            p.surface_points = [SurfacePoint._from_c(v.points[i]) for i in range(k)]
        else:
            p.points, p.faces, p.surface_points = np.empty((0, 3)), np.empty(0, np.int64), []
        return p

    @property
    def proven(self) -> bool:
        """True when the path is proven globally shortest."""
        return self.global_ == "proven"

    def transport(self, vector: Any) -> np.ndarray:
        """Parallel transport along the path: the tangent vector `vector` (3 numbers, not zero; its
        projection onto the first segment's face is the direction, its length the result's) at
        the start, carried to every point keeping its angle to the path (exact along a path
        straight in the unfolding, as the default exact paths are). Returns (k, 3) float64, point
        i's vector in the plane of segment i's face. The same numbers as tg_path_transport."""
        if self._mesh is None:
            raise _bad("transport: this path has no mesh (make it with Mesh.path or Mesh.path_through)")
        return self._mesh._polyline_transport(self.points, self.faces, vector, "transport")

    def __len__(self) -> int:
        return self.points.shape[0]

    def __repr__(self) -> str:
        return (f"<trigeo.Path length={self.length!r} points={len(self)} status={self.status} "
                f"global={self.global_} max_angle_defect={self.max_angle_defect:.3g}>")


# ---------------------------------------------------------------------------------------------
# Trace
# ---------------------------------------------------------------------------------------------

class Trace:
    """A geodesic trace (from Mesh.trace). Attributes:

    points          (k, 3) float64: the start, every edge crossing and vertex passage, the end
    faces           (k - 1,) int64: the face each segment lies in
    surface_points  list of k SurfacePoints (the same points on the mesh)
    status          "complete", "boundary", "singular", "step_limit" or "stalled"
    length          the length walked (the requested one when status is "complete")
    end             the end SurfacePoint; end_xyz (3,), end_direction (3,) unit, end_face
    crossings       edges crossed; vertices: vertices passed through; branches: non-manifold
                    edges crossed, at points[branch_points]
    """

    __slots__ = ("points", "faces", "surface_points", "status", "length", "end", "end_xyz", "end_direction",
                 "end_face", "crossings", "vertices", "branches", "branch_points")

    @classmethod
    def _from_view(cls, v: _c.TraceView) -> "Trace":
        t = cls.__new__(cls)
        k = int(v.point_count)
        t.points = np.ctypeslib.as_array(v.xyz, shape=(k, 3)).copy()
        t.faces = np.ctypeslib.as_array(v.faces, shape=(k - 1,)).astype(np.int64) if k > 1 else np.empty(0, np.int64)
        t.surface_points = [SurfacePoint._from_c(v.points[i]) for i in range(k)]
        e = v.end
        t.status = _L.tg_trace_status_name(e.status).decode()
        t.length = float(e.length)
        t.end = SurfacePoint._from_c(e.point)
        t.end_xyz = np.array(e.xyz[:])
        t.end_direction = np.array(e.direction[:])
        t.end_face = int(e.face)
        t.crossings, t.vertices, t.branches = int(e.crossings), int(e.vertices), int(e.branches)
        nb = int(v.branch_count)
        t.branch_points = (np.ctypeslib.as_array(v.branch_points, shape=(nb,)).astype(np.int64) if nb
                           else np.empty(0, np.int64))
        return t

    def __len__(self) -> int:
        return self.points.shape[0]

    def __repr__(self) -> str:
        return f"<trigeo.Trace length={self.length!r} points={len(self)} status={self.status}>"
