"""The Python binding gives the command-line tool's results on the same scan: the record
of ``sherd.process_file`` is the one ``sherd orient --json`` prints, and the pipeline
called step by step (read, repair, orient, refine, measure) finds the same axis and
measurements; where the tool fails, the binding raises with the same message. On a
synthetic sherd and on the real scan ../shared/data/dacord/A011.ply."""

import json
import math
import subprocess

import numpy as np
import pytest

import sherd
from conftest import ROOT, sherd_command

REAL_SCAN = ROOT.parent / "shared" / "data" / "dacord" / "A011.ply"
#: Fields of the record that are measured figures (timings differ from run to run).
FIGURES = ["rim_radius_mm", "rim_diameter_mm", "rim_diameter_interval_mm", "base_diameter_mm",
           "base_diameter_interval_mm", "sector_angle_deg", "sector_percent", "height_mm", "wall_thickness_mm",
           "capacity_litres", "residual_mm", "axis_angle_interval_deg"]


@pytest.fixture(scope="module", params=["synthetic", "A011"])
def scan(request, tmp_path_factory):
    if request.param == "A011":
        if not REAL_SCAN.is_file():
            pytest.skip(f"{REAL_SCAN} is absent (../shared/data)")
        return REAL_SCAN
    # Seed 13: a rim piece the pipeline orients (the README's demo sherd).
    mesh, _, _ = sherd.synthetic_sherd(13, "rim", target_faces=12000)
    path = tmp_path_factory.mktemp("cli") / "seed13.ply"
    mesh.write_ply(path)
    return path


class CommandFailed(Exception):
    """``sherd orient`` exited non-zero; the message is its error without the ``sherd: ``."""


def run_cli(scan):
    """The record ``sherd orient SCAN --json`` prints, or :class:`CommandFailed`."""
    run = subprocess.run([str(sherd_command()), "orient", str(scan), "--json"], capture_output=True, text=True)
    if run.returncode != 0:
        assert run.stdout == "" and run.stderr.startswith("sherd: "), (run.stdout, run.stderr)
        raise CommandFailed(run.stderr.strip()[len("sherd: "):])
    return json.loads(run.stdout)


@pytest.fixture(scope="module")
def cli_record(scan):
    try:
        return run_cli(scan)
    except CommandFailed as failure:
        return failure


def fails_like_the_cli(cli_record, call):
    """True when the CLI failed on the scan and ``call`` raises the same error (the
    binding's message names the C function where the CLI's says ``sherd``)."""
    if not isinstance(cli_record, CommandFailed):
        return False
    with pytest.raises(sherd.SherdError) as raised:
        call()
    assert raised.value.message.split(": ", 1)[1] == str(cli_record)
    return True


def assert_close(actual, expected, what):
    if expected is None:
        assert actual is None, f"{what}: {actual} where the CLI has null"
        return
    np.testing.assert_allclose(np.array(actual, dtype=float), np.array(expected, dtype=float), rtol=1e-6,
                               atol=1e-9, err_msg=what)


def test_process_file_gives_the_cli_record(scan, cli_record):
    if fails_like_the_cli(cli_record, lambda: sherd.process_file(scan)):
        return
    analysis = sherd.process_file(scan)
    record = analysis.record
    assert analysis.oriented == (cli_record["status"] in ("ok", "axis_uncertain"))
    assert analysis.axis_uncertain == (cli_record["status"] == "axis_uncertain")
    for key in ("file", "status", "reason", "error", "method"):
        assert record[key] == cli_record[key], key
    for key in FIGURES:
        assert_close(record[key], cli_record[key], key)
    # The wheel rills and, for a declined sherd, the three points on the longest rill.
    assert (record["rills"] is None) == (cli_record["rills"] is None)
    if record["rills"] is not None:
        for key in ("count", "slope_deg", "slope_spread_deg", "longest_arc_mm"):
            assert_close(record["rills"][key], cli_record["rills"][key], f"rills {key}")
    assert_close(record["manual_points_on_rill"], cli_record["manual_points_on_rill"], "manual points on the rill")
    # A declined sherd's best guess, not trusted: the same as the CLI's.
    guess, cli_guess = analysis.best_guess, cli_record["best_guess"]
    assert (guess is None) == (cli_guess is None)
    if guess is not None:
        assert_close(guess.axis.point, cli_guess["axis"]["point"], "best guess point")
        assert_close(guess.axis.direction, cli_guess["axis"]["direction"], "best guess direction")
        assert (guess.against, guess.sense_known) == (cli_guess["against"], cli_guess["sense_known"])
    if analysis.oriented or analysis.sense_uncertain:
        # A sense-uncertain sherd's axis line is an answer too, its sense not.
        assert_close(analysis.axis.point, cli_record["axis"]["point"], "axis point")
        assert_close(analysis.axis.direction, cli_record["axis"]["direction"], "axis direction")
    else:
        assert analysis.axis is None and analysis.reason


def test_the_pipeline_step_by_step_agrees_with_the_cli(scan, cli_record):
    mesh = sherd.Mesh.read(scan)
    mesh.repair()
    orientation = sherd.orient_automatic(mesh)
    assert orientation.oriented == (isinstance(cli_record, CommandFailed) or cli_record["status"] in ("ok", "axis_uncertain"))
    if not orientation.oriented:
        if orientation.sense_uncertain:
            # The pipeline judges the sense again under the refined axis: the same verdict,
            # its cues' figures read off a slightly different axis.
            assert cli_record["status"] == "sense_uncertain"
            prefix = "the axis line is found but not which way is up"
            assert cli_record["reason"].startswith(prefix) and prefix in orientation.reason
        else:
            assert cli_record["reason"] in orientation.reason
        if not orientation.sense_uncertain:
            # Where to pick, under the declined axis, as the CLI's record gives it.
            points = sherd.points_on_longest_rill(mesh, orientation.axis)
            assert_close(None if points is None else points.tolist(), cli_record["manual_points_on_rill"], "rill points")
        return
    refine = lambda: sherd.refine(mesh, orientation.axis, criterion="auto", surface="both")  # noqa: E731
    if fails_like_the_cli(cli_record, refine):
        return
    refined = refine()
    cli_axis = sherd.Axis(cli_record["axis"]["point"], cli_record["axis"]["direction"])
    angle = math.degrees(math.acos(min(1.0, float(refined.axis.direction @ cli_axis.direction))))
    assert angle < 1e-6, f"the binding's axis is {angle} deg from the CLI's"
    measured = sherd.measure(mesh, refined.axis, refine_options={"criterion": "auto", "surface": "both"})
    for key in ("rim_diameter_mm", "rim_diameter_interval_mm", "sector_angle_deg", "height_mm"):
        value = getattr(measured, key)
        expected = cli_record[key]
        if expected is None:
            assert np.all(np.isnan(value)), key
        else:
            assert_close(value, expected, key)
    # The measurements' flag is what the record's axis_uncertain status is made of.
    if cli_record["status"] in ("ok", "axis_uncertain"):
        assert measured.axis_uncertain == (cli_record["status"] == "axis_uncertain")


def test_analyse_in_memory_matches_the_file(scan, cli_record):
    if fails_like_the_cli(cli_record, lambda: sherd.analyse(sherd.Mesh.read(scan))):
        return
    analysis = sherd.analyse(sherd.Mesh.read(scan))
    assert analysis.record["file"] == "<memory>"
    assert analysis.record["status"] == cli_record["status"]
    for key in FIGURES:
        assert_close(analysis.record[key], cli_record[key], key)


def test_drawing_options_have_the_command_lines_names(tmp_path):
    """``sherd.Drawing``'s layout keywords are ``sherd draw``'s options under the same
    names (underscores for hyphens): the same options give the same drawing."""
    mesh, axis, _ = sherd.synthetic_sherd(13, "rim", target_faces=8000)
    path = tmp_path / "seed13.ply"
    mesh.write_ply(path)
    mesh = sherd.Mesh.read(path)
    axis_file = tmp_path / "axis.json"
    axis_file.write_text(json.dumps({"point": [float(v) for v in axis.point], "direction": [float(v) for v in axis.direction]}))
    layout = dict(placement="true_distance", section_fill="hatched", interior_view=False, prolongation=False,
                  title="Py 13 mm", annotations="height,wall_thickness")
    cli = tmp_path / "cli.svg"
    arguments = [str(sherd_command()), "draw", str(path), "--axis", str(axis_file), "--style", "linear,light",
                 "--dpi", "60", "--section-angle", "4", "-o", str(cli)]
    for name, value in layout.items():
        arguments += ["--" + name.replace("_", "-"), str(value).lower() if isinstance(value, bool) else value]
    run = subprocess.run(arguments, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    drawing = sherd.Drawing(mesh, axis, style="linear,light", dpi=60, section_angle_rad=math.radians(4), **layout)
    assert cli.read_bytes() == drawing.to_bytes("svg")
    default = sherd.Drawing(mesh, axis, style="linear,light", dpi=60)
    assert default.to_bytes("svg") != cli.read_bytes()
