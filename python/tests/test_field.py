# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

import numpy as np
import pytest

import strata
from conftest import ticks_during


def test_evaluate_shape_dtype_and_bits(small_scene):
    field = small_scene.field
    points = np.random.default_rng(7).uniform(-12.0, 12.0, (5000, 3))
    values = field.evaluate(points)
    assert values.shape == (5000,) and values.dtype == np.float64
    # The block path gives the scalar path's bits, point by point.
    scalar = np.array([field.density(p) for p in points[:300]])
    assert np.array_equal(values[:300], scalar)
    # Same bits on one thread and on all of them.
    assert np.array_equal(field.evaluate(points, threads=1), values)


def test_scattered_points_in_any_row_order_give_the_scalar_bits():
    # Rows are evaluated in blocks of nearby points: a permutation of the
    # rows permutes the values, and far-apart points (many worm cave
    # regions) keep the scalar path's bits.
    field = strata.default_scene().field
    points = np.random.default_rng(5).uniform(-90.0, 90.0, (20_000, 3))
    values = field.evaluate(points)
    permutation = np.random.default_rng(6).permutation(len(points))
    assert np.array_equal(field.evaluate(points[permutation]), values[permutation])
    scalar = np.array([field.density(p) for p in points[::97]])
    assert np.array_equal(values[::97], scalar)


def test_evaluate_takes_any_float_layout(small_scene):
    field = small_scene.field
    points = np.random.default_rng(3).uniform(-5.0, 5.0, (777, 3))
    expected = field.evaluate(points)
    assert np.array_equal(field.evaluate(points.astype(np.float32).astype(np.float64)),
                          field.evaluate(points.astype(np.float32)))
    assert np.array_equal(field.evaluate(np.asfortranarray(points)), expected)
    assert np.array_equal(field.evaluate(points.tolist()), expected)
    assert field.evaluate(np.empty((0, 3))).shape == (0,)


def test_evaluate_refuses_bad_shapes(small_scene):
    with pytest.raises(strata.BadInputError, match=r"\(N, 3\)"):
        small_scene.field.evaluate(np.zeros((10, 2)))
    with pytest.raises(strata.BadInputError) as caught:
        small_scene.field.evaluate(np.zeros((4, 3)), threads=-1)
    assert caught.value.key == "threads"


def test_evaluate_refuses_non_finite_and_far_points_naming_the_row(small_scene):
    points = np.zeros((6, 3))
    for value, column in ((np.nan, 1), (np.inf, 0), (2e9, 2)):
        bad = points.copy()
        bad[4, column] = value
        with pytest.raises(strata.BadInputError, match=r"points\[4, %d\]" % column) as caught:
            small_scene.field.evaluate(bad)
        assert caught.value.key == "points[4, %d]" % column


def test_lattice_is_the_field_at_its_points(small_scene):
    field = small_scene.field
    origin, spacing, shape = (-3.0, -2.0, 1.5), (0.5, 0.25, 0.75), (9, 17, 5)
    box = field.evaluate_lattice(origin, spacing, shape)
    assert box.shape == shape
    i, j, k = np.meshgrid(*[np.arange(n) for n in shape], indexing="ij")
    points = np.stack([origin[0] + spacing[0] * i, origin[1] + spacing[1] * j, origin[2] + spacing[2] * k], -1)
    assert np.array_equal(box, field.evaluate(points.reshape(-1, 3)).reshape(shape))


def test_far_from_origin_stays_finite(small_scene):
    points = np.array([[2.0 ** 20, 0.0, 2.0 ** 20], [1e7, 3.0, -1e7], [-1e7, -5.0, 1e7]])
    values = small_scene.field.evaluate(points)
    assert np.all(np.isfinite(values))


def test_bounds_hold_the_values(small_scene):
    field = small_scene.field
    lo, hi = field.bounds((-2.0, -1.0, -2.0), (2.0, 1.0, 2.0))
    box = field.evaluate_lattice((-2.0, -1.0, -2.0), 0.25, (17, 9, 17))
    assert lo <= box.min() and box.max() <= hi
    with pytest.raises(strata.BadInputError):
        field.bounds((1.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def test_evaluate_releases_the_gil():
    field = strata.default_scene().field
    points = np.random.default_rng(1).uniform(-90.0, 90.0, (1_500_000, 3))
    # Several passes, so the call lasts long enough for the other thread to
    # tick many times (about 2 s here); with the GIL held it could not tick at all.
    ticks, seconds = ticks_during(lambda: [field.evaluate(points, threads=1) for _ in range(3)])
    assert ticks >= 10, f"the other thread ran {ticks} times in {seconds:.2f} s"
