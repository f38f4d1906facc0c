#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A few thousand spheres and boxes flying and spinning in a walled arena, stepped with numpy.

Run from the top of the source tree:

    PYTHONPATH=python /usr/bin/python3 examples/python/world_demo.py [--objects 3000] [--steps 100]

Each step moves every object in one World.move batch (ids (n,), end poses (n, 7) computed with
numpy), steps the world, reads the contacts as one structured array, and bounces the objects
that hit a wall (velocity reflected, placed where they hit) with numpy on that array. A few
objects are fast "bullets": the demo counts the contacts that a check at the frames alone would
miss (the pair apart at both the start and the end of the step: one distance_batch at each).
With matplotlib installed (Debian: python3-matplotlib) it draws the final positions and the
contacts to a PNG; without it, it prints the summary only.

Units: lengths in arena units (the arena spans [-20, 20] on each axis), times in steps.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

try:
    import kairos
except ImportError as e:
    sys.exit(f"cannot import kairos ({e}); run with PYTHONPATH=python from the source tree")

ARENA = 20.0   # half size of the arena, inside the walls
WALL = 0.5     # half thickness of each wall


def quat_multiply(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Row-wise Hamilton product p * q of (n, 4) arrays (x, y, z, w)."""
    px, py, pz, pw = p.T
    qx, qy, qz, qw = q.T
    return np.stack([pw * qx + px * qw + py * qz - pz * qy,
                     pw * qy - px * qz + py * qw + pz * qx,
                     pw * qz + px * qy - py * qx + pz * qw,
                     pw * qw - px * qx - py * qy - pz * qz], axis=1)


def wall_poses() -> np.ndarray:
    """(6, 7) poses of the walls: -x, +x, -y, +y, -z, +z, just outside the arena."""
    out = np.zeros((6, 7))
    out[:, 6] = 1.0
    for w in range(6):
        axis, side = divmod(w, 2)
        out[w, axis] = (ARENA + WALL) * (1 if side else -1)
    return out


class Scene:
    """n movers then 6 static walls; object i has user_data i, shape palette[kind[i]]."""

    def __init__(self, world: kairos.World, n: int, rng: np.random.Generator) -> None:
        self.n = n
        self.palette = [kairos.Sphere(0.3), kairos.Sphere(0.5), kairos.Box((0.4, 0.25, 0.15)),
                        kairos.Box((0.2, 0.2, 0.6))]
        for axis in range(3):  # one slab per axis, used by both walls of that axis
            half = np.full(3, ARENA + 2 * WALL)
            half[axis] = WALL
            self.palette.append(kairos.Box(half))
        self.kind = np.concatenate([rng.integers(0, 4, n), 4 + np.repeat(np.arange(3), 2)])
        q = rng.normal(size=(n, 4))
        self.poses = np.hstack([rng.uniform(-ARENA + 1, ARENA - 1, size=(n, 3)),
                                q / np.linalg.norm(q, axis=1, keepdims=True)])
        # 3% bullets at 5-10 units per step, the rest 0.05-0.6.
        speed = np.where(rng.random(n) < 0.03, rng.uniform(5, 10, n), rng.uniform(0.05, 0.6, n))
        d = rng.normal(size=(n, 3))
        self.velocity = d / np.linalg.norm(d, axis=1, keepdims=True) * speed[:, None]
        # A constant turn per step about a random axis, up to 0.3 rad.
        axis = rng.normal(size=(n, 3))
        axis /= np.linalg.norm(axis, axis=1, keepdims=True)
        angle = rng.uniform(0, 0.3, n)
        self.spin = np.hstack([axis * np.sin(angle / 2)[:, None], np.cos(angle / 2)[:, None]])
        self.walls = wall_poses()
        self.ids = np.empty(n + 6, dtype=np.uint64)
        for i in range(n):
            self.ids[i] = world.add(self.palette[self.kind[i]], self.poses[i], user_data=i)
        for w in range(6):
            self.ids[n + w] = world.add(self.palette[self.kind[n + w]], self.walls[w],
                                        user_data=n + w)
            world.set_static(int(self.ids[n + w]), True)

    def end_poses(self) -> np.ndarray:
        ends = np.empty_like(self.poses)
        ends[:, :3] = self.poses[:, :3] + self.velocity
        q = quat_multiply(self.spin, self.poses[:, 3:])
        ends[:, 3:] = q / np.linalg.norm(q, axis=1, keepdims=True)
        return ends

    def missed_at_frames(self, contacts: np.ndarray, start: np.ndarray, end: np.ndarray) -> int:
        """Contacts whose pair is apart both at the start and at the end of the step."""
        if len(contacts) == 0:
            return 0
        ua = contacts["user_a"].astype(np.intp)
        ub = contacts["user_b"].astype(np.intp)
        shapes_a = kairos.ShapeArray(self.palette, self.kind[ua])
        shapes_b = kairos.ShapeArray(self.palette, self.kind[ub])
        at_start = np.vstack([start, self.walls])
        at_end = np.vstack([end, self.walls])
        d0 = kairos.distance_batch(shapes_a, at_start[ua], shapes_b, at_start[ub])
        d1 = kairos.distance_batch(shapes_a, at_end[ua], shapes_b, at_end[ub])
        return int(np.count_nonzero((d0["intersecting"] == 0) & (d1["intersecting"] == 0)))

    def bounce(self, world: kairos.World, contacts: np.ndarray, start: np.ndarray) -> np.ndarray:
        """Reflects the velocity of each object at its first wall contact of the step and puts
        it where it hit. Returns the wall-contact mask."""
        n = self.n
        ua = contacts["user_a"].astype(np.intp)
        ub = contacts["user_b"].astype(np.intp)
        wall_hit = (ua >= n) | (ub >= n)
        wall_is_a = ua[wall_hit] >= n
        obj = np.where(wall_is_a, ub[wall_hit], ua[wall_hit])
        obj, first = np.unique(obj, return_index=True)  # contacts are sorted by toi
        if len(obj) == 0:
            return wall_hit
        hits = contacts[wall_hit][first]
        # The normal goes from a to b: from the wall toward the object when the wall is a.
        inward = np.where(wall_is_a[first][:, None], hits["normal"], -hits["normal"])
        v = self.velocity[obj]
        v_n = np.einsum("ij,ij->i", v, inward)
        # Only objects moving into the wall bounce (one touching it while leaving goes on).
        into = v_n < 0
        obj, v, v_n, inward, toi = obj[into], v[into], v_n[into], inward[into], hits["toi"][into]
        self.velocity[obj] = v - 2 * v_n[:, None] * inward
        # Back where it hit, at its start orientation (which touched nothing before toi).
        self.poses[obj, :3] = start[obj, :3] + toi[:, None] * v
        self.poses[obj, 3:] = start[obj, 3:]
        for i in obj:  # a few per step: no batch for set_pose in the C API
            world.set_pose(int(self.ids[i]), self.poses[i])
        return wall_hit


def draw(path: str, positions: np.ndarray, points: np.ndarray, toi: np.ndarray) -> None:
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed (Debian: python3-matplotlib): no plot drawn")
        return
    fig, ax = plt.subplots(figsize=(8, 8))
    ax.scatter(positions[:, 0], positions[:, 1], s=2, c="0.7", label="objects (final, x-y)")
    sc = ax.scatter(points[:, 0], points[:, 1], s=6, c=toi, cmap="viridis", vmin=0, vmax=1,
                    label="contact points")
    fig.colorbar(sc, ax=ax, label="time of impact (fraction of the step)")
    ax.add_patch(plt.Rectangle((-ARENA, -ARENA), 2 * ARENA, 2 * ARENA, fill=False, lw=2))
    ax.set_xlim(-ARENA - 2, ARENA + 2)
    ax.set_ylim(-ARENA - 2, ARENA + 2)
    ax.set_aspect("equal")
    ax.set_xlabel("x (arena units)")
    ax.set_ylabel("y (arena units)")
    ax.set_title("Kairos world: contacts of every step, projected on x-y")
    ax.legend(loc="upper right")
    fig.savefig(path, dpi=120)
    print(f"plot written to {path}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--objects", type=int, default=3000)
    parser.add_argument("--steps", type=int, default=100)
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--workers", type=int, default=2, help="narrow-phase threads")
    parser.add_argument("--png", default="world_demo.png", help="plot file (with matplotlib)")
    parser.add_argument("--quiet", action="store_true", help="print the summary only")
    args = parser.parse_args()

    world = kairos.World(worker_count=args.workers)
    scene = Scene(world, args.objects, np.random.default_rng(args.seed))
    movers = scene.ids[:args.objects]
    points, tois = [], []
    total = walls = missed = 0
    t_move = t_step = t_read = 0.0
    for step in range(args.steps):
        start = scene.poses
        end = scene.end_poses()
        t0 = time.perf_counter()
        world.move(movers, end)
        t1 = time.perf_counter()
        world.step()
        t2 = time.perf_counter()
        contacts = world.contacts()
        t3 = time.perf_counter()
        t_move, t_step, t_read = t_move + t1 - t0, t_step + t2 - t1, t_read + t3 - t2
        missed_now = scene.missed_at_frames(contacts, start, end)
        scene.poses = end.copy()
        wall_hit = scene.bounce(world, contacts, start)
        total += len(contacts)
        walls += int(wall_hit.sum())
        missed += missed_now
        points.append(contacts["point"])
        tois.append(contacts["toi"])
        if not args.quiet:
            print(f"step {step:3d}: {len(contacts):4d} contacts ({int(wall_hit.sum()):3d} with "
                  f"walls, {missed_now:2d} between frames)  move {1e3 * (t1 - t0):6.3f} ms  "
                  f"step {1e3 * (t2 - t1):7.2f} ms  contacts {1e3 * (t3 - t2):6.3f} ms")
    steps = max(args.steps, 1)
    stats = world.step_stats()
    print(f"\n{args.objects} objects and 6 static walls, {args.steps} steps, "
          f"{args.workers} narrow-phase threads")
    print(f"contacts: {total} ({walls} with walls); {missed} between frames (the pair apart at "
          f"both ends of its step: a check at the frames alone misses them)")
    print(f"mean per step: move {1e3 * t_move / steps:.3f} ms, step {1e3 * t_step / steps:.2f} ms, "
          f"contacts read {1e3 * t_read / steps:.3f} ms; last step {stats.broad_phase_pairs} "
          f"broad-phase pairs, {stats.narrow_phase_queries} casts")
    draw(args.png, scene.poses[:, :3], np.concatenate(points), np.concatenate(tois))
    world.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
