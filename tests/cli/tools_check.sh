#!/usr/bin/env bash
# The tools a user runs next to raylane: tools/converge and tools/bench_table list
# every option with its default in --help and take the programs they run as options;
# tools/converge, run from elsewhere with --raylane, reads each render's --stats-json and draws
# its plot (gnuplot, which tools/dev installs); bench_trace documents --export and --bunny, finds
# the bunny in its own build tree and takes another with --bunny.
#
#   tools_check.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source_dir=$(realpath "$1") build=$(realpath "$2") work=$3
rm -rf "$work" && mkdir -p "$work"
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }

# Every option of each tool, with its default, in its --help.
for tool in converge bench_table; do
  "$source_dir/tools/$tool" --help >"$tool.help" || fail "$tool --help exits $?"
  options=$(grep -o -E '^  --[a-z-]+' "$tool.help" | sort -u)
  [ "$(echo "$options" | wc -l)" -ge 6 ] || fail "$tool --help lists only: $options"
  for o in $options; do
    # The option's paragraph (up to the next option) names its default.
    awk -v o="$o" '/^  --/ { if (on) exit; if ($1 == o) on = 1 } on' "$tool.help" |
      grep -q 'default:' || fail "$tool --help: $o has no default"
  done
done
# tools/avx512-emulated (it boots an emulator, too slow to run here): its --help lists every
# option with a default, and an unknown option is refused before anything is installed or built.
"$source_dir/tools/avx512-emulated" --help >emulated.help || fail "avx512-emulated --help exits $?"
for o in --render --trace --simd --bvh --minutes; do
  awk -v o="$o" '$1 == o {on = 1} on && /default:/ {found = 1} on && /^  --/ && $1 != o {on = 0}
    END {exit !found}' emulated.help || fail "avx512-emulated --help: $o has no default"
done
status=0
"$source_dir/tools/avx512-emulated" --no-such-option >emulated.out 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "unknown option --no-such-option" emulated.out ||
  fail "avx512-emulated took an unknown option (exit $status): $(cat emulated.out)"
grep -q -- '--raylane PATH' converge.help || fail "converge takes no --raylane"
grep -q -- '--bench PATH' bench_table.help || fail "bench_table takes no --bench"
if "$source_dir/tools/bench_table" --bench "$work/none" >bt.out 2>&1; then
  fail "bench_table ran without its benchmark program"
fi
grep -q "missing or not executable" bt.out || fail "bench_table: $(cat bt.out)"

# A small convergence report, from a folder that is not the repository's.
"$source_dir/tools/converge" "$source_dir/scenes/sphere.scn" --raylane "$build/raylane" \
  --ref-spp 8 --max-spp 4 --methods mis,nee --out report >converge.out 2>&1 ||
  { cat converge.out; fail "converge exits $?"; }
[ "$(wc -l <report/converge.csv)" -eq 7 ] || fail "converge.csv: $(cat report/converge.csv)"
# Its seconds are the renders' --stats-json `seconds`: positive, and no JSON file left behind.
awk -F, 'NR > 1 && !($3 > 0) {exit 1}' report/converge.csv || fail "seconds: $(cat report/converge.csv)"
! ls report/*.json >/dev/null 2>&1 || fail "converge left $(ls report/*.json)"
if command -v gnuplot >/dev/null; then
  [ "$(head -c 4 report/converge.png | tail -c 3)" = "PNG" ] || fail "no plot: $(cat converge.out)"
fi

# The same report from one --save-at render per method (--series), against the same reference:
# each series image is the render stopped there, so every error is the per-count run's exactly;
# its CPU seconds (the render's own, up to each save) are positive and grow with the count.
mkdir series && cp report/ref.pfm series/
"$source_dir/tools/converge" "$source_dir/scenes/sphere.scn" --raylane "$build/raylane" \
  --ref-spp 8 --max-spp 4 --methods mis,nee --out series --series >series.out 2>&1 ||
  { cat series.out; fail "converge --series exits $?"; }
errors() { awk -F, '{print $1, $2, $5, $6}' "$1"; }
[ "$(errors series/converge.csv)" = "$(errors report/converge.csv)" ] ||
  fail "--series errors differ: $(diff <(errors report/converge.csv) <(errors series/converge.csv))"
[ "$(wc -l <series/converge.csv)" -eq 7 ] || fail "series: $(cat series/converge.csv)"
awk -F, 'NR > 1 { if (!($3 > 0 && $4 > 0) || ($1 == m && $4 < cpu)) exit 1; m = $1; cpu = $4 }' \
  series/converge.csv || fail "series times: $(cat series/converge.csv)"
[ -z "$(ls series | grep -v -x -e ref.pfm -e converge.csv -e converge.dat -e converge.png)" ] ||
  fail "converge --series left $(ls series)"

# Variants on one plot: two --variant line sets of one scene at chosen --passes,
# each against its own reference; then two scenes. A bad --variant or --passes is refused.
"$source_dir/tools/converge" "$source_dir/scenes/sphere.scn" --raylane "$build/raylane" \
  --ref-spp 8 --passes 4,1 --methods mis --out variants --variant 'plain:' \
  --variant 'grey: ambient 0.5 0.5 0.5; screen 24 18' >variants.out 2>&1 ||
  { cat variants.out; fail "converge --variant exits $?"; }
[ "$(cut -d, -f1,2,7 variants/converge.csv | tr -d '\r' | tr '\n' ' ')" = \
  "method,spp,variant mis,1,plain mis,4,plain mis,1,grey mis,4,grey " ] ||
  fail "variants: $(cat variants/converge.csv)"
cmp -s variants/ref-plain.pfm variants/ref-grey.pfm && fail "the variants share a reference"
grep -q "^grey .*4 spp" variants.out || fail "variants' lines: $(cat variants.out)"
"$source_dir/tools/converge" "$source_dir/scenes/sphere.scn" "$source_dir/scenes/box.scn" \
  --raylane "$build/raylane" --ref-spp 4 --passes 1 --methods mis --out scenes >scenes.out 2>&1 ||
  { cat scenes.out; fail "converge with two scenes exits $?"; }
[ -f scenes/ref-sphere.pfm ] && [ -f scenes/ref-box.pfm ] || fail "two scenes: $(ls scenes)"
[ "$(cut -d, -f7 scenes/converge.csv | tr -d '\r' | tr '\n' ' ')" = "variant sphere box " ] ||
  fail "two scenes: $(cat scenes/converge.csv)"
! "$source_dir/tools/converge" "$source_dir/scenes/sphere.scn" --raylane "$build/raylane" \
  --variant 'no colon' >bad.out 2>&1 || fail "a --variant without a colon was taken"
grep -q "expected --variant 'NAME: LINE; LINE'" bad.out || fail "bad --variant: $(cat bad.out)"
! "$source_dir/tools/converge" "$source_dir/scenes/sphere.scn" --raylane "$build/raylane" \
  --passes 0,8 >bad.out 2>&1 || fail "--passes 0 was taken"
grep -q "expected sample counts >= 1" bad.out || fail "bad --passes: $(cat bad.out)"

# bench_trace: its help, the bunny of its own build tree, another with --bunny.
bench=$build/bench/bench_trace
"$bench" --help >bench.help || fail "bench_trace --help exits $?"
grep -q -- '--export=DIR' bench.help && grep -q -- '--bunny=FILE' bench.help ||
  fail "bench_trace --help: $(head -20 bench.help)"
filter='--benchmark_filter=build/bunny/raylane/threads:1/ --benchmark_min_time=0.01'
"$bench" $filter >default.out 2>&1 || true
if [ ! -f "$build/bench-data/bunny.ply" ]; then
  grep -q "'$build/bench-data/bunny.ply'" default.out || fail "the bunny path: $(cat default.out)"
fi
"$bench" $filter --bunny="$source_dir/scenes/letterX.ply" >bunny.out 2>&1 ||
  fail "bench_trace --bunny: $(cat bunny.out)"
grep -q 'prims=4 ' bunny.out || fail "bench_trace --bunny did not read the file: $(cat bunny.out)"
# bench_table's "raylane best" counts the render's own tracer: a kept run (--from-json) where
# raylane-render is raylane's fastest shows it there, with its counters.
python3 - <<'PY'
import json
def run(tracer, rays_per_s, **counters):
    name = "trace/s/primary/%s/threads:1/real_time" % tracer
    return dict(name=name, run_name=name, run_type="iteration", **{"rays/s": rays_per_s}, **counters)
json.dump({"context": {}, "benchmarks": [
    run("raylane-render", 3e6, **{"nodes/ray": 5.0, "lanes_used": 0.5}),
    run("raylane-avx2", 2e6, **{"nodes/ray": 9.0, "lanes_used": 0.9}),
    run("embree-16", 4e6)]}, open("kept.json", "w"))
PY
"$source_dir/tools/bench_table" --from-json kept.json >kept.out 2>&1 || fail "bench_table: $(cat kept.out)"
grep -q '^| s | primary | 1 | 3.00 | 0.75 | 3.00 (render) | 5.0 | 50 % |' kept.out ||
  fail "raylane best leaves out the render's tracer: $(cat kept.out)"

# A user's own ray set (--rays, --mesh; docs/ray-sets.md's formats, written here byte by byte):
# 64 triangles in a row and 65 rays down onto them, traced by every tracer under one name
# after the reference check; one of the two options alone is refused.
python3 - <<'PY'
import struct
tris = b"TRISOUP1" + struct.pack("<II", 64, 0)
for i in range(64):
    tris += struct.pack("<9f", 3 * i - 1, -1, i, 3 * i + 1, -1, i, 3 * i, 1, i)
open("row.tris", "wb").write(tris)
rays = b"RAYSET1\0" + struct.pack("<IIII", 65, 0, 0, 0) + bytes(8)
for i in range(65):
    rays += struct.pack("<8f", 3 * i if i < 64 else -50, 0, 100, 0, 0, -1, 0, float("inf"))
open("down.rays", "wb").write(rays)
PY
"$bench" --rays=down.rays --mesh=row.tris --benchmark_filter='trace/row/down/.*/threads:1/' \
  --benchmark_min_time=0.001 >user.out 2>&1 || fail "bench_trace --rays: $(cat user.out)"
grep -E -q 'trace/row/down/raylane-render/threads:1/.* disagree=0 .*rays=65 ' user.out ||
  fail "bench_trace --rays: $(cat user.out)"
if grep -q 'trace/testscene/.*/embree-1/' <("$bench" --benchmark_list_tests); then
  grep -E -q 'trace/row/down/embree-16/threads:1/.* disagree=0 ' user.out ||
    fail "Embree did not trace the user's rays: $(cat user.out)"
fi
! "$bench" --rays=down.rays >alone.out 2>&1 || fail "--rays without --mesh was taken"
grep -q 'expected --rays=FILE and --mesh=FILE together' alone.out || fail "$(cat alone.out)"

echo "converge, bench_table and bench_trace: help, programs as options, plot, bunny, user rays"
