#!/usr/bin/env bash
# Several sessions in one map (docs/benchmarks.md "Sessions merged into one map"): gasp-slam over
# fr1_xyz whole and cut into sessions (given with --session, tracked each on its own, with no
# relation known between them), over two sequences that share no place (fr1_xyz and
# fr3_cabinet_kf), and over the simulated long loop two_rooms whole and as two sessions that enter
# the rooms by different doors (A -> north corridor -> B, then B -> south corridor -> A), once per
# loop search (radius: relocalisation by the other sessions' latest
# keyframes; retrieval: by the nearest place descriptors). One markdown row per run: the maps the
# sessions ended in, the constraints between sessions, each session's ATE in its map's frame (one
# alignment over the map), the map's ATE, and the wall time.
#
# Usage: scripts/sessions_bench.sh [DATA_DIR] [OUT_DIR] [BUILD_DIR]
#   defaults: ../shared/data/tum, a temporary directory, build/ci
set -euo pipefail
data=${1:-../shared/data/tum}
out=${2:-$(mktemp -d)}
build=${3:-build/ci}
slam="$build/bin/gasp-slam"
for p in gasp-slam gasp-simulate; do
  [ -x "$build/bin/$p" ] || { echo "error: $build/bin/$p not built" >&2; exit 1; }
done
for d in fr1_xyz fr3_cabinet_kf; do
  [ -d "$data/$d" ] || { echo "error: no data folder $data/$d" >&2; exit 1; }
done
mkdir -p "$out"
xyz="$data/fr1_xyz"
rooms="$out/two_rooms"
if [ ! -f "$rooms/groundtruth.txt" ]; then
  "$build/bin/gasp-simulate" --scene two_rooms --frames 400 --rate 5 --out "$rooms" > "$out/simulate.log" 2>&1 \
    || { echo "error: gasp-simulate failed (see $out/simulate.log)" >&2; exit 1; }
fi

echo "| Case | Loop search | Sessions | Maps | Constraints between sessions | Session ATE in the map's frame [cm] | Map ATE [cm] | Wall time |"
echo "|---|---|---|---|---|---|---|---|"
run() {  # tag, label, search, --session arguments...
  local tag=$1 label=$2 search=$3
  shift 3
  printf 'loop_closure:\n  loop_search: %s\n' "$search" > "$out/$search.yaml"
  local log="$out/$tag-$search.log"
  local rc=0
  "$slam" "$@" --params "$out/$search.yaml" --out "$out/$tag-$search.txt" \
    --sessions-report "$out/$tag-$search.yaml" > "$log" 2> "$log.err" || rc=$?
  # 0: one piece; 3: written, the graph in pieces (sessions apart). Anything else failed.
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 3 ]; then echo "error: gasp-slam failed ($rc), see $log.err" >&2; exit 1; fi
  local sessions maps links ates map_ate wall
  sessions=$(sed -n 's/^sessions: \([0-9]*\) in \([0-9]*\) map.*/\1/p' "$log")
  maps=$(sed -n 's/^sessions: \([0-9]*\) in \([0-9]*\) map.*/\2/p' "$log")
  if [ "$sessions" = 1 ]; then  # the single-session run: gasp-slam's own evaluation
    links="-"
    ates=$(sed -n 's/^ate_rmse_m: \([0-9.]*\).*/\1/p' "$log" | awk '{printf "%.2f", 100 * $1}')
    map_ate=$ates
  else
    links=$(grep -o 'joined to [^;]*' "$log" | sed 's/joined to //' | awk -v ORS='; ' '{print "s" NR ": " $0}' | sed 's/; $//')
    # In the map's frame when the session was joined, else aligned alone (marked "alone").
    ates=$(sed -n 's/^session \([0-9]*\): ate_rmse_m: \([0-9.]*\) (aligned alone)\(, \([0-9.]*\) in its map.*\)\{0,1\}$/\1 \2 \4/p' "$log" \
      | awk -v ORS=', ' '{if (NF == 3) printf "s%s %.2f, ", $1, 100 * $3; else printf "s%s %.2f alone, ", $1, 100 * $2}' \
      | sed 's/, $//')
    map_ate=$(sed -n 's/^map \([0-9]*\): ate_rmse_m: \([0-9.]*\).*/\1 \2/p' "$log" \
      | awk -v ORS=', ' '{printf "map %s: %.2f, ", $1, 100 * $2}' | sed 's/, $//')
  fi
  printf '| %s | %s | %s | %s | %s | %s | %s | %s s |\n' "$label" "$search" "$sessions" "$maps" "${links:--}" \
    "${ates:--}" "${map_ate:--}" "$(sed -n 's/^wall_time_s: \([^ ]*\).*/\1/p' "$log")"
}
for search in radius retrieval; do
  run one "fr1_xyz, one session" "$search" --session "$xyz"
  run two "fr1_xyz in two (0-399, 400-797)" "$search" --session "$xyz@0-399" --session "$xyz@400-"
  run three "fr1_xyz in three (0-265, 266-531, 532-797)" "$search" --session "$xyz@0-265" --session "$xyz@266-531" \
    --session "$xyz@532-"
  run reversed "fr1_xyz in two, the later first" "$search" --session "$xyz@400-" --session "$xyz@0-399"
  run apart "fr1_xyz and fr3_cabinet_kf (no shared place)" "$search" --session "$xyz" --session "$data/fr3_cabinet_kf"
  run rooms "two_rooms, one session" "$search" --session "$rooms"
  # Frames 0-164: room A, the north corridor, into room B; 202-399: from room B's south door
  # through the south corridor back into room A (docs/simulator.md, the walk's segments).
  run rooms_doors "two_rooms in two by different doors (0-164, 202-399)" "$search" --session "$rooms@0-164" \
    --session "$rooms@202-399"
done
echo "logs and sessions reports: $out"
