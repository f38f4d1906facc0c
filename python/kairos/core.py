# SPDX-License-Identifier: MIT
"""Poses, motions, query settings, result types and constants.

Units and frames (as in the C API): lengths are in any unit used consistently; times are fractions
of one step in [0, 1]. A pose maps a shape's local frame to the world frame:
``x -> R(orientation) * x + position``. Quaternions are ``(qx, qy, qz, qw)`` (w the real part)
and must have unit length within :data:`QUAT_TOLERANCE` (1e-6; the library then normalises them).
Every number must be finite and within :data:`MAX_MAGNITUDE` (1e100).

Single-query results hold vectors as tuples of 3 Python floats (the exact doubles the library
wrote); batch results are numpy structured arrays (see :data:`DISTANCE_DTYPE`).
"""

from __future__ import annotations

import enum
import struct
from dataclasses import dataclass
from typing import Any, Optional, Sequence, Tuple, Union

import numpy as np

from . import _capi

__all__ = [
    "Pose", "Motion", "QuerySettings", "DistanceResult", "CastResult", "Termination",
    "BroadPhase", "PoseLike", "MotionLike", "Vec3Like", "QUAT_TOLERANCE", "MAX_MAGNITUDE",
    "DISTANCE_DTYPE", "CAST_DTYPE", "CONTACT_DTYPE", "IDENTITY",
]

QUAT_TOLERANCE: float = _capi.QUAT_TOLERANCE
MAX_MAGNITUDE: float = _capi.MAX_MAGNITUDE

#: numpy dtype of ``kairos_distance_result`` (96 bytes, padding included): ``distance`` f8,
#: ``point_a``, ``point_b``, ``axis`` (3,) f8 world frame, ``intersecting`` i4,
#: ``iterations`` u4, ``termination`` i4.
DISTANCE_DTYPE: np.dtype = _capi.DISTANCE_DTYPE
#: numpy dtype of ``kairos_cast_result`` (72 bytes): ``hit`` i4 at 0, ``toi`` f8 at 8,
#: ``point`` (3,) f8 at 16, ``normal`` (3,) f8 at 40, ``iterations`` u4 at 64,
#: ``termination`` i4 at 68.
CAST_DTYPE: np.dtype = _capi.CAST_DTYPE
#: numpy dtype of ``kairos_contact`` (88 bytes): ``a``, ``b`` (ids, a < b), ``user_a``,
#: ``user_b`` u8, ``toi`` f8, ``point``, ``normal`` (3,) f8 world frame (normal from a to b).
CONTACT_DTYPE: np.dtype = _capi.CONTACT_DTYPE

Vec3 = Tuple[float, float, float]
Vec3Like = Union[Sequence[float], np.ndarray]

_PACK3 = struct.Struct("<3d").pack
_PACK7 = struct.Struct("<7d").pack
_PACK14 = struct.Struct("<14d").pack
_UNPACK7 = struct.Struct("<7d").unpack_from
_CPose = _capi.Pose
_CVec3 = _capi.Vec3
_CMotion = _capi.Motion


class Termination(enum.IntEnum):
    """Which rule ended a query's iteration (``termination`` of a result); docs/algorithms.md."""
    NONE = 0
    RELATIVE_ERROR = 1
    NEAR_CONTACT = 2
    FULL_SIMPLEX = 3
    JOHNSON_FAILED = 4
    REPEATED_SUPPORT = 5
    NO_PROGRESS = 6
    MAX_ITERATIONS = 7
    SEPARATED = 8
    HIT = 9


class BroadPhase(enum.IntEnum):
    """A world's broad phase (``kairos_world_settings.broad_phase``)."""
    SPACETIME_SAP = 0          #: default: space-time sweep and prune
    ENCAPSULATING_SAP = 1      #: boxes swept over the whole step (false positives)
    BRUTE_FORCE = 2            #: every pair, O(n^2): a reference
    SPACETIME_SAP_QUEUED = 3   #: the talks' queued-swap sweep (same pairs as SPACETIME_SAP)


@dataclass(frozen=True)
class Pose:
    """A rigid placement: local frame -> world frame, ``x -> R(orientation) x + position``.

    ``position`` is in the caller's length unit; ``orientation`` is a unit quaternion
    ``(qx, qy, qz, qw)``. Anywhere a pose is taken, a length-7 sequence or array
    ``(x, y, z, qx, qy, qz, qw)`` works too, and None means the identity (except
    ``World.set_pose`` and ``World.move``, which require a pose, as the C API does).
    """

    position: Vec3 = (0.0, 0.0, 0.0)
    orientation: Tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)

    def __post_init__(self) -> None:
        p = tuple(float(v) for v in self.position)
        q = tuple(float(v) for v in self.orientation)
        if len(p) != 3 or len(q) != 4:
            raise ValueError(f"Pose: position needs 3 numbers and orientation 4, got {len(p)} "
                             f"and {len(q)}")
        object.__setattr__(self, "position", p)
        object.__setattr__(self, "orientation", q)
        # The C struct's bytes, kept beside the fields (not a dataclass field).
        object.__setattr__(self, "_packed", _PACK7(*p, *q))

    @classmethod
    def identity(cls) -> "Pose":
        return IDENTITY

    @classmethod
    def from_sequence(cls, values: Union[Sequence[float], np.ndarray]) -> "Pose":
        """From ``(x, y, z, qx, qy, qz, qw)``."""
        v = [float(x) for x in np.asarray(values, dtype=np.float64).reshape(-1)]
        if len(v) != 7:
            raise ValueError(f"a pose needs 7 numbers (x, y, z, qx, qy, qz, qw), got {len(v)}")
        return cls(tuple(v[:3]), tuple(v[3:]))

    def as_tuple(self) -> Tuple[float, ...]:
        """``(x, y, z, qx, qy, qz, qw)``."""
        return self.position + self.orientation

    def to_array(self) -> np.ndarray:
        """A (7,) float64 array ``(x, y, z, qx, qy, qz, qw)``: one row of a batch's poses."""
        return np.array(self.as_tuple(), dtype=np.float64)

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        a = self.to_array()
        return a if dtype is None else a.astype(dtype)


IDENTITY = Pose()

PoseLike = Union[Pose, Sequence[float], np.ndarray, None]


@dataclass(frozen=True)
class Motion:
    """One step of a rigid motion, t in [0, 1]: the local origin moves linearly from
    ``start.position`` to ``end.position`` and turns about it at constant angular velocity along
    the shortest arc between the orientations. World frame.

    Anywhere a motion is taken, a pair ``(start, end)`` of pose-likes or a length-14 sequence
    (two poses back to back) works too.
    """

    start: Pose = IDENTITY
    end: Pose = IDENTITY

    def __post_init__(self) -> None:
        for name in ("start", "end"):
            v = getattr(self, name)
            if v is None:
                object.__setattr__(self, name, IDENTITY)
            elif not isinstance(v, Pose):
                object.__setattr__(self, name, Pose.from_sequence(v))

    def to_array(self) -> np.ndarray:
        """A (14,) float64 array: start pose then end pose (one row of a batch's motions)."""
        return np.array(self.start.as_tuple() + self.end.as_tuple(), dtype=np.float64)

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        a = self.to_array()
        return a if dtype is None else a.astype(dtype)


MotionLike = Union[Motion, Tuple[PoseLike, PoseLike], Sequence[float], np.ndarray]


@dataclass(frozen=True)
class QuerySettings:
    """Accuracy settings of a query (``kairos_query_settings``).

    tolerance: relative accuracy in (0, 1) (default 1e-10), the accuracy/speed knob: for a
        distance the relative error of the distance; for ray and shape casts the gap to the
        surface, relative to the shapes' size, at which the iteration stops; for a motion cast
        the time of impact's error as a fraction of the step.
    max_iterations: an iteration guard, >= 1 (default 256).

    Values are checked by the library when a query uses them (InvalidArgumentError).
    """

    tolerance: float = 1e-10
    max_iterations: int = 256

    def __post_init__(self) -> None:
        if not 0 <= int(self.max_iterations) <= 0xFFFFFFFF:
            raise ValueError(f"max_iterations {self.max_iterations} does not fit a uint32")
        c = _capi.QuerySettings()
        _capi.lib.kairos_query_settings_init(c)
        c.tolerance = float(self.tolerance)
        c.max_iterations = int(self.max_iterations)
        # The C struct, built once and passed by pointer to every query (read only there).
        object.__setattr__(self, "_c", c)


@dataclass(frozen=True)
class DistanceResult:
    """Result of :func:`distance` / :func:`signed_distance` (world frame).

    distance: >= 0 apart, 0 touching; signed_distance gives minus the depth when overlapping.
    point_a, point_b: closest (or deepest) points on A and B, world frame.
    axis: unit, from A toward B (a separating axis when apart).
    intersecting: the shapes overlap or touch.
    iterations: GJK iterations used; termination: a :class:`Termination` value.
    """

    distance: float
    point_a: Vec3
    point_b: Vec3
    axis: Vec3
    intersecting: bool
    iterations: int
    termination: int


@dataclass(frozen=True)
class CastResult:
    """Result of :func:`ray_cast`, :func:`shape_cast` and :func:`motion_cast`.

    hit: contact happens within the step. toi: the time of impact, a fraction of the step in
    [0, 1] (1 when no hit). point: the contact point at toi, world frame (unspecified without a
    hit). normal: unit, from A toward B (for a ray cast, outward from the shape), world frame.
    iterations: iterations used; termination: a :class:`Termination` value.
    """

    hit: bool
    toi: float
    point: Vec3
    normal: Vec3
    iterations: int
    termination: int


# ---- Conversions to the C structs (internal) --------------------------------------------------
def _bad(what: str, value: Any, need: str) -> ValueError:
    return ValueError(f"{what} must be {need}, got {value!r:.80}")


def pose_c(p: PoseLike, what: str = "pose") -> Optional[_CPose]:
    """A ``kairos_pose`` for a pose-like; None stays None (the C API's identity)."""
    if p is None:
        return None
    t = type(p)
    try:
        if t is tuple or t is list:
            return _CPose.from_buffer_copy(_PACK7(*p))
        if t is Pose:
            return _CPose.from_buffer_copy(p._packed)
        if isinstance(p, Pose):
            return _CPose.from_buffer_copy(p._packed)
        a = np.ascontiguousarray(p, dtype=np.float64)
    except (struct.error, TypeError, ValueError):
        raise _bad(what, p, "a Pose or 7 numbers (x, y, z, qx, qy, qz, qw)") from None
    if a.shape != (7,):
        raise _bad(what, p, "a Pose or 7 numbers (x, y, z, qx, qy, qz, qw)")
    return _CPose.from_buffer_copy(a)


def vec3_c(v: Vec3Like, what: str = "vector") -> _CVec3:
    """A ``kairos_vec3`` for 3 numbers."""
    try:
        if type(v) is tuple or type(v) is list:
            return _CVec3.from_buffer_copy(_PACK3(*v))
        a = np.ascontiguousarray(v, dtype=np.float64)
    except (struct.error, TypeError, ValueError):
        raise _bad(what, v, "3 numbers") from None
    if a.shape != (3,):
        raise _bad(what, v, "3 numbers")
    return _CVec3.from_buffer_copy(a)


def motion_c(m: MotionLike, what: str = "motion") -> _CMotion:
    """A ``kairos_motion`` for a motion-like (required: no NULL motion in the C API)."""
    if isinstance(m, Motion):
        return _CMotion.from_buffer_copy(m.start._packed + m.end._packed)
    try:
        if (type(m) is tuple or type(m) is list) and len(m) == 2:
            start = pose_c(m[0], what + ".start")
            end = pose_c(m[1], what + ".end")
            if start is None:
                start = _CPose.from_buffer_copy(IDENTITY._packed)
            if end is None:
                end = _CPose.from_buffer_copy(IDENTITY._packed)
            return _CMotion(start, end)
        if type(m) is tuple or type(m) is list:
            return _CMotion.from_buffer_copy(_PACK14(*m))
        a = np.ascontiguousarray(m, dtype=np.float64)
    except (struct.error, TypeError):
        raise _bad(what, m, "a Motion, a (start, end) pair of poses or 14 numbers") from None
    if a.size != 14 or a.shape not in ((14,), (2, 7)):
        raise _bad(what, m, "a Motion, a (start, end) pair of poses or 14 numbers")
    return _CMotion.from_buffer_copy(a)


def settings_c(s: Optional[QuerySettings]) -> Any:
    """The ``kairos_query_settings`` of a QuerySettings; None stays None (the defaults)."""
    if s is None:
        return None
    if not isinstance(s, QuerySettings):
        raise TypeError(f"settings must be a kairos.QuerySettings or None, got {type(s).__name__}")
    return s._c


def float_array(x: Any) -> np.ndarray:
    """A float64 array of rows; a list of Pose or Motion objects is converted item by item."""
    if type(x) is np.ndarray and x.dtype == np.float64:
        return x
    if type(x) in (list, tuple) and x and isinstance(x[0], (Pose, Motion)):
        x = [np.asarray(v, dtype=np.float64).reshape(-1) for v in x]
    return np.asarray(x, dtype=np.float64)


def pose_from_c(c: _CPose) -> Pose:
    v = _UNPACK7(c)
    return Pose(v[:3], v[3:])
