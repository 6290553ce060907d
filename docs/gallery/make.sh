#!/usr/bin/env bash
# Regenerates the gallery's drawings (docs/gallery/*.png) from gallery.tsv: synthetic
# sherds made with `sherd synth` and drawn along their true axes, and A011 where
# ../shared/data is present (oriented by three points on its wheel rill, as the README
# shows). The same drawings are the references of the pixel regression test
# (tests/gallery.rs), so after a deliberate change of the drawing, refresh them with:
#
#   bash docs/gallery/make.sh
#
# SHERD names the sherd command (default: built here with cargo, in release).
# GALLERY_DPI sets the resolution (default 100: small files). GALLERY_OUT writes the
# drawings to another folder (the regression test renders them there to compare).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
gallery="$root/docs/gallery"
if [ -z "${SHERD:-}" ]; then
  cargo build --release -q --bin sherd
  SHERD="${CARGO_TARGET_DIR:-$root/target}/release/sherd"
fi
dpi=${GALLERY_DPI:-100}
shared="$root/../shared/data"
# The three rill points of A011 (README, "Command line").
a011_points="30.508,-66.920,39.363;18.614,-75.548,43.705;8.663,-86.138,42.986"
out_dir=${GALLERY_OUT:-$gallery}
mkdir -p "$out_dir"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

made=0
while IFS=$'\t' read -r name scan options; do
  case "$name" in ''|'#'*) continue ;; esac
  out="$out_dir/$name.png"
  case "$scan" in
    synth:*)
      folder="$work/$name"
      # shellcheck disable=SC2086 # the manifest's arguments split on spaces
      "$SHERD" synth "$folder" --faces 60000 ${scan#synth:} >/dev/null
      ply=$(ls "$folder"/*.ply | head -n 1)
      # shellcheck disable=SC2086
      "$SHERD" draw "$ply" --axis "${ply%.ply}.truth.json" --dpi "$dpi" $options -o "$out"
      ;;
    shared:*)
      file="$shared/${scan#shared:}"
      if [ ! -f "$file" ]; then
        echo "SKIP $name: $file is absent (its reference is kept as it was)"
        continue
      fi
      # shellcheck disable=SC2086
      "$SHERD" draw "$file" --manual "$a011_points" --dpi "$dpi" $options -o "$out" 2>/dev/null
      ;;
    *) echo "gallery.tsv: $name: unknown scan $scan" >&2; exit 1 ;;
  esac
  echo "$out"
  made=$((made + 1))
done < "$gallery/gallery.tsv"
echo "$made drawings in $out_dir"
