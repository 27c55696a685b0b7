#!/usr/bin/env bash
# Stops the cluster tests/farm/slurm_up.sh DIR started: slurmd, slurmctld, munged, by the pid
# files under DIR only (never by process name, so other Slurm installations are left alone).
set -uo pipefail
dir=${1:?usage: slurm_down.sh STATE_DIR}
for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
  [ -f "$pidfile" ] || continue
  pid=$(cat "$pidfile")
  [ -n "$pid" ] || continue
  kill "$pid" 2>/dev/null || continue
  for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -9 "$pid" 2>/dev/null || true
done
exit 0
