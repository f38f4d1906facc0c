# SPDX-License-Identifier: MIT
"""Loading, version, layouts, status names, errors."""

import ctypes
import ctypes.util
import os
import sysconfig
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

import kairos
from kairos import _capi, errors

PACKAGE_DIR = Path(kairos.__file__).resolve().parent


def run_python(code, env_update, cwd=None):
    env = dict(os.environ)
    env.pop("KAIROS_LIBRARY", None)
    env.update(env_update)
    return subprocess.run([sys.executable, "-c", code], env=env, cwd=cwd, capture_output=True,
                          text=True, timeout=60)


def test_version_and_abi():
    v = kairos.version()
    assert v == kairos.version_tuple()[0] * 10000 + kairos.version_tuple()[1] * 100 + \
        kairos.version_tuple()[2]
    assert kairos.version_tuple()[0] == 0 and v > 0
    table = ctypes.c_void_p()
    assert _capi.lib.kairos_get_api(kairos.ABI_VERSION, ctypes.byref(table)) == 0
    # The table of ABI 2 has 49 entries after its 8-byte header.
    assert ctypes.c_uint32.from_address(table.value).value >= 8 + 8 * 49
    assert ctypes.c_uint32.from_address(table.value + 4).value >= 2
    assert os.path.exists(kairos.library_path())


def test_struct_sizes_and_dtypes_match_the_c_layout():
    # Numbers of tests/abi/layout.c.
    sizes = {"Vec3": 24, "Quat": 32, "Pose": 56, "Motion": 112, "QuerySettings": 24,
             "DistanceResult": 96, "CastResult": 72, "WorldSettings": 64, "Contact": 88,
             "StepStats": 64, "Filter": 12, "WorldHit": 80}
    for name, size in sizes.items():
        assert ctypes.sizeof(getattr(_capi, name)) == size, name
    offsets = {
        kairos.DISTANCE_DTYPE: dict(distance=0, point_a=8, point_b=32, axis=56, intersecting=80,
                                    iterations=84, termination=88),
        kairos.CAST_DTYPE: dict(hit=0, toi=8, point=16, normal=40, iterations=64,
                                termination=68),
        kairos.CONTACT_DTYPE: dict(a=0, b=8, user_a=16, user_b=24, toi=32, point=40, normal=64),
    }
    for dtype, fields in offsets.items():
        assert list(dtype.names) == list(fields)
        for name, off in fields.items():
            assert dtype.fields[name][1] == off, name
    assert (kairos.DISTANCE_DTYPE.itemsize, kairos.CAST_DTYPE.itemsize,
            kairos.CONTACT_DTYPE.itemsize) == (96, 72, 88)
    assert _capi.WorldSettings.worker_count.offset == 32
    assert _capi.WorldSettings.task_user_context.offset == 56
    assert _capi.WorldHit.normal.offset == 56
    assert _capi.StepStats.narrow_phase_seconds.offset == 56


def test_constants():
    assert kairos.QUAT_TOLERANCE == 1e-6 and kairos.MAX_MAGNITUDE == 1e100
    assert [int(t) for t in kairos.Termination] == list(range(10))
    assert int(kairos.BroadPhase.SPACETIME_SAP_QUEUED) == 3


def test_status_names_and_last_error():
    names = {0: "KAIROS_OK", -1: "KAIROS_ERROR_NULL_ARGUMENT", -2: "KAIROS_ERROR_INVALID_ARGUMENT",
             -3: "KAIROS_ERROR_STRUCT_SIZE", -4: "KAIROS_ERROR_DEGENERATE",
             -5: "KAIROS_ERROR_STALE_ID", -6: "KAIROS_ERROR_OUT_OF_MEMORY",
             -7: "KAIROS_ERROR_NOT_IMPLEMENTED", -8: "KAIROS_ERROR_UNSUPPORTED_VERSION",
             -9: "KAIROS_ERROR_INTERNAL", -10: "KAIROS_ERROR_LIMIT"}
    for code, name in names.items():
        assert kairos.status_name(code) == name
    assert kairos.status_name(777) == "KAIROS_UNKNOWN_STATUS"
    seen = []
    t = threading.Thread(target=lambda: seen.append(kairos.last_error()))
    t.start()
    t.join()
    assert seen == [""]
    with pytest.raises(kairos.InvalidArgumentError):
        kairos.Sphere(float("nan"))
    assert "radius" in kairos.last_error()


def test_every_status_maps_to_its_exception():
    expected = {
        -1: (kairos.NullArgumentError, ()),
        -2: (kairos.InvalidArgumentError, (ValueError,)),
        -3: (kairos.StructSizeError, ()),
        -4: (kairos.DegenerateError, (ValueError,)),
        -5: (kairos.StaleIdError, (LookupError,)),
        -6: (kairos.OutOfMemoryError, (MemoryError,)),
        -7: (kairos.UnimplementedError, (NotImplementedError,)),
        -8: (kairos.UnsupportedVersionError, ()),
        -9: (kairos.InternalError, ()),
        -10: (kairos.LimitError, ()),
    }
    for status, (cls, bases) in expected.items():
        e = errors.error_for(status)
        assert type(e) is cls and isinstance(e, kairos.Error)
        for base in bases:
            assert isinstance(e, base)
        assert e.status == status and e.status_name == kairos.status_name(status)
    unknown = errors.error_for(-99)
    assert type(unknown) is kairos.Error and unknown.status_name == "KAIROS_UNKNOWN_STATUS"
    errors.check(0)
    import pickle
    e = pickle.loads(pickle.dumps(errors.error_for(-5)))
    assert type(e) is kairos.StaleIdError and e.status == -5


def test_unsupported_version_error_from_the_library():
    out = ctypes.c_void_p(1234)
    status = _capi.lib.kairos_get_api(99, ctypes.byref(out))
    with pytest.raises(kairos.UnsupportedVersionError) as info:
        errors.check(status)
    assert "99" in str(info.value)
    assert out.value == 1234  # a failed call writes nothing


def test_candidate_paths_for_an_installed_package():
    pkg = Path("/opt/k/lib/python3/dist-packages/kairos")
    got = list(_capi._candidates(pkg))
    assert got[0] == "/opt/k/lib/python3/dist-packages/kairos/libkairos.so.0"
    assert "/opt/k/lib/libkairos.so.0" in got
    assert "/opt/k/lib64/libkairos.so.0" in got
    multiarch = sysconfig.get_config_var("MULTIARCH")
    if multiarch:
        assert f"/opt/k/lib/{multiarch}/libkairos.so.0" in got
    # The installed locations come before the source-tree walk.
    assert got.index("/opt/k/lib/libkairos.so.0") < got.index("/opt/k/build/release/libkairos.so.0")
    src = list(_capi._candidates(Path("/src/kairos/python/kairos")))
    assert "/src/kairos/build/release/libkairos.so.0" in src


def test_loading_from_an_installed_prefix(tmp_path):
    site = tmp_path / "lib" / "python3" / "dist-packages"
    shutil.copytree(PACKAGE_DIR, site / "kairos", ignore=shutil.ignore_patterns("__pycache__"))
    os.symlink(kairos.library_path(), tmp_path / "lib" / "libkairos.so.0")
    r = run_python("import kairos; print(kairos.library_path())", {"PYTHONPATH": str(site)},
                   cwd=str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == str(tmp_path / "lib" / "libkairos.so.0")


def test_loading_from_the_path_recorded_at_install(tmp_path):
    # As the CMake install writes it: the library's path relative to the package directory.
    site = tmp_path / "usr" / "lib" / "python3" / "dist-packages"
    shutil.copytree(PACKAGE_DIR, site / "kairos", ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "usr" / "lib" / "x86_64-elsewhere").mkdir()
    target = tmp_path / "usr" / "lib" / "x86_64-elsewhere" / "libkairos.so.0"
    os.symlink(kairos.library_path(), target)
    (site / "kairos" / "_location.py").write_text(
        'LIBRARY_FROM_PACKAGE = "../../../x86_64-elsewhere/libkairos.so.0"\n')
    r = run_python("import kairos; print(kairos.library_path())", {"PYTHONPATH": str(site)},
                   cwd=str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == str(target)
    # Second, after the package directory itself.
    assert list(_capi._candidates(site / "kairos"))[1] == str(target)


def test_loading_from_the_source_tree_and_the_environment(tmp_path):
    in_tree = [p for p in _capi._candidates(PACKAGE_DIR)
               if p.endswith("build/release/libkairos.so.0") and os.path.exists(p)]
    if in_tree:
        r = run_python("import kairos; print(kairos.library_path())",
                       {"PYTHONPATH": str(PACKAGE_DIR.parent)}, cwd=str(tmp_path))
        assert r.returncode == 0, r.stderr
        assert r.stdout.strip() == in_tree[0]
    link = tmp_path / "somewhere.so"
    os.symlink(kairos.library_path(), link)
    r = run_python("import kairos; print(kairos.library_path())",
                   {"PYTHONPATH": str(PACKAGE_DIR.parent), "KAIROS_LIBRARY": str(link)})
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == str(link)


def test_nothing_found_lists_every_place_tried(tmp_path):
    pkg = tmp_path / "site"
    shutil.copytree(PACKAGE_DIR, pkg / "kairos", ignore=shutil.ignore_patterns("__pycache__"))
    r = run_python("import kairos", {"PYTHONPATH": str(pkg), "LD_LIBRARY_PATH": ""},
                   cwd=str(tmp_path))
    if r.returncode == 0:
        pytest.skip("libkairos.so.0 is installed system-wide: the last fallback found it")
    assert "ImportError" in r.stderr and "KAIROS_LIBRARY" in r.stderr
    assert str(pkg / "kairos" / "libkairos.so.0") in r.stderr
    assert str(tmp_path / "build" / "release" / "libkairos.so.0") in r.stderr
    assert "libkairos.so.0: cannot open shared object file" in r.stderr


def test_loading_failures_raise_import_error():
    r = run_python("import kairos", {"PYTHONPATH": str(PACKAGE_DIR.parent),
                                     "KAIROS_LIBRARY": "/nonexistent/libkairos.so.0"})
    assert r.returncode != 0
    assert "ImportError" in r.stderr and "/nonexistent/libkairos.so.0" in r.stderr
    # A library without the batch functions (here: not Kairos at all) is refused clearly.
    libm = ctypes.util.find_library("m")
    r = run_python("import kairos", {"PYTHONPATH": str(PACKAGE_DIR.parent), "KAIROS_LIBRARY": libm})
    assert r.returncode != 0
    assert "too old" in r.stderr and "kairos_distance_batch" in r.stderr


def test_every_public_name_and_method_is_exercised_by_the_tests():
    sources = "".join(p.read_text() for p in Path(__file__).parent.glob("test_*.py"))
    for name in kairos.__all__:
        if name.endswith("Like"):
            continue  # type aliases for hints
        assert name in sources, f"kairos.{name} is not exercised by any test"
    for cls in (kairos.Shape, kairos.World, kairos.ShapeArray, kairos.Pose, kairos.Motion,
                kairos.AxisCache):
        for name in vars(cls):
            if not name.startswith("_"):
                assert f".{name}" in sources, f"{cls.__name__}.{name} is not exercised"


def test_package_docstring_example():
    import doctest
    assert doctest.testmod(kairos).failed == 0
