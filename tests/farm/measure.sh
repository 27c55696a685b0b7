#!/usr/bin/env bash
# Measures the farm's per-task overhead and merge time on this machine (README, "Rendering on
# a Slurm cluster"): starts the localhost test cluster, submits rib/pipelines/farm/turntable.rib
# (3 frames, depth pass + MakeShadow each) as ${1:-4x4} tiles per frame, waits, prints
# `farm status` (its timing lines) and the plain render time of the same RIB, stops the cluster.
# Needs root, slurm-wlm and munge, and `cargo build --release -p render -p farm`.
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
bin=${ILLUME_BIN_DIR:-${CARGO_TARGET_DIR:-$repo/target}/release}
scene=$repo/rib/pipelines/farm/turntable.rib
work=$(mktemp -d /tmp/illume-farm-measure.XXXXXX)
trap '"$repo/tests/farm/slurm_down.sh" "$work/slurm"; rm -rf "$work"' EXIT
eval "$("$repo/tests/farm/slurm_up.sh" "$work/slurm")"
mkdir -p "$work/plain" "$work/farm"
t0=$(date +%s.%N)
(cd "$work/plain" && "$bin/render" -q --threads 1 "$scene")
t1=$(date +%s.%N)
echo "plain render, 1 thread: $(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.3f", b-a}') s"
cd "$work/farm"
t0=$(date +%s.%N)
"$bin/farm" submit "$scene" --tiles "${1:-4x4}" --jobdir "$work/farm/job"
ids=$(awk '{print $2}' job/jobs | paste -sd, -)
while [ -n "$(squeue -h -j "$ids")" ]; do sleep 0.2; done
t1=$(date +%s.%N)
echo "farm: sbatch to last job done: $(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.2f", b-a}') s"
"$bin/farm" status job
for n in 1 2 3; do cmp turntable_$n.tif "$work/plain/turntable_$n.tif"; done && echo "merged images identical to plain render"
