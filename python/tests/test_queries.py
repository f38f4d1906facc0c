# SPDX-License-Identifier: MIT
"""Pair queries against closed forms; pose, motion and settings arguments."""

import math

import numpy as np
import pytest

import kairos
from conftest import SEED

H = math.sqrt(0.5)


def at(x=0.0, y=0.0, z=0.0):
    return (x, y, z, 0.0, 0.0, 0.0, 1.0)


def test_sphere_sphere_distance_closed_form(rng):
    for _ in range(200):
        r1, r2 = rng.uniform(0.1, 2.0, size=2)
        c1, c2 = rng.uniform(-5, 5, size=(2, 3))
        a, b = kairos.Sphere(r1), kairos.Sphere(r2)
        d = kairos.distance(a, at(*c1), b, at(*c2))
        gap = np.linalg.norm(c2 - c1) - r1 - r2
        msg = f"seed {SEED}"
        if gap > 0:
            assert d.distance == pytest.approx(gap, rel=1e-12, abs=1e-12), msg
            assert not d.intersecting
            u = (c2 - c1) / np.linalg.norm(c2 - c1)
            assert np.allclose(d.axis, u, atol=1e-12), msg
            assert np.allclose(d.point_a, c1 + r1 * u, atol=1e-12), msg
            assert np.allclose(d.point_b, c2 - r2 * u, atol=1e-12), msg
        else:
            assert d.distance == 0.0 and d.intersecting, msg
            s = kairos.signed_distance(a, at(*c1), b, at(*c2))
            assert s.distance == pytest.approx(gap, abs=1e-12), msg
            assert s.intersecting
    assert isinstance(d, kairos.DistanceResult) and isinstance(d.point_a, tuple)
    assert d.termination in set(kairos.Termination) and d.iterations >= 1
    with pytest.raises(Exception):
        d.distance = 3.0  # frozen


def test_box_box_axis_aligned_gaps(rng):
    settings = kairos.QuerySettings(tolerance=1e-12)
    seen_apart = seen_overlap = 0
    for _ in range(200):
        ha, hb = rng.uniform(0.2, 1.5, size=(2, 3))
        offset = rng.uniform(-4, 4, size=3)
        a, b = kairos.Box(ha), kairos.Box(hb)
        gaps = np.maximum(np.abs(offset) - ha - hb, 0.0)
        want = np.linalg.norm(gaps)
        d = kairos.distance(a, None, b, at(*offset), settings)
        assert d.distance == pytest.approx(want, rel=1e-9, abs=1e-12), f"seed {SEED}"
        assert kairos.intersect(a, None, b, at(*offset)) == (want == 0.0)
        if want == 0.0:
            seen_overlap += 1
            depth = np.min(ha + hb - np.abs(offset))
            s = kairos.signed_distance(a, None, b, at(*offset), settings)
            assert s.distance == pytest.approx(-depth, rel=1e-9, abs=1e-12), f"seed {SEED}"
            assert s.intersecting
        else:
            seen_apart += 1
    assert seen_apart > 20 and seen_overlap > 20, f"seed {SEED}"


def test_intersect_with_axis_cache():
    a, b = kairos.Box((1, 1, 1)), kairos.Sphere(0.5)
    cache = kairos.AxisCache()
    assert cache.axis == (0.0, 0.0, 0.0)
    assert kairos.intersect(a, None, b, at(3, 0, 0), cache) is False
    axis = np.array(cache.axis)
    assert np.linalg.norm(axis) > 0 and axis[0] > 0  # separating: points from a toward b
    # Seeded from the cached axis next frame, same answer.
    assert kairos.intersect(a, None, b, at(3.1, 0, 0), cache) is False
    assert kairos.intersect(a, None, b, at(1.2, 0, 0), cache) is True
    assert "AxisCache" in repr(cache)
    # A non-finite cached axis is a fresh start, not an error.
    assert kairos.intersect(a, None, b, at(1.2, 0, 0), kairos.AxisCache((np.nan, 0, 0)))


def test_ray_cast_sphere_analytic(rng):
    hits = 0
    n = 300
    for _ in range(n):
        r = rng.uniform(0.3, 2.0)
        c = rng.uniform(-2, 2, size=3)
        o = rng.uniform(-6, 6, size=3)
        # Aimed near the sphere, reaching it or not: both outcomes are common.
        d = (c + rng.uniform(-2 * r, 2 * r, size=3) - o) * rng.uniform(0.5, 2.0)
        res = kairos.ray_cast(kairos.Sphere(r), at(*c), o, d)
        # |o + t d - c| = r: a t^2 + 2 b t + k = 0.
        oc = o - c
        qa, qb, qk = d @ d, oc @ d, oc @ oc - r * r
        disc = qb * qb - qa * qk
        t = (-qb - math.sqrt(disc)) / qa if disc >= 0 else None
        if qk <= 0:
            want = 0.0  # starts inside
        elif t is not None and 0 <= t <= 1:
            want = t
        else:
            want = None
        if want is None:
            assert not res.hit and res.toi == 1.0, f"seed {SEED}"
        else:
            hits += 1
            assert res.hit and res.toi == pytest.approx(want, abs=1e-9), f"seed {SEED}"
            if want > 0:
                p = o + res.toi * d
                assert np.allclose(res.point, p, atol=1e-8)
                assert np.allclose(res.normal, (p - c) / r, atol=1e-8)
    assert 0.1 * n < hits < 0.9 * n, f"seed {SEED}: {hits} hits of {n}"


def test_shape_cast_spheres_analytic(rng):
    hits = 0
    n = 300
    for _ in range(n):
        r1, r2 = rng.uniform(0.2, 1.0, size=2)
        c1, c2 = rng.uniform(-3, 3, size=(2, 3))
        t1 = rng.uniform(-2, 2, size=3)
        # b aimed near a's path, reaching it or not.
        t2 = t1 + (c1 - c2 + rng.uniform(-2, 2, size=3)) * rng.uniform(0.5, 2.0)
        res = kairos.shape_cast(kairos.Sphere(r1), at(*c1), t1, kairos.Sphere(r2), at(*c2), t2)
        # Centre gap c(t) = (c2 - c1) + t (t2 - t1) reaches r1 + r2.
        g, v, R = c2 - c1, t2 - t1, r1 + r2
        qa, qb, qk = v @ v, g @ v, g @ g - R * R
        disc = qb * qb - qa * qk
        if qk <= 0:
            want = 0.0
        elif disc >= 0 and qa > 0 and 0 <= (-qb - math.sqrt(disc)) / qa <= 1:
            want = (-qb - math.sqrt(disc)) / qa
        else:
            want = None
        if want is None:
            assert not res.hit, f"seed {SEED}"
        else:
            hits += 1
            assert res.hit and res.toi == pytest.approx(want, abs=1e-9), f"seed {SEED}"
            if want > 0:
                gt = g + res.toi * v
                assert np.allclose(res.normal, gt / np.linalg.norm(gt), atol=1e-8)
                assert np.allclose(res.point, c1 + res.toi * t1 + r1 * gt / R, atol=1e-7)
    assert 0.1 * n < hits < 0.9 * n, f"seed {SEED}: {hits} hits of {n}"
    # None translations mean standing still.
    r = kairos.shape_cast(kairos.Sphere(1), at(), None, kairos.Sphere(1), at(5), (-4, 0, 0))
    assert r.hit and r.toi == pytest.approx(0.75)
    assert isinstance(r, kairos.CastResult) and r.termination == kairos.Termination.HIT


def test_motion_cast_rotating_rod_hits_a_wall():
    rod = kairos.Segment(1.0)  # along local z
    wall = kairos.Box((0.5, 1.0, 2.0))  # face at x = 0.5 when centred at x = 1
    quarter_turn_y = (0.0, H, 0.0, H)  # z axis -> x axis
    motion = kairos.Motion(kairos.Pose(), kairos.Pose((0, 0, 0), quarter_turn_y))
    still = kairos.Motion(kairos.Pose((1, 0, 0)), kairos.Pose((1, 0, 0)))
    tol = 1e-6
    r = kairos.motion_cast(rod, motion, wall, still, kairos.QuerySettings(tolerance=tol))
    # The tip (sin a, 0, cos a) meets x = 0.5 at a = 30 degrees: a third of the turn.
    assert r.hit and 1 / 3 - 2 * tol <= r.toi <= 1 / 3 + 1e-9
    # The same motion as a (start, end) pair, as 14 numbers, and as a (2, 7) array.
    flat = motion.to_array()
    for m in ((at(), (0, 0, 0) + quarter_turn_y), list(flat), flat, flat.reshape(2, 7)):
        again = kairos.motion_cast(rod, m, wall, (at(1), at(1)), kairos.QuerySettings(tol))
        assert again == r
    # A motion that does not turn is the shape cast.
    slide = kairos.motion_cast(kairos.Sphere(1), (at(), at(10)), wall, still)
    cast = kairos.shape_cast(kairos.Sphere(1), at(), (10, 0, 0), wall, at(1), None)
    assert slide.hit and slide.toi == cast.toi
    with pytest.raises(ValueError):
        kairos.motion_cast(rod, (1, 2, 3), wall, still)


def test_pose_arguments_and_errors():
    a, b = kairos.Sphere(1.0), kairos.Sphere(1.0)
    want = kairos.distance(a, None, b, at(5)).distance
    assert want == 3.0
    for pose in (at(5), list(at(5)), np.array(at(5)), kairos.Pose((5, 0, 0)),
                 kairos.Pose.from_sequence(at(5)), np.array(at(5), dtype=np.float32)):
        assert kairos.distance(a, kairos.IDENTITY, b, pose).distance == want
    for bad in ((1, 2, 3), np.zeros(6), "pose", np.zeros((1, 7))):
        with pytest.raises(ValueError):
            kairos.distance(a, None, b, bad)
    with pytest.raises(kairos.InvalidArgumentError) as info:
        kairos.distance(a, None, b, (0, 0, 0, 0, 0, 0, 0.9))
    assert "pose_b" in str(info.value) and "unit quaternion" in str(info.value)
    with pytest.raises(kairos.InvalidArgumentError, match="must be finite"):
        kairos.distance(a, (np.nan, 0, 0, 0, 0, 0, 1), b, None)
    for not_a_shape in ("sphere", None, 3):
        with pytest.raises(TypeError, match="a must be a kairos.Shape"):
            kairos.distance(not_a_shape, None, b, None)
    with pytest.raises(TypeError, match="shape must be a kairos.Shape"):
        kairos.ray_cast("sphere", None, (0, 0, 0), (1, 0, 0))
    p = kairos.Pose((1, 2, 3), (0, 0, H, H))
    assert p.as_tuple() == (1.0, 2.0, 3.0, 0.0, 0.0, H, H)
    assert np.array_equal(np.asarray(p), p.to_array())
    assert kairos.Pose.identity() == kairos.Pose()
    with pytest.raises(ValueError):
        kairos.Pose((1, 2), (0, 0, 0, 1))


def test_query_settings():
    s = kairos.QuerySettings()
    assert (s.tolerance, s.max_iterations) == (1e-10, 256)
    a, b = kairos.Cylinder(1, 1), kairos.Cone(1, 1)
    loose = kairos.distance(a, None, b, at(3, 0.5, 0), kairos.QuerySettings(1e-3, 5))
    tight = kairos.distance(a, None, b, at(3, 0.5, 0))
    assert loose.iterations <= 5 and tight.distance <= loose.distance * (1 + 1e-12)
    with pytest.raises(kairos.InvalidArgumentError, match="tolerance"):
        kairos.distance(a, None, b, None, kairos.QuerySettings(tolerance=1.0))
    with pytest.raises(kairos.InvalidArgumentError, match="max_iterations"):
        kairos.shape_cast(a, None, None, b, None, None, kairos.QuerySettings(max_iterations=0))
    with pytest.raises(ValueError):
        kairos.QuerySettings(max_iterations=-1)
    with pytest.raises(TypeError):
        kairos.distance(a, None, b, None, settings={"tolerance": 1e-3})
    for fn in (kairos.ray_cast,):
        with pytest.raises(kairos.InvalidArgumentError, match="translation"):
            fn(a, None, (0, 0, 0), (np.inf, 0, 0))
