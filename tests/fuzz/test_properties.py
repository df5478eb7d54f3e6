"""Property-based tests (hypothesis) over the geometric and array-taking API: NaN, inf, huge, empty,
wrong shape, wrong dtype, non-contiguous input. The property is always the same: a call either
returns an answer of the documented shape, or raises ValueError / TypeError; nothing else, and never a
silent answer for a non-finite input. Profile "short" (seeded, `make test`) or "long" (`make fuzz`):
OCTOREACH_FUZZ_PROFILE."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import octoreach as o

FLOATS = st.floats(allow_nan=True, allow_infinity=True, width=64)
NICE = st.floats(min_value=-5, max_value=5, allow_nan=False, allow_infinity=False)
SPECIAL = st.sampled_from([np.nan, np.inf, -np.inf, 1e300, -1e300, 1e17, 0.0, -0.0, 5e-324])
VALUES = st.one_of(NICE, SPECIAL, FLOATS)
BAD = (ValueError, TypeError)


def arrays(cols, max_rows=12, dtype=np.float64, elements=VALUES):
    return hnp.arrays(dtype, st.tuples(st.integers(0, max_rows), st.just(cols)), elements=elements)


@st.composite
def array_like(draw, cols):
    """(N, cols) float arrays, sometimes non-contiguous, sometimes another dtype, shape or kind."""
    kind = draw(st.integers(0, 9))
    if kind <= 5:
        a = draw(arrays(cols))
        if kind == 1 and a.shape[0] > 0:
            a = np.repeat(a, 2, axis=0)[::2]  # non-contiguous rows
        if kind == 2:
            a = np.asfortranarray(a)
        return a
    if kind == 6:
        return draw(hnp.arrays(np.int64, (draw(st.integers(0, 5)), cols), elements=st.integers(-2**62, 2**62)))
    if kind == 7:
        return draw(hnp.arrays(np.float64, draw(hnp.array_shapes(min_dims=0, max_dims=3, max_side=4)), elements=VALUES))
    if kind == 8:
        return np.array([["a"] * cols])
    return draw(st.sampled_from([None, [], [[1, 2]], "x", 3.0, [[np.nan] * cols]]))


def expect_answer_or_rejection(f, x, n_rows_out=None):
    try:
        out = f(x)
    except BAD:
        return None
    a = np.asarray(x, dtype=float) if not isinstance(x, (str, type(None))) else None
    if a is not None and a.size and not np.all(np.isfinite(a)):
        pytest.fail(f"answered {out!r} for non-finite input")
    if n_rows_out is not None and a is not None and a.ndim == 2:
        assert len(out) == a.shape[0]
    return out


@given(array_like(3))
def test_surface_contains(world, x):
    expect_answer_or_rejection(world["surface"].contains, x, n_rows_out=True)


@given(array_like(3))
def test_capability_reachability(world, x):
    expect_answer_or_rejection(world["cap"].reachability, x, n_rows_out=True)


@given(array_like(4))
def test_surface_and_point_map_lookups(world, x):
    expect_answer_or_rejection(world["sm"].reachability, x, n_rows_out=True)
    expect_answer_or_rejection(world["pm"].reachability, x, n_rows_out=True)


@given(array_like(3))
def test_exploration_state(world, x):
    # state() answers Unknown outside the map, including for non-finite points (documented): shape only
    try:
        out = world["m"].state(x)
    except BAD:
        return
    assert len(out) == np.asarray(x).shape[0]


@given(st.lists(VALUES, min_size=3, max_size=3))
def test_point_queries(world, p):
    finite = all(np.isfinite(p))
    for f in (world["m"].inside_hull,):
        try:
            f(p)
            assert finite
        except BAD:
            assert not finite or max(abs(v) for v in p) > 1e3
    try:
        world["scene"].raycast(p, [1, 0, 0])
        assert finite
    except BAD:
        assert not finite


@given(st.lists(VALUES, min_size=3, max_size=3), st.lists(VALUES, min_size=3, max_size=3))
def test_collides_box(world, size, t):
    pose = np.eye(4)
    pose[:3, 3] = t
    ok = all(np.isfinite(size)) and all(np.isfinite(t)) and min(size) >= 0 and max(size) <= 1e6
    try:
        world["obs"].collides_box(size, pose)
        assert ok
    except BAD:
        pass


@given(array_like(3), st.lists(VALUES, min_size=3, max_size=3))
def test_exploration_insert(world, pts, origin):
    m = o.ExplorationMap(resolution=0.1)
    try:
        st_ = m.insert(pts, origin)
    except BAD:
        return
    assert all(np.isfinite(origin))
    assert st_["points"] + st_["dropped"] == np.asarray(pts).shape[0]
    s, r = m.snapshot(), m.recompute_from_scratch()
    assert np.array_equal(s["frontier_cells"], r["frontier_cells"])


@given(array_like(6))
def test_chain_fk_and_wrap(world, q):
    c = world["chain"]
    try:
        T = c.fk_batch(q)
    except BAD:
        return
    assert T.shape == (np.asarray(q).shape[0], 4, 4)
    for row in np.asarray(q, dtype=float)[:3]:
        try:
            c.wrap(row)
        except BAD:
            pass


@given(st.lists(VALUES, min_size=3, max_size=3))
def test_ik_targets(world, t):
    c = world["chain"]
    T = np.eye(4)
    T[:3, 3] = t
    try:
        c.ik(T, attempts=2, max_iterations=20)
    except BAD:
        assert not all(np.isfinite(t))


@given(arrays(3, max_rows=6, dtype=np.float64), arrays(3, max_rows=6, dtype=np.int64, elements=st.integers(-2**40, 2**40)))
def test_meshes(world, v, tri):
    for add in (lambda: o.Scene().add_mesh(v, tri), lambda: o.Obstacles().add_triangles(v, tri)):
        try:
            add()
        except BAD:
            continue
        assert np.all(np.isfinite(v)) and (tri.size == 0 or (tri.min() >= 0 and tri.max() < len(v)))


@given(st.integers(-2**63, 2**63 - 1), st.integers(-10, 400), st.integers(-2, 70))
def test_orientation_set_counts(count, rolls, symmetry):
    try:
        s = o.OrientationSet.sphere(count, rolls=rolls, symmetry=symmetry) if count <= 2000 else None
    except BAD:
        return
    if s is None:
        with pytest.raises(BAD):
            if count > 100000:
                o.OrientationSet.sphere(count, rolls=rolls, symmetry=symmetry)
            else:
                raise ValueError("skipped: large but valid")
        return
    assert 1 <= count and 1 <= rolls and 1 <= symmetry <= 64
    assert len(s) == s.directions.shape[0] * rolls


@given(st.lists(VALUES, min_size=3, max_size=3))
def test_nearest_direction(d):
    s = o.OrientationSet.sphere(50)
    try:
        k = s.nearest_direction(d)
    except BAD:
        assert not all(np.isfinite(d)) or not any(d)
        return
    assert 0 <= k < len(s.directions) and all(np.isfinite(d))  # sphere(50): 52 (rounded to a multiple of symmetry 4)
