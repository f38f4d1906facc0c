# SPDX-License-Identifier: MIT
"""World: objects, steps, contacts against closed forms, batch moves, queries, errors."""

import math

import numpy as np
import pytest

import kairos
from conftest import SEED, make_zoo, random_poses


def at(x=0.0, y=0.0, z=0.0):
    return (x, y, z, 0.0, 0.0, 0.0, 1.0)


def test_head_on_spheres_contact_is_analytic():
    with kairos.World() as w:
        s = kairos.Sphere(1.0)
        left = w.add(s, at(-3), user_data=11)
        right = w.add(s, at(3), user_data=22)
        s.close()  # the world holds its own reference
        w.move(left, at(0))
        w.move(right, kairos.Pose((0, 0, 0)))
        w.step()
        c = w.contacts()
        assert c.dtype == kairos.CONTACT_DTYPE and c.shape == (1,)
        # Gap 4 closing at 6 per step: toi 2/3, touching at the origin, normal a -> b (+x).
        assert (c["a"][0], c["b"][0]) == (min(left, right), max(left, right))
        assert (c["user_a"][0], c["user_b"][0]) == (11, 22)
        assert c["toi"][0] == pytest.approx(2 / 3, abs=1e-9)
        assert np.allclose(c["point"][0], (0, 0, 0), atol=1e-8)
        assert np.allclose(c["normal"][0], (1, 0, 0), atol=1e-9)
        assert w.overlaps().tolist() == [[left, right]]
        stats = w.step_stats()
        assert stats.broad_phase_pairs == 1 and stats.narrow_phase_queries == 1
        assert stats.gjk_iterations >= 1 and stats.narrow_phase_seconds >= 0
        # After the step both stand at their end poses (overlapping: a contact at 0 next step,
        # the world does no response); set apart, nothing touches.
        assert w.get_pose(left) == kairos.Pose()
        w.step()
        assert w.contacts()["toi"].tolist() == [0.0]
        w.set_pose(left, at(-3))
        w.step()
        assert len(w.contacts()) == 0 and w.overlaps().shape == (0, 2)


def test_objects_poses_user_data_and_stale_ids():
    w = kairos.World(broad_phase=kairos.BroadPhase.BRUTE_FORCE, tolerance=1e-9,
                     max_iterations=64, worker_count=2)
    assert "BRUTE_FORCE" in repr(w)
    box = kairos.Box((1, 1, 1))
    a = w.add(box)
    b = w.add(box, (5, 0, 0, 0, 0, math.sqrt(0.5), math.sqrt(0.5)), user_data=2**64 - 1)
    assert a != 0 and b != a
    assert w.handle and not w.closed
    assert w.get_pose(a) == kairos.Pose()
    p = w.get_pose(b)
    assert p.position == (5.0, 0.0, 0.0)
    assert np.allclose(p.orientation, (0, 0, math.sqrt(0.5), math.sqrt(0.5)), atol=1e-15)
    assert w.get_user_data(b) == 2**64 - 1 and w.get_user_data(a) == 0
    w.set_pose(a, at(1, 2, 3))
    assert w.get_pose(a).position == (1.0, 2.0, 3.0)
    w.remove(a)
    for call in (lambda: w.remove(a), lambda: w.get_pose(a), lambda: w.move(a, at()),
                 lambda: w.get_user_data(0), lambda: w.set_static(12345, True)):
        with pytest.raises(kairos.StaleIdError) as info:
            call()
        assert isinstance(info.value, LookupError) and info.value.status == -5
    c = w.add(box)
    assert c != a  # a removed id stays stale when its slot is reused
    with pytest.raises(kairos.StaleIdError):
        w.get_pose(a)
    with pytest.raises(ValueError):
        w.add(box, user_data=-1)
    with pytest.raises(kairos.InvalidArgumentError, match="pose"):
        w.add(box, at(np.inf))
    w.close()
    w.close()
    assert w.closed and "closed" in repr(w)
    with pytest.raises(kairos.NullArgumentError):
        w.step()


def test_world_settings_are_checked():
    with pytest.raises(kairos.InvalidArgumentError, match="broad_phase"):
        kairos.World(broad_phase=99)
    with pytest.raises(kairos.InvalidArgumentError, match="tolerance"):
        kairos.World(tolerance=2.0)
    with pytest.raises(ValueError):
        kairos.World(worker_count=-1)


def test_static_and_filters():
    with kairos.World() as w:
        s = kairos.Sphere(1.0)
        wall = w.add(kairos.Box((0.5, 5, 5)), at(0))
        w.set_static(wall, True)
        with pytest.raises(kairos.InvalidArgumentError) as info:
            w.move(wall, at(1))
        assert "static" in str(info.value)
        ball = w.add(s, at(-5))
        ghost = w.add(s, at(-5, 3))
        w.set_filter(ghost, kairos.Filter(category_bits=2, mask_bits=0xFFFFFFFE))
        w.move(ball, at(5))
        w.move(ghost, at(5, 3))
        w.step()
        c = w.contacts()
        # The ball meets the wall face x = -0.5 after 3.5 of its 10: toi 0.35. The ghost's
        # mask leaves out the wall's category 1.
        assert c.shape == (1,) and set(c[0][["a", "b"]].tolist()) == {wall, ball}
        assert c["toi"][0] == pytest.approx(0.35, abs=1e-9)
        # Two statics are never tested; an object can be made dynamic again.
        w.set_static(wall, False)
        w.move(wall, at(0.1))
        w.set_static(wall, True)
        with pytest.raises(TypeError):
            w.set_filter(ball, None)
    with pytest.raises(ValueError):
        kairos.Filter(mask_bits=-1)
    with pytest.raises(ValueError):
        kairos.Filter(group=2**31)
    # A negative shared group never collides.
    with kairos.World() as w:
        s = kairos.Sphere(1.0)
        a, b = w.add(s, at(-3)), w.add(s, at(3))
        for i in (a, b):
            w.set_filter(i, kairos.Filter(group=-4))
        w.move(a, at(0))
        w.move(b, at(0))
        w.step()
        assert len(w.contacts()) == 0


def test_world_queries():
    with kairos.World(worker_count=2) as w:
        box = kairos.Box((1, 1, 1))
        first = w.add(box, at(5), user_data=100)
        second = w.add(box, at(10), user_data=101)
        hit = w.ray_cast((0, 0, 0), (10, 0, 0))
        assert isinstance(hit, kairos.WorldHit)
        assert (hit.hit, hit.id, hit.user_data) == (True, first, 100)
        assert hit.toi == pytest.approx(0.4, abs=1e-9)  # face x = 4
        assert np.allclose(hit.normal, (-1, 0, 0), atol=1e-9)
        assert np.allclose(hit.point, (4, 0, 0), atol=1e-8)
        w.set_filter(first, kairos.Filter(category_bits=2))
        only_second = w.ray_cast(np.zeros(3), np.array([10.0, 0, 0]), kairos.Filter(1, 1, 0))
        assert only_second.id == second and only_second.toi == pytest.approx(0.9, abs=1e-9)
        miss = w.ray_cast((0, 5, 0), (10, 0, 0))
        assert (miss.hit, miss.id, miss.user_data, miss.toi) == (False, 0, 0, 1.0)
        # A unit sphere swept to x = 10 meets the first face at x = 3: toi 0.3.
        sweep = w.shape_cast(kairos.Sphere(1.0), (at(), at(10)))
        assert sweep.id == first and sweep.toi == pytest.approx(0.3, abs=1e-9)
        assert np.allclose(sweep.normal, (-1, 0, 0), atol=1e-9)
        sweep = w.shape_cast(kairos.Sphere(1.0),
                             kairos.Motion(kairos.Pose(), kairos.Pose((10, 0, 0))),
                             kairos.Filter(1, 1, 0), kairos.QuerySettings(1e-8))
        assert sweep.id == second and sweep.toi == pytest.approx(0.8, abs=1e-6)
        ids = w.query_box((3.5, -1, -1), (9.5, 1, 1))
        assert ids.dtype == np.uint64 and ids.tolist() == sorted([first, second])
        assert w.query_box((3.5, -1, -1), (4.5, 1, 1)).tolist() == [first]
        assert w.query_box((3.5, -1, -1), (9.5, 1, 1), kairos.Filter(1, 1, 0)).tolist() == [second]
        with pytest.raises(kairos.InvalidArgumentError, match="min.x"):
            w.query_box((1, 0, 0), (0, 1, 1))
        # More results than the first buffer holds: queried again with room for all.
        many = [w.add(kairos.Sphere(0.1), at(20 + 0.01 * i)) for i in range(300)]
        found = w.query_box((19, -1, -1), (30, 1, 1))
        assert found.tolist() == sorted(many)
        assert w.query_box((100, 100, 100), (101, 101, 101)).shape == (0,)


def test_move_batch_equals_single_moves_and_is_all_or_nothing():
    rng = np.random.default_rng(SEED + 10)
    zoo = make_zoo()
    n = 300
    by_batch, by_call = kairos.World(), kairos.World(worker_count=3)
    start = random_poses(rng, n, 6.0)
    ids = np.array([by_batch.add(zoo[i % len(zoo)], start[i], i) for i in range(n)],
                   dtype=np.uint64)
    ids_call = [by_call.add(zoo[i % len(zoo)], start[i], i) for i in range(n)]
    assert ids.tolist() == ids_call
    by_batch.set_static(int(ids[0]), True)
    by_call.set_static(ids_call[0], True)
    total = 0
    for step in range(4):
        which = ids[1:]
        ends = random_poses(rng, n - 1, 6.0)
        bad = which.copy()
        bad[40] = ids[0]
        with pytest.raises(kairos.InvalidArgumentError, match=r"ids\[40\] is"):
            by_batch.move(bad, ends)
        bad[40] = which[40]
        bad[90] = 12345
        with pytest.raises(kairos.StaleIdError, match=r"ids\[90\] is 12345"):
            by_batch.move(bad, ends)
        bad_ends = ends.copy()
        bad_ends[100, 6] = 7.0
        with pytest.raises(kairos.InvalidArgumentError, match=r"ends\[100\]\.orientation"):
            by_batch.move(which, bad_ends)
        by_batch.move(which, ends)
        for i, e in zip(ids_call[1:], ends):
            by_call.move(i, e)
        by_batch.step()
        by_call.step()
        cb, cc = by_batch.contacts(), by_call.contacts()
        assert cb.view(np.uint8).tobytes() == cc.view(np.uint8).tobytes(), f"step {step}"
        assert np.array_equal(by_batch.overlaps(), by_call.overlaps())
        for i in (1, 77, n - 1):
            assert by_batch.get_pose(int(ids[i])) == by_call.get_pose(ids_call[i])
        total += len(cb)
    assert total > 5, f"seed {SEED + 10}: {total} contacts"
    # A refused batch leaves the next step with nothing moving; one pose broadcasts to all.
    before = by_batch.get_pose(int(ids[3]))
    with pytest.raises(kairos.StaleIdError):
        by_batch.move(np.array([ids[3], 0], dtype=np.uint64), random_poses(rng, 2, 6.0))
    by_batch.step()
    assert by_batch.get_pose(int(ids[3])) == before
    by_batch.move(ids[1:4].tolist(), at(1, 2, 3))
    by_batch.step()
    assert by_batch.get_pose(int(ids[2])).position == (1.0, 2.0, 3.0)
    by_batch.move(ids[1:3], [kairos.Pose((4, 5, 6)), kairos.Pose((7, 8, 9))])
    by_batch.step()
    assert by_batch.get_pose(int(ids[2])).position == (7.0, 8.0, 9.0)
    by_batch.move(np.array([], dtype=np.uint64), np.zeros((0, 7)))
    with pytest.raises(ValueError):
        by_batch.move(ids[1:4], np.zeros((2, 7)))
    with pytest.raises(ValueError):
        by_batch.move(ids[1:4].reshape(3, 1), at())
    by_batch.close()
    by_call.close()


def test_every_broad_phase_and_worker_count_give_the_same_contacts():
    rng = np.random.default_rng(SEED + 11)
    zoo = make_zoo()
    n = 200
    start, end = random_poses(rng, n, 4.0), random_poses(rng, n, 4.0)
    results = []
    for bp in kairos.BroadPhase:
        for workers in (0, 3):
            with kairos.World(broad_phase=bp, worker_count=workers) as w:
                ids = np.array([w.add(zoo[i % len(zoo)], start[i], i) for i in range(n)],
                               dtype=np.uint64)
                w.move(ids, end)
                w.step()
                c = w.contacts()
                results.append((bp.name, workers, c[["a", "b", "toi"]].tolist()))
    assert len(results[0][2]) > 10, f"seed {SEED + 11}"
    for name, workers, got in results[1:]:
        # ENCAPSULATING_SAP and BRUTE_FORCE find the same first contacts.
        assert got == results[0][2], f"{name} with {workers} workers, seed {SEED + 11}"
