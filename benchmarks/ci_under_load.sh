#!/usr/bin/env bash
# .ci/run on fresh clones of this checkout, N times in a row (default 5), beside one CPU-bound hog on the 2-core
# machine; stops at the first failure. Prints one line per run (exit code, seconds, commit, load average) and the
# test runners' closing lines. Note: each run does `pip install -e .` from its clone, so afterwards re-run
# `pip install -e .` here.
#   bash benchmarks/ci_under_load.sh [N] [WORKDIR]
set -u
runs=${1:-5}
work=${2:-$(mktemp -d)}
repo=$(cd "$(dirname "$0")/.." && pwd)
python -c 'while 1: pass' &
hog=$!
trap 'kill $hog 2>/dev/null' EXIT
for i in $(seq 1 "$runs"); do
  rm -rf "$work/run$i" && git clone -q "$repo" "$work/run$i"
  start=$(date +%s)
  (cd "$work/run$i" && env -u PYTHONPATH CI=true bash .ci/run > "$work/run$i.log" 2>&1 < /dev/null)
  rc=$?
  echo "run $i: exit $rc, $(( $(date +%s) - start )) s, commit $(git -C "$work/run$i" log --oneline -1 | cut -c1-7)," \
       "load $(cut -d' ' -f1-3 /proc/loadavg)"
  grep -E "^=+ .*(passed|failed).* in " "$work/run$i.log" | sed 's/^/    /'
  if [ "$rc" -ne 0 ]; then exit "$rc"; fi
done
