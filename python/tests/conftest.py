# SPDX-License-Identifier: MIT
"""Shared fixtures: a zoo of every shape kind and random pose generators (fixed seeds)."""

import numpy as np
import pytest

import kairos

SEED = 20261127


def random_quaternions(rng: np.random.Generator, n: int) -> np.ndarray:
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def random_poses(rng: np.random.Generator, n: int, spread: float) -> np.ndarray:
    """(n, 7) poses: positions uniform in [-spread, spread]^3, uniform random unit quaternions."""
    return np.hstack([rng.uniform(-spread, spread, size=(n, 3)), random_quaternions(rng, n)])


def make_zoo():
    """One shape of every kind, sizes about 0.5 (as tests/capi/test_capi_batch.cpp)."""
    box = kairos.Box((0.5, 0.3, 0.2))
    sphere = kairos.Sphere(0.4)
    octahedron = kairos.ConvexHull([(0, 0, 0.6), (0.5, 0, 0), (0, 0.5, 0), (-0.5, 0, 0),
                                    (0, -0.5, 0), (0, 0, -0.6)])
    return [
        box, sphere,
        kairos.Capsule(0.2, 0.5), kairos.Cylinder(0.3, 0.4), kairos.Cone(0.4, 0.5),
        kairos.Segment(0.6), kairos.Point(), octahedron,
        kairos.Triangle((-0.7, -0.5, 0), (0.7, -0.5, 0), (0, 0.8, 0)),
        kairos.minkowski_sum(box, sphere),
        kairos.hull(kairos.Sphere(0.2), kairos.transformed(box, None, (0.3, 0, 0))),
        kairos.transformed(octahedron, [[1, 0.2, 0], [0, 0.8, 0], [0, 0, -1.1]], (0.1, 0, 0)),
    ]


@pytest.fixture(scope="session")
def zoo():
    return make_zoo()


@pytest.fixture
def rng():
    return np.random.default_rng(SEED)
