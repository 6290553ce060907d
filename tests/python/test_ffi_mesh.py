"""The Python binding's mesh layer: numpy in and out, exceptions from status codes,
the library found through SHERD_LIBRARY, and the constants equal to the header's."""

import re
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

import sherd

ROOT = Path(__file__).resolve().parents[2]

POSITIONS = np.array([[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]], dtype=np.float64)
TRIANGLES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.uint32)


def header_constants(prefix):
    text = (ROOT / "include" / "sherd.h").read_text()
    return {name: int(value) for name, value in re.findall(rf"\b{prefix}(\w+) = (\d+)", text)}


def test_constants_match_the_header():
    assert header_constants("SHERD_STATUS_") == {status.name: status.value for status in sherd.Status}
    assert header_constants("SHERD_MESH_ATTRIBUTE_") == {flag.name: flag.value for flag in sherd.Attribute}
    abi = re.search(r"#define SHERD_ABI_VERSION (\d+)", (ROOT / "include" / "sherd.h").read_text())
    assert int(abi.group(1)) == sherd.ABI_VERSION
    assert re.fullmatch(r"\d+\.\d+\.\d+", sherd.__version__)


def test_round_trip_float64_and_float32():
    mesh = sherd.Mesh.from_arrays(POSITIONS, TRIANGLES)
    assert (mesh.vertex_count, mesh.face_count) == (4, 4)
    np.testing.assert_array_equal(mesh.positions, POSITIONS)
    np.testing.assert_array_equal(mesh.triangles, TRIANGLES)
    assert mesh.attributes == sherd.Attribute(0)
    assert mesh.normals is None and mesh.colors is None and mesh.corner_uvs is None and mesh.quality is None

    # Blender's foreach_get gives flat float32 buffers.
    flat = (POSITIONS + 0.5).astype(np.float32).ravel()
    single = sherd.Mesh.from_arrays(flat, TRIANGLES.ravel().astype(np.int64))
    np.testing.assert_array_equal(single.positions, POSITIONS + 0.5)
    assert single.positions_f32().dtype == np.float32


def test_attributes_round_trip_and_copies_are_independent():
    normals = np.array([[0, 0, -3], [2, 0, 0], [0, 1, 0], [1, 1, 1]], dtype=np.float32)
    colors = np.array([[1.0, 0, 0, 1], [0, 1.0, 0, 1], [0, 0, 1.0, 1], [0.5, 0.5, 0.5, 1]])
    uvs = np.linspace(0, 1, 24).reshape(12, 2)
    mesh = sherd.Mesh.from_arrays(POSITIONS, TRIANGLES, normals=normals, colors=colors, corner_uvs=uvs)
    assert mesh.attributes == sherd.Attribute.NORMALS | sherd.Attribute.COLORS | sherd.Attribute.CORNER_UVS
    copy = mesh.copy()
    mesh.close()
    expected = normals / np.linalg.norm(normals, axis=1, keepdims=True)
    np.testing.assert_allclose(copy.normals, expected, atol=1e-7)
    np.testing.assert_array_equal(copy.colors[:, 0], [255, 0, 0, 128])
    np.testing.assert_allclose(copy.corner_uvs, uvs, atol=1e-7)
    with pytest.raises(ValueError, match="closed"):
        mesh.positions


def test_errors_carry_status_and_message():
    bad = POSITIONS.copy()
    bad[2, 1] = np.nan
    with pytest.raises(sherd.InvalidArgumentError, match="vertex 2") as caught:
        sherd.Mesh.from_arrays(bad, TRIANGLES)
    assert caught.value.status == sherd.Status.INVALID_ARGUMENT
    assert "sherd_mesh_from_arrays" in sherd.last_error_message()

    with pytest.raises(sherd.InvalidArgumentError, match="face 3 refers to vertex 4"):
        sherd.Mesh.from_arrays(POSITIONS, np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 4]]))
    with pytest.raises(sherd.InvalidArgumentError, match="negative"):
        sherd.Mesh.from_arrays(POSITIONS, np.array([[0, 1, -1]]))
    with pytest.raises(sherd.InvalidArgumentError, match=r"shape \(n, 3\)"):
        sherd.Mesh.from_arrays(POSITIONS[:, :2], TRIANGLES)
    mesh = sherd.Mesh.from_arrays(POSITIONS, TRIANGLES)
    with pytest.raises(sherd.InvalidArgumentError, match="the mesh has 4 vertices"):
        mesh.set_normals(np.ones((3, 3)))
    with pytest.raises(sherd.InvalidArgumentError, match="non-zero direction"):
        mesh.oriented_transform(sherd.Axis([0, 0, 0], [0, 0, 0]))
    # Any SherdError is also the matching builtin, so generic handlers catch it.
    assert issubclass(sherd.ParseError, ValueError) and issubclass(sherd.SherdIOError, OSError)


def test_oriented_transform_places_axis_on_z_and_reference_on_plus_x():
    axis = sherd.Axis([3, -2, 5], [0.3, -0.5, 0.8])
    reference = np.array([10.0, 4.0, 1.0])
    matrix = sherd.oriented_transform(axis, reference)
    rotation = matrix[:3, :3]
    np.testing.assert_allclose(rotation @ rotation.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(rotation) == pytest.approx(1.0)
    direction = axis.direction / np.linalg.norm(axis.direction)
    on_axis = matrix @ np.append(axis.point + 7 * direction, 1)
    np.testing.assert_allclose(on_axis[:3], [0, 0, 7], atol=1e-12)
    placed = matrix @ np.append(reference, 1)
    radius = np.linalg.norm(np.cross(reference - axis.point, direction))
    np.testing.assert_allclose(placed[:3], [radius, 0, placed[2]], atol=1e-12)

    mesh = sherd.Mesh.from_arrays(POSITIONS, TRIANGLES)
    np.testing.assert_array_equal(mesh.oriented_transform(axis),
                                  sherd.oriented_transform(axis, POSITIONS.mean(axis=0)))


def test_error_messages_are_per_thread():
    def fail_in_thread(results):
        try:
            sherd.Mesh.from_arrays(POSITIONS, np.array([[0, 1, 9]]))
        except sherd.InvalidArgumentError:
            results.append(sherd.last_error_message())

    with pytest.raises(sherd.InvalidArgumentError):
        sherd.Mesh.from_arrays(np.full((1, 3), np.inf))
    results = []
    thread = threading.Thread(target=fail_in_thread, args=(results,))
    thread.start()
    thread.join()
    assert "vertex 9" in results[0]
    assert "vertex 0" in sherd.last_error_message() and "vertex 9" not in sherd.last_error_message()


def test_missing_library_is_a_clear_import_error(tmp_path):
    code = "import sherd"
    env = {"SHERD_LIBRARY": str(tmp_path / "nowhere" / "libsherd.so"), "PATH": "/usr/bin:/bin"}
    result = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                            cwd=ROOT / "bindings" / "python")
    assert result.returncode != 0
    assert "libsherd not found; set SHERD_LIBRARY" in result.stderr
