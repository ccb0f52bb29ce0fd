# The helpers of the viewer's end-to-end tests under Xvfb (view_e2e.sh, view_large_e2e.sh),
# which run the viewer with its stdout in out.txt and its stderr in err.txt, its window $wid.
fail() {
  echo "FAIL: $*"
  echo "--- the viewer's stdout:"; cat out.txt || true
  echo "--- its stderr:"; cat err.txt || true
  exit 1
}
# wait_for SECONDS COMMAND...: until COMMAND succeeds; fails after SECONDS (a slow 2-core CI
# machine, maybe under the sanitizers, gets generous time; a fast one does not wait for it).
wait_for() {
  local end=$((SECONDS + $1))
  shift
  until "$@"; do
    ((SECONDS < end)) || return 1
    sleep 0.1
  done
}
# has WORD N: out.txt holds at least N lines that start with WORD (counted at every call).
has() { (($(grep -c "^$1 " out.txt || true) >= $2)); }
title_says() { xdotool getwindowname "$wid" 2>/dev/null | grep -q "$1"; }
# quit_viewer: Q, then the viewer ($pid) exits, with status 0; its EXIT trap is dropped.
quit_viewer() {
  xdotool key q
  wait_for 30 bash -c "! kill -0 $pid 2>/dev/null" || fail "Q did not quit"
  wait "$pid" || fail "the viewer exited with status $?"
  trap - EXIT
}
