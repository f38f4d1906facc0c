# SPDX-License-Identifier: MIT
"""Batches: bit for bit the single calls, broadcasting, and refused batches."""

import numpy as np
import pytest

import kairos
from conftest import SEED, random_poses

N = 2000


def bits(x):
    """Raw bits of a float or int array (or of a list of Python floats / tuples)."""
    a = np.ascontiguousarray(x)
    return a.view(np.uint64) if a.dtype == np.float64 else a


def assert_same_bits(batch, singles, fields, seed):
    for name in fields:
        got = bits(batch[name])
        want = bits(np.array([getattr(s, name) for s in singles],
                             dtype=batch.dtype.fields[name][0].base))
        bad = np.nonzero((got != want).reshape(len(got), -1).any(axis=1))[0]
        assert bad.size == 0, f"seed {seed}: field {name} differs at queries {bad[:10]}"


@pytest.fixture(scope="module")
def pool():
    with kairos.World(worker_count=3) as w:
        yield w


def scene(zoo, n, seed):
    rng = np.random.default_rng(seed)
    k = len(zoo)
    ia = np.arange(n) % k
    ib = (np.arange(n) // k) % k
    return dict(
        a=[zoo[i] for i in ia], b=[zoo[i] for i in ib],
        arr_a=kairos.ShapeArray(zoo, ia), arr_b=kairos.ShapeArray(zoo, ib),
        pa=random_poses(rng, n, 1.0), pb=random_poses(rng, n, 1.0),
        ta=rng.uniform(-2, 2, size=(n, 3)), tb=rng.uniform(-2, 2, size=(n, 3)),
        ea=random_poses(rng, n, 1.0), eb=random_poses(rng, n, 1.0),
    )


DIST_FIELDS = ("distance", "point_a", "point_b", "axis", "intersecting", "iterations",
               "termination")
CAST_FIELDS = ("hit", "toi", "point", "normal", "iterations", "termination")


def test_distance_batch_equals_single_calls(zoo, pool):
    q = scene(zoo, N, SEED)
    settings = kairos.QuerySettings()
    singles = [kairos.distance(q["a"][i], q["pa"][i], q["b"][i], q["pb"][i], settings)
               for i in range(N)]
    rate = np.mean([s.intersecting for s in singles])
    assert 0.1 < rate < 0.9, f"seed {SEED}: intersecting rate {rate}"
    for workers in (None, pool):
        for a, b in ((q["arr_a"], q["arr_b"]), (q["a"], q["b"])):
            out = kairos.distance_batch(a, q["pa"], b, q["pb"], settings, workers=workers)
            assert out.dtype == kairos.DISTANCE_DTYPE and out.shape == (N,)
            assert_same_bits(out, singles, DIST_FIELDS, SEED)
    # Signed distance has no batch; its results agree with distance when apart.
    s = kairos.signed_distance(q["a"][0], q["pa"][0], q["b"][0], q["pb"][0])
    assert (s.distance >= 0) == (not s.intersecting) or s.distance == 0


def test_shape_cast_batch_equals_single_calls(zoo, pool):
    q = scene(zoo, N, SEED + 1)
    singles = [kairos.shape_cast(q["a"][i], q["pa"][i], q["ta"][i], q["b"][i], q["pb"][i],
                                 q["tb"][i]) for i in range(N)]
    hits = np.array([s.hit for s in singles])
    later = np.array([s.hit and s.toi > 0 for s in singles])
    assert 0.1 < hits.mean() < 0.9, f"seed {SEED + 1}: hit rate {hits.mean()}"
    assert later.mean() > 0.05, f"seed {SEED + 1}"
    for workers in (None, pool):
        out = kairos.shape_cast_batch(q["arr_a"], q["pa"], q["ta"], q["arr_b"], q["pb"], q["tb"],
                                      workers=workers)
        assert out.dtype == kairos.CAST_DTYPE
        assert_same_bits(out, singles, CAST_FIELDS, SEED + 1)
    # None arrays: identity poses and zero translations on that side.
    out = kairos.shape_cast_batch(q["a"], None, None, q["b"], q["pb"], q["tb"])
    some = range(0, N, 37)
    one = [kairos.shape_cast(q["a"][i], None, None, q["b"][i], q["pb"][i], q["tb"][i])
           for i in some]
    assert_same_bits(out[list(some)], one, CAST_FIELDS, SEED + 1)


def test_motion_cast_batch_equals_single_calls(zoo, pool):
    n = 600
    q = scene(zoo, n, SEED + 2)
    settings = kairos.QuerySettings(tolerance=1e-6)
    ma = np.stack([q["pa"], q["ea"]], axis=1)  # (n, 2, 7)
    mb = np.hstack([q["pb"], q["eb"]])          # (n, 14)
    singles = [kairos.motion_cast(q["a"][i], ma[i], q["b"][i], mb[i], settings) for i in range(n)]
    rate = np.mean([s.hit for s in singles])
    assert 0.1 < rate < 0.9, f"seed {SEED + 2}: hit rate {rate}"
    for workers in (None, pool):
        out = kairos.motion_cast_batch(q["arr_a"], ma, q["arr_b"], mb, settings, workers=workers)
        assert_same_bits(out, singles, CAST_FIELDS, SEED + 2)


def test_broadcasting(zoo):
    rng = np.random.default_rng(SEED + 3)
    n = 50
    poses = random_poses(rng, n, 1.0)
    sphere, box = zoo[1], zoo[0]
    pose = poses[7]
    t = np.array([0.5, -1.0, 2.0])
    out = kairos.shape_cast_batch(sphere, pose, t, box, poses, None)
    full = kairos.shape_cast_batch([sphere] * n, np.tile(pose, (n, 1)), np.tile(t, (n, 1)),
                                   [box] * n, poses, np.zeros((n, 3)))
    assert all(np.array_equal(bits(out[f]), bits(full[f])) for f in CAST_FIELDS)
    # Lists and Pose objects as rows; float32 and non-contiguous arrays are converted.
    d1 = kairos.distance_batch(sphere, None, box, poses.tolist())
    d2 = kairos.distance_batch(sphere, None, box, np.asfortranarray(poses))
    d3 = kairos.distance_batch(sphere, [0, 0, 0, 0, 0, 0, 1], box, poses)
    for f in DIST_FIELDS:
        assert np.array_equal(bits(d1[f]), bits(d2[f])) and np.array_equal(bits(d1[f]), bits(d3[f]))
    m = kairos.Motion(kairos.Pose(), kairos.Pose((1, 0, 0)))
    r = kairos.motion_cast_batch(sphere, m.to_array(), box, np.hstack([poses, poses]))
    r2 = kairos.motion_cast_batch(sphere, m.to_array().reshape(2, 7), box,
                                  np.stack([poses, poses], axis=1))
    assert np.array_equal(bits(r["toi"]), bits(r2["toi"]))
    single = kairos.motion_cast(sphere, m, box, (poses[3], poses[3]))
    assert r["toi"][3] == single.toi and bool(r["hit"][3]) == single.hit
    # Pose and Motion objects instead of rows (converted one by one).
    objs = kairos.distance_batch(sphere, None, box, [kairos.Pose.from_sequence(p) for p in poses])
    assert np.array_equal(bits(objs["distance"]), bits(d1["distance"]))
    motions = [kairos.Motion(kairos.Pose.from_sequence(p), kairos.Pose.from_sequence(p))
               for p in poses]
    r3 = kairos.motion_cast_batch(sphere, m, box, motions)
    assert np.array_equal(bits(r3["toi"]), bits(r["toi"]))
    # Empty batches.
    assert kairos.distance_batch(sphere, None, box, np.zeros((0, 7))).shape == (0,)
    assert kairos.shape_cast_batch([], None, None, [], None, None).shape == (0,)


def test_preallocated_out(zoo):
    rng = np.random.default_rng(SEED + 4)
    poses = random_poses(rng, 100, 1.0)
    out = np.zeros(100, dtype=kairos.DISTANCE_DTYPE)
    got = kairos.distance_batch(zoo[0], None, zoo[2], poses, out=out)
    assert got is out and np.any(out["distance"] != 0)
    for bad in (np.zeros(99, kairos.DISTANCE_DTYPE), np.zeros(100, kairos.CAST_DTYPE),
                np.zeros(200, kairos.DISTANCE_DTYPE)[::2]):
        with pytest.raises(ValueError):
            kairos.distance_batch(zoo[0], None, zoo[2], poses, out=bad)


def test_refused_batches_name_the_first_bad_query_and_write_nothing(zoo, pool):
    n = 50
    q = scene(zoo, n, SEED + 5)
    # Raw bytes, padding included (a structured copy need not copy padding).
    out_d = np.full(96 * n, 0xA5, dtype=np.uint8).view(kairos.DISTANCE_DTYPE)
    out_c = np.full(72 * n, 0x5A, dtype=np.uint8).view(kairos.CAST_DTYPE)

    def refused(cls, needle, fn, *args, **kw):
        with pytest.raises(cls) as info:
            fn(*args, **kw)
        assert needle in str(info.value), str(info.value)
        assert np.all(out_d.view(np.uint8) == 0xA5) and np.all(out_c.view(np.uint8) == 0x5A)
        return info.value

    for workers in (None, pool):
        kw_d = dict(workers=workers, out=out_d)
        kw_c = dict(workers=workers, out=out_c)
        bad = q["pa"].copy()
        bad[5, 6] += 0.5
        e = refused(kairos.InvalidArgumentError, "poses_a[5].orientation must be a unit quaternion",
                    kairos.distance_batch, q["arr_a"], bad, q["arr_b"], q["pb"], **kw_d)
        assert e.status == -2 and isinstance(e, ValueError)
        holes = list(q["b"])
        closed = kairos.Sphere(1.0)
        closed.close()
        holes[17] = closed
        later = q["pa"].copy()
        later[23, 6] += 0.5
        # A NULL shape at 17 comes before the bad pose at 23: it is the one named.
        refused(kairos.NullArgumentError, "b[17] is NULL",
                kairos.distance_batch, q["a"], later, holes, None, **kw_d)
        last = q["pb"].copy()
        last[n - 1, 1] = np.nan
        refused(kairos.InvalidArgumentError, "poses_b[49].position.y must be finite",
                kairos.distance_batch, q["a"], None, q["b"], last, **kw_d)
        far = q["tb"].copy()
        far[8, 2] = 1e300
        refused(kairos.InvalidArgumentError, "translations_b[8].z",
                kairos.shape_cast_batch, q["a"], None, None, q["b"], None, far, **kw_c)
        mb = np.hstack([q["pb"], q["eb"]])
        mb[5, 7 + 3] = np.inf
        refused(kairos.InvalidArgumentError, "motions_b[5].end.orientation.x must be finite",
                kairos.motion_cast_batch, q["a"], np.hstack([q["pa"], q["ea"]]), q["b"], mb,
                **kw_c)
        refused(kairos.InvalidArgumentError, "settings->tolerance must be in (0, 1)",
                kairos.shape_cast_batch, q["a"], None, None, q["b"], None, None,
                kairos.QuerySettings(tolerance=1.0), **kw_c)
    # Refused in Python before the library: shapes of arrays, counts, arguments.
    refused(ValueError, "disagree", kairos.distance_batch, q["a"], q["pa"][:10], q["b"], None,
            out=out_d)
    refused(ValueError, "cannot tell", kairos.distance_batch, zoo[0], None, zoo[1], None)
    refused(ValueError, "poses_b must have shape", kairos.distance_batch, zoo[0], None, zoo[1],
            np.zeros((n, 6)))
    refused(ValueError, "motions_a", kairos.motion_cast_batch, zoo[0], None, zoo[1],
            np.zeros((n, 14)))
    refused(TypeError, "a must be", kairos.distance_batch, [1, 2], None, zoo[1], q["pb"][:2])
    refused(TypeError, "workers", kairos.distance_batch, q["a"], None, q["b"], None,
            workers="pool")
    dead = kairos.World()
    dead.close()
    refused(ValueError, "closed", kairos.distance_batch, q["a"], None, q["b"], None, workers=dead)
    # out may not overlap an input: a pose array viewed as the result array.
    shared = np.zeros((n, 96 // 8))
    with pytest.raises(ValueError, match="overlap"):
        kairos.distance_batch(q["a"], shared.reshape(-1)[:7 * n].reshape(n, 7), q["b"], None,
                              out=shared.view(np.uint8).reshape(-1).view(kairos.DISTANCE_DTYPE))
