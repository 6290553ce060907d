"""pytest fixtures for tests/blender/test_addon_blender.py where bpy is a Python module
(the bpy wheel of Blender 4.2): the add-on installed once per session."""

import pytest


@pytest.fixture(scope="session")
def installed():
    from test_addon_blender import install_addon
    return install_addon()


@pytest.fixture(scope="session")
def vendored(installed):
    """The sherd package the add-on uses."""
    return installed[0]


@pytest.fixture(scope="session")
def operators(installed):
    """The add-on's operators module."""
    return installed[1]
