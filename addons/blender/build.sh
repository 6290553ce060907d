#!/usr/bin/env bash
# Builds the Blender add-on of sherd:
#   target/blender/sherd_blender/          the assembled add-on folder
#   target/blender/sherd_blender.zip       legacy add-on (Blender 3.x: Preferences > Add-ons > Install)
#   target/blender/sherd_extension.zip     Blender 4.2+ extension (manifest at the zip's root)
# Both hold the add-on, the sherd Python package vendored as sherd_blender.sherd and the
# release libsherd.so inside it (where sherd/_library.py looks first).
#
#   bash addons/blender/build.sh            (SHERD_SKIP_CARGO=1 to reuse target/release)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
if [ "${SHERD_SKIP_CARGO:-0}" != 1 ]; then
  cargo build --release --lib
fi
library="$root/target/release/libsherd.so"
[ -f "$library" ] || { echo "build.sh: $library is missing" >&2; exit 1; }

out="$root/target/blender"
folder="$out/sherd_blender"
rm -rf "$folder"
mkdir -p "$folder"
cp addons/blender/sherd_blender/*.py addons/blender/sherd_blender/blender_manifest.toml "$folder/"
mkdir -p "$folder/sherd"
cp bindings/python/sherd/*.py "$folder/sherd/"
cp "$library" "$folder/sherd/libsherd.so"

python3 - "$folder" "$out" <<'PY'
import os, sys, zipfile
folder, out = sys.argv[1], sys.argv[2]
def write(zip_path, prefix):
    temporary = zip_path + ".part"
    with zipfile.ZipFile(temporary, "w", zipfile.ZIP_DEFLATED) as archive:
        for directory, _, files in sorted(os.walk(folder)):
            for name in sorted(files):
                path = os.path.join(directory, name)
                archive.write(path, os.path.join(prefix, os.path.relpath(path, folder)))
    os.replace(temporary, zip_path)
    print(zip_path)
# Legacy add-ons install from a zip holding the package folder; extensions want the
# manifest at the zip's root.
write(os.path.join(out, "sherd_blender.zip"), "sherd_blender")
write(os.path.join(out, "sherd_extension.zip"), "")
PY
