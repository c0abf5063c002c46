"""Python threads query one Mesh at once (the GIL is released in C calls), and Ctrl-C stops a
long field."""
import os
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np

import trigeo
from conftest import REPO, SPOT, grid, interrupt


def test_threads_share_a_mesh():
    m = trigeo.load(SPOT)
    rng = np.random.default_rng(5)
    q = rng.uniform(-1, 1, size=(3000, 3))
    pairs = rng.integers(0, m.vertex_count, size=(40, 2))
    want_d = m.closest(q, threads=1)[0]
    want_l = m.path_lengths(pairs, threads=1)
    want_f = m.field(17)
    errors, results = [], []

    def work(k):
        try:
            for _ in range(3):
                results.append(("c", np.array_equal(m.closest(q, threads=1)[0], want_d)))
                results.append(("p", np.array_equal(m.path_lengths(pairs, threads=1), want_l)))
                results.append(("f", np.array_equal(m.field(17), want_f)))
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    ts = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert not errors and len(results) == 36 and all(ok for _, ok in results)


def test_gil_released_during_c_calls():
    """While one thread is inside a long C call, another thread keeps running Python code."""
    v, f = grid(150, 0.3)  # a field of about 0.3 s (grid(400): 4 s, the longest Python test)
    m = trigeo.Mesh(v, f)
    ticks = []
    done = threading.Event()

    def ticker():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=ticker)
    m._get_geo()
    t.start()
    t0 = time.perf_counter()
    m.field(0)
    t1 = time.perf_counter()
    done.set()
    t.join()
    inside = [x for x in ticks if t0 < x < t1]
    # the field takes a while; a held GIL would allow at most a tick every switch interval
    # (5 ms) and only through the progress callbacks; released, the ticker runs every ~1 ms
    assert t1 - t0 > 0.05 and len(inside) >= 0.3 * (t1 - t0) / 0.001


def test_ctrl_c_stops_long_fields():
    code = textwrap.dedent(f"""
        import sys, time
        sys.path.insert(0, {os.path.join(REPO, 'python')!r})
        sys.path.insert(0, {os.path.dirname(__file__)!r})
        import trigeo
        from conftest import grid
        m = trigeo.Mesh(*grid(700, 0.3))
        print("ready", flush=True)
        try:
            m.distance_matrix(list(range(0, 40000, 100)), threads=1)  # 400 fields: minutes
            print("finished", flush=True)
        except KeyboardInterrupt:
            print("interrupted %.6f" % time.process_time(), flush=True)
    """)
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True, env=os.environ.copy())
    assert p.stdout.readline().strip() == "ready"
    time.sleep(0.3)
    cpu, out = interrupt(p, timeout=900)
    # uninterrupted, the 400 fields take minutes of CPU; honoured, the interrupt ends the call
    # after a few milliseconds of it (CPU time: on a loaded machine the wall time stretches)
    assert cpu is not None and cpu < 1.0, f"{cpu} CPU seconds after the signal; {out[-1500:]}"
