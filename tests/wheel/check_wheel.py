"""Run by tests/wheel/run.sh inside a venv where only the built wheel is installed."""

import sys
import sysconfig
import zipfile
from pathlib import Path

import numpy as np

import sherd

wheel = Path(sys.argv[1])
site_packages = Path(sysconfig.get_paths()["purelib"]).resolve()
loaded = Path(sherd.lib._name).resolve()
assert loaded == site_packages / "sherd" / "libsherd.so", f"loaded {loaded}, not the wheel's library"
assert Path(sherd.__file__).resolve().parent == site_packages / "sherd", sherd.__file__
with zipfile.ZipFile(wheel) as archive:
    names = archive.namelist()
    wheel_info = archive.read(next(n for n in names if n.endswith(".dist-info/WHEEL"))).decode()
assert "sherd/libsherd.so" in names, names
assert "Root-Is-Purelib: false" in wheel_info and "Tag: py3-none-manylinux_2_28_x86_64" in wheel_info, wheel_info

mesh, truth, _ = sherd.synthetic_sherd(13, "rim", target_faces=6000)
orientation = sherd.orient_automatic(mesh)
angle = np.degrees(np.arccos(np.clip(orientation.axis.direction @ truth.direction, -1, 1)))
assert orientation.oriented and angle < 2.0, (orientation.oriented, angle)
vessel = sherd.reconstruct(mesh, orientation.axis, segments=36)
assert vessel.vertex_count % 36 == 0
print(f"wheel {wheel.name}: sherd {sherd.__version__} from {loaded}; synthetic sherd oriented {angle:.2f} deg "
      f"from the truth, reconstruction {vessel.vertex_count} vertices")
