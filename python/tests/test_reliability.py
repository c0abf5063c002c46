"""The package at the edges of its input and its run: thread counts refused above MAX_THREADS
(threads=100000 crashed); close() while other threads run calls waits for them (it crashed); Ctrl-C interrupts
paths, path_lengths, point batches and renders within about a second (a path ran on for 26 s);
save() and render() never leave a cut file on a full disk; the probe's unclear errors name their
real causes (NUL in a path, no sources, coordinates beyond 1e150, lying counts)."""
import os
import re
import resource
import signal
import stat
import subprocess
import sys
import textwrap
import threading
import time
import warnings

import numpy as np
import pytest

import trigeo
from conftest import REPO, SPOT, grid, interrupt, run_cli

HERE = os.path.dirname(os.path.abspath(__file__))


def test_max_threads_is_the_headers():
    header = open(os.path.join(REPO, "include", "trigeo.h")).read()
    assert int(re.search(r"#define TG_MAX_THREADS (\d+)", header).group(1)) == trigeo.MAX_THREADS


def _python(code: str, timeout: float = 300, preexec_fn=None) -> subprocess.CompletedProcess:
    """Runs code in a fresh interpreter (a crash there fails the test instead of ending pytest)."""
    prelude = f"import sys\nsys.path.insert(0, {os.path.join(REPO, 'python')!r})\nsys.path.insert(0, {HERE!r})\n"
    return subprocess.run([sys.executable, "-c", prelude + textwrap.dedent(code)], capture_output=True, text=True,
                          timeout=timeout, env=os.environ.copy(), preexec_fn=preexec_fn)


def test_thread_counts_beyond_the_limit_are_refused():
    """m.closest(np.zeros((2, 3)), threads=100000) crashed the interpreter (so: a subprocess)."""
    r = _python(f"""
        import numpy as np
        import trigeo
        m = trigeo.load({SPOT!r})
        q = np.zeros((2, 3))
        for threads in (100000, 257):
            for call in (lambda: m.closest(q, threads=threads), lambda: m.signed_distance(q, threads=threads),
                         lambda: m.winding_number(q, threads=threads),
                         lambda: m.path_lengths([[0, 1]], threads=threads),
                         lambda: m.distance_matrix([0], threads=threads)):
                try:
                    call()
                    print("accepted")
                except trigeo.InvalidArgumentError as e:
                    print("refused" if "at most 256" in str(e) else repr(e))
        print(m.closest(q, threads=4)[0].shape)
    """)
    assert r.returncode == 0, f"exit {r.returncode}: {r.stderr[-2000:]}"
    assert r.stdout.split() == ["refused"] * 10 + ["(2,)"], r.stdout


def test_close_while_eight_threads_hammer_the_mesh():
    r = _python(f"""
        import threading, time
        import numpy as np
        import trigeo
        from conftest import grid
        errors = []
        for rnd in range(3):
            m = trigeo.Mesh(*grid(120, 0.3))
            q = np.random.default_rng(rnd).uniform(0, 119, size=(20000, 3))
            calls = [lambda: m.path(0, 14000), lambda: m.distance_matrix([0, 5000], threads=1),
                     lambda: m.field(100), lambda: m.closest(q, threads=1),
                     lambda: m.path_lengths([[0, 14000], [5, 9000]], threads=2), lambda: m.winding_number(q[:500]),
                     lambda: m.path(3, 13000, method="straighten"), lambda: m.report]
            def hammer(k):
                while True:
                    try:
                        calls[k]()
                    except trigeo.InvalidArgumentError as e:
                        if "closed" not in str(e):
                            errors.append(repr(e))
                        return
                    except BaseException as e:
                        errors.append(repr(e))
                        return
            ts = [threading.Thread(target=hammer, args=(k,)) for k in range(8)]
            for t in ts:
                t.start()
            time.sleep(0.3 + 0.2 * rnd)
            m.close()  # waits for the calls running now; later ones are refused
            for t in ts:
                t.join()
        # close() from a progress callback would wait for itself: refused
        m = trigeo.Mesh(*grid(60, 0.3))
        seen = []
        def cb(fraction):
            try:
                m.close()
            except trigeo.InvalidArgumentError as e:
                seen.append(str(e))
            return False
        try:
            m.field(0, progress=cb)
        except trigeo.CancelledError:
            pass
        m.close()
        print("errors", errors, "callback", seen)
    """)
    assert r.returncode == 0, f"exit {r.returncode}: {r.stderr[-2000:]}"
    assert "errors [] callback ['close() from inside a progress callback" in r.stdout, r.stdout


# ---- Ctrl-C ----

ICOSPHERE = """
    import numpy as np
    def icosphere(level):
        t = (1 + 5 ** 0.5) / 2
        V = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t],
                      [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], float)
        F = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
                      [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
                      [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]])
        V /= np.linalg.norm(V, axis=1)[:, None]
        for _ in range(level):
            e = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
            uniq, inv = np.unique(e, axis=0, return_inverse=True)
            inv = inv.ravel() + len(V)
            mid = V[uniq[:, 0]] + V[uniq[:, 1]]
            V = np.concatenate([V, mid / np.linalg.norm(mid, axis=1)[:, None]])
            n = len(F)
            a, b, c = inv[:n], inv[n:2 * n], inv[2 * n:]
            F = np.concatenate([np.stack([F[:, 0], a, c], 1), np.stack([F[:, 1], b, a], 1),
                                np.stack([F[:, 2], c, b], 1), np.stack([a, b, c], 1)])
        return V, F
"""


def _interrupt(call: str, setup: str = "", delay: float = 0.4):
    """Runs `call` on an icosphere of 328k faces (vertices 0 and 3 are antipodes) in a fresh
    interpreter, sends SIGINT after `delay` seconds; returns (the CPU seconds the interpreter
    spent from the signal to the KeyboardInterrupt, or None, its output)."""
    code = ICOSPHERE + f"""
    import sys, time, os
    import trigeo
    m = trigeo.Mesh(*icosphere(7))
    m._get_geo(); m._get_bvh()
    {setup}
    print("ready", flush=True)
    try:
        {call}
        print("finished", flush=True)
    except KeyboardInterrupt:
        print("interrupted %.6f" % time.process_time(), flush=True)
    """
    prelude = f"import sys\nsys.path.insert(0, {os.path.join(REPO, 'python')!r})\n"
    p = subprocess.Popen([sys.executable, "-c", prelude + textwrap.dedent(code)], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=os.environ.copy())
    assert p.stdout.readline().strip() == "ready", p.stderr.read()
    time.sleep(delay)
    return interrupt(p)


@pytest.mark.parametrize("what,call,setup", [
    ("path", "m.path(0, 3)", ""),
    ("path_lengths 1 thread", "m.path_lengths([[0, 3], [1, 2]], threads=1)", ""),
    ("path_lengths 2 threads", "m.path_lengths([[0, 3], [1, 2], [4, 5], [6, 7]], threads=2)", ""),
    # points at 0.3 of the radius, ~8 us of CPU each (the nearest faces are far): ~6 s on two
    # threads, where 600000 points in the box took ~0.5 s and could end before the signal
    ("closest", "m.closest(q)", "q = np.random.default_rng(1).normal(size=(1500000, 3)); "
                                "q *= 0.3 / np.linalg.norm(q, axis=1)[:, None]"),
    ("render", "m.render('never.png', width=5000, height=5000)", ""),
])
def test_ctrl_c_interrupts(what, call, setup, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cpu, out = _interrupt(call, setup)
    # uninterrupted, each call works for many seconds (the path 26 s); stopped, ~0.05 s of CPU
    assert cpu is not None and cpu < 1.0, f"{what}: {cpu} CPU seconds after the signal; {out[-1500:]}"
    left = [f for f in os.listdir(tmp_path)]
    assert not left, f"{what} left {left}"


# ---- files written whole ----

def test_save_and_render_never_cut_a_file(tmp_path):
    """A full disk (here: RLIMIT_FSIZE) cut an existing keep.ply to 20 KB and keep.png to 4 KB,
    and left a new .obj at 0 bytes."""
    r = _python(f"""
        import os, resource, signal
        import trigeo
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write beyond the limit fails with EFBIG
        m = trigeo.load({SPOT!r})
        d = {str(tmp_path)!r}
        keep_ply, keep_png, new_obj = (os.path.join(d, n) for n in ("keep.ply", "keep.png", "new.obj"))
        m.save(keep_ply, fields={{"distance": m.field(0)}})
        m.render(keep_png)
        before = (open(keep_ply, "rb").read(), open(keep_png, "rb").read())
        resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))
        results = []
        for call in (lambda: m.save(keep_ply, fields={{"d": m.field(0), "e": m.field(1)}}),
                     lambda: m.render(keep_png, width=1500, height=1200), lambda: m.save(new_obj)):
            try:
                call()
                results.append("written")
            except trigeo.FileError as e:
                results.append("FileError")
        after = (open(keep_ply, "rb").read(), open(keep_png, "rb").read())
        print(results, after == before, os.path.exists(new_obj), sorted(os.listdir(d)))
    """)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip() == "['FileError', 'FileError', 'FileError'] True False ['keep.ply', 'keep.png']", r.stdout


def test_save_onto_a_directory_or_fifo(spot, tmp_path):
    (tmp_path / "d.obj").mkdir()
    with pytest.raises(trigeo.FileError, match="directory"):
        spot.save(tmp_path / "d.obj")
    os.rmdir(tmp_path / "d.obj")
    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(open(fifo, "rb").read()))
    reader.start()
    spot.save(fifo)  # written directly: a rename would replace the FIFO
    reader.join(30)
    assert got and b"\nv " in got[0] and stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert sorted(os.listdir(tmp_path)) == ["pipe.obj"]


# ---- unclear errors ----

def test_nul_in_a_path_is_refused(spot, tmp_path):
    for call in (lambda: trigeo.load(SPOT + "\0junk"), lambda: spot.save(str(tmp_path / "a.obj") + "\0x"),
                 lambda: spot.render(str(tmp_path / "a.png") + "\0x")):
        with pytest.raises(trigeo.InvalidArgumentError, match="NUL"):
            call()
    assert not os.listdir(tmp_path)


def test_empty_source_lists_reach_nothing(spot):
    """One rule for every call taking sources, as the library's: an empty list is accepted and
    reaches no vertex (field and voronoi used to disagree: one refused it, one answered)."""
    n = spot.vertex_count
    d = spot.field([])
    assert d.shape == (n,) and np.all(np.isinf(d))
    assert np.all(np.isinf(spot.field_at([], [0, 5])))
    labels, dist = spot.voronoi([])
    assert np.all(labels == -1) and np.all(np.isinf(dist))
    assert spot.isolines([], [0.1]) == [[]]
    assert spot.distance_matrix([]).shape == (0, n)
    assert spot.distance_matrix([], max_distance=0.1, sparse=True).shape == (0, n)


def test_coordinates_beyond_the_range_are_named(spot):
    with pytest.raises(trigeo.InvalidArgumentError, match=r"1e\+?150"):
        spot.closest([[1e200, 0, 0]])
    with pytest.raises(trigeo.InvalidArgumentError, match=r"1e\+?150"):
        spot.path((1e200, 0, 0), 0)


def test_counts_are_checked_and_padding_warned(tmp_path):
    import struct
    facet = lambda tri: struct.pack("<12fH", 0, 0, 1, *tri, 0)
    tris = [(0, 0, 0, 1, 0, 0, 0, 1, 0), (1, 0, 0, 1, 1, 0, 0, 1, 0)]
    body = b"".join(facet(t) for t in tris)
    lie, pad = tmp_path / "lie.stl", tmp_path / "pad.stl"
    lie.write_bytes(b"x" * 80 + struct.pack("<I", 1) + body)
    pad.write_bytes(b"x" * 80 + struct.pack("<I", 2) + body + b"\0" * 4)
    with pytest.raises(trigeo.ParseError, match="declares 1 facet but the data holds 2"):
        trigeo.load(lie)
    with pytest.warns(trigeo.LoadWarning, match="4 bytes after the last"):
        m = trigeo.load(pad)
    assert m.face_count == 2


def test_load_bytes_inflates_gzip():
    import gzip
    data = open(SPOT, "rb").read()
    m = trigeo.load_bytes(gzip.compress(data), "spot.obj")
    assert m.face_count == 5856 and np.array_equal(m.vertices, trigeo.load(SPOT).vertices)


def test_one_field_on_several_threads(spot, tmp_path):
    """field(threads=N): every N > 1 gives the same bits (and the CLI's field --from --threads N
    the same numbers), within the engine's filter margin (1e-12 relative) of one thread's."""
    one = spot.field(0)
    two = spot.field(0, threads=2)
    assert np.array_equal(two, spot.field(0, threads=3)) and np.array_equal(two, spot.field(0, threads=0))
    fin = np.isfinite(one)
    assert np.array_equal(fin, np.isfinite(two))
    assert np.all(np.abs(two[fin] - one[fin]) <= 1e-12 * one[fin])
    out = tmp_path / "f.npy"
    r = run_cli("field", SPOT, "--from", "v:0", "--threads", "2", "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    assert np.array_equal(np.load(out), two)
    for bad in (-1, 1.5, True, "2"):
        with pytest.raises(trigeo.InvalidArgumentError, match="threads"):
            spot.field(0, threads=bad)


def test_every_call_on_one_field_on_several_threads(spot, tmp_path):
    """threads= on field_at, log_map, voronoi, isolines and farthest_point_sampling: 2 and 3
    threads the same bits, one thread's numbers within 1e-12 (labels, samples and angles equal
    here: no ties on spot), and the CLI's --threads gives the same numbers."""
    pts = [trigeo.SurfacePoint.face(40, (0.2, 0.3, 0.5)), trigeo.SurfacePoint.vertex(77), trigeo.SurfacePoint.vertex(1200)]
    a1, a2 = spot.field_at(0, pts), spot.field_at(0, pts, threads=2)
    assert np.array_equal(a2, spot.field_at(0, pts, threads=3))
    assert np.all(np.abs(a2 - a1) <= 1e-12 * a1)
    r1, t1, _ = spot.log_map(5)
    r2, t2, uv2 = spot.log_map(5, threads=2)
    r3, t3, _ = spot.log_map(5, threads=3)
    assert np.array_equal(r2, r3) and np.array_equal(t2, t3)
    assert np.all(np.abs(r2 - r1) <= 1e-12 * r1) and np.all(np.abs(t2 - t1) <= 1e-9)
    l1, d1 = spot.voronoi([0, 900, 2000])
    l2, d2 = spot.voronoi([0, 900, 2000], threads=2)
    assert np.array_equal(l1, l2) and np.all(np.abs(d2 - d1) <= 1e-12 * d1)
    i1 = spot.isolines(0, [0.3, 0.7])
    i2, i3 = spot.isolines(0, [0.3, 0.7], threads=2), spot.isolines(0, [0.3, 0.7], threads=3)
    assert [len(c) for c in i2] == [len(c) for c in i1] and all(
        np.array_equal(p, q) for a, b in zip(i2, i3) for p, q in zip(a, b))
    s1, sd1, sl1 = spot.farthest_point_sampling(10)
    s2, sd2, sl2 = spot.farthest_point_sampling(10, threads=2)
    assert np.array_equal(s1, s2) and np.array_equal(sl1, sl2) and np.all(np.abs(sd2 - sd1) <= 1e-12 * sd1)
    out = tmp_path / "lm.npy"
    r = run_cli("logmap", SPOT, "--from", "v:5", "--threads", "2", "-o", str(out), "--quiet")
    assert r.returncode == 0, r.stderr
    lm = np.load(out)
    assert np.array_equal(lm[:, 0], r2) and np.array_equal(lm[:, 1], t2)
    for call in (lambda t: spot.field_at(0, pts, threads=t), lambda t: spot.log_map(5, threads=t),
                 lambda t: spot.voronoi([0, 9], threads=t), lambda t: spot.isolines(0, 0.3, threads=t),
                 lambda t: spot.farthest_point_sampling(3, threads=t)):
        for bad in (-1, 1.5, True, "2"):
            with pytest.raises(trigeo.InvalidArgumentError, match="threads"):
                call(bad)
