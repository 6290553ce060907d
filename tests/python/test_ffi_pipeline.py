"""The pipeline through the Python binding on synthetic sherds with known axes."""

import numpy as np
import pytest

import sherd
from rim_points import pick_rim_vertices


def angle_deg(a, b, signed=True):
    cosine = np.dot(a.direction, b.direction) / np.linalg.norm(a.direction) / np.linalg.norm(b.direction)
    return np.degrees(np.arccos(np.clip(cosine if signed else abs(cosine), -1, 1)))


@pytest.fixture(scope="module")
def rim_sherd():
    # Seed 13 is a rim piece the orientation orients rim up; several other rim seeds come out upside down (a known defect of the base-to-rim sense, issue 3).
    return sherd.synthetic_sherd(13, "rim", target_faces=12000, noise_mm=0.02)


def test_synthetic_sherd_and_its_truth(rim_sherd):
    mesh, axis, truth = rim_sherd
    assert mesh.face_count == pytest.approx(12000, rel=0.2)
    assert sherd.Attribute.NORMALS in mesh.attributes
    assert truth["rim_radius_mm"] > 0 and truth["sector_angle_deg"] > 0
    np.testing.assert_allclose(np.linalg.norm(axis.direction), 1.0)
    again, same_axis, _ = sherd.synthetic_sherd(13, "rim", target_faces=12000, noise_mm=0.02)
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


def test_three_points_on_the_rim(rim_sherd):
    mesh, truth, _ = rim_sherd
    picked = mesh.positions[pick_rim_vertices(mesh.positions, mesh.oriented_transform(truth))]
    orientation = sherd.orient_from_three_points(mesh, picked)
    assert angle_deg(orientation.axis, truth, signed=False) < 5.0
    with pytest.raises(sherd.InvalidArgumentError, match="point 1"):
        sherd.orient_from_three_points(mesh, picked + [1000.0, 0, 0])


def test_a_flat_base_piece_needs_manual_orientation():
    # The orientation layer refuses some flat pieces and not others: the first refused of
    # a few seeds must carry its reason and a (guessed) axis.
    for seed in range(1, 9):
        mesh, _, _ = sherd.synthetic_sherd(seed, "flat_base", target_faces=6000)
        orientation = sherd.orient_automatic(mesh)
        assert np.linalg.norm(orientation.axis.direction) == pytest.approx(1.0)
        if not orientation.oriented:
            assert orientation.reason.startswith("sherd_orient_automatic: ") and len(orientation.reason) > 40
            # The declined axis is its best guess, flagged by the reason against it.
            guess = orientation.best_guess
            assert guess is not None and guess.sense_known is None
            assert orientation.reason == f"sherd_orient_automatic: {guess.against}"
            np.testing.assert_array_equal(guess.axis.direction, orientation.axis.direction)
            return
        assert orientation.reason == "" and orientation.best_guess is None
    pytest.fail("no flat base piece was refused")


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


@pytest.fixture(scope="module")
def oriented_rim(rim_sherd):
    mesh, truth, _ = rim_sherd
    return mesh, truth, sherd.orient_automatic(mesh).axis


@pytest.mark.parametrize("criterion", ["circles", "pareto", "profile", "tangent", "auto"])
def test_refine_with_each_criterion(oriented_rim, criterion):
    mesh, truth, start = oriented_rim
    refinement = sherd.refine(mesh, start, criterion=criterion, surface="both")
    assert angle_deg(refinement.axis, truth, signed=False) < 3.0
    assert refinement.criterion == criterion or criterion == "auto"
    assert refinement.surface == "both"
    assert refinement.residual_mm >= 0 and refinement.section_count > 0
    assert refinement.report["residual_mm"] == pytest.approx(refinement.residual_mm)
    assert refinement.flagged == refinement.report["flagged"]
    if criterion == "pareto":
        front = refinement.pareto_front
        assert front.shape[1] == 4 and len(front) >= 2
        # Non-dominated: no point is better in both costs than another.
        dominated = (front[:, None, 2] < front[None, :, 2]) & (front[:, None, 3] < front[None, :, 3])
        assert not dominated.any()
        # The plot has a point per solution of the front and the chosen one circled.
        plot = refinement.pareto_plot_svg
        assert plot.startswith("<svg") and plot.count('fill="#3060c0"') == len(front)
        assert plot.count("<title>chosen:") == 1
    else:
        assert refinement.pareto_front.shape == (0, 4)
        assert refinement.pareto_plot_svg == ""


@pytest.mark.parametrize("choice, column", [("centres", 2), ("residuals", 3)])
def test_the_pareto_choice_takes_the_end_of_the_front_it_names(oriented_rim, choice, column):
    mesh, _, start = oriented_rim
    refinement = sherd.refine(mesh, start, criterion="pareto", pareto_choice=choice)
    front = refinement.pareto_front
    best = front[np.argmin(front[:, column])]
    # The front's tilts are from the start axis, as the refinement's tilt is.
    assert refinement.tilt_deg == pytest.approx(np.hypot(best[0], best[1]), abs=0.05)


def test_the_mean_of_the_best_pareto_solutions_and_the_tangent_plane_options(oriented_rim):
    mesh, truth, start = oriented_rim
    knee = sherd.refine(mesh, start, criterion="pareto")
    mean = sherd.refine(mesh, start, criterion="pareto", pareto_choice=("mean_of_best", 2),
                        pareto_section_limits=(12, 5.0))
    assert len(mean.pareto_front) >= 2 and angle_deg(mean.axis, truth, signed=False) < 5.0
    assert angle_deg(mean.axis, knee.axis, signed=False) > 0.0 or len(knee.pareto_front) != len(mean.pareto_front)
    tangent = sherd.refine(mesh, start, criterion="tangent", edge="rim", tangent_tolerance_mm=1.0)
    assert tangent.criterion == "tangent" and angle_deg(tangent.axis, truth, signed=False) < 3.0
    assert tangent.report["edge"] == "Rim"
    with pytest.raises(sherd.InvalidArgumentError, match="unknown pareto_choice"):
        sherd.refine(mesh, start, pareto_choice="median")
    with pytest.raises(sherd.InvalidArgumentError, match="at least 1"):
        sherd.refine(mesh, start, pareto_choice=("mean_of_best", 0))
    with pytest.raises(sherd.InvalidArgumentError, match="min_points"):
        sherd.refine(mesh, start, pareto_section_limits=(2, 3.0))
    with pytest.raises(sherd.InvalidArgumentError, match="tolerance_mm"):
        sherd.refine(mesh, start, tangent_tolerance_mm=-1.0)
    with pytest.raises(sherd.InvalidArgumentError, match="unknown edge"):
        sherd.refine(mesh, start, edge="lip")



def test_the_profile_criterions_forms_and_the_pareto_circle_fit(oriented_rim):
    mesh, truth, start = oriented_rim
    axes = {name: sherd.refine(mesh, start, criterion="profile", profile_method=(name, parameter)).axis
            for name, parameter in (("reference", 12), ("polynomial", 4), ("spline", 1.5))}
    default = sherd.refine(mesh, start, criterion="profile").axis
    assert np.allclose(axes["spline"].direction, default.direction, atol=1e-12)
    assert angle_deg(axes["reference"], axes["polynomial"], signed=False) > 0.0
    geometric = sherd.refine(mesh, start, criterion="pareto", circle_fit="geometric")
    assert len(geometric.pareto_front) >= 2 and angle_deg(geometric.axis, truth, signed=False) < 5.0
    with pytest.raises(sherd.InvalidArgumentError, match="whole number"):
        sherd.refine(mesh, start, profile_method=("polynomial", 2.5))
    with pytest.raises(sherd.InvalidArgumentError, match="unknown profile_method"):
        sherd.refine(mesh, start, profile_method=("legendre", 4))
    with pytest.raises(sherd.InvalidArgumentError, match="unknown circle_fit"):
        sherd.refine(mesh, start, circle_fit="hyper")


def test_refine_rejects_unknown_values(oriented_rim):
    mesh, _, start = oriented_rim
    with pytest.raises(sherd.InvalidArgumentError, match="unknown criterion"):
        sherd.refine(mesh, start, criterion="least squares")
    with pytest.raises(sherd.InvalidArgumentError, match="SHERD_SURFACE"):
        sherd.refine(mesh, start, surface=7)
    with pytest.raises(sherd.InvalidArgumentError, match="bound_deg"):
        sherd.refine(mesh, start, search_bound_deg=120)


def test_measurements_with_intervals(rim_sherd, oriented_rim):
    mesh, truth_axis, truth = rim_sherd
    _, _, start = oriented_rim
    axis = sherd.refine(mesh, start).axis
    measured = sherd.measure(mesh, axis, bootstrap_samples=8, bootstrap_seed=3)
    assert measured.rim_radius_mm == pytest.approx(truth["rim_radius_mm"], rel=0.05)
    low, high = measured.rim_diameter_interval_mm
    assert low <= measured.rim_diameter_mm <= high
    assert measured.sector_percent == pytest.approx(measured.sector_angle_deg / 3.6)
    assert np.isnan(measured.capacity_litres)
    assert measured.details["rim_diameter_mm"] == pytest.approx(measured.rim_diameter_mm)
    assert measured.axis_uncertain == measured.details["axis_uncertain"] == (
        measured.axis_angle_interval_deg[1] > 4.0 or measured.axis_distance_interval_mm[1] > 5.0)
    again = sherd.measure(mesh, axis, bootstrap_samples=8, bootstrap_seed=3, refine_options={"criterion": "auto"})
    assert again.rim_diameter_interval_mm == measured.rim_diameter_interval_mm
    no_intervals = sherd.measure(mesh, axis, bootstrap_samples=0)
    assert np.isnan(no_intervals.rim_diameter_interval_mm).all()
    with pytest.raises(sherd.InvalidArgumentError, match="confidence"):
        sherd.measure(mesh, axis, confidence=1.5)


def test_reconstruction_export(tmp_path, oriented_rim):
    mesh, _, axis = oriented_rim
    path = tmp_path / "reconstruction.ply"
    sherd.export_reconstruction_ply(mesh, axis, path, segments=90)
    ring = sherd.Mesh.read(path)
    radius = np.hypot(ring.positions[:, 0], ring.positions[:, 1])
    assert ring.vertex_count > 90 and radius.max() > 10
    # A revolution: every height has the same radii at every turn of 4 degrees.
    assert ring.vertex_count % 90 == 0 or ring.vertex_count % 90 <= 2


SIGNATURES = {"svg": b"<svg", "eps": b"%!PS-Adobe", "pdf": b"%PDF-", "png": b"\x89PNG\r\n\x1a\n"}


def test_drawing_in_each_format(tmp_path, oriented_rim):
    mesh, _, axis = oriented_rim
    with sherd.Drawing(mesh, axis, style="linear,light", dpi=72, section_fill="hatched",
                       title="Python test sherd") as drawing:
        for format, signature in SIGNATURES.items():
            data = drawing.to_bytes(format)
            assert (signature in data[:200]) if format == "svg" else data.startswith(signature)
        assert b"Python test sherd" in drawing.to_bytes("svg")
        drawing.write(tmp_path / "sherd.png")
        assert (tmp_path / "sherd.png").read_bytes() == drawing.to_bytes("png")
        with pytest.raises(sherd.InvalidArgumentError, match="unknown format"):
            drawing.to_bytes("tiff")
        with pytest.raises(sherd.InvalidArgumentError):
            drawing.write(tmp_path / "sherd.tiff")
    with pytest.raises(sherd.InvalidArgumentError, match="unknown style"):
        sherd.Drawing(mesh, axis, style="watercolour")
    with pytest.raises(sherd.InvalidArgumentError, match="dpi"):
        sherd.Drawing(mesh, axis, style="linear", dpi=1)


def test_drawing_annotations_by_name(oriented_rim):
    """``annotations`` writes the measurements asked for under the drawing, by the names of
    ``sherd draw --annotations``; a rim sherd's profile does not reach the base, so it has
    no capacity to write even when asked."""
    mesh, _, axis = oriented_rim

    def texts(**options):
        svg = sherd.Drawing(mesh, axis, style="linear", dpi=40, **options).to_bytes("svg")
        return {label for label in (b">height ", b">wall ", b">capacity ") if label in svg}, svg

    assert texts()[0] == set()
    assert texts(annotations="none")[0] == set()
    assert texts(annotations="height")[0] == {b">height "}
    both, svg = texts(annotations="height, wall-thickness")
    assert both == {b">height ", b">wall "}
    assert texts(annotations=["wall_thickness", "height"])[1] == svg
    assert texts(annotations=1 | 2)[1] == svg
    assert texts(annotations="all")[0] == {b">height ", b">wall "}
    assert texts(annotations=[])[0] == set()
    with pytest.raises(sherd.InvalidArgumentError, match="unknown annotation 'volume'"):
        sherd.Drawing(mesh, axis, style="linear", annotations="height,volume")
    with pytest.raises(sherd.InvalidArgumentError, match="cannot be combined"):
        sherd.Drawing(mesh, axis, style="linear", annotations="all,height")
    with pytest.raises(sherd.InvalidArgumentError, match="no annotation given"):
        sherd.Drawing(mesh, axis, style="linear", annotations=" ")
    with pytest.raises(sherd.InvalidArgumentError, match="SHERD_ANNOTATION_"):
        sherd.Drawing(mesh, axis, style="linear", annotations=8)


def test_a_sense_uncertain_sherd_says_so_and_keeps_its_axis_line():
    # synthetic_sherd(30): its axis line is found, which way is up is not (as in
    # tests/pipeline_working_copy.rs); the status, not the reason's wording, tells a host.
    mesh, truth, _ = sherd.synthetic_sherd(30)
    orientation = sherd.orient_automatic(mesh)
    assert not orientation.oriented and orientation.sense_uncertain
    assert "which way is up" in orientation.reason
    assert angle_deg(orientation.axis, truth, signed=False) < 5.0
    analysis = sherd.analyse(mesh)
    assert analysis.sense_uncertain and not analysis.oriented
    assert analysis.record["status"] == "sense_uncertain" and analysis.axis is not None
    refused = sherd.orient_automatic(sherd.synthetic_sherd(1, "flat_base", target_faces=6000)[0])
    assert not refused.sense_uncertain
    assert not sherd.analyse(sherd.synthetic_sherd(1, "flat_base", target_faces=6000)[0]).sense_uncertain
