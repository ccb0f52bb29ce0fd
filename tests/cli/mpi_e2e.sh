#!/usr/bin/env bash
# `mpirun -np R raylane render` end to end (docs/cluster.md): the same file, byte for byte, as a
# plain run for R = 1..4 and 1 or 2 threads; --time and a stop request end every process after
# the same pass; tiles dealt again by cost keep the image; --save-at writes the plain images; a
# checkpoint written at R = 3 resumes at R = 2 to the uninterrupted image; a --region is shared
# and resumed likewise;
# a scene error is printed once and the job exits 2; a killed process ends the job without a
# hang; Ctrl-C writes the image once. Usage: mpi_e2e.sh RAYLANE SCENE WORKDIR MPIEXEC [PREFLAGS...]
set -uo pipefail
raylane=$(realpath "$1") scene=$(realpath "$2") work=$3 mpiexec=$4
shift 4
preflags=("$@")
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
# Root may run mpirun only when told so; the variables do what --allow-run-as-root does.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# 72x52: a partial tile column and row, and a height that is no multiple of the tile (the
# render numbers tiles from the bottom row up, the film stores rows from the top).
small=(--set "screen 72 52")
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
mpi() { local np=$1; shift; timeout 120 "$mpiexec" "${preflags[@]}" -np "$np" "$@"; }
# The passes taken, from the summary line ("rendered WxH (path/..., N spp, ...").
spp_of() {
  tr '\r' '\n' < "$1" | grep '^rendered' | grep -o '[0-9]* spp' | head -1 | cut -d' ' -f1
}

"$raylane" render "$scene" "${small[@]}" --spp 6 -q -o plain.pfm > /dev/null || fail "plain run"
for np in 1 2 3 4; do
  for threads in 1 2; do
    mpi "$np" "$raylane" render "$scene" "${small[@]}" --spp 6 --threads "$threads" -q \
      -o "np$np-t$threads.pfm" > /dev/null 2>&1 || fail "np $np threads $threads: exit $?"
    cmp -s plain.pfm "np$np-t$threads.pfm" || fail "np $np threads $threads: another image"
  done
done

# Tiles dealt again by measured cost after passes 2 and 4 (--balance always): sums move
# between processes with their tiles, and the image stays the same.
for np in 2 3; do
  mpi "$np" "$raylane" render "$scene" "${small[@]}" --spp 6 --threads 1 --balance always \
    --stats -o "balanced$np.pfm" > /dev/null 2> "balanced$np.err" || fail "balanced np $np: exit $?"
  cmp -s plain.pfm "balanced$np.pfm" || fail "balanced np $np: another image"
  grep -q "dealt again by measured cost: 2 times" "balanced$np.err" ||
    fail "balanced np $np: $(grep 'dealt again' "balanced$np.err")"
done

# --region, one tile column wide (5 tiles a row: dealing every tile round-robin would give the
# column's tiles to one process): the processes share the region's tiles and write the
# one-process region render (which the unit tests hold to the whole render's pixels); a region
# checkpoint written by 3 processes resumes at 2 to it.
region=(--region 16,0,32,52)
"$raylane" render "$scene" "${small[@]}" "${region[@]}" --spp 6 -q -o region.pfm > /dev/null ||
  fail "region: plain run"
for np in 2 3; do
  mpi "$np" "$raylane" render "$scene" "${small[@]}" "${region[@]}" --spp 6 --threads 1 \
    --balance always -q -o "region$np.pfm" > /dev/null 2>&1 || fail "region np $np: exit $?"
  cmp -s region.pfm "region$np.pfm" || fail "region np $np: another image"
done
mpi 3 "$raylane" render "$scene" "${small[@]}" "${region[@]}" --spp 3 --threads 1 -q \
  --checkpoint region.film -o region-3spp.pfm > /dev/null 2>&1 || fail "region checkpoint: exit $?"
mpi 2 "$raylane" render "$scene" "${small[@]}" "${region[@]}" --spp 6 --threads 1 -q \
  --resume region.film -o region-resumed.pfm > /dev/null 2>&1 || fail "region resume: exit $?"
cmp -s region.pfm region-resumed.pfm || fail "region resumed at R = 2: not the uninterrupted image"

# --save-at: each pass of the series is assembled from every process (tiles dealt again after
# passes 2 and 4) and written once, by rank 0, as the plain run stopped at that pass writes it.
mpi 3 "$raylane" render "$scene" "${small[@]}" --spp 6 --threads 1 --balance always -q \
  --save-at 1,3,6 -o series.pfm > series.out 2>&1 || fail "--save-at: exit $?"
for n in 1 3; do
  "$raylane" render "$scene" "${small[@]}" --spp "$n" -q -o "plain$n.pfm" > /dev/null
  cmp -s "plain$n.pfm" "series.$n.pfm" || fail "--save-at: series.$n.pfm is not the plain image"
done
cmp -s plain.pfm series.6.pfm || fail "--save-at: series.6.pfm is not the plain image"
[ "$(grep -c 'series.3.pfm' series.out)" = 1 ] || fail "--save-at: series.3.pfm not named once"

# --time: rank 0's clock decides for everyone, so the image is a plain run's at that spp.
mpi 3 "$raylane" render "$scene" "${small[@]}" --time 1 --threads 1 -o timed.pfm \
  > timed.out 2> timed.err || fail "--time: exit $?"
spp=$(spp_of timed.err)
if [ -z "$spp" ]; then fail "--time: no summary"; else
  "$raylane" render "$scene" "${small[@]}" --spp "$spp" -q -o "plain$spp.pfm" > /dev/null
  cmp -s "plain$spp.pfm" timed.pfm || fail "--time: not the plain image at $spp spp"
fi

# A stop request (SIGUSR1, which mpirun forwards) at R = 3 with a checkpoint, resumed at R = 2.
# (mpirun itself in the background, so that $! is its process and the signal reaches it.)
"$mpiexec" "${preflags[@]}" -np 3 "$raylane" render "$scene" "${small[@]}" --spp 100000 \
  --threads 1 --balance always --checkpoint run.film -o stopped.pfm > stopped.out 2> stopped.err &
job=$!
(sleep 100 && kill -KILL "$job" 2> /dev/null) &
watchdog=$!
for _ in $(seq 100); do grep -q 'spp' stopped.err 2> /dev/null && break; sleep 0.1; done
sleep 1
kill -USR1 "$job"
wait "$job"
status=$?
kill "$watchdog" 2> /dev/null
[ "$status" = 130 ] || fail "stop request: exit $status, expected 130"
spp=$(spp_of stopped.err)
if [ -z "$spp" ] || [ ! -f run.film ]; then fail "stop request: no summary or no film"; else
  "$raylane" render "$scene" "${small[@]}" --spp "$spp" -q -o "plain$spp.pfm" > /dev/null
  cmp -s "plain$spp.pfm" stopped.pfm || fail "stop request: not the plain image at $spp spp"
  more=$((spp + 5))
  mpi 2 "$raylane" render "$scene" "${small[@]}" --spp "$more" --resume run.film -q \
    --balance always -o resumed.pfm > /dev/null 2>&1 || fail "resume at R = 2: exit $?"
  "$raylane" render "$scene" "${small[@]}" --spp "$more" -q -o "plain$more.pfm" > /dev/null
  cmp -s "plain$more.pfm" resumed.pfm || fail "resume at R = 2: not the uninterrupted image"
fi

# Ctrl-C in a terminal: SIGINT to the whole process group (mpirun and its processes). Every
# process stops after its pass and rank 0 writes the image; mpirun's own status is 1 (it
# aborts the job on SIGINT), so only the image is checked.
setsid "$mpiexec" "${preflags[@]}" -np 2 "$raylane" render "$scene" "${small[@]}" --spp 100000 \
  --threads 1 -o ctrlc.pfm > ctrlc.out 2> ctrlc.err &
job=$!
sleep 2
kill -INT -- "-$job"
wait "$job"
spp=$(spp_of ctrlc.err)
if [ -z "$spp" ] || [ ! -f ctrlc.pfm ]; then fail "Ctrl-C: no summary or no image"; else
  "$raylane" render "$scene" "${small[@]}" --spp "$spp" -q -o "plain$spp.pfm" > /dev/null
  cmp -s "plain$spp.pfm" ctrlc.pfm || fail "Ctrl-C: not the plain image at $spp spp"
fi

# A scene error: printed once, every process exits 2.
printf 'screen 8 8\ncamera 0 0 5 0.5\nbogus 1\n' > bad.scn
mpi 3 "$raylane" render bad.scn -o bad.pfm > bad.out 2> bad.err
status=$?
[ "$status" = 2 ] || fail "scene error: exit $status, expected 2"
n=$(grep -c "unknown command 'bogus'" bad.err)
[ "$n" = 1 ] || fail "scene error printed $n times"
[ ! -e bad.pfm ] || fail "scene error: an image was written"

# A killed process ends the job, non-zero, without a hang (mpi's timeout would say 124).
mpi 3 "$raylane" render "$scene" "${small[@]}" --spp 100000 --threads 1 -o killed.pfm \
  > /dev/null 2>&1 &
job=$!
sleep 2
pkill -KILL -n -f "raylane render .*killed.pfm"
wait "$job"
status=$?
{ [ "$status" != 0 ] && [ "$status" != 124 ]; } || fail "killed process: exit $status"

if [ "$failures" = 0 ]; then echo "mpi_e2e: all checks passed"; fi
exit $((failures > 0))
