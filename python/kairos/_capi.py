# SPDX-License-Identifier: MIT
"""The C ABI of libkairos as ctypes declarations and numpy dtypes (internal).

Every struct here has the size and field offsets of include/kairos/kairos.h on x86-64 LP64
(pinned in tests/abi/layout.c); the package checks them when it is imported. Pointer arguments
that the package fills from numpy arrays (the batches, hull points, 3x3 matrices) are declared
``c_void_p``: the same ABI as the typed pointer, and it takes an address as a Python int.

The library is looked for, in order:

1. the path in the environment variable ``KAIROS_LIBRARY`` (only that one when it is set);
2. ``libkairos.so.0`` in this package's directory;
3. the path recorded at install: ``LIBRARY_FROM_PACKAGE`` in ``kairos/_location.py`` (written by
   the CMake install, relative to the package's directory; absent in the source tree);
4. an installed prefix: for a package at ``<prefix>/lib*/python3*/{site,dist}-packages/kairos``,
   ``<prefix>/lib*/`` and ``<prefix>/lib/<multiarch>/``;
5. ``build/release/libkairos.so.0`` under any parent directory of the package (the source tree);
6. the system search of ``ctypes.CDLL("libkairos.so.0")``.
"""

from __future__ import annotations

import ast
import ctypes
import os
import sysconfig
from pathlib import Path
from typing import Iterator, List, Optional, Tuple

import numpy as np

LIBRARY_NAME = "libkairos.so.0"
# The function table version that has the batches (Kairos 0.2).
REQUIRED_ABI = 2
# The major version this binding is written against (equal majors are ABI compatible).
SUPPORTED_MAJOR = 0

c_double = ctypes.c_double
c_int32 = ctypes.c_int32
c_uint32 = ctypes.c_uint32
c_uint64 = ctypes.c_uint64
c_size_t = ctypes.c_size_t
c_void_p = ctypes.c_void_p
POINTER = ctypes.POINTER

# ---- Status, termination and broad-phase constants (values from kairos.h, never renumbered) ----
OK = 0
ERROR_NULL_ARGUMENT = -1
ERROR_INVALID_ARGUMENT = -2
ERROR_STRUCT_SIZE = -3
ERROR_DEGENERATE = -4
ERROR_STALE_ID = -5
ERROR_OUT_OF_MEMORY = -6
ERROR_NOT_IMPLEMENTED = -7
ERROR_UNSUPPORTED_VERSION = -8
ERROR_INTERNAL = -9
ERROR_LIMIT = -10

QUAT_TOLERANCE = 1e-6
MAX_MAGNITUDE = 1e100


# ---- Structs -------------------------------------------------------------------------------
class Vec3(ctypes.Structure):
    _fields_ = [("x", c_double), ("y", c_double), ("z", c_double)]


class Quat(ctypes.Structure):
    _fields_ = [("x", c_double), ("y", c_double), ("z", c_double), ("w", c_double)]


class Pose(ctypes.Structure):
    _fields_ = [("position", Vec3), ("orientation", Quat)]


class Motion(ctypes.Structure):
    _fields_ = [("start", Pose), ("end", Pose)]


class QuerySettings(ctypes.Structure):
    _fields_ = [("struct_size", c_uint32), ("tolerance", c_double), ("max_iterations", c_uint32)]


class DistanceResult(ctypes.Structure):
    _fields_ = [("distance", c_double), ("point_a", Vec3), ("point_b", Vec3), ("axis", Vec3),
                ("intersecting", c_int32), ("iterations", c_uint32), ("termination", c_int32)]


class CastResult(ctypes.Structure):
    _fields_ = [("hit", c_int32), ("toi", c_double), ("point", Vec3), ("normal", Vec3),
                ("iterations", c_uint32), ("termination", c_int32)]


# The task hook's function pointers are plain pointers here: the package never sets them.
class WorldSettings(ctypes.Structure):
    _fields_ = [("struct_size", c_uint32), ("broad_phase", c_int32), ("query", QuerySettings),
                ("worker_count", c_uint32), ("enqueue_task", c_void_p), ("finish_task", c_void_p),
                ("task_user_context", c_void_p)]


class Contact(ctypes.Structure):
    _fields_ = [("a", c_uint64), ("b", c_uint64), ("user_a", c_uint64), ("user_b", c_uint64),
                ("toi", c_double), ("point", Vec3), ("normal", Vec3)]


class StepStats(ctypes.Structure):
    _fields_ = [("struct_size", c_uint32), ("broad_phase_pairs", c_uint64), ("swaps", c_uint64),
                ("heap_operations", c_uint64), ("narrow_phase_queries", c_uint64),
                ("gjk_iterations", c_uint64), ("broad_phase_seconds", c_double),
                ("narrow_phase_seconds", c_double)]


class Filter(ctypes.Structure):
    _fields_ = [("category_bits", c_uint32), ("mask_bits", c_uint32), ("group", c_int32)]


class WorldHit(ctypes.Structure):
    _fields_ = [("hit", c_int32), ("id", c_uint64), ("user_data", c_uint64), ("toi", c_double),
                ("point", Vec3), ("normal", Vec3)]


# Sizes of tests/abi/layout.c.
STRUCT_SIZES = {Vec3: 24, Quat: 32, Pose: 56, Motion: 112, QuerySettings: 24, DistanceResult: 96,
                CastResult: 72, WorldSettings: 64, Contact: 88, StepStats: 64, Filter: 12,
                WorldHit: 80}


# ---- numpy dtypes the C functions write into directly (padding included) -----------------------
def _dtype(fields: List[Tuple[str, object, int]], itemsize: int) -> np.dtype:
    return np.dtype({"names": [f[0] for f in fields], "formats": [f[1] for f in fields],
                     "offsets": [f[2] for f in fields], "itemsize": itemsize})


_V3 = ("<f8", (3,))
DISTANCE_DTYPE = _dtype([("distance", "<f8", 0), ("point_a", _V3, 8), ("point_b", _V3, 32),
                         ("axis", _V3, 56), ("intersecting", "<i4", 80),
                         ("iterations", "<u4", 84), ("termination", "<i4", 88)], 96)
CAST_DTYPE = _dtype([("hit", "<i4", 0), ("toi", "<f8", 8), ("point", _V3, 16),
                     ("normal", _V3, 40), ("iterations", "<u4", 64),
                     ("termination", "<i4", 68)], 72)
CONTACT_DTYPE = _dtype([("a", "<u8", 0), ("b", "<u8", 8), ("user_a", "<u8", 16),
                        ("user_b", "<u8", 24), ("toi", "<f8", 32), ("point", _V3, 40),
                        ("normal", _V3, 64)], 88)

# Each dtype beside the ctypes struct of the same C type, checked field by field below.
DTYPE_STRUCTS = ((DISTANCE_DTYPE, DistanceResult), (CAST_DTYPE, CastResult),
                 (CONTACT_DTYPE, Contact))


def _check_layouts() -> None:
    for struct, size in STRUCT_SIZES.items():
        if ctypes.sizeof(struct) != size:
            raise ImportError(f"kairos: ctypes {struct.__name__} is {ctypes.sizeof(struct)} bytes, "
                              f"the C ABI says {size}")
    for dtype, struct in DTYPE_STRUCTS:
        if dtype.itemsize != ctypes.sizeof(struct):
            raise ImportError(f"kairos: dtype for {struct.__name__} has the wrong itemsize")
        for name, _ctype in struct._fields_:
            if dtype.fields[name][1] != getattr(struct, name).offset:
                raise ImportError(f"kairos: dtype field {struct.__name__}.{name} is misplaced")


_check_layouts()

# ---- Prototypes ----------------------------------------------------------------------------
_ShapeP = c_void_p  # kairos_shape* (opaque); passed and returned as an int address
_WorldP = c_void_p  # kairos_world* (opaque)
_Status = c_int32
_P = POINTER

PROTOTYPES = {
    "kairos_status_name": (ctypes.c_char_p, [c_int32]),
    "kairos_last_error": (ctypes.c_char_p, []),
    "kairos_version": (c_uint32, []),
    "kairos_get_api": (_Status, [c_uint32, _P(c_void_p)]),
    # Shapes
    "kairos_shape_sphere": (_Status, [c_double, _P(_ShapeP)]),
    "kairos_shape_box": (_Status, [Vec3, _P(_ShapeP)]),
    "kairos_shape_capsule": (_Status, [c_double, c_double, _P(_ShapeP)]),
    "kairos_shape_cylinder": (_Status, [c_double, c_double, _P(_ShapeP)]),
    "kairos_shape_cone": (_Status, [c_double, c_double, _P(_ShapeP)]),
    "kairos_shape_point": (_Status, [_P(_ShapeP)]),
    "kairos_shape_segment": (_Status, [c_double, _P(_ShapeP)]),
    "kairos_shape_convex_hull": (_Status, [c_void_p, c_size_t, _P(_ShapeP)]),
    "kairos_shape_triangle": (_Status, [Vec3, Vec3, Vec3, _P(_ShapeP)]),
    "kairos_shape_minkowski_sum": (_Status, [_ShapeP, _ShapeP, _P(_ShapeP)]),
    "kairos_shape_hull": (_Status, [_ShapeP, _ShapeP, _P(_ShapeP)]),
    "kairos_shape_transformed": (_Status, [_ShapeP, c_void_p, Vec3, _P(_ShapeP)]),
    "kairos_shape_retain": (None, [_ShapeP]),
    "kairos_shape_release": (None, [_ShapeP]),
    "kairos_shape_support": (_Status, [_ShapeP, Vec3, _P(Vec3)]),
    "kairos_shape_bounds": (_Status, [_ShapeP, _P(Pose), _P(Vec3), _P(Vec3)]),
    # Pair queries
    "kairos_query_settings_init": (None, [_P(QuerySettings)]),
    "kairos_distance": (_Status, [_ShapeP, _P(Pose), _ShapeP, _P(Pose), _P(QuerySettings),
                                  _P(DistanceResult)]),
    "kairos_signed_distance": (_Status, [_ShapeP, _P(Pose), _ShapeP, _P(Pose),
                                         _P(QuerySettings), _P(DistanceResult)]),
    "kairos_intersect": (_Status, [_ShapeP, _P(Pose), _ShapeP, _P(Pose), _P(Vec3), _P(c_int32)]),
    "kairos_ray_cast": (_Status, [_ShapeP, _P(Pose), Vec3, Vec3, _P(QuerySettings),
                                  _P(CastResult)]),
    "kairos_shape_cast": (_Status, [_ShapeP, _P(Pose), Vec3, _ShapeP, _P(Pose), Vec3,
                                    _P(QuerySettings), _P(CastResult)]),
    "kairos_motion_cast": (_Status, [_ShapeP, _P(Motion), _ShapeP, _P(Motion), _P(QuerySettings),
                                     _P(CastResult)]),
    # World
    "kairos_world_settings_init": (None, [_P(WorldSettings)]),
    "kairos_world_create": (_Status, [_P(WorldSettings), _P(_WorldP)]),
    "kairos_world_destroy": (None, [_WorldP]),
    "kairos_world_add": (_Status, [_WorldP, _ShapeP, _P(Pose), c_uint64, _P(c_uint64)]),
    "kairos_world_remove": (_Status, [_WorldP, c_uint64]),
    "kairos_world_set_pose": (_Status, [_WorldP, c_uint64, _P(Pose)]),
    "kairos_world_move": (_Status, [_WorldP, c_uint64, _P(Pose)]),
    "kairos_world_step": (_Status, [_WorldP]),
    # const kairos_contact** and const kairos_object_id**: the package reads them as addresses.
    "kairos_world_contacts": (_Status, [_WorldP, _P(c_void_p), _P(c_size_t)]),
    "kairos_world_overlaps": (_Status, [_WorldP, _P(c_void_p), _P(c_size_t)]),
    "kairos_step_stats_init": (None, [_P(StepStats)]),
    "kairos_world_step_stats": (_Status, [_WorldP, _P(StepStats)]),
    "kairos_world_set_filter": (_Status, [_WorldP, c_uint64, _P(Filter)]),
    "kairos_world_set_static": (_Status, [_WorldP, c_uint64, c_int32]),
    "kairos_world_get_pose": (_Status, [_WorldP, c_uint64, _P(Pose)]),
    "kairos_world_get_user_data": (_Status, [_WorldP, c_uint64, _P(c_uint64)]),
    "kairos_world_ray_cast": (_Status, [_WorldP, Vec3, Vec3, _P(Filter), _P(WorldHit)]),
    "kairos_world_shape_cast": (_Status, [_WorldP, _ShapeP, _P(Motion), _P(Filter),
                                          _P(QuerySettings), _P(WorldHit)]),
    "kairos_world_query_box": (_Status, [_WorldP, Vec3, Vec3, _P(Filter), c_void_p, c_size_t,
                                         _P(c_size_t)]),
    # Batches (ABI 2): every array is a C array of the structs above, passed as its address.
    "kairos_distance_batch": (_Status, [c_void_p, c_void_p, c_void_p, c_void_p, c_size_t,
                                        _P(QuerySettings), _WorldP, c_void_p]),
    "kairos_shape_cast_batch": (_Status, [c_void_p, c_void_p, c_void_p, c_void_p, c_void_p,
                                          c_void_p, c_size_t, _P(QuerySettings), _WorldP,
                                          c_void_p]),
    "kairos_motion_cast_batch": (_Status, [c_void_p, c_void_p, c_void_p, c_void_p, c_size_t,
                                           _P(QuerySettings), _WorldP, c_void_p]),
    "kairos_world_move_batch": (_Status, [_WorldP, c_void_p, c_void_p, c_size_t]),
}


# ---- Loading -------------------------------------------------------------------------------
def _recorded(package_dir: Path) -> Optional[str]:
    """The library path _location.py records, relative to the package directory, or None."""
    location = package_dir / "_location.py"
    if not location.is_file():
        return None
    # Read as data (the one string assignment), not executed.
    try:
        tree = ast.parse(location.read_text(), str(location))
    except (OSError, SyntaxError, ValueError) as e:
        raise ImportError(f"kairos: unreadable {location}: {e}") from None
    for node in tree.body:
        if (isinstance(node, ast.Assign) and len(node.targets) == 1
                and isinstance(node.targets[0], ast.Name)
                and node.targets[0].id == "LIBRARY_FROM_PACKAGE"
                and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str)
                and node.value.value):
            return os.path.normpath(os.path.join(package_dir, node.value.value))
    return None


def _candidates(package_dir: Path) -> Iterator[str]:
    yield str(package_dir / LIBRARY_NAME)
    recorded = _recorded(package_dir)
    if recorded:
        yield recorded
    # Installed: <prefix>/<libdir>/python3.X/{site,dist}-packages/kairos.
    for parent in package_dir.parents:
        if parent.name.startswith("python") and parent.parent.name.startswith("lib"):
            libdir = parent.parent
            prefix = libdir.parent
            dirs = [libdir, prefix / "lib", prefix / "lib64"]
            multiarch = sysconfig.get_config_var("MULTIARCH")
            if multiarch:
                dirs.append(prefix / "lib" / multiarch)
            seen = set()
            for d in dirs:
                if d not in seen:
                    seen.add(d)
                    yield str(d / LIBRARY_NAME)
            break
    # The source tree: python/kairos -> ../../build/release.
    for parent in package_dir.parents:
        yield str(parent / "build" / "release" / LIBRARY_NAME)


def load() -> Tuple[ctypes.CDLL, str]:
    """Finds and opens libkairos.so.0 (search order in the module docstring)."""
    tried: List[str] = []
    env = os.environ.get("KAIROS_LIBRARY")
    if env:
        paths = [env]
    else:
        paths = [p for p in _candidates(Path(__file__).resolve().parent) if os.path.exists(p)]
        paths.append(LIBRARY_NAME)  # the dynamic loader's own search
    for path in paths:
        try:
            lib = ctypes.CDLL(path)
        except OSError as e:
            tried.append(f"{path}: {e}")
            continue
        return lib, path
    if not env:
        tried.insert(0, "(no file at the package, prefix or build-tree locations: "
                        + ", ".join(_candidates(Path(__file__).resolve().parent)) + ")")
    raise ImportError("kairos: cannot load " + LIBRARY_NAME + "; set KAIROS_LIBRARY to its path. "
                      "Tried:\n  " + "\n  ".join(tried))


def _declare(lib: ctypes.CDLL, path: str) -> None:
    missing = []
    for name, (restype, argtypes) in PROTOTYPES.items():
        try:
            fn = getattr(lib, name)
        except AttributeError:
            missing.append(name)
            continue
        fn.restype = restype
        fn.argtypes = argtypes
    if missing:
        raise ImportError(f"kairos: {path} is too old for this package (it lacks "
                          f"{', '.join(missing)}); the package needs Kairos 0.2 (ABI version "
                          f"{REQUIRED_ABI}, the batch functions)")
    version = lib.kairos_version()
    if version // 10000 != SUPPORTED_MAJOR:
        raise ImportError(f"kairos: {path} is version {version // 10000}.{version // 100 % 100}."
                          f"{version % 100}; this package supports major version "
                          f"{SUPPORTED_MAJOR} only")
    table = c_void_p()
    status = lib.kairos_get_api(REQUIRED_ABI, ctypes.byref(table))
    if status != OK:
        raise ImportError(f"kairos: {path} does not provide ABI version {REQUIRED_ABI} "
                          f"(the batch functions): "
                          f"{lib.kairos_last_error().decode('utf-8', 'replace')}")
    # The default symbol version of kairos_world_settings_init must be the 0.2 one (64 bytes).
    settings = WorldSettings()
    lib.kairos_world_settings_init(ctypes.byref(settings))
    if settings.struct_size != ctypes.sizeof(WorldSettings):
        raise ImportError(f"kairos: {path}'s kairos_world_settings_init writes a "
                          f"{settings.struct_size}-byte struct, not the 0.2 "
                          f"{ctypes.sizeof(WorldSettings)}-byte one")


lib, path = load()
_declare(lib, path)


def address(array: np.ndarray) -> int:
    """The address of a numpy array's first element (the array must stay alive meanwhile)."""
    return array.ctypes.data
