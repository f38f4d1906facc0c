# SPDX-License-Identifier: MIT
"""Convex shapes: Python objects that own one reference to a ``kairos_shape``.

Frames: each shape is defined in its local frame (table in docs/c-api.md, "Primitive frames");
a pose places it in the world. Sizes are in the caller's length unit, finite and > 0 unless
noted. Shapes are immutable: any number of threads may query one at once.

Lifetime: a shape's reference is released when the object is garbage collected, by
:meth:`Shape.close`, or at the end of a ``with`` block (whichever comes first; releasing twice
is harmless). The library reference-counts shapes itself: composites (:func:`transformed`,
:func:`minkowski_sum`, :func:`hull`) and worlds retain the parts they hold, so a part may be
closed or dropped in Python while a composite or world still uses it. A closed shape passed to a
query raises :class:`~kairos.NullArgumentError`. Closing is the owner's act: do not close a shape
while another thread is querying it or closing it too.
"""

from __future__ import annotations

import ctypes
from typing import Any, Dict, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from . import _capi
from .core import PoseLike, Vec3, Vec3Like, pose_c, vec3_c
from .errors import check

__all__ = [
    "Shape", "Sphere", "Box", "Capsule", "Cylinder", "Cone", "Point", "Segment", "ConvexHull",
    "Triangle", "Transformed", "MinkowskiSum", "HullOfTwo", "transformed", "minkowski_sum",
    "hull", "ShapeArray",
]

_lib = _capi.lib
_release = _lib.kairos_shape_release
_retain = _lib.kairos_shape_retain


class Shape:
    """Base class: one owned reference to an immutable convex shape.

    ``handle`` is the ``kairos_shape*`` address as an int (0 once closed); it is valid while
    this object is open (use :meth:`retain_handle` to keep the shape beyond it in C code).
    """

    kind: str = "shape"
    _h: int = 0  # set once the C constructor succeeded; 0 before and after release

    # Class attributes, so they are still reachable from __del__ at interpreter exit.
    _release = staticmethod(_release)

    def __init__(self) -> None:
        raise TypeError("kairos.Shape is abstract: use Sphere, Box, ..., transformed, hull")

    def _create(self, fn: Any, *args: Any, params: Optional[Dict[str, Any]] = None) -> None:
        out = ctypes.c_void_p()
        check(fn(*args, ctypes.byref(out)))
        self._h = out.value
        self._params = params or {}

    @property
    def handle(self) -> int:
        return self._h

    @property
    def closed(self) -> bool:
        return not self._h

    def retain_handle(self) -> int:
        """Adds a C reference and returns the handle; the caller owes one kairos_shape_release."""
        _retain(self._h)
        return self._h

    def close(self) -> None:
        """Releases this object's reference now (idempotent)."""
        h = self._h
        if h:
            self._h = 0
            self._release(h)

    def __del__(self) -> None:
        h = self._h
        if h:
            self._h = 0
            self._release(h)

    def __enter__(self) -> "Shape":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __repr__(self) -> str:
        params = ", ".join(f"{k}={v!r}" for k, v in getattr(self, "_params", {}).items())
        state = "" if self._h else " (closed)"
        return f"<kairos.{type(self).__name__} {self.kind}({params}){state}>"

    def support(self, direction: Vec3Like) -> Vec3:
        """A point of the shape (local frame) farthest along ``direction`` (any finite length;
        for a zero direction some point of the shape)."""
        out = _capi.Vec3()
        check(_lib.kairos_shape_support(self._h, vec3_c(direction, "direction"),
                                        ctypes.byref(out)))
        return (out.x, out.y, out.z)

    def bounds(self, pose: PoseLike = None) -> Tuple[Vec3, Vec3]:
        """The tight axis-aligned box ``(min, max)`` of the shape at ``pose``, world frame."""
        lo, hi = _capi.Vec3(), _capi.Vec3()
        check(_lib.kairos_shape_bounds(self._h, pose_c(pose), ctypes.byref(lo), ctypes.byref(hi)))
        return (lo.x, lo.y, lo.z), (hi.x, hi.y, hi.z)


class Sphere(Shape):
    """Ball of ``radius`` (> 0) centred at the local origin."""
    kind = "sphere"

    def __init__(self, radius: float) -> None:
        self._create(_lib.kairos_shape_sphere, float(radius), params={"radius": float(radius)})


class Box(Shape):
    """Box ``[-h, h]`` on each axis of the local frame; ``half_extents`` 3 numbers > 0."""
    kind = "box"

    def __init__(self, half_extents: Vec3Like) -> None:
        v = vec3_c(half_extents, "half_extents")
        self._create(_lib.kairos_shape_box, v, params={"half_extents": (v.x, v.y, v.z)})


class Capsule(Shape):
    """The segment (0, 0, -half_height)..(0, 0, +half_height) grown by ``radius`` (> 0):
    spans +-(half_height + radius) along local z. ``half_height`` >= 0 (0: a sphere)."""
    kind = "capsule"

    def __init__(self, radius: float, half_height: float) -> None:
        r, h = float(radius), float(half_height)
        self._create(_lib.kairos_shape_capsule, r, h, params={"radius": r, "half_height": h})


class Cylinder(Shape):
    """Solid cylinder, axis local z, z in [-half_height, half_height], of ``radius``."""
    kind = "cylinder"

    def __init__(self, radius: float, half_height: float) -> None:
        r, h = float(radius), float(half_height)
        self._create(_lib.kairos_shape_cylinder, r, h, params={"radius": r, "half_height": h})


class Cone(Shape):
    """Solid cone: apex (0, 0, +half_height), base disk of ``radius`` at z = -half_height.
    The local origin is the axis midpoint (as in FCL and Bullet), not the centre of mass."""
    kind = "cone"

    def __init__(self, radius: float, half_height: float) -> None:
        r, h = float(radius), float(half_height)
        self._create(_lib.kairos_shape_cone, r, h, params={"radius": r, "half_height": h})


class Point(Shape):
    """The local origin alone."""
    kind = "point"

    def __init__(self) -> None:
        self._create(_lib.kairos_shape_point)


class Segment(Shape):
    """The segment from (0, 0, -half_length) to (0, 0, +half_length), local frame."""
    kind = "segment"

    def __init__(self, half_length: float) -> None:
        h = float(half_length)
        self._create(_lib.kairos_shape_segment, h, params={"half_length": h})


class ConvexHull(Shape):
    """Convex hull of ``points``, an (n, 3) array-like in the local frame (never recentred;
    copied; only the hull's vertices are kept). Points near a plane, a line or one point give a
    flat polygon, a segment or a point; no points raise :class:`~kairos.DegenerateError`."""
    kind = "convex_hull"

    def __init__(self, points: Union[np.ndarray, Sequence[Sequence[float]]]) -> None:
        pts = np.ascontiguousarray(points, dtype=np.float64)
        if pts.size == 0:
            pts = pts.reshape(0, 3)
        if pts.ndim != 2 or pts.shape[1] != 3:
            raise ValueError(f"ConvexHull: points must be an (n, 3) array, got shape {pts.shape}")
        self._create(_lib.kairos_shape_convex_hull, pts.ctypes.data if len(pts) else None,
                     len(pts), params={"points": len(pts)})


class Triangle(Shape):
    """The flat triangle a, b, c (local frame, as given). Collinear or coinciding corners raise
    :class:`~kairos.DegenerateError`."""
    kind = "triangle"

    def __init__(self, a: Vec3Like, b: Vec3Like, c: Vec3Like) -> None:
        va, vb, vc = vec3_c(a, "a"), vec3_c(b, "b"), vec3_c(c, "c")
        self._create(_lib.kairos_shape_triangle, va, vb, vc,
                     params={"a": (va.x, va.y, va.z), "b": (vb.x, vb.y, vb.z),
                             "c": (vc.x, vc.y, vc.z)})


class _Composite(Shape):
    def __init__(self) -> None:  # built by the functions below
        raise TypeError("use kairos.transformed, kairos.minkowski_sum or kairos.hull")


class Transformed(_Composite):
    """``shape`` mapped by ``x -> linear x + translation`` (see :func:`transformed`)."""
    kind = "transformed"


class MinkowskiSum(_Composite):
    """``a + b = {x + y}`` (see :func:`minkowski_sum`)."""
    kind = "minkowski_sum"


class HullOfTwo(_Composite):
    """Convex hull of the union of two shapes (see :func:`hull`)."""
    kind = "hull"


def _build(cls: type, fn: Any, *args: Any, params: Dict[str, Any]) -> Shape:
    s = cls.__new__(cls)
    s._create(fn, *args, params=params)
    return s


def transformed(shape: Shape, linear: Union[np.ndarray, Sequence[float], None] = None,
                translation: Vec3Like = (0.0, 0.0, 0.0)) -> Shape:
    """``shape`` mapped by ``x -> linear @ x + translation`` (in its local frame).

    ``linear``: a 3x3 matrix (or 9 numbers, row-major), finite and invertible (|det| > 1e-12
    times the product of its row lengths); it may scale, shear or mirror. None: the identity.
    The library retains ``shape``.
    """
    m = np.eye(3) if linear is None else linear
    m = np.ascontiguousarray(m, dtype=np.float64)
    if m.size != 9 or m.shape not in ((3, 3), (9,)):
        raise ValueError(f"transformed: linear must be 3x3 or 9 numbers, got shape {m.shape}")
    t = vec3_c(translation, "translation")
    return _build(Transformed, _lib.kairos_shape_transformed, handle_of(shape, "shape"),
                  m.ctypes.data, t, params={"shape": shape.kind, "translation": (t.x, t.y, t.z)})


def minkowski_sum(a: Shape, b: Shape) -> Shape:
    """Minkowski sum ``a + b`` (both in the same local frame), e.g. a rounded box as box +
    sphere. The library retains ``a`` and ``b``."""
    return _build(MinkowskiSum, _lib.kairos_shape_minkowski_sum, handle_of(a, "a"),
                  handle_of(b, "b"), params={"a": a.kind, "b": b.kind})


def hull(a: Shape, b: Shape) -> Shape:
    """Convex hull of the union of ``a`` and ``b`` (both in the same local frame). The library
    retains ``a`` and ``b``."""
    return _build(HullOfTwo, _lib.kairos_shape_hull, handle_of(a, "a"), handle_of(b, "b"),
                  params={"a": a.kind, "b": b.kind})


def handle_of(shape: Shape, name: str) -> int:
    """The handle of a Shape argument (0 when closed: the library then names ``name`` NULL)."""
    try:
        return shape._h
    except AttributeError:
        raise TypeError(f"{name} must be a kairos.Shape, got {type(shape).__name__}") from None


class ShapeArray:
    """A fixed array of shapes for the batch queries, built once and reused.

    Holds the ``kairos_shape*`` addresses as a uint64 array (``handles``) and one C reference
    to each distinct shape, so the batch needs no per-shape Python work and a shape closed in
    Python meanwhile stays valid. Either ``ShapeArray(shapes)`` (one entry per shape) or
    ``ShapeArray(palette, indices)`` (entry i is ``palette[indices[i]]``, built with numpy).
    Released like a Shape (close(), ``with``, garbage collection).
    """

    _owned: Tuple[int, ...] = ()

    def __init__(self, shapes: Union[Iterable[Shape], Shape],
                 indices: Union[np.ndarray, Sequence[int], None] = None) -> None:
        palette = [shapes] if isinstance(shapes, Shape) else list(shapes)
        for i, s in enumerate(palette):
            if not isinstance(s, Shape):
                raise TypeError(f"ShapeArray: item {i} is a {type(s).__name__}, not a Shape")
            if not s._h:
                raise ValueError(f"ShapeArray: shape {i} is closed")
        palette_handles = np.fromiter((s._h for s in palette), dtype=np.uint64,
                                      count=len(palette))
        if indices is None:
            handles = palette_handles
        else:
            idx = np.asarray(indices)
            if idx.ndim != 1 or not np.issubdtype(idx.dtype, np.integer):
                raise ValueError("ShapeArray: indices must be a 1-D integer array")
            handles = palette_handles[idx]
        owned = tuple(dict.fromkeys(s._h for s in palette))
        for h in owned:
            _retain(h)
        self._owned = owned
        handles = np.ascontiguousarray(handles, dtype=np.uint64)
        handles.flags.writeable = False
        self.handles: np.ndarray = handles

    def __len__(self) -> int:
        return len(self.handles)

    def close(self) -> None:
        """Drops this array's references (idempotent); using it afterwards raises."""
        owned, self._owned = self._owned, ()
        for h in owned:
            _release(h)
        self.handles = None  # type: ignore[assignment]

    def __del__(self) -> None:
        owned, self._owned = self._owned, ()
        for h in owned:
            Shape._release(h)

    def __enter__(self) -> "ShapeArray":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __repr__(self) -> str:
        n = "closed" if self.handles is None else f"{len(self.handles)} entries"
        return f"<kairos.ShapeArray {n}, {len(self._owned)} distinct shapes>"
