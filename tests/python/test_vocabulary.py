"""The binding's names are the library's: every vocabulary the binding offers (criteria,
surfaces, styles, record statuses...) is the list the C ABI gives (sherd_vocabulary_entry),
and names are parsed by the library (sherd_vocabulary_value)."""

import re
from pathlib import Path

import pytest
import sherd
from sherd import draw, pipeline, vocabulary

ROOT = Path(__file__).resolve().parents[2]


def header_constants(prefix):
    text = (ROOT / "include" / "sherd.h").read_text()
    return {name: int(value) for name, value in re.findall(rf"\b{prefix}(\w+) = (\d+)", text)}


def test_vocabulary_kinds_match_the_header():
    assert header_constants("SHERD_VOCABULARY_") == {kind.name: kind.value for kind in sherd.Vocabulary}


@pytest.mark.parametrize("offered, kind, prefix", [
    (pipeline.CRITERIA, sherd.Vocabulary.CRITERION, "SHERD_CRITERION_"),
    (pipeline.SURFACES, sherd.Vocabulary.SURFACE, "SHERD_SURFACE_"),
    (pipeline.PARETO_CHOICES, sherd.Vocabulary.PARETO_CHOICE, "SHERD_PARETO_CHOICE_"),
    (pipeline.EDGES, sherd.Vocabulary.EDGE, "SHERD_EDGE_"),
    (pipeline.PROFILE_METHODS, sherd.Vocabulary.PROFILE_METHOD, "SHERD_PROFILE_METHOD_"),
    (pipeline.CIRCLE_FITS, sherd.Vocabulary.CIRCLE_FIT, "SHERD_CIRCLE_FIT_"),
    (draw.STYLES, sherd.Vocabulary.STYLE, "SHERD_STYLE_"),
    (draw.ANNOTATIONS, sherd.Vocabulary.ANNOTATION, "SHERD_ANNOTATION_"),
    (draw.FILLS, sherd.Vocabulary.SECTION_FILL, "SHERD_SECTION_FILL_"),
    (draw.PLACEMENTS, sherd.Vocabulary.PLACEMENT, "SHERD_PLACEMENT_"),
    (draw.REGULARITY, sherd.Vocabulary.REGULARITY, "SHERD_REGULARITY_"),
    (draw.FORMATS, sherd.Vocabulary.FORMAT, "SHERD_FORMAT_"),
])
def test_the_bindings_names_are_the_c_abis(offered, kind, prefix):
    listed = vocabulary.entries(kind)
    assert list(offered) == [name for name, _, _ in listed]
    # Each name's value is the header's constant of the same name.
    assert {name.upper(): value for name, value in offered.items()} == header_constants(prefix)
    assert all(description for _, _, description in listed)


def test_record_statuses_are_the_librarys():
    assert [status.value for status in sherd.RecordStatus] == vocabulary.names(sherd.Vocabulary.RECORD_STATUS)
    statuses = vocabulary.mapping(sherd.Vocabulary.RECORD_STATUS)
    assert {name.upper(): value for name, value in statuses.items()} == header_constants("SHERD_RECORD_STATUS_")


def test_statuses_are_named_by_the_library():
    assert sherd.Status.OK == 0 and sherd.Status.SENSE_UNCERTAIN.name == "SENSE_UNCERTAIN"
    assert {status.name: status.value for status in sherd.Status} == header_constants("SHERD_STATUS_")


def test_names_are_parsed_by_the_library():
    assert vocabulary.value_of(sherd.Vocabulary.STYLE, "Color", "style") == draw.STYLES["colour"]
    assert vocabulary.value_of(sherd.Vocabulary.PLACEMENT, "true-distance", "placement") == draw.PLACEMENTS["true_distance"]
    assert vocabulary.value_of(sherd.Vocabulary.CRITERION, 3, "criterion") == 3
    with pytest.raises(sherd.InvalidArgumentError, match=r"unknown criterion 'bogus'; one of \['auto', 'circles'"):
        vocabulary.value_of(sherd.Vocabulary.CRITERION, "bogus", "criterion")
    assert vocabulary.name_of(sherd.Vocabulary.CRITERION, pipeline.CRITERIA["tangent"]) == "tangent"
