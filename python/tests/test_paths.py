"""Path methods: the default is the exact method (globally shortest, proven); straightening is
asked for by name and is locally shortest, unproven unless certified."""
import numpy as np

import trigeo


def test_default_is_exact(spot):
    for a, b in ((0, 2000), (17, 2900), (trigeo.SurfacePoint.face(100, (0.2, 0.3, 0.5)), 1500)):
        p, e = spot.path(a, b), spot.path(a, b, method="exact")
        assert p.length == e.length and np.array_equal(p.points, e.points)
        assert p.global_ == "proven" and p.proven and p.status == "converged"
        # no edge path is computed: the view repeats the length, no sweeps
        assert p.initial_length == p.length and p.iterations == 0
        assert p.max_angle_defect <= 1e-10


def test_straighten_by_name_is_unproven_and_never_shorter(spot):
    pairs = np.array([[0, 2000], [17, 2900], [5, 1234], [300, 2500]])
    exact = spot.path_lengths(pairs)
    assert np.array_equal(exact, spot.path_lengths(pairs, method="exact"))
    straight = spot.path_lengths(pairs, method="straighten")
    assert (straight >= exact * (1 - 1e-12)).all()
    for (a, b), d in zip(pairs, exact):
        s = spot.path(int(a), int(b), method="straighten")
        assert s.global_ == "unproven" and s.initial_length >= s.length
        c = spot.path(int(a), int(b), method="straighten", certify=True)
        assert c.global_ == "proven" and abs(c.length - d) <= 1e-9 * d
