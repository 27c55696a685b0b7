#!/usr/bin/env bash
# The farm's fixed costs on the localhost test cluster (README, "Try it in a minute"): submits
# a 1-frame, 1-tile scene ${1:-5} times, one after another, and from the task logs prints per run
#   submit->start   `farm submit` invoked -> the tile task's script starts on the node
#   submit->tile    `farm submit` invoked -> the tile written (an upper bound on "first pixel")
#   render          seconds `render` itself ran in the task
#   merge           `farm merge`'s own time for the frame (read, paste, write the TIFF)
#   tile->merged    tile task done -> merge task done (dependency release, launch, merge)
# then the median of each. Needs root, slurm-wlm and munge, and
# `cargo build --release -p render -p farm` (ILLUME_BIN_DIR overrides target/release).
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
bin=${ILLUME_BIN_DIR:-${CARGO_TARGET_DIR:-$repo/target}/release}
runs=${1:-5}
for exe in render farm; do
  [ -x "$bin/$exe" ] || { echo "overhead: $bin/$exe missing: cargo build --release -p render -p farm" >&2; exit 2; }
done
work=$(mktemp -d /tmp/illume-farm-overhead.XXXXXX)
trap '"$repo/tests/farm/slurm_down.sh" "$work/slurm"; rm -rf "$work"' EXIT
eval "$("$repo/tests/farm/slurm_up.sh" "$work/slurm")"
cat >"$work/one.rib" <<'RIB'
FrameBegin 1
Format 64 48 1
Display "one.tif" "tiff" "rgb"
Projection "perspective" "fov" [40]
WorldBegin
Translate 0 0 4
LightSource "distantlight" 1
Surface "plastic"
Sphere 1 -1 1 360
WorldEnd
FrameEnd
RIB
cd "$work"
# The value after `key` on the line of $1 matching $2.
field() { awk -v pat="$2" -v key="$3" '$0 ~ pat { for (i = 1; i < NF; i++) if ($i == key) v = $(i + 1) } END { print v }' "$1"; }
printf '%-4s %14s %13s %8s %8s %13s\n' run submit-\>start submit-\>tile render merge tile-\>merged
: >rows
for r in $(seq "$runs"); do
  job="$work/job$r"
  rm -f one.tif
  t0=$(date +%s.%N)
  "$bin/farm" submit one.rib --tiles 1x1 --jobdir "$job" >/dev/null
  ids=$(awk '{print $2}' "$job/jobs" | paste -sd, -)
  for _ in $(seq 600); do [ -z "$(squeue -h -j "$ids")" ] && break; sleep 0.05; done
  [ -f one.tif ] || { echo "overhead: run $r wrote no one.tif; logs:" >&2; cat "$job"/logs/* >&2; exit 1; }
  tlog=$(ls "$job"/logs/tiles_*); mlog=$(ls "$job"/logs/merge_*)
  start=$(field "$tlog" "tiles task 0 attempt" start)
  done_=$(field "$tlog" "tiles task 0 done" done)
  render=$(field "$tlog" "tiles task 0 done" render_seconds)
  merge=$(field "$mlog" "merged f0001 in" in)
  merged=$(field "$mlog" "merge task 0 done" done)
  awk -v r="$r" -v t0="$t0" -v s="$start" -v d="$done_" -v rs="$render" -v m="$merge" -v md="$merged" \
    'BEGIN { printf "%-4s %14.3f %13.3f %8.3f %8.3f %13.3f\n", r, s - t0, d - t0, rs, m, md - d }' | tee -a rows
done
sort_col() { awk -v c="$1" '{print $c}' rows | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
printf '%-4s %14s %13s %8s %8s %13s\n' median "$(sort_col 2)" "$(sort_col 3)" "$(sort_col 4)" "$(sort_col 5)" "$(sort_col 6)"
