#!/usr/bin/env bash
# Builds the Blender add-on of sherd:
#   target/blender/sherd_extension.zip     Blender 4.2+ extension: the add-on and the
#                                          manylinux_2_28 wheel of the sherd package (with
#                                          libsherd.so) that Blender installs with it
#   target/blender/sherd_blender.zip       legacy add-on (Blender 3.x: Preferences > Add-ons >
#                                          Install): the add-on with the sherd package and the
#                                          same libsherd.so vendored as sherd_blender.sherd
# The wheel comes from bindings/python/build_wheel.sh. The extension zip is built (and its
# manifest validated) by Blender's own extension tool, blender_ext.py of the bpy module in
# BPY_PYTHON (default target/bpy-venv/bin/python, as tests/blender/run.sh installs it);
# without it, by Python's zipfile in the same layout.
#
#   bash addons/blender/build.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
wheel=$(bash bindings/python/build_wheel.sh | tail -1)
out="$root/target/blender"
mkdir -p "$out"

# The extension: the manifest names the wheel Blender installs.
extension="$out/sherd_extension"
rm -rf "$extension"
mkdir -p "$extension/wheels"
cp addons/blender/sherd_blender/*.py addons/blender/sherd_blender/blender_manifest.toml "$extension/"
cp "$wheel" "$extension/wheels/"
sed -i "s|^platforms = .*|&\nwheels = [\"./wheels/$(basename "$wheel")\"]|" "$extension/blender_manifest.toml"

# The legacy add-on: Blender 3.x installs no wheels, so the package is vendored.
legacy="$out/sherd_blender"
rm -rf "$legacy"
mkdir -p "$legacy/sherd"
cp addons/blender/sherd_blender/*.py "$legacy/"
cp bindings/python/sherd/*.py "$legacy/sherd/"
python3 -c 'import sys, zipfile; open(sys.argv[2], "wb").write(zipfile.ZipFile(sys.argv[1]).read("sherd/libsherd.so"))' \
  "$wheel" "$legacy/sherd/libsherd.so"

bpy_python=${BPY_PYTHON:-$root/target/bpy-venv/bin/python}
blender_ext=""
if [ -x "$bpy_python" ]; then
  blender_ext=$("$bpy_python" -c 'import bpy, pathlib
tool = pathlib.Path(bpy.utils.system_resource("SCRIPTS"), "addons_core", "bl_pkg", "cli", "blender_ext.py")
print(tool if tool.is_file() else "")' 2>/dev/null | tail -1 || true)
fi

python3 - "$out" "$blender_ext" "$bpy_python" <<'PY'
import os, subprocess, sys, zipfile
out, blender_ext, bpy_python = sys.argv[1:4]
def write(folder, zip_path, prefix):
    temporary = zip_path + ".part"
    with zipfile.ZipFile(temporary, "w", zipfile.ZIP_DEFLATED) as archive:
        for directory, _, files in sorted(os.walk(folder)):
            for name in sorted(files):
                path = os.path.join(directory, name)
                archive.write(path, os.path.join(prefix, os.path.relpath(path, folder)))
    os.replace(temporary, zip_path)
    print(zip_path)
extension_zip = os.path.join(out, "sherd_extension.zip")
if blender_ext:
    subprocess.run([bpy_python, blender_ext, "build", "--source-dir", os.path.join(out, "sherd_extension"),
                    "--output-filepath", extension_zip], check=True, stdout=sys.stderr)
    print(extension_zip)
else:
    print("build.sh: no bpy module for Blender's extension tool; zipping the extension directly", file=sys.stderr)
    write(os.path.join(out, "sherd_extension"), extension_zip, "")
# Legacy add-ons install from a zip holding the package folder.
write(os.path.join(out, "sherd_blender"), os.path.join(out, "sherd_blender.zip"), "sherd_blender")
PY
