#!/usr/bin/env bash
# `cmake --install BUILD --prefix DIR` (README, "Install"): raylane and make_maps in DIR/bin,
# the README and docs in DIR/share/doc/raylane, the example scenes with what they read in
# DIR/share/raylane/scenes; the installed raylane, run from elsewhere, renders the installed
# textured and sky scenes and finds their meshes, texture and sky beside them.
#
#   install_check.sh CMAKE BUILD_DIR WORK_DIR
set -euo pipefail
cmake=$1 build=$2 work=$3
rm -rf "$work" && mkdir -p "$work/run"
prefix=$work/prefix
"$cmake" --install "$build" --prefix "$prefix" >"$work/install.log"
fail() { echo "FAIL: $*"; exit 1; }
for f in bin/raylane bin/make_maps; do
  [ -x "$prefix/$f" ] || fail "$f is not installed (or not executable)"
done
for f in share/doc/raylane/README.md share/doc/raylane/scene-language.md \
  share/raylane/scenes/testscene.scn \
  share/raylane/scenes/letterX.ply share/raylane/scenes/checker.png \
  share/raylane/scenes/sky.hdr; do
  [ -f "$prefix/$f" ] || fail "$f is not installed"
done
cd "$work/run"
export PATH=$prefix/bin:$PATH
for scene in testscene-textured testscene-sky box; do
  raylane render "$prefix/share/raylane/scenes/$scene.scn" --spp 1 --set 'screen 32 24' \
    -o "$scene.hdr" -q >out.txt 2>err.txt || { cat err.txt; fail "the installed raylane cannot render $scene.scn"; }
  [ -f "$scene.hdr" ] || fail "no $scene.hdr"
done
make_maps checker c.png >/dev/null || fail "the installed make_maps does not run"
echo "installed under $prefix: bin, docs and scenes; the scenes render"
