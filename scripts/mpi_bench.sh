#!/usr/bin/env bash
# gasp-slam --mpi over ranks (docs/benchmarks.md "A map-building job over MPI ranks"): fr1_xyz as
# two sessions sharing frames 350-449, the loop searches in place, run by one process and under
# mpirun with 2, 3 and 4 ranks (--bind-to none, --oversubscribe; the sessions tracked on ranks 1
# and up). One markdown row per run: wall time, loop registrations, those made on other ranks and
# on rank 0 while none was free, views sent, how long rank 0 waited for tracked frames,
# registrations per second of wall time, the mean registration time, and whether the trajectories
# and graph are the single process's byte for byte.
#
# Usage: scripts/mpi_bench.sh [DATA_DIR] [OUT_DIR] [BUILD_DIR]
#   defaults: ../shared/data/tum, a temporary directory, build/ci (built with GASP_WITH_MPI)
set -euo pipefail
data=${1:-../shared/data/tum}
out=${2:-$(mktemp -d)}
build=${3:-build/ci}
slam="$build/bin/gasp-slam"
[ -x "$slam" ] || { echo "error: $slam not built" >&2; exit 1; }
[ -d "$data/fr1_xyz" ] || { echo "error: no data folder $data/fr1_xyz" >&2; exit 1; }
command -v mpirun > /dev/null || { echo "error: no mpirun (Debian: openmpi-bin)" >&2; exit 1; }
mkdir -p "$out"
xyz="$data/fr1_xyz"
printf 'loop_closure:\n  background: false\n' > "$out/inplace.yaml"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
job() {  # name
  echo "--session $xyz@0-449 --session $xyz@350-797 --params $out/inplace.yaml --out $out/$1.txt --graph $out/$1.graph --loops-csv $out/$1.csv"
}
echo "| Ranks | Wall time | Loop registrations | On other ranks | On rank 0 | Views sent | Rank 0 waited for frames | Registrations per second | Mean registration | Outputs as one process's |"
echo "|---|---|---|---|---|---|---|---|---|---|"
row() {  # ranks, name, log
  local wall regs other here views waited mean same
  wall=$(grep -m1 '^wall_time_s:' "$3" | awk '{print $2}')
  regs=$(($(wc -l < "$out/$2.csv") - 1))
  other=$(grep -m1 'pairs registered on the other ranks' "$3" | sed 's/^mpi: \([0-9]*\) pairs.*/\1/' || true)
  here=$(grep -m1 'pairs registered on the other ranks' "$3" | sed 's/.* and \([0-9]*\) on rank 0.*/\1/' || true)
  views=$(grep -m1 'pairs registered on the other ranks' "$3" | sed 's/.*, \([0-9]*\) views sent (\([0-9.]*\) MB).*/\1 (\2 MB)/' || true)
  waited=$(grep -m1 'waited .* s for tracked frames' "$3" | sed 's/.*waited \([0-9.]*\) s for.*/\1 s/' || true)
  mean=$(awk -F, 'NR > 1 { s += $7; n++ } END { printf "%.0f ms", s / n }' "$out/$2.csv")
  same=yes
  for f in .session1.txt .session2.txt .graph; do cmp -s "$out/one$f" "$out/$2$f" || same=no; done
  echo "| $1 | ${wall} s | $regs | ${other:--} | ${here:--} | ${views:--} | ${waited:--} | $(awk -v r="$regs" -v w="$wall" 'BEGIN { printf "%.1f", r / w }') | $mean | $same |"
}
"$slam" $(job one) > "$out/one.log" 2>&1 || [ $? -eq 3 ] || { echo "error: gasp-slam failed (see $out/one.log)" >&2; exit 1; }
row 1 one "$out/one.log"
for n in 2 3 4; do
  mpirun --bind-to none --oversubscribe -np "$n" "$slam" $(job "ranks$n") --mpi > "$out/ranks$n.log" 2>&1 || true
  grep -q '^wall_time_s:' "$out/ranks$n.log" || { echo "error: the $n-rank run failed (see $out/ranks$n.log)" >&2; exit 1; }
  row "$n" "ranks$n" "$out/ranks$n.log"
done
