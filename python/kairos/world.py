# SPDX-License-Identifier: MIT
"""A world of moving objects: broad phase and narrow phase over one step.

Each step, every object moves from its current pose to the end pose given by :meth:`World.move`
(or stays), and :meth:`World.step` finds each colliding pair's first contact, with the time of
impact ``toi`` a fraction of the step in [0, 1]; poses, points and normals are in the world
frame, lengths in the caller's unit. Object ids are nonzero 64-bit ints; a removed object's id
stays invalid (:class:`~kairos.StaleIdError`).

Threads: a world is used by one thread at a time (no locking here or in the library); the
queries (ray_cast, shape_cast, query_box, get_pose, ...) may run on several threads at once while
none changes the world. The step's narrow phase runs on ``worker_count`` threads of the world's
own. The C API's task hook (running the step on an engine's scheduler) is not exposed: Python
callbacks would run under the GIL and gain nothing.
"""

from __future__ import annotations

import ctypes
from dataclasses import dataclass
from typing import Any, Optional, Union

import numpy as np

from . import _capi
from .core import (CONTACT_DTYPE, BroadPhase, MotionLike, Pose, PoseLike, QuerySettings, Vec3,
                   Vec3Like, float_array, motion_c, pose_c, pose_from_c, settings_c,
                   vec3_c)
from .errors import check, error_for
from .shapes import Shape, handle_of

__all__ = ["World", "Filter", "WorldHit", "StepStats"]

_lib = _capi.lib
_c_move = _lib.kairos_world_move
_c_move_batch = _lib.kairos_world_move_batch
_destroy = _lib.kairos_world_destroy
_U32 = 0xFFFFFFFF


@dataclass(frozen=True)
class Filter:
    """Which pairs collide. Two objects of the same nonzero ``group`` always collide when it
    is > 0 and never when < 0; otherwise a pair collides when each one's ``category_bits``
    meets the other's ``mask_bits``. Defaults: category 1, mask all, group 0. For a query,
    category_bits says what the query is and mask_bits what it sees."""

    category_bits: int = 1
    mask_bits: int = _U32
    group: int = 0

    def __post_init__(self) -> None:
        for name in ("category_bits", "mask_bits"):
            v = int(getattr(self, name))
            if not 0 <= v <= _U32:
                raise ValueError(f"Filter.{name} {v} does not fit a uint32")
        if not -2**31 <= int(self.group) < 2**31:
            raise ValueError(f"Filter.group {self.group} does not fit an int32")
        object.__setattr__(self, "_c", _capi.Filter(int(self.category_bits), int(self.mask_bits),
                                                    int(self.group)))


@dataclass(frozen=True)
class WorldHit:
    """The earliest hit of a world query. On a miss: hit False, id 0, user_data 0, toi 1.

    id: the object hit (ties at one toi: the smaller id); user_data: its user data;
    toi: fraction of the query's motion in [0, 1]; point: the contact at toi, world frame;
    normal: unit, outward from the object hit, world frame."""

    hit: bool
    id: int
    user_data: int
    toi: float
    point: Vec3
    normal: Vec3


@dataclass(frozen=True)
class StepStats:
    """Counters of the last step (wall times in seconds)."""

    broad_phase_pairs: int
    swaps: int
    heap_operations: int
    narrow_phase_queries: int
    gjk_iterations: int
    broad_phase_seconds: float
    narrow_phase_seconds: float


def _filter_c(f: Optional[Filter]) -> Any:
    if f is None:
        return None
    if not isinstance(f, Filter):
        raise TypeError(f"filter must be a kairos.Filter or None, got {type(f).__name__}")
    return f._c


def _hit(c: _capi.WorldHit) -> WorldHit:
    return WorldHit(bool(c.hit), c.id, c.user_data, c.toi, (c.point.x, c.point.y, c.point.z),
                    (c.normal.x, c.normal.y, c.normal.z))


class World:
    """A world of moving objects (``kairos_world``).

    Args:
        broad_phase: a :class:`~kairos.BroadPhase` (default SPACETIME_SAP).
        tolerance, max_iterations: the narrow phase's query settings (see
            :class:`~kairos.QuerySettings`); the world queries use them too.
        worker_count: threads of the narrow phase, the caller's included: 0 or 1 the calling
            thread alone, n > 1 (at most 256) n - 1 threads the world starts and keeps. Results
            are bit for bit the same for every worker_count. A world also serves as ``workers``
            of the batch queries.

    The world keeps its own reference to every shape added (the Python Shape may be closed).
    Destroyed by :meth:`close`, at the end of a ``with`` block, or when garbage collected; a
    closed world's methods raise NullArgumentError. Ids are Python ints (numpy integers work).
    """

    _w: int = 0
    _destroy = staticmethod(_destroy)

    def __init__(self, broad_phase: Union[BroadPhase, int] = BroadPhase.SPACETIME_SAP,
                 tolerance: float = 1e-10, max_iterations: int = 256,
                 worker_count: int = 0) -> None:
        for name, v in (("max_iterations", max_iterations), ("worker_count", worker_count)):
            if not 0 <= int(v) <= _U32:
                raise ValueError(f"World: {name} {v} does not fit a uint32")
        if not -2**31 <= int(broad_phase) < 2**31:
            raise ValueError(f"World: broad_phase {broad_phase} does not fit an int32")
        s = _capi.WorldSettings()
        _lib.kairos_world_settings_init(ctypes.byref(s))
        s.broad_phase = int(broad_phase)
        s.query.tolerance = float(tolerance)
        s.query.max_iterations = int(max_iterations)
        s.worker_count = int(worker_count)
        out = ctypes.c_void_p()
        check(_lib.kairos_world_create(ctypes.byref(s), ctypes.byref(out)))
        self._w = out.value
        self.broad_phase = int(broad_phase)
        self.tolerance = float(tolerance)
        self.max_iterations = int(max_iterations)
        self.worker_count = int(worker_count)
        self._query_ids = np.empty(64, dtype=np.uint64)

    # ---- lifetime ----
    @property
    def handle(self) -> int:
        """The ``kairos_world*`` address (0 once closed)."""
        return self._w

    @property
    def closed(self) -> bool:
        return not self._w

    def close(self) -> None:
        """Destroys the world now (idempotent); its objects' shapes are released."""
        w = self._w
        if w:
            self._w = 0
            self._destroy(w)

    def __del__(self) -> None:
        w = self._w
        if w:
            self._w = 0
            self._destroy(w)

    def __enter__(self) -> "World":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __repr__(self) -> str:
        state = "closed" if not self._w else f"broad_phase={BroadPhase(self.broad_phase).name}"
        return f"<kairos.World {state}, worker_count={self.worker_count}>"

    # ---- objects ----
    def add(self, shape: Shape, pose: PoseLike = None, user_data: int = 0) -> int:
        """Adds an object with ``shape`` (retained by the world) at ``pose`` (world frame;
        None: identity), standing still until moved. ``user_data`` (uint64) comes back in
        contacts and hits. Returns the new object's id."""
        out = ctypes.c_uint64()
        if not 0 <= user_data <= 0xFFFFFFFFFFFFFFFF:
            raise ValueError(f"user_data {user_data} does not fit a uint64")
        check(_lib.kairos_world_add(self._w, handle_of(shape, "shape"), pose_c(pose), user_data,
                                    ctypes.byref(out)))
        return out.value

    def remove(self, id: int) -> None:
        """Removes an object; its id becomes stale."""
        check(_lib.kairos_world_remove(self._w, id))

    def set_pose(self, id: int, pose: PoseLike) -> None:
        """Teleports an object at once (no sweep) and cancels its pending move. The pose is
        required (None raises NullArgumentError, as the C API has no default here)."""
        check(_lib.kairos_world_set_pose(self._w, id, pose_c(pose)))

    def move(self, id: Union[int, np.ndarray, Any], pose: Any) -> None:
        """Sets the end pose (world frame) of the next step for one object or many.

        ``move(id, pose)``: one object. ``move(ids, poses)``: ``ids`` an (n,) uint64 array,
        ``poses`` an (n, 7) float64 array (or one (7,) pose for all), in one C call, all or
        nothing: an id that is stale or static or a bad pose moves nothing, and the error names
        the first bad index. An id given twice keeps its last pose. Static objects cannot move.
        The pose is required (None raises NullArgumentError).
        """
        if type(id) is int or isinstance(id, np.integer):
            status = _c_move(self._w, id, pose_c(pose))
            if status:
                raise error_for(status)
            return
        ids = id
        if type(ids) is not np.ndarray or ids.dtype != np.uint64:
            ids = np.asarray(ids, dtype=np.uint64)
        if ids.ndim != 1:
            raise ValueError(f"move: ids must be a 1-D array, got shape {ids.shape}")
        n = len(ids)
        poses = float_array(pose)
        if poses.shape == (7,):
            poses = np.broadcast_to(poses, (n, 7))
        elif poses.shape != (n, 7):
            raise ValueError(f"move: poses must have shape ({n}, 7), got {poses.shape}")
        ids = np.ascontiguousarray(ids)
        poses = np.ascontiguousarray(poses)
        status = _c_move_batch(self._w, ids.ctypes.data, poses.ctypes.data, n)
        if status:
            raise error_for(status)

    def set_static(self, id: int, is_static: bool = True) -> None:
        """A static object never moves in a step (move on it raises InvalidArgumentError;
        set_pose still places it), and a pair of two static objects is never tested."""
        check(_lib.kairos_world_set_static(self._w, id, 1 if is_static else 0))

    def set_filter(self, id: int, filter: Filter) -> None:
        """Sets the object's collision filter, used from the next step on."""
        if not isinstance(filter, Filter):
            raise TypeError(f"filter must be a kairos.Filter, got {type(filter).__name__}")
        check(_lib.kairos_world_set_filter(self._w, id, filter._c))

    def get_pose(self, id: int) -> Pose:
        """The object's pose now (the start of the next step), world frame."""
        out = _capi.Pose()
        check(_lib.kairos_world_get_pose(self._w, id, ctypes.byref(out)))
        return pose_from_c(out)

    def get_user_data(self, id: int) -> int:
        """The user data given to :meth:`add`."""
        out = ctypes.c_uint64()
        check(_lib.kairos_world_get_user_data(self._w, id, ctypes.byref(out)))
        return out.value

    # ---- stepping ----
    def step(self) -> None:
        """Finds each pair's first contact in [0, 1], then moves every object to its end pose."""
        check(_lib.kairos_world_step(self._w))

    def contacts(self) -> np.ndarray:
        """The last step's contacts, one per pair, sorted by toi (ties by (a, b)): a copy, as an
        array of :data:`~kairos.CONTACT_DTYPE` (``a`` < ``b`` ids, ``user_a``, ``user_b``,
        ``toi``, ``point``, ``normal`` unit from a toward b, world frame)."""
        ptr = ctypes.c_void_p()
        count = ctypes.c_size_t()
        check(_lib.kairos_world_contacts(self._w, ctypes.byref(ptr), ctypes.byref(count)))
        n = count.value
        out = np.empty(n, dtype=CONTACT_DTYPE)
        if n:
            ctypes.memmove(out.ctypes.data, ptr.value, n * CONTACT_DTYPE.itemsize)
        return out

    def overlaps(self) -> np.ndarray:
        """The last step's broad-phase pairs as an (m, 2) uint64 array (a copy), smaller id
        first in each pair."""
        ptr = ctypes.c_void_p()
        count = ctypes.c_size_t()
        check(_lib.kairos_world_overlaps(self._w, ctypes.byref(ptr), ctypes.byref(count)))
        n = count.value
        out = np.empty((n, 2), dtype=np.uint64)
        if n:
            ctypes.memmove(out.ctypes.data, ptr.value, n * 16)
        return out

    def step_stats(self) -> StepStats:
        """Counters of the last step."""
        s = _capi.StepStats()
        _lib.kairos_step_stats_init(ctypes.byref(s))
        check(_lib.kairos_world_step_stats(self._w, ctypes.byref(s)))
        return StepStats(s.broad_phase_pairs, s.swaps, s.heap_operations, s.narrow_phase_queries,
                         s.gjk_iterations, s.broad_phase_seconds, s.narrow_phase_seconds)

    # ---- queries (objects at their current poses; pending moves not applied) ----
    def ray_cast(self, origin: Vec3Like, translation: Vec3Like,
                 filter: Optional[Filter] = None) -> WorldHit:
        """The earliest object the ray ``origin + t * translation`` (t in [0, 1], world frame)
        hits, with the world's query settings. A ray starting inside an object hits it at 0."""
        out = _capi.WorldHit()
        check(_lib.kairos_world_ray_cast(self._w, vec3_c(origin, "origin"),
                                         vec3_c(translation, "translation"), _filter_c(filter),
                                         ctypes.byref(out)))
        return _hit(out)

    def shape_cast(self, shape: Shape, motion: MotionLike, filter: Optional[Filter] = None,
                   settings: Optional[QuerySettings] = None) -> WorldHit:
        """The earliest object ``shape`` hits while it follows ``motion`` (world frame; the
        objects standing still). settings None: the world's query settings. The shape is only
        read (not retained)."""
        out = _capi.WorldHit()
        check(_lib.kairos_world_shape_cast(self._w, handle_of(shape, "shape"), motion_c(motion),
                                           _filter_c(filter), settings_c(settings),
                                           ctypes.byref(out)))
        return _hit(out)

    def query_box(self, min: Vec3Like, max: Vec3Like,
                  filter: Optional[Filter] = None) -> np.ndarray:
        """Ids (uint64, increasing) of the objects whose bounding box at the current pose
        overlaps the closed box [min, max] (world frame, min <= max on every axis)."""
        lo, hi = vec3_c(min, "min"), vec3_c(max, "max")
        f = _filter_c(filter)
        buf = self._query_ids
        count = ctypes.c_size_t()
        check(_lib.kairos_world_query_box(self._w, lo, hi, f, buf.ctypes.data, len(buf),
                                          ctypes.byref(count)))
        n = count.value
        if n > len(buf):
            buf = np.empty(n, dtype=np.uint64)
            check(_lib.kairos_world_query_box(self._w, lo, hi, f, buf.ctypes.data, len(buf),
                                              ctypes.byref(count)))
            n = count.value
            self._query_ids = buf
        return buf[:n].copy()
