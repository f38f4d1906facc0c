# SPDX-License-Identifier: MIT
"""Handles are released: 100k shapes (and worlds) created and dropped with flat memory."""

import os
import time

import numpy as np

import kairos
from conftest import SEED

PAGE = os.sysconf("SC_PAGE_SIZE")


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * PAGE


def churn(i, points, pose):
    # A hull of 32 points keeps its vertices (~1 KB): a leak of 80k of them would be ~80 MB.
    hull = kairos.ConvexHull(points)
    sphere = kairos.Sphere(0.5)
    rounded = kairos.minkowski_sum(hull, sphere)
    if i % 7 == 0:
        with kairos.Box((1, 1, 1)) as box:  # released by the with block
            kairos.distance(box, None, rounded, pose)
    if i % 200 == 0:
        w = kairos.World()
        for k in range(20):
            w.add(rounded if k % 2 else sphere, (k, 0, 0, 0, 0, 0, 1))
        w.step()
        arr = kairos.ShapeArray([hull, sphere], np.arange(64) % 2)
        kairos.distance_batch(arr, None, rounded, pose)
        del w, arr


def test_100k_shapes_leave_memory_flat():
    rng = np.random.default_rng(SEED)
    points = rng.normal(size=(32, 3))
    pose = (3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0)
    start = time.perf_counter()
    for i in range(20_000):
        churn(i, points, pose)
    at_20k = rss_bytes()
    for i in range(20_000, 100_000):
        churn(i, points, pose)
    at_100k = rss_bytes()
    growth = at_100k - at_20k
    assert growth < 4 * 2**20, (f"RSS grew by {growth / 2**20:.1f} MB between the 20k-th and "
                                f"the 100k-th iteration (seed {SEED}, "
                                f"{time.perf_counter() - start:.1f} s)")
