"""Path methods: the default is the exact method (globally shortest, proven); straightening is
asked for by name and is locally shortest, unproven unless certified."""
import numpy as np
import pytest

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


def test_points_of_zero_area_faces_and_degenerate_neighbourhoods():
    """tm_capsule.obj has 200 zero-area faces at its poles. A point of such a face lies on an edge
    of the faces around it: the field must reach it straight through them (before, it bent at a
    corner and came out 1.2e-5 too long, so a shorter straightened path was "proven"), and the
    default path to it is the exact one. A path traced next to those faces can have a large
    certificate yet the exact length: it is the shortest, and proven."""
    from conftest import corpus
    m = trigeo.load(corpus("tm_capsule.obj"))
    a = trigeo.SurfacePoint.face(5426, (0.22236331016142988, 0.3286156411819707, 0.4490210486565995))
    b = trigeo.SurfacePoint.face(24, (0.304267763672446, 0.37310857120287727, 0.3226236651246766))
    ab, ba = m.field_at([a], [b])[0], m.field_at([b], [a])[0]
    assert abs(ab - ba) <= 1e-12 * ab
    s = m.path(a, b, method="straighten")
    assert ab <= s.length * (1 + 1e-12)  # no real path is shorter than the exact distance
    p = m.path(a, b)
    assert p.proven and abs(p.length - ab) <= 1e-9 * ab
    q = m.path(a, 4907)
    d = m.field_at([a], [4907])[0]
    assert q.proven and abs(q.length - d) <= 1e-9 * d


def test_points_of_duplicate_faces():
    """tm_chair_model.obj is a double-sided sheet: each face is also present with the opposite
    winding, and the copy of higher index is not part of the surface. A point given in such a copy
    is the same point of the kept face (before, a source there reached the surface only through its
    corners: distances were 0.3% too long and not symmetric, and such paths were "proven")."""
    from conftest import corpus
    m = trigeo.load(corpus("tm_chair_model.obj"))
    a = trigeo.SurfacePoint.face(3484, (0.3440219962581603, 0.23812283626972908, 0.41785516747211054))
    b = trigeo.SurfacePoint.face(892, (0.28898586762277967, 0.0565452398853585, 0.6544688924918618))
    ab, ba = m.field_at([a], [b])[0], m.field_at([b], [a])[0]
    assert abs(ab - ba) <= 1e-12 * ab
    for p, q in ((a, b), (b, a)):
        path = m.path(p, q)
        assert path.proven and abs(path.length - ab) <= 1e-9 * ab
        assert m.path(p, q, method="straighten").length >= ab * (1 - 1e-12)


def test_mixed_endpoint_lists(spot):
    """A list may mix the three kinds of endpoint (README: "a vertex index, a SurfacePoint or an
    (x, y, z)"): the same answers as the list of the SurfacePoints they stand for. A list of
    vertices and positions without a SurfacePoint once failed inside numpy (a ragged array)."""
    xyz = (0.2, 0.1, 0.5)
    sp = spot.locate(xyz)
    fp = trigeo.SurfacePoint(10, (0.2, 0.3, 0.5))
    mixed, same = [5, xyz, (0, 0, 0)], [trigeo.SurfacePoint.vertex(5), sp, spot.locate((0, 0, 0))]
    assert np.array_equal(spot.field_at([0], mixed), spot.field_at([0], same))
    assert np.array_equal(spot.distance_matrix([0, xyz], targets=mixed),
                          spot.distance_matrix([trigeo.SurfacePoint.vertex(0), sp], targets=same))
    assert np.array_equal(spot.path_lengths(froms=[0, xyz], tos=[100, fp]),
                          spot.path_lengths(froms=[trigeo.SurfacePoint.vertex(0), sp], tos=[trigeo.SurfacePoint.vertex(100), fp]))
    assert np.array_equal(spot.field([0, xyz]), spot.field([trigeo.SurfacePoint.vertex(0), sp]))
    for bad in ([0, (1.0, 2.0)], [0, "v:1"], [0, None], [0, 99999]):
        with pytest.raises(trigeo.InvalidArgumentError):
            spot.field_at([0], bad)
