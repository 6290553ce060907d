"""The pipeline through the Python binding on synthetic sherds with known axes."""

import numpy as np
import pytest

import sherd


def angle_deg(a, b, signed=True):
    cosine = np.dot(a.direction, b.direction) / np.linalg.norm(a.direction) / np.linalg.norm(b.direction)
    return np.degrees(np.arccos(np.clip(cosine if signed else abs(cosine), -1, 1)))


@pytest.fixture(scope="module")
def rim_sherd():
    # Seed 10 is a rim piece the orientation layer orients (many others it refuses).
    return sherd.synthetic_sherd(10, "rim", target_faces=12000, noise_mm=0.02)


def test_synthetic_sherd_and_its_truth(rim_sherd):
    mesh, axis, truth = rim_sherd
    assert mesh.face_count == pytest.approx(12000, rel=0.2)
    assert sherd.Attribute.NORMALS in mesh.attributes
    assert truth["rim_radius_mm"] > 0 and truth["sector_angle_deg"] > 0
    np.testing.assert_allclose(np.linalg.norm(axis.direction), 1.0)
    again, same_axis, _ = sherd.synthetic_sherd(10, "rim", target_faces=12000, noise_mm=0.02)
    np.testing.assert_array_equal(again.positions, mesh.positions)
    np.testing.assert_array_equal(same_axis.direction, axis.direction)
    with pytest.raises(sherd.InvalidArgumentError, match="unknown kind"):
        sherd.synthetic_sherd(1, "amphora")
    with pytest.raises(sherd.InvalidArgumentError, match="SHERD_SYNTH_KIND"):
        sherd.synthetic_sherd(1, 42)


def test_automatic_orientation_finds_the_axis(rim_sherd):
    mesh, truth, _ = rim_sherd
    orientation = sherd.orient_automatic(mesh)
    assert orientation.oriented and orientation.reason == ""
    assert angle_deg(orientation.axis, truth) < 1.0
    assert orientation.angle_uncertainty_deg > 0
    assert orientation.report["method"]
    # The same arrays passed again (as a host would) give the same axis.
    copy = sherd.Mesh.from_arrays(mesh.positions, mesh.triangles, normals=mesh.normals)
    np.testing.assert_array_equal(sherd.orient_automatic(copy).axis.direction, orientation.axis.direction)


def pick_rim_points(mesh, truth):
    """Three vertices on the rim as a user picks them: in the true oriented frame, the
    highest vertex near the middle of each third of the fragment's angular extent."""
    matrix = mesh.oriented_transform(truth)
    oriented = mesh.positions @ matrix[:3, :3].T + matrix[:3, 3]
    angles = np.arctan2(oriented[:, 1], oriented[:, 0])
    share = 3 * (angles - angles.min()) / (angles.max() - angles.min())
    picked = []
    for third in range(3):
        candidates = np.flatnonzero(np.abs(share - third - 0.5) < 0.3)
        picked.append(mesh.positions[candidates[np.argmax(oriented[candidates, 2])]])
    return np.array(picked)


def test_three_points_on_the_rim(rim_sherd):
    mesh, truth, _ = rim_sherd
    picked = pick_rim_points(mesh, truth)
    orientation = sherd.orient_from_three_points(mesh, picked)
    assert angle_deg(orientation.axis, truth, signed=False) < 5.0
    with pytest.raises(sherd.InvalidArgumentError, match="point 1"):
        sherd.orient_from_three_points(mesh, picked + [1000.0, 0, 0])


def test_a_flat_base_piece_needs_manual_orientation():
    mesh, _, _ = sherd.synthetic_sherd(4, "flat_base", target_faces=6000)
    orientation = sherd.orient_automatic(mesh)
    assert not orientation.oriented
    assert "sherd_orient_automatic" in orientation.reason and len(orientation.reason) > 30
    assert np.linalg.norm(orientation.axis.direction) == pytest.approx(1.0)


def test_repair_and_decimate(rim_sherd):
    mesh, _, _ = rim_sherd
    copy = mesh.copy()
    report = copy.repair(keep_largest_component=True, merge_tolerance_mm=1e-6)
    assert report["faces_after"] == copy.face_count
    assert report["vertices_after"] == copy.vertex_count
    decimated = mesh.decimate(3000)
    assert decimated.face_count == pytest.approx(3000, rel=0.15)
    assert mesh.face_count > decimated.face_count  # the original is unchanged
    with pytest.raises(sherd.InvalidArgumentError, match="target_faces"):
        mesh.decimate(0)
    with pytest.raises(TypeError, match="unexpected keyword"):
        mesh.repair(colour=1)
