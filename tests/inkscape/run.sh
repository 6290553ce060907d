#!/usr/bin/env bash
# The drawing in the hosts an illustrator opens it with: Inkscape opens the SVG and
# converts it to PDF and PNG with no warning on its output, and Ghostscript renders the
# EPS and the PDF (-dSAFER, -q: any message on its output is a failure).
#
#   bash tests/inkscape/run.sh
#
# Installs Inkscape and Ghostscript with apt where they are missing. The drawings are
# those of a synthetic rim sherd and a rim-to-base plate drawn with `sherd draw` along
# their true axes, in every style, both placements and both fills. SHERD names the sherd
# command (default: built here in release, in $CARGO_TARGET_DIR or target/).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
say() { printf -- '--- inkscape: %s\n' "$*"; }

missing=()
command -v inkscape >/dev/null 2>&1 || missing+=(inkscape)
command -v gs >/dev/null 2>&1 || missing+=(ghostscript)
if [ ${#missing[@]} -gt 0 ]; then
  say "installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
if [ -z "${SHERD:-}" ]; then
  (cd "$root" && cargo build --release -q --bin sherd)
  SHERD="${CARGO_TARGET_DIR:-$root/target}/release/sherd"
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Inkscape wants a writable home for its preferences, and no display.
export HOME="$work/home" XDG_CONFIG_HOME="$work/home/.config" XDG_CACHE_HOME="$work/home/.cache"
mkdir -p "$XDG_CONFIG_HOME" "$XDG_CACHE_HOME"
unset DISPLAY WAYLAND_DISPLAY

"$SHERD" synth "$work/rim" --part rim --seed 4 --faces 20000 >/dev/null
"$SHERD" synth "$work/plate" --part rim_to_base --seed 2 --shape plate --faces 20000 >/dev/null
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
# Inkscape and GLib print these on a machine without a session bus or display (Inkscape
# 1.2 warns that it cannot wrap GtkRecentManager, its list of recent files, before any
# file is read); they are about the machine, not the file. Every other line on its output
# counts as a warning.
benign="^(\$|Gtk-Message|dbus-daemon|Fontconfig warning: ignoring UTF-8|.*Failed to connect to the bus|.*GLib-GIO-.*(dbus|session bus)|.*Unable to init server|.*Failed to wrap object of type 'GtkRecentManager')"

drawn=0
for scan in "$work"/rim/*.ply "$work"/plate/*.ply; do
  truth="${scan%.ply}.truth.json"
  for case in "linear,light|beside|black" "light,occlusion|true-distance|hatched" "stipple|beside|hatched" \
              "colour,light|true-distance|black" "regularity|beside|black" "linear,occlusion,stipple|true-distance|black"; do
    IFS='|' read -r style placement fill <<<"$case"
    name="$(basename "${scan%.ply}")-${style//,/+}-$placement-$fill"
    base="$work/$name"
    for ext in svg eps pdf; do
      "$SHERD" draw "$scan" --axis "$truth" --style "$style" --placement "$placement" --section-fill "$fill" \
        --dpi 100 --title "$(basename "${scan%.ply}")" -o "$base.$ext"
    done
    drawn=$((drawn + 1))

    # Inkscape: the SVG to PDF and to PNG, nothing but the machine's messages on its output.
    log="$base.inkscape.log"
    if ! inkscape "$base.svg" --export-type=pdf --export-filename="$base.inkscape.pdf" >"$log" 2>&1; then
      fail "$name: inkscape could not convert the SVG to PDF"; cat "$log" >&2
    fi
    if ! inkscape "$base.svg" --export-type=png --export-dpi=96 --export-filename="$base.inkscape.png" >>"$log" 2>&1; then
      fail "$name: inkscape could not convert the SVG to PNG"; cat "$log" >&2
    fi
    if grep -Ev "$benign" "$log" | grep -q .; then
      fail "$name: inkscape warned:"; grep -Ev "$benign" "$log" >&2
    fi
    for out in "$base.inkscape.pdf" "$base.inkscape.png"; do
      [ -s "$out" ] || fail "$name: inkscape wrote no $(basename "$out")"
    done
    head -c 4 "$base.inkscape.pdf" | grep -q '%PDF' || fail "$name: inkscape's PDF is no PDF"

    # Ghostscript: the EPS and the PDF render, with no error or warning.
    for ext in eps pdf; do
      gs_log="$base.gs-$ext.log"
      extra=()
      [ "$ext" = eps ] && extra=(-dEPSCrop)
      if ! gs -q -dBATCH -dNOPAUSE -dSAFER "${extra[@]}" -sDEVICE=png16m -r72 -sOutputFile="$base.gs-$ext.png" \
           "$base.$ext" >"$gs_log" 2>&1; then
        fail "$name: ghostscript failed on the $ext"; cat "$gs_log" >&2
      elif grep -q . "$gs_log"; then
        fail "$name: ghostscript said something about the $ext:"; cat "$gs_log" >&2
      fi
      [ -s "$base.gs-$ext.png" ] || fail "$name: ghostscript rendered no page of the $ext"
    done
  done
done
[ "$drawn" -ge 12 ] || fail "only $drawn drawings made"
if [ "$failures" -gt 0 ]; then
  echo "tests/inkscape/run.sh: $failures failures" >&2
  exit 1
fi
say "$drawn drawings: SVG converted by Inkscape to PDF and PNG without warnings, EPS and PDF rendered by Ghostscript"
