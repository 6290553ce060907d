"""Makes the Python binding (and tests/support) importable from the source tree and
points it at the library cargo built (``target/release`` as tests/run_all.sh builds it,
or ``$SHERD_PROFILE``), unless ``SHERD_LIBRARY`` already says where it is."""

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bindings" / "python"))
sys.path.insert(0, str(ROOT / "tests" / "support"))

if "SHERD_LIBRARY" not in os.environ:
    profile = os.environ.get("SHERD_PROFILE", "release")
    library = ROOT / "target" / profile / "libsherd.so"
    if not library.exists():
        command = ["cargo", "build", "--lib"] + (["--release"] if profile == "release" else [])
        subprocess.run(command, cwd=ROOT, check=True)
    os.environ["SHERD_LIBRARY"] = str(library)


def sherd_command():
    """The ``sherd`` command-line tool of the same build as the library."""
    profile = os.environ.get("SHERD_PROFILE", "release")
    command = ROOT / "target" / profile / "sherd"
    if not command.exists():
        subprocess.run(["cargo", "build", "--bin", "sherd"] + (["--release"] if profile == "release" else []),
                       cwd=ROOT, check=True)
    return command
