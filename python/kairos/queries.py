# SPDX-License-Identifier: MIT
"""Pair queries, one at a time and in batches.

Frames and units: shapes are posed in the world frame by their poses (None: identity); every
point, normal and axis in a result is in the world frame; translations are world-frame
displacements over the step; ``toi`` is a fraction of the step in [0, 1]. Lengths in any unit used
consistently. Queries only read shapes: any number may run at once on several threads (ctypes
releases the GIL during each C call).

The batches take numpy arrays laid out as the C structs (no copy when they already are float64
and C-contiguous): poses ``(n, 7)`` as ``(x, y, z, qx, qy, qz, qw)``, translations ``(n, 3)``,
motions ``(n, 14)`` or ``(n, 2, 7)`` (start pose, end pose). A single row (``(7,)``, ``(3,)``,
``(14,)``, ``(2, 7)``) is broadcast to every query; None means identity poses or zero
translations. Shapes: one :class:`~kairos.Shape` for every query, a sequence of n shapes, or a
:class:`~kairos.ShapeArray` (prebuilt: no per-shape Python work). Results are structured arrays
of :data:`~kairos.DISTANCE_DTYPE` or :data:`~kairos.CAST_DTYPE` that the library writes in place,
bit for bit the single calls' results. A batch is checked whole before it runs: the first bad
query is named in the exception (``poses_a[17].orientation must be ...``) and nothing is written.
The input arrays must not change while a batch runs (the GIL is released: another Python thread
writing them is a data race).
"""

from __future__ import annotations

import ctypes
import struct
from typing import TYPE_CHECKING, Any, List, Optional, Sequence, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike

from . import _capi
from .core import (CAST_DTYPE, DISTANCE_DTYPE, CastResult, DistanceResult, MotionLike,
                   PoseLike, QuerySettings, Vec3, Vec3Like, float_array, motion_c, pose_c,
                   settings_c, vec3_c)
from .errors import error_for
from .shapes import Shape, ShapeArray, handle_of

if TYPE_CHECKING:
    from .world import World

__all__ = [
    "distance", "signed_distance", "intersect", "AxisCache", "ray_cast", "shape_cast",
    "motion_cast", "distance_batch", "shape_cast_batch", "motion_cast_batch", "ShapesLike",
]

_lib = _capi.lib
_CDistance = _capi.DistanceResult
_CCast = _capi.CastResult
_c_distance = _lib.kairos_distance
_c_signed_distance = _lib.kairos_signed_distance
_c_ray_cast = _lib.kairos_ray_cast
_c_shape_cast = _lib.kairos_shape_cast
_c_motion_cast = _lib.kairos_motion_cast
# kairos_distance_result: distance, 3 vec3, intersecting, iterations, termination, 4 bytes pad.
_UNPACK_DISTANCE = struct.Struct("<10diIi4x").unpack_from
# kairos_cast_result: hit, 4 bytes pad, toi, point, normal, iterations, termination.
_UNPACK_CAST = struct.Struct("<i4x7dIi").unpack_from
_ZERO3 = _capi.Vec3(0.0, 0.0, 0.0)

ShapesLike = Union[Shape, ShapeArray, Sequence[Shape]]
# (n, 7) poses, (n, 3) translations or (n, 14) / (n, 2, 7) motions; one row broadcasts.
Rows = Optional[ArrayLike]


def _distance_result(c: Any) -> DistanceResult:
    v = _UNPACK_DISTANCE(c)
    return DistanceResult(v[0], v[1:4], v[4:7], v[7:10], bool(v[10]), v[11], v[12])


def _cast_result(c: Any) -> CastResult:
    v = _UNPACK_CAST(c)
    return CastResult(bool(v[0]), v[1], v[2:5], v[5:8], v[8], v[9])


# ---- Pair queries ------------------------------------------------------------------------------
def distance(a: Shape, pose_a: PoseLike, b: Shape, pose_b: PoseLike,
             settings: Optional[QuerySettings] = None) -> DistanceResult:
    """Distance, closest points (world frame) and separating axis (unit, A toward B) of ``a`` at
    ``pose_a`` and ``b`` at ``pose_b``. 0 with ``intersecting`` True when they overlap.
    ``settings.tolerance`` is the relative error of the distance."""
    out = _CDistance()
    status = _c_distance(handle_of(a, "a"), pose_c(pose_a, "pose_a"),
                         handle_of(b, "b"), pose_c(pose_b, "pose_b"),
                         settings_c(settings), out)
    if status:
        raise error_for(status)
    return _distance_result(out)


def signed_distance(a: Shape, pose_a: PoseLike, b: Shape, pose_b: PoseLike,
                    settings: Optional[QuerySettings] = None) -> DistanceResult:
    """As :func:`distance` when apart; overlapping, ``distance`` is minus the penetration depth,
    ``axis`` the minimum translation's direction (B moved by depth along it just touches A),
    ``point_a``/``point_b`` the deepest points (world frame)."""
    out = _CDistance()
    status = _c_signed_distance(handle_of(a, "a"), pose_c(pose_a, "pose_a"),
                                handle_of(b, "b"), pose_c(pose_b, "pose_b"),
                                settings_c(settings), out)
    if status:
        raise error_for(status)
    return _distance_result(out)


class AxisCache:
    """A separating-axis cache for :func:`intersect` (world frame, any length): keep one per
    pair across frames and a smoothly moving pair needs about one iteration. Starts at zero (a
    fresh search). Not thread safe: one cache per thread and pair."""

    __slots__ = ("_c",)

    def __init__(self, axis: Vec3Like = (0.0, 0.0, 0.0)) -> None:
        self._c = vec3_c(axis, "axis")

    @property
    def axis(self) -> Vec3:
        c = self._c
        return (c.x, c.y, c.z)

    def __repr__(self) -> str:
        return f"AxisCache({self.axis!r})"


def intersect(a: Shape, pose_a: PoseLike, b: Shape, pose_b: PoseLike,
              cache: Optional[AxisCache] = None) -> bool:
    """True when ``a`` at ``pose_a`` and ``b`` at ``pose_b`` overlap or touch. ``cache`` seeds
    the search and receives the separating axis found (see :class:`AxisCache`)."""
    out = ctypes.c_int32()
    status = _lib.kairos_intersect(handle_of(a, "a"), pose_c(pose_a, "pose_a"),
                                   handle_of(b, "b"), pose_c(pose_b, "pose_b"),
                                   None if cache is None else ctypes.byref(cache._c),
                                   ctypes.byref(out))
    if status:
        raise error_for(status)
    return bool(out.value)


def ray_cast(shape: Shape, pose: PoseLike, origin: Vec3Like, translation: Vec3Like,
             settings: Optional[QuerySettings] = None) -> CastResult:
    """First hit of the ray ``origin + t * translation``, t in [0, 1] (world frame), on ``shape``
    at ``pose``. ``toi`` is t; ``normal`` is outward from the shape. A ray starting inside hits at
    toi 0 with normal -translation (unit)."""
    out = _CCast()
    status = _c_ray_cast(handle_of(shape, "shape"), pose_c(pose), vec3_c(origin, "origin"),
                         vec3_c(translation, "translation"), settings_c(settings), out)
    if status:
        raise error_for(status)
    return _cast_result(out)


def shape_cast(a: Shape, pose_a: PoseLike, translation_a: Optional[Vec3Like],
               b: Shape, pose_b: PoseLike, translation_b: Optional[Vec3Like],
               settings: Optional[QuerySettings] = None) -> CastResult:
    """First time of impact of ``a`` and ``b`` translating by ``translation_a`` and
    ``translation_b`` (world frame, over the step; None: not moving) from their poses.
    ``normal``: unit, from A toward B; ``point``: the contact at toi (world frame). Never later
    than the true contact beyond the tolerance, never a missed contact. Overlapping at the
    start: toi 0 with the minimum translation's axis."""
    out = _CCast()
    status = _c_shape_cast(handle_of(a, "a"), pose_c(pose_a, "pose_a"),
                           _ZERO3 if translation_a is None else vec3_c(translation_a,
                                                                       "translation_a"),
                           handle_of(b, "b"), pose_c(pose_b, "pose_b"),
                           _ZERO3 if translation_b is None else vec3_c(translation_b,
                                                                       "translation_b"),
                           settings_c(settings), out)
    if status:
        raise error_for(status)
    return _cast_result(out)


def motion_cast(a: Shape, motion_a: MotionLike, b: Shape, motion_b: MotionLike,
                settings: Optional[QuerySettings] = None) -> CastResult:
    """First time of impact of ``a`` and ``b`` following their motions (translation and
    rotation, world frame). Conservative: toi is never later than the true first contact by
    more than ``settings.tolerance`` (a fraction of the step), no contact is missed; a near miss
    closer than tolerance times the smaller shape's bounding radius counts as a hit."""
    out = _CCast()
    status = _c_motion_cast(handle_of(a, "a"), motion_c(motion_a, "motion_a"), handle_of(b, "b"),
                            motion_c(motion_b, "motion_b"), settings_c(settings), out)
    if status:
        raise error_for(status)
    return _cast_result(out)


# ---- Batches -----------------------------------------------------------------------------------
class _Batch:
    """Arguments of one batch call: leading lengths gathered, broadcasts resolved, the arrays
    kept alive until the call returns."""

    def __init__(self) -> None:
        self.lengths: List[Tuple[str, int]] = []
        self.pending: List[Tuple[int, str, Any, int]] = []  # (slot, kind, value, width)
        self.args: List[Any] = []

    def shapes(self, x: ShapesLike, name: str) -> None:
        if isinstance(x, ShapeArray):
            if x.handles is None:
                raise ValueError(f"{name}: the ShapeArray is closed")
            self.lengths.append((name, len(x.handles)))
            self.args.append(x.handles)
        elif isinstance(x, Shape):
            self.pending.append((len(self.args), "shape", x, 0))
            self.args.append(None)
        else:
            items = list(x)
            try:
                handles = np.fromiter((s._h for s in items), dtype=np.uint64, count=len(items))
            except AttributeError:
                raise TypeError(f"{name} must be a Shape, a ShapeArray or a sequence of Shapes"
                                ) from None
            self.lengths.append((name, len(items)))
            self.args.append((handles, items))

    def rows(self, x: Any, name: str, width: int, single_shapes: Tuple[Tuple[int, ...], ...]
             ) -> None:
        if x is None:
            self.args.append(None)
            return
        try:
            x = float_array(x)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be a float array of rows of {width}") from None
        if x.shape in single_shapes:
            self.pending.append((len(self.args), "row", x.reshape(width), width))
            self.args.append(None)
            return
        if x.ndim == 2 and x.shape[1] == width:
            pass
        elif len(single_shapes) > 1 and x.ndim == 3 and x.shape[1:] == single_shapes[1]:
            x = x.reshape(len(x), width)
        else:
            expect = " or ".join(str(("n",) + s) for s in single_shapes)
            raise ValueError(f"{name} must have shape {expect} (or a single row), got {x.shape}")
        self.lengths.append((name, len(x)))
        self.args.append(np.ascontiguousarray(x))

    def count(self) -> int:
        if not self.lengths:
            raise ValueError("cannot tell the number of queries: every argument is a single "
                             "shape or row; give at least one as an array of n")
        n = self.lengths[0][1]
        for name, m in self.lengths:
            if m != n:
                listed = ", ".join(f"{k} has {v}" for k, v in self.lengths)
                raise ValueError(f"batch arguments disagree on the number of queries: {listed}")
        return n

    def addresses(self, n: int) -> List[Optional[int]]:
        for slot, kind, value, width in self.pending:
            if kind == "shape":
                self.args[slot] = np.full(n, value._h, dtype=np.uint64)
            else:
                self.args[slot] = np.ascontiguousarray(np.broadcast_to(value, (n, width)))
        out: List[Optional[int]] = []
        for a in self.args:
            if a is None:
                out.append(None)
            elif type(a) is tuple:
                out.append(a[0].ctypes.data)
            else:
                out.append(a.ctypes.data)
        return out


def _workers(workers: Any) -> Optional[int]:
    if workers is None:
        return None
    h = getattr(workers, "_w", None)
    if h is None:
        raise TypeError(f"workers must be a kairos.World or None, got {type(workers).__name__}")
    if not h:
        raise ValueError("workers: the World is closed")
    return h


def _out(out: Optional[np.ndarray], n: int, dtype: np.dtype, inputs: List[Any]) -> np.ndarray:
    if out is None:
        return np.empty(n, dtype=dtype)
    if (type(out) is not np.ndarray or out.dtype != dtype or out.shape != (n,)
            or not out.flags.c_contiguous or not out.flags.writeable):
        raise ValueError(f"out must be a writeable C-contiguous array of {n} "
                         f"elements of the result dtype")
    for a in inputs:
        arr = a[0] if type(a) is tuple else a
        if arr is not None and np.may_share_memory(out, arr):
            raise ValueError("out must not overlap the input arrays")
    return out


def _call(batch: _Batch, fn: Any, dtype: np.dtype, settings: Optional[QuerySettings],
          workers: Optional[World], out: Optional[np.ndarray]) -> np.ndarray:
    """Runs a C batch function on the gathered arguments: its arrays in order, then the count,
    the settings, the workers and the result array (the layout of all three batches)."""
    n = batch.count()
    w = _workers(workers)
    ptrs = batch.addresses(n)
    result = _out(out, n, dtype, batch.args)
    status = fn(*ptrs, n, settings_c(settings), w, result.ctypes.data)
    if status:
        raise error_for(status)
    return result


_POSE = ((7,),)
_VEC = ((3,),)
_MOTION = ((14,), (2, 7))


def distance_batch(a: ShapesLike, poses_a: Rows, b: ShapesLike, poses_b: Rows,
                   settings: Optional[QuerySettings] = None, workers: Optional[World] = None,
                   out: Optional[np.ndarray] = None) -> np.ndarray:
    """:func:`distance` over n queries: query i is ``a[i]`` at ``poses_a[i]`` against ``b[i]``
    at ``poses_b[i]``. Returns an (n,) array of :data:`~kairos.DISTANCE_DTYPE` (fields named as
    :class:`~kairos.DistanceResult`; vectors world frame).

    workers: None runs the batch on the calling thread; a :class:`~kairos.World` runs it on that
    world's threads (its ``worker_count``, the caller's included), and no other thread may use
    that world until the batch returns. out: an optional preallocated result array (left
    untouched when the batch is refused); for batches repeated every frame, reusing one array
    saves allocating fresh memory per call (its page faults can cost more than the queries: on
    a test VM, 0.5 us per cast for a 10,000-cast batch).
    """
    batch = _Batch()
    batch.shapes(a, "a")
    batch.rows(poses_a, "poses_a", 7, _POSE)
    batch.shapes(b, "b")
    batch.rows(poses_b, "poses_b", 7, _POSE)
    return _call(batch, _lib.kairos_distance_batch, DISTANCE_DTYPE, settings, workers, out)


def shape_cast_batch(a: ShapesLike, poses_a: Rows, translations_a: Rows,
                     b: ShapesLike, poses_b: Rows, translations_b: Rows,
                     settings: Optional[QuerySettings] = None, workers: Optional[World] = None,
                     out: Optional[np.ndarray] = None) -> np.ndarray:
    """:func:`shape_cast` over n queries (translations world frame, per step; None: zero).
    Returns an (n,) array of :data:`~kairos.CAST_DTYPE`; ``workers`` and ``out`` as in
    :func:`distance_batch`."""
    batch = _Batch()
    batch.shapes(a, "a")
    batch.rows(poses_a, "poses_a", 7, _POSE)
    batch.rows(translations_a, "translations_a", 3, _VEC)
    batch.shapes(b, "b")
    batch.rows(poses_b, "poses_b", 7, _POSE)
    batch.rows(translations_b, "translations_b", 3, _VEC)
    return _call(batch, _lib.kairos_shape_cast_batch, CAST_DTYPE, settings, workers, out)


def motion_cast_batch(a: ShapesLike, motions_a: ArrayLike, b: ShapesLike, motions_b: ArrayLike,
                      settings: Optional[QuerySettings] = None, workers: Optional[World] = None,
                      out: Optional[np.ndarray] = None) -> np.ndarray:
    """:func:`motion_cast` over n queries; motions ``(n, 14)`` or ``(n, 2, 7)`` (start pose,
    end pose, world frame), required (no None). Returns an (n,) array of
    :data:`~kairos.CAST_DTYPE`; ``workers`` and ``out`` as in :func:`distance_batch`."""
    if motions_a is None or motions_b is None:
        raise ValueError("motion_cast_batch: motions_a and motions_b are required")
    batch = _Batch()
    batch.shapes(a, "a")
    batch.rows(motions_a, "motions_a", 14, _MOTION)
    batch.shapes(b, "b")
    batch.rows(motions_b, "motions_b", 14, _MOTION)
    return _call(batch, _lib.kairos_motion_cast_batch, CAST_DTYPE, settings, workers, out)
