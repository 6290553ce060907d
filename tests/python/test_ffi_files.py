"""Files through the Python binding: PLY round trips, the oriented export checked in the
oriented frame, the profile section, and reading errors as exceptions."""

import numpy as np
import pytest

import sherd


def wall(inner_mm=45.0, outer_mm=50.0, height_mm=40.0, sector_deg=60.0, steps=24, rows=10):
    """A closed piece of cylindrical wall about z, then moved by a rigid motion; returns
    (positions, triangles, true axis)."""
    angles = np.radians(np.linspace(-sector_deg / 2, sector_deg / 2, steps + 1))
    heights = np.linspace(0, height_mm, rows + 1)
    grid = []
    for radius in (inner_mm, outer_mm):
        for a in angles:
            for h in heights:
                grid.append((radius * np.cos(a), radius * np.sin(a), h))
    index = lambda skin, step, row: (skin * (steps + 1) + step) * (rows + 1) + row
    quads = []
    for s in range(steps):
        for r in range(rows):
            quads.append((index(1, s, r), index(1, s + 1, r), index(1, s + 1, r + 1), index(1, s, r + 1)))
            quads.append((index(0, s, r), index(0, s, r + 1), index(0, s + 1, r + 1), index(0, s + 1, r)))
        quads.append((index(0, s, rows), index(1, s, rows), index(1, s + 1, rows), index(0, s + 1, rows)))
        quads.append((index(0, s, 0), index(0, s + 1, 0), index(1, s + 1, 0), index(1, s, 0)))
    for r in range(rows):
        quads.append((index(0, 0, r), index(1, 0, r), index(1, 0, r + 1), index(0, 0, r + 1)))
        quads.append((index(0, steps, r), index(0, steps, r + 1), index(1, steps, r + 1), index(1, steps, r)))
    triangles = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.uint32)
    # Rotation by 30 degrees about (1, 1, 0)/sqrt(2), then a shift.
    u = np.array([1.0, 1.0, 0.0]) / np.sqrt(2)
    angle = np.radians(30)
    cross = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    rotation = np.cos(angle) * np.eye(3) + np.sin(angle) * cross + (1 - np.cos(angle)) * np.outer(u, u)
    shift = np.array([12.0, -7.0, 30.0])
    positions = np.array(grid) @ rotation.T + shift
    return positions, triangles, sherd.Axis(shift, rotation @ [0, 0, 1])


@pytest.fixture
def wall_mesh():
    positions, triangles, axis = wall()
    return sherd.Mesh.from_arrays(positions, triangles), axis


@pytest.mark.parametrize("binary", [True, False])
def test_ply_round_trip(tmp_path, wall_mesh, binary):
    mesh, _ = wall_mesh
    path = tmp_path / "wall.ply"
    mesh.write_ply(path, binary=binary)
    back = sherd.Mesh.read(path)
    np.testing.assert_array_equal(back.triangles, mesh.triangles)
    # Scan-sized coordinates are stored as floats.
    np.testing.assert_allclose(back.positions, mesh.positions, atol=1e-5)
    if binary:
        np.testing.assert_array_equal(back.positions, mesh.positions.astype(np.float32))


def test_oriented_export_puts_the_wall_about_z(tmp_path, wall_mesh):
    mesh, axis = wall_mesh
    path = tmp_path / "oriented.ply"
    sherd.export_oriented_ply(mesh, axis, path)
    oriented = sherd.Mesh.read(path).positions
    radius = np.hypot(oriented[:, 0], oriented[:, 1])
    assert np.all(np.minimum(abs(radius - 45), abs(radius - 50)) < 1e-4)
    assert np.all(oriented[:, 0] > 0)
    assert oriented[:, 2].min() == pytest.approx(0, abs=1e-4)
    assert oriented[:, 2].max() == pytest.approx(40, abs=1e-4)
    # The same placement as the transform the host applies itself.
    matrix = mesh.oriented_transform(axis)
    placed = mesh.positions @ matrix[:3, :3].T + matrix[:3, 3]
    np.testing.assert_allclose(oriented, placed, atol=1e-4)


def test_profile_section_is_the_wall_rectangle(tmp_path, wall_mesh):
    mesh, axis = wall_mesh
    angle = sherd.most_informative_angle(mesh, axis)
    assert abs(angle) < np.radians(30)
    curves = sherd.profile_section(mesh, axis)
    points = np.vstack([p for p, _ in curves])
    assert points[:, 0].min() == pytest.approx(45, abs=0.02)
    assert points[:, 0].max() == pytest.approx(50, abs=0.02)  # chords between vertices
    assert points[:, 1].min() == pytest.approx(0, abs=1e-6)
    assert points[:, 1].max() == pytest.approx(40, abs=1e-6)
    assert sherd.profile_csv(mesh, axis, angle) == sherd.profile_csv(mesh, axis)
    path = tmp_path / "profile.csv"
    sherd.export_profile_csv(mesh, axis, path, angle_rad=0.1)
    assert path.read_text().startswith("curve,index,r_mm,z_mm,closed\n")
    with pytest.raises(sherd.DegenerateGeometryError, match="does not cut"):
        sherd.profile_csv(mesh, axis, 2.0)


def test_reading_errors(tmp_path):
    with pytest.raises(sherd.SherdIOError, match="missing.ply") as caught:
        sherd.Mesh.read(tmp_path / "missing.ply")
    assert isinstance(caught.value, OSError)
    broken = tmp_path / "broken.ply"
    broken.write_text("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                      "property float z\nend_header\n1 banana 3\n")
    with pytest.raises(sherd.ParseError, match="broken.ply"):
        sherd.Mesh.read(broken)
