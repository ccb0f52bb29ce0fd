#!/usr/bin/env bash
# The README's commands run as written: every command line of the README's ```sh
# blocks runs, in order, in a folder laid out like a fresh clone after the quick start (the
# build tree as build/, the repository's scenes/ and tools/), so a later line reads what an
# earlier one wrote (room.hdr, room.film). Each must exit 0 (`raylane diff`: 0 or 1, its
# verdict) and print no usage message, and every image a render names on stdout must exist.
#
# What a test cannot run as written runs smaller, and the log says how: renders at 48×36 (a
# --region line at the scene's size, which its rectangle needs) and 2 spp (3 when resuming)
# with --time 1 and --save-at 1,2; the benchmarks and the convergence report (minutes
# each) show their --help or list their benchmarks. Lines that need a display or mpirun are
# left to View.EndToEndUnderXvfb and Mpi.EndToEnd, and `bash tools/dev` is the quick start this
# test runs after. HOME is a folder of the test's, so the install block installs there.
#
#   readme_commands.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source_dir=$(realpath "$1") build_dir=$(realpath "$2") work=$3
rm -rf "$work" && mkdir -p "$work"
work=$(realpath "$work")
cp -r "$source_dir/scenes" "$work/scenes"
ln -s "$source_dir/tools" "$work/tools"
ln -s "$source_dir/docs" "$work/docs"
ln -s "$build_dir" "$work/build"
cd "$work"
# The install block installs under ~/.local and puts its bin on PATH: here, the test's own.
export HOME=$work/home
mkdir -p "$HOME"
export PATH=$HOME/.local/bin:$PATH

# The command lines of the README's sh blocks, comments stripped.
mapfile -t lines < <(awk '/^```/ { block = ($0 == "```sh") ? !block : 0; next } block' \
  "$source_dir/README.md" | sed -E 's/[[:space:]]+#[[:space:]].*$//; s/[[:space:]]+$//' | grep -v '^$')

# The line as the test runs it (empty: left to another test), and why it differs.
smaller() {
  local line=$1
  case "$line" in
    "bash tools/dev "* | mpirun* | "build/raylane view"*) echo "" ;;
    "tools/bench_table"* | "tools/converge"*) echo "${line%% *} --help" ;;
    "build/bench/bench_render"*) echo "build/bench/bench_render --benchmark_list_tests" ;;
    "build/raylane render"* | "build/raylane scenes/"* | "raylane render"*)
      local spp=2 screen=" --set 'screen 48 36'"
      [[ $line == *--resume* ]] && spp=3
      [[ $line == *--region* ]] && screen=""  # its rectangle is in the scene's own screen
      echo "$line$screen" | sed -E "s/--spp [0-9]+/--spp $spp/; s/--time [0-9]+/--time 1/; s/--save-at [0-9,]+/--save-at 1,2/" ;;
    *) echo "$line" ;;
  esac
}

ran=0 failed=0
for line in "${lines[@]}"; do
  run=$(smaller "$line")
  if [ -z "$run" ]; then
    echo "LEFT TO ANOTHER TEST: $line"
    continue
  fi
  [ "$run" = "$line" ] || echo "SMALLER: $line  =>  $run"
  status=0
  bash -c "$run" >out.txt 2>err.txt </dev/null || status=$?
  ran=$((ran + 1))
  ok=1
  if [ "$status" -ne 0 ] && ! { [[ $line == "build/raylane diff"* ]] && [ "$status" -eq 1 ]; }; then
    ok=0
  fi
  grep -q -e 'see raylane' -e '^usage:' err.txt && ok=0
  if [[ $line == *"raylane render"* ]]; then
    while read -r written; do
      [ -f "$written" ] || { echo "  $written was printed but not written"; ok=0; }
    done <out.txt
  fi
  if [ "$ok" -eq 0 ]; then
    failed=$((failed + 1))
    echo "FAIL (exit $status): $run"
    sed 's/^/  stdout: /' out.txt | head -20
    sed 's/^/  stderr: /' err.txt | head -20
  else
    echo "ok: $run"
  fi
done
echo "$ran README lines run, $failed failed"
rm -rf "$work/sets"  # the exported benchmark scenes: 200 MB
# So that the check itself can fail: the README's usage block alone has more than 15 lines.
[ "$ran" -ge 15 ] || { echo "FAIL: only $ran lines found: is the extraction right?"; exit 1; }
[ "$failed" -eq 0 ]
