# SPDX-License-Identifier: MIT
"""Kairos: continuous (space-time) collision detection of convex shapes, from Python.

A thin binding of libkairos's C API (ctypes and numpy, no compiler needed): the names are the C
names without their ``kairos_`` prefix.

    >>> import kairos
    >>> a, b = kairos.Sphere(1.0), kairos.Box((1, 2, 3))
    >>> r = kairos.shape_cast(a, (0, 0, 0, 0, 0, 0, 1), (10, 0, 0), b, (5, 0, 0, 0, 0, 0, 1), None)
    >>> r.hit, r.toi
    (True, 0.3)

Conventions (those of the C API):

- Lengths in any unit used consistently; times (``toi``) fractions of one step in [0, 1].
- Shapes are defined in their local frames and placed by poses; every point, normal and axis in
  a result is in the world frame.
- A pose is a :class:`Pose`, a length-7 sequence ``(x, y, z, qx, qy, qz, qw)``, or None (the
  identity); quaternions must have unit length within ``QUAT_TOLERANCE`` (1e-6).
- Every number must be finite and within ``MAX_MAGNITUDE`` (1e100).
- Failures raise a :class:`Error` subclass carrying the library's message.
- Batches (``*_batch``, ``World.move`` with arrays) take and return numpy arrays in the C
  layout: poses (n, 7), translations (n, 3), motions (n, 14); results are structured arrays.

The library ``libkairos.so.0`` is found through ``KAIROS_LIBRARY``, next to this package, in an
installed prefix's lib directory, or in a source tree's ``build/release`` (see ``_capi``).
"""

from __future__ import annotations

from . import _capi
from .core import (CAST_DTYPE, CONTACT_DTYPE, DISTANCE_DTYPE, IDENTITY, MAX_MAGNITUDE,
                   QUAT_TOLERANCE, BroadPhase, CastResult, DistanceResult, Motion, MotionLike,
                   Pose, PoseLike, QuerySettings, Termination, Vec3Like)
from .errors import (DegenerateError, Error, InternalError, InvalidArgumentError, LimitError,
                     NullArgumentError, OutOfMemoryError, StaleIdError, StructSizeError,
                     UnimplementedError, UnsupportedVersionError, last_error, status_name)
from .queries import (AxisCache, ShapesLike, distance, distance_batch, intersect, motion_cast,
                      motion_cast_batch, ray_cast, shape_cast, shape_cast_batch, signed_distance)
from .shapes import (Box, Capsule, Cone, ConvexHull, Cylinder, HullOfTwo, MinkowskiSum, Point,
                     Segment, Shape, ShapeArray, Sphere, Transformed, Triangle, hull,
                     minkowski_sum, transformed)
from .world import Filter, StepStats, World, WorldHit

def library_path() -> str:
    """The path libkairos was loaded from."""
    return _capi.path


#: ABI version of the function table this package requires (the batches).
ABI_VERSION: int = _capi.REQUIRED_ABI


def version() -> int:
    """The loaded library's version, major*10000 + minor*100 + patch."""
    return int(_capi.lib.kairos_version())


def version_tuple() -> tuple:
    """The loaded library's version as (major, minor, patch)."""
    v = version()
    return (v // 10000, v // 100 % 100, v % 100)


#: The loaded library's version: the package is the library's own binding, released with it.
__version__ = "%d.%d.%d" % version_tuple()

__all__ = [
    # library
    "library_path", "version", "version_tuple", "status_name", "last_error", "ABI_VERSION",
    # errors
    "Error", "NullArgumentError", "InvalidArgumentError", "StructSizeError", "DegenerateError",
    "StaleIdError", "OutOfMemoryError", "UnimplementedError", "UnsupportedVersionError",
    "InternalError", "LimitError",
    # values
    "Pose", "Motion", "QuerySettings", "DistanceResult", "CastResult", "Termination",
    "BroadPhase", "IDENTITY", "QUAT_TOLERANCE", "MAX_MAGNITUDE", "DISTANCE_DTYPE", "CAST_DTYPE",
    "CONTACT_DTYPE", "PoseLike", "MotionLike", "Vec3Like", "ShapesLike",
    # shapes
    "Shape", "Sphere", "Box", "Capsule", "Cylinder", "Cone", "Point", "Segment", "ConvexHull",
    "Triangle", "Transformed", "MinkowskiSum", "HullOfTwo", "transformed", "minkowski_sum",
    "hull", "ShapeArray",
    # queries
    "distance", "signed_distance", "intersect", "AxisCache", "ray_cast", "shape_cast",
    "motion_cast", "distance_batch", "shape_cast_batch", "motion_cast_batch",
    # world
    "World", "Filter", "WorldHit", "StepStats",
]
