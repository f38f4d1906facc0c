# SPDX-License-Identifier: MIT
"""The example and the benchmark run (small settings) from the source tree."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import kairos

ROOT = Path(kairos.__file__).resolve().parents[2]


def run(script, *args, cwd):
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "python")
    return subprocess.run([sys.executable, str(ROOT / script), *args], env=env, cwd=cwd,
                          capture_output=True, text=True, timeout=120)


@pytest.mark.skipif(not (ROOT / "examples/python/world_demo.py").exists(), reason="no example")
def test_world_demo_runs(tmp_path):
    r = run("examples/python/world_demo.py", "--objects", "400", "--steps", "5",
            "--png", str(tmp_path / "demo.png"), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "step   4:" in r.stdout and "contacts:" in r.stdout
    try:
        __import__("matplotlib")
        assert (tmp_path / "demo.png").exists()
    except ImportError:
        assert "matplotlib is not installed" in r.stdout


@pytest.mark.skipif(not (ROOT / "bench/python/bench_batch.py").exists(), reason="no benchmark")
def test_benchmark_json_and_scene_file(tmp_path):
    scene = tmp_path / "scene.bin"
    r = run("bench/python/bench_batch.py", "--json", "--repeat", "1", "--save-scene", str(scene),
            cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    n = out["n_casts"]
    assert n == 10_000 and 0 < out["hit_rate"] < 1
    for key in ("shape_cast_batch", "shape_cast_loop", "world_move_batch", "world_move_loop"):
        assert out["median_ns"][key] > 0
    assert scene.stat().st_size == 8 + n * (4 + 4 + 8 * (7 + 3 + 7 + 3)) + 8 * 32 * 3
