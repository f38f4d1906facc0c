# SPDX-License-Identifier: MIT
"""Shapes: constructors, support mappings and bounds against closed forms, lifetime."""

import gc
import math

import numpy as np
import pytest

import kairos

H = math.sqrt(0.5)  # cos and sin of 45 degrees


def approx(v, want, tol=1e-12):
    assert np.allclose(v, want, atol=tol, rtol=0), (v, want)


def test_sphere_box_support_and_bounds():
    s = kairos.Sphere(2.0)
    approx(s.support((0, 0, 5)), (0, 0, 2))
    approx(s.support(np.array([-1.0, 0, 1])), (-math.sqrt(2), 0, math.sqrt(2)))
    approx(s.bounds((1, 2, 3, 0, 0, 0, 1)), [(-1, 0, 1), (3, 4, 5)])
    b = kairos.Box(np.array([1.0, 2.0, 3.0]))
    approx(b.support([1, -1, -1]), (1, -2, -3))
    # A quarter turn about x swaps the y and z extents.
    approx(b.bounds(kairos.Pose((0, 0, 0), (H, 0, 0, H))), [(-1, -3, -2), (1, 3, 2)])
    approx(b.bounds(), [(-1, -2, -3), (1, 2, 3)])
    assert isinstance(b.support((1, 1, 1)), tuple)


def test_capsule_cylinder_cone_point_segment():
    approx(kairos.Capsule(0.5, 1.0).support((0, 0, -3)), (0, 0, -1.5))
    approx(kairos.Capsule(0.5, 0.0).bounds(), [(-0.5,) * 3, (0.5,) * 3])
    cyl = kairos.Cylinder(1.0, 2.0)
    approx(cyl.support((1, 0, 1)), (1, 0, 2))
    approx(cyl.bounds(), [(-1, -1, -2), (1, 1, 2)])
    cone = kairos.Cone(1.0, 2.0)
    approx(cone.support((0, 0, 1)), (0, 0, 2))
    approx(cone.support((0, 1, -1)), (0, 1, -2))
    approx(kairos.Point().support((3, -2, 1)), (0, 0, 0))
    seg = kairos.Segment(0.75)
    approx(seg.support((0, 0, -1)), (0, 0, -0.75))
    approx(seg.bounds((1, 0, 0, 0, 0, 0, 1)), [(1, 0, -0.75), (1, 0, 0.75)])


def test_convex_hull_and_triangle():
    corners = [(x, y, z) for x in (-1.0, 2.0) for y in (-1.0, 1.0) for z in (0.0, 1.0)]
    hull = kairos.ConvexHull(np.array(corners + [(0.5, 0, 0.5)]))  # an interior point too
    approx(hull.support((1, 1, 1)), (2, 1, 1))
    approx(hull.bounds(), [(-1, -1, 0), (2, 1, 1)])
    flat = kairos.ConvexHull([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)])
    assert flat.support((1, 1, 5)) == (1.0, 1.0, 0.0)
    tri = kairos.Triangle((0, 0, 0), (2, 0, 0), (0, 3, 0))
    approx(tri.support((-1, 1, 0)), (0, 3, 0))
    approx(tri.bounds((0, 0, 1, 0, 0, 0, 1)), [(0, 0, 1), (2, 3, 1)])
    with pytest.raises(kairos.DegenerateError) as info:
        kairos.ConvexHull([])
    assert isinstance(info.value, ValueError) and info.value.status == -4
    with pytest.raises(kairos.DegenerateError) as info:
        kairos.Triangle((0, 0, 0), (1, 0, 0), (2, 0, 0))
    assert "kairos_shape_triangle" in str(info.value)
    with pytest.raises(ValueError):
        kairos.ConvexHull([(0, 0), (1, 1)])


def test_composites_retain_their_parts():
    cone = kairos.Cone(1.0, 2.0)
    moved = kairos.transformed(cone, [[1, 0, 0], [0, 3, 0], [0, 0, 1]], (0, 0, 10))
    sphere = kairos.Sphere(0.5)
    box = kairos.Box((1, 1, 1))
    rounded = kairos.minkowski_sum(box, sphere)
    both = kairos.hull(kairos.transformed(sphere, None, (-3, 0, 0)), box)
    # The library holds the parts: dropping and closing them in Python changes nothing.
    cone.close()
    del sphere, box
    gc.collect()
    approx(moved.support((0, 1, -1)), (0, 3, 8))
    approx(moved.support(np.array([0, 1, -1])), (0, 3, 8))
    approx(rounded.bounds(), [(-1.5,) * 3, (1.5,) * 3])
    assert rounded.support((1, 0, 0))[0] == 1.5  # the box face (x = 1) plus the radius
    approx(both.bounds(), [(-3.5, -1, -1), (1, 1, 1)])
    assert isinstance(moved, kairos.Transformed) and isinstance(both, kairos.HullOfTwo)
    assert isinstance(rounded, kairos.MinkowskiSum) and rounded.kind == "minkowski_sum"
    mirrored = kairos.transformed(kairos.Cone(1.0, 2.0), np.diag([1.0, 1.0, -1.0]).ravel())
    approx(mirrored.support((0, 0, -1)), (0, 0, -2))
    with pytest.raises(kairos.InvalidArgumentError):
        kairos.transformed(moved, np.zeros((3, 3)))
    with pytest.raises(ValueError):
        kairos.transformed(moved, np.eye(2))


def test_constructor_errors_name_the_argument():
    for bad in (-1.0, 0.0, float("nan"), float("inf")):
        with pytest.raises(kairos.InvalidArgumentError) as info:
            kairos.Sphere(bad)
        assert "radius" in str(info.value) and info.value.status_name == \
            "KAIROS_ERROR_INVALID_ARGUMENT"
    with pytest.raises(kairos.InvalidArgumentError, match="half_extents"):
        kairos.Box((1, -2, 1))
    with pytest.raises(kairos.InvalidArgumentError, match="half_height"):
        kairos.Cylinder(1, -1)
    with pytest.raises(kairos.InvalidArgumentError):
        kairos.Capsule(1, 2e100)
    with pytest.raises(ValueError):
        kairos.Box((1, 2))
    with pytest.raises(TypeError):
        kairos.Shape()
    with pytest.raises(kairos.InvalidArgumentError, match="direction"):
        kairos.Sphere(1).support((0, float("inf"), 0))
    with pytest.raises(kairos.InvalidArgumentError, match="pose"):
        kairos.Sphere(1).bounds((0, 0, 0, 0, 0, 0, 0.5))


def test_close_is_idempotent_and_closed_shapes_raise():
    s = kairos.Sphere(1.0)
    assert s.handle and not s.closed
    s.close()
    s.close()
    assert s.handle == 0 and s.closed and "closed" in repr(s)
    with pytest.raises(kairos.NullArgumentError):
        s.support((1, 0, 0))
    with pytest.raises(kairos.NullArgumentError):
        kairos.distance(s, None, kairos.Sphere(1), None)
    with kairos.Box((1, 1, 1)) as b:
        assert b.support((1, 1, 1)) == (1.0, 1.0, 1.0)
    assert b.closed


def test_retain_handle():
    s = kairos.Sphere(1.0)
    h = s.retain_handle()
    s.close()
    # Our own reference keeps the C shape alive.
    out = kairos._capi.Vec3()
    assert kairos._capi.lib.kairos_shape_support(h, kairos._capi.Vec3(1, 0, 0), out) == 0
    assert out.x == 1.0
    kairos._capi.lib.kairos_shape_release(h)


def test_shape_array():
    a, b = kairos.Sphere(1.0), kairos.Box((1, 1, 1))
    arr = kairos.ShapeArray([a, b, a])
    assert len(arr) == 3 and arr.handles.dtype == np.uint64
    assert list(arr.handles) == [a.handle, b.handle, a.handle]
    assert not arr.handles.flags.writeable
    picked = kairos.ShapeArray([a, b], np.array([1, 1, 0, 1]))
    assert list(picked.handles) == [b.handle, b.handle, a.handle, b.handle]
    # The array holds its own references: closing the Python shapes keeps it usable.
    handle_a = a.handle
    a.close()
    r = kairos.distance_batch(picked, None, picked, np.array([[3.0, 0, 0, 0, 0, 0, 1]] * 4))
    assert r["distance"][2] == pytest.approx(1.0)  # sphere vs sphere 3 apart
    assert handle_a in picked.handles
    with pytest.raises(ValueError):
        kairos.ShapeArray([a])  # closed
    with pytest.raises(TypeError):
        kairos.ShapeArray([b, 3])
    with pytest.raises(IndexError):
        kairos.ShapeArray([b], [0, 1])
    with picked:
        pass
    assert "closed" in repr(picked)
    with pytest.raises(ValueError):
        kairos.distance_batch(picked, None, b, np.zeros((4, 7)))
    picked.close()
    arr.close()


def test_repr():
    assert repr(kairos.Sphere(1.5)) == "<kairos.Sphere sphere(radius=1.5)>"
    assert "points=4" in repr(kairos.ConvexHull(np.eye(4, 3)))
