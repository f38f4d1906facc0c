#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Batch shape casts and batch world moves from Python, against the same work one call at a time.

Run from the top of the source tree:

    PYTHONPATH=python /usr/bin/python3 bench/python/bench_batch.py [--json] [--c-json FILE]
        [--save-scene FILE] [--repeat N]

Scene (make_scene), mirrored by the C++ benchmark bench/bench_batch.cpp (same shapes, kinds and
distributions; its generator is std::mt19937_64, so the draws differ, not their law):

    seed                 20261127, numpy.random.default_rng(seed) (PCG64)
    n                    10,000 shape casts
    shape mix            ("box", "sphere", "hull"), taken in turn: query i casts
                         mix[i % 3] (a) against mix[(i // 3) % 3] (b)
                           box     kairos_shape_box half extents (0.5, 0.4, 0.3)
                           sphere  kairos_shape_sphere radius 0.5
                           hull    kairos_shape_convex_hull of 32 points, each coordinate normal
                                   with mean 0 and deviation 0.5 (the first draws: rng.normal)
    pose spread 2.0      poses_a, then poses_b: positions uniform in [-2, 2]^3 (rng.uniform, n x 3),
                         then orientations: 4 standard normals per pose (rng.normal, n x 4),
                         normalised; each array (n, 7) = (x, y, z, qx, qy, qz, qw)
    translation spread   translations_a, then translations_b: uniform in [-4, 4]^3, (n, 3)
      4.0
    settings             the defaults (tolerance 1e-10, max_iterations 256), calling thread
    moves                a world of 1,000 spheres of radius 0.1 (no step is run), start and end
                         poses with positions uniform in [-20, 20]^3 (seed + 1)

--save-scene FILE writes the casts as raw little-endian data for an exact replay: int64 n,
int32 kinds_a[n], int32 kinds_b[n], float64 hull_points[32][3], poses_a[n][7],
translations_a[n][3], poses_b[n][7], translations_b[n][3].

Measured (median over repetitions, time.perf_counter):
  (a) kairos.shape_cast_batch over the n casts on the calling thread, shapes as a prebuilt
      ShapeArray: into a result array allocated once (out=, as the C benchmark writes into one
      vector) and with a fresh result array per call (the plain call); also with plain lists of
      Shapes; ns per cast;
  (b) a Python loop of n kairos.shape_cast calls, ns per cast;
  (c) World.move of 1,000 objects as one batch (ids uint64 (n,), poses (n, 7)), ns per object;
  (d) 1,000 World.move calls from a Python loop, ns per object.
The Python overhead of a batch is fixed per call: the "batch of 1" rows measure it.

The C side: build/release/bench/bench_batch --benchmark_repetitions=5 --benchmark_format=json
> c.json, then --c-json c.json adds each row's ratio to the C loop of single calls (run both
pinned to one core, e.g. taskset -c 0, on a shared machine).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from typing import Callable, Dict, List, Sequence

import numpy as np

try:
    import kairos
except ImportError as e:
    sys.exit(f"cannot import kairos ({e}); run with PYTHONPATH=python from the source tree")

SEED = 20261127
N_CASTS = 10_000
MIX = ("box", "sphere", "hull")
POSE_SPREAD = 2.0
TRANSLATION_SPREAD = 4.0
N_MOVES = 1_000
MOVE_SPREAD = 20.0
HULL_POINTS = 32


def make_shape(kind: str, hull_points: np.ndarray) -> kairos.Shape:
    if kind == "box":
        return kairos.Box((0.5, 0.4, 0.3))
    if kind == "sphere":
        return kairos.Sphere(0.5)
    if kind == "hull":
        return kairos.ConvexHull(hull_points)
    raise ValueError(f"unknown shape kind {kind!r}")


def random_poses(rng: np.random.Generator, n: int, spread: float) -> np.ndarray:
    position = rng.uniform(-spread, spread, size=(n, 3))
    q = rng.normal(size=(n, 4))
    return np.hstack([position, q / np.linalg.norm(q, axis=1, keepdims=True)])


def make_scene(seed: int = SEED, n: int = N_CASTS, mix: Sequence[str] = MIX,
               pose_spread: float = POSE_SPREAD,
               translation_spread: float = TRANSLATION_SPREAD) -> Dict[str, object]:
    """The benchmark's shape casts (see the module docstring for the exact draw order)."""
    rng = np.random.default_rng(seed)
    hull_points = rng.normal(0.0, 0.5, size=(HULL_POINTS, 3))
    palette = [make_shape(k, hull_points) for k in mix]
    i = np.arange(n)
    kinds_a = (i % len(mix)).astype(np.int32)
    kinds_b = ((i // len(mix)) % len(mix)).astype(np.int32)
    poses_a = random_poses(rng, n, pose_spread)
    poses_b = random_poses(rng, n, pose_spread)
    translations_a = rng.uniform(-translation_spread, translation_spread, size=(n, 3))
    translations_b = rng.uniform(-translation_spread, translation_spread, size=(n, 3))
    return dict(palette=palette, hull_points=hull_points, kinds_a=kinds_a, kinds_b=kinds_b,
                poses_a=poses_a, poses_b=poses_b, translations_a=translations_a,
                translations_b=translations_b)


def save_scene(scene: Dict[str, object], path: str) -> None:
    with open(path, "wb") as f:
        f.write(np.int64(len(scene["kinds_a"])).tobytes())
        for key in ("kinds_a", "kinds_b", "hull_points", "poses_a", "translations_a", "poses_b",
                    "translations_b"):
            f.write(np.ascontiguousarray(scene[key]).astype(scene[key].dtype.newbyteorder("<"))
                    .tobytes())


def median_seconds(fn: Callable[[], object], repeat: int, number: int = 1) -> float:
    fn()  # warm up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t0) / number)
    return statistics.median(times)


def c_medians(path: str) -> Dict[str, float]:
    """ns per query of bench/bench_batch.cpp's Google Benchmark JSON (--benchmark_format=json),
    medians when it ran with repetitions."""
    with open(path) as f:
        runs = json.load(f)["benchmarks"]
    names = {"shape_cast_single/10000": ("cast_loop", "ns_per_query"),
             "shape_cast_batch/n:10000/workers:0/real_time": ("cast_batch", "ns_per_query"),
             "world_move_single/1000": ("move_loop", "ns_per_move"),
             "world_move_batch/1000": ("move_batch", "ns_per_move")}
    samples: Dict[str, List[float]] = {}
    for run in runs:
        key = names.get(run.get("run_name", run["name"]))
        if key is None or run.get("aggregate_name", "median") != "median":
            continue
        # The counters are rates inverted: seconds per query.
        samples.setdefault(key[0], []).append(run[key[1]] * 1e9)
    return {k: statistics.median(v) for k, v in samples.items()}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--json", action="store_true", help="print the medians as JSON")
    parser.add_argument("--repeat", type=int, default=9, help="repetitions (median taken)")
    parser.add_argument("--save-scene", metavar="FILE", help="write the scene's arrays")
    parser.add_argument("--c-json", metavar="FILE",
                        help="bench/bench_batch.cpp's JSON output, for the ratios to C")
    args = parser.parse_args()

    scene = make_scene()
    if args.save_scene:
        save_scene(scene, args.save_scene)
    palette = scene["palette"]
    a = kairos.ShapeArray(palette, scene["kinds_a"])
    b = kairos.ShapeArray(palette, scene["kinds_b"])
    pa, pb = scene["poses_a"], scene["poses_b"]
    ta, tb = scene["translations_a"], scene["translations_b"]
    n = len(pa)
    list_a = [palette[k] for k in scene["kinds_a"]]
    list_b = [palette[k] for k in scene["kinds_b"]]
    out = kairos.shape_cast_batch(a, pa, ta, b, pb, tb)
    hit_rate = float(out["hit"].mean())
    cast_batch = kairos.shape_cast_batch
    ns: Dict[str, float] = {}

    def per(key: str, fn: Callable[[], object], count: int, number: int = 1) -> None:
        ns[key] = median_seconds(fn, args.repeat, number) / count * 1e9

    # As the C benchmark does: results written into one array allocated once.
    per("shape_cast_batch_out", lambda: cast_batch(a, pa, ta, b, pb, tb, out=out), n)
    # The plain call: a fresh (n,) result array each time (720 KB for n = 10,000).
    per("shape_cast_batch", lambda: cast_batch(a, pa, ta, b, pb, tb), n)
    per("shape_cast_batch_lists", lambda: cast_batch(list_a, pa, ta, list_b, pb, tb), n)
    a1 = kairos.ShapeArray(palette, scene["kinds_a"][:1])
    b1 = kairos.ShapeArray(palette, scene["kinds_b"][:1])
    per("shape_cast_batch_of_1", lambda: cast_batch(a1, pa[:1], ta[:1], b1, pb[:1], tb[:1]), 1,
        2000)

    # Singles take what a Python caller naturally has: Shape objects and rows as tuples.
    pa_t, pb_t = [tuple(r) for r in pa.tolist()], [tuple(r) for r in pb.tolist()]
    ta_t, tb_t = [tuple(r) for r in ta.tolist()], [tuple(r) for r in tb.tolist()]
    cast = kairos.shape_cast

    def singles() -> None:
        for i in range(n):
            cast(list_a[i], pa_t[i], ta_t[i], list_b[i], pb_t[i], tb_t[i])
    ns["shape_cast_loop"] = median_seconds(singles, max(3, args.repeat // 3)) / n * 1e9

    rng = np.random.default_rng(SEED + 1)
    world = kairos.World()
    dot = kairos.Sphere(0.1)
    start = random_poses(rng, N_MOVES, MOVE_SPREAD)
    ids = np.array([world.add(dot, start[i], i) for i in range(N_MOVES)], dtype=np.uint64)
    ends = random_poses(rng, N_MOVES, MOVE_SPREAD)
    per("world_move_batch", lambda: world.move(ids, ends), N_MOVES, 20)
    per("world_move_batch_of_1", lambda: world.move(ids[:1], ends[:1]), 1, 2000)
    id_list, end_list = ids.tolist(), [tuple(r) for r in ends.tolist()]
    move = world.move

    def moves() -> None:
        for i, e in zip(id_list, end_list):
            move(i, e)
    per("world_move_loop", moves, N_MOVES)

    c = c_medians(args.c_json) if args.c_json else {}
    if args.json:
        print(json.dumps({"n_casts": n, "n_moves": N_MOVES, "seed": SEED, "hit_rate": hit_rate,
                          "library": kairos.library_path(), "median_ns": ns,
                          "c_median_ns": c}, indent=2))
        return 0
    print(f"kairos {'.'.join(map(str, kairos.version_tuple()))} at {kairos.library_path()}")
    print(f"scene: seed {SEED}, n = {n} casts, mix {'/'.join(MIX)}, hit rate {hit_rate:.1%}; "
          f"world of {N_MOVES} objects; median of {args.repeat} repetitions\n")
    table = [
        ("(a) shape_cast_batch, calling thread, out= (as C)", "per cast", "shape_cast_batch_out",
         "cast_loop"),
        ("    shape_cast_batch, fresh result array", "per cast", "shape_cast_batch", "cast_loop"),
        ("    shape_cast_batch, lists of Shapes", "per cast", "shape_cast_batch_lists", None),
        ("    shape_cast_batch of 1 (fixed overhead)", "per call", "shape_cast_batch_of_1", None),
        ("(b) Python loop of shape_cast", "per cast", "shape_cast_loop", "cast_loop"),
        ("(c) World.move batch of 1,000", "per object", "world_move_batch", "move_loop"),
        ("    World.move batch of 1 (fixed overhead)", "per call", "world_move_batch_of_1", None),
        ("(d) Python loop of 1,000 World.move", "per object", "world_move_loop", "move_loop"),
    ]
    width = max(len(t[0]) for t in table)
    for label, unit, key, c_key in table:
        ratio = f"  {ns[key] / c[c_key]:5.2f}x the C loop" if c and c_key in c else ""
        print(f"{label:<{width}}  {ns[key]:10.1f} ns {unit}{ratio}")
    if c:
        print("\nC (bench/bench_batch.cpp): " + ", ".join(f"{k} {v:.1f} ns" for k, v in c.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
