#!/usr/bin/env bash
# `raylane view` end to end, as a person uses it, under a virtual X server (Xvfb): open the
# window, fly, look and orbit with xdotool's keys and mouse, print the camera (V), save (S),
# quit (Q). Then check that
#   - the printed screen and camera lines parse (raylane render reads them) and the camera moved;
#   - the saved image skips a name already taken and is, bit for bit, what `raylane render`
#     writes for the printed lines at the printed spp;
#   - a screenshot of the window is a picture, not a blank;
#   - with --region, S saves the rectangle, bit for bit what `raylane render --region` writes.
#
#   view_e2e.sh RAYLANE SCENE WORKDIR [SCREENSHOT]   (SCREENSHOT: also keep the window's picture)
#
# Exit status 77 (ctest: skipped) without xvfb-run, xdotool or ImageMagick.
set -euo pipefail

if [ "${1:-}" != "--inside" ]; then
  self=$(realpath "${BASH_SOURCE[0]}") raylane=$(realpath "$1") scene=$(realpath "$2")
  work=$3 shot=${4:-}
  for tool in xvfb-run xauth xdotool import convert; do
    if ! command -v "$tool" >/dev/null; then
      echo "SKIP: $tool is not installed (Debian: xvfb xauth xdotool imagemagick)"
      exit 77
    fi
  done
  rm -rf "$work" && mkdir -p "$work"
  [ -z "$shot" ] || shot=$(realpath "$shot")
  # A copy of the scene with the meshes beside it: the test edits it to see it reloaded.
  cp "$scene" "$(dirname "$scene")"/*.ply "$work/"
  scene=$work/$(basename "$scene")
  cd "$work"
  # A server of its own (-a: the first free display number), 24-bit colour.
  exec timeout -k 5 100 xvfb-run -a -s "-screen 0 640x480x24 -nolisten tcp" \
    bash "$self" --inside "$raylane" "$scene" "$shot"
fi

raylane=$2 scene=$3 shot=$4
. "$(dirname "${BASH_SOURCE[0]}")/view_e2e_lib.sh"

touch view-0001.png  # taken: the viewer must not write over it
# Under the sanitizers (LSAN_OPTIONS set), the viewer runs without the leak check: SDL unloads
# the X11 libraries it opened at SDL_Quit, so LeakSanitizer can neither name nor suppress what
# they keep until exit ("<unknown module>"). Every other check stays on; ViewCli's tests run
# the viewer up to SDL_Init with the leak check.
view_env=()
[ -z "${LSAN_OPTIONS:-}" ] || view_env=(env "ASAN_OPTIONS=${ASAN_OPTIONS:-}:detect_leaks=0")
"${view_env[@]}" "$raylane" view "$scene" --set 'screen 160 120' --spp-limit 4 --pfm >out.txt 2>err.txt &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT

wid=$(timeout 60 xdotool search --sync --name '^raylane view' | head -1) || true
[ -n "$wid" ] || fail "no window titled 'raylane view' within 60 s"
xdotool windowfocus --sync "$wid"
# The window found first must stay the window (SDL once replaced its X window at the first
# frame, under ASan's slower start, and every later step lost it).
windows() { xdotool search --name '^raylane view' 2>/dev/null | tr '\n' ' '; }
wait_for 60 title_says "path 4 spp" ||
  fail "not at 4 spp within 60 s: window $wid is titled '$(xdotool getwindowname "$wid" 2>&1)'; windows now: $(windows)"

xdotool key v
wait_for 30 has camera 1 || fail "V printed no camera line"
# Fly forward (the Up arrow held), look (left drag), orbit (right drag).
# Small moves: the room stays in view.
xdotool keydown Up
sleep 0.15
xdotool keyup Up
xdotool mousemove --window "$wid" 80 60 mousedown 1 mousemove_relative --sync 6 2 mouseup 1
xdotool mousemove --window "$wid" 80 60 mousedown 3 mousemove_relative --sync -- -4 -2 mouseup 3
# The camera stands still again: the film fills up to the limit.
wait_for 60 title_says "path 4 spp" || fail "not back at 4 spp within 60 s"
xdotool key v
wait_for 30 has camera 2 || fail "the second V printed no camera line"
xdotool key s
wait_for 30 has saved 1 || fail "S saved nothing"
import -window "$wid" shot.png
cp "$scene" scene-as-saved.scn
# An edit to the scene reloads it, and a new camera line in the file wins over the flown one.
echo "camera 5 3 3 0.2 q 0.416981 0.279589 0.480987 0.718247" >>"$scene"
wait_for 30 grep -q "reloaded the scene, and its new camera" err.txt || fail "no reload"
xdotool key v
wait_for 30 has camera 3 || fail "the third V printed no camera line"
quit_viewer

# The lines: screen, camera, and a camera that moved.
screen=$(grep '^screen ' out.txt | tail -1)
first=$(grep '^camera ' out.txt | head -1)
last=$(grep '^camera ' out.txt | sed -n 2p)
[ "$screen" = "screen 160 120" ] || fail "printed '$screen'"
[ "$first" != "$last" ] || fail "the camera did not move: $last"
reloaded=$(grep '^camera ' out.txt | sed -n 3p)
[[ "$reloaded" == "camera 5 3 3 0.20000000000000001 q "* ]] ||
  fail "after the reload, V printed '$reloaded', not the file's new camera"

# saved view-0002.hdr view-0002.png view-0002.pfm (path, 4 spp)
saved=$(grep '^saved ' out.txt | tail -1)
[[ "$saved" =~ ^saved\ (view-0002\.hdr)\ (view-0002\.png)\ (view-0002\.pfm)\ \(path,\ ([0-9]+)\ spp\)$ ]] ||
  fail "printed '$saved', not 'saved view-0002.hdr view-0002.png view-0002.pfm (path, N spp)'"
hdr=${BASH_REMATCH[1]} png=${BASH_REMATCH[2]} spp=${BASH_REMATCH[4]}
[ -s view-0001.png ] && fail "view-0001.png was written over"
[ -s "$png" ] || fail "no $png"
grep -aq "RAYLANE_SPP=$spp" "$hdr" || fail "$hdr does not say RAYLANE_SPP=$spp"

# Float for float (PFM; the HDR's 8-bit mantissas would hide a small difference), and the HDR.
"$raylane" render scene-as-saved.scn --set "$screen" --set "$last" --spp "$spp" -o render.pfm \
  -o render.hdr -q >render.txt 2>&1 || fail "raylane render of the printed lines: $(cat render.txt)"
for ext in pfm hdr; do
  "$raylane" diff "view-0002.$ext" "render.$ext" >diff.txt 2>&1 ||
    fail "the saved view-0002.$ext is not the render's: $(cat diff.txt)"
done

# The image and the window show the room: many colours, the screen's size.
read -r colours <<<"$(convert "$png" -format '%k' info:)"
((colours > 100)) || fail "$png has $colours colours: the camera left the room?"
read -r colours size <<<"$(convert shot.png -format '%k %wx%h' info:)"
[ "$size" = 160x120 ] || fail "the screenshot is $size"
((colours > 100)) || fail "the screenshot has $colours colours: blank?"
[ -z "$shot" ] || cp shot.png "$shot"

# --region: the viewer renders the rectangle alone and S saves it, bit for bit what
# `raylane render --region` writes at the saved spp (the scene as edited above: its camera).
mkdir region && cd region
"${view_env[@]}" "$raylane" view "$scene" --set 'screen 160 120' --spp-limit 2 --pfm \
  --region 20,10,100,70 >out.txt 2>err.txt &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
wid=$(timeout 60 xdotool search --sync --name '^raylane view' | head -1) || true
[ -n "$wid" ] || fail "--region: no window within 60 s"
xdotool windowfocus --sync "$wid"
wait_for 60 title_says "path 2 spp" || fail "--region: not at 2 spp within 60 s"
xdotool key s
wait_for 30 has saved 1 || fail "--region: S saved nothing"
quit_viewer
[[ "$(grep '^saved ' out.txt)" == *"(path, 2 spp)" ]] || fail "--region: not saved at 2 spp"
"$raylane" render "$scene" --set 'screen 160 120' --region 20,10,100,70 --spp 2 -o render.pfm \
  -q >render.txt 2>&1 || fail "--region: raylane render: $(cat render.txt)"
"$raylane" diff view-0001.pfm render.pfm >diff.txt 2>&1 ||
  fail "--region: the saved view-0001.pfm is not render --region's: $(cat diff.txt)"
cd ..

echo "ok: moved from '$first' to '$last'; the saved image is the render's at $spp spp;" \
  "the window shows $colours colours; a --region view saves render --region's image"
