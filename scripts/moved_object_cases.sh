# The simulator's moved-object cases, shared by scripts/moved_object_pairs.sh and
# scripts/scene_change_odometry.sh (sourced, not run): ten cases, each moved at frame 7, 16, 25,
# 40 or 52 (docs/pipeline.md "Objects that moved", docs/odometry.md "Scenes that change").

# name scene move [move ...] (several moves of one case, at the same frame)
moved_cases=(
  "chair room chair:0,-0.6,0"
  "chair_turned room chair:0.3,0,0,90"
  "table room table:0,-0.5,0 book:0,-0.5,0 vase:0,-0.5,0 ball:0,-0.5,0"
  "cabinet room cabinet:-0.4,0.3,0,30"
  "big_ball room big_ball:0,-0.8,0"
  "bin room bin:-0.6,-0.3,0"
  "crate room crate:0.5,0.3,0"
  "person room occluder:0,0.8,0"
  "box repeated box0:0.3,0.4,0,20"
  "sparse_box sparse box:0.5,0.5,0,20"
)
moved_frames=(7 16 25 40 52)

# simulate_moved_cases BUILD_DIR OUT_DIR CALLBACK [GASP_SIMULATE_ARGS...]: renders every case
# moved at every frame into OUT_DIR/NAME_M (gasp-simulate's output in OUT_DIR/NAME_M.sim.txt) and
# calls CALLBACK OUT_DIR/NAME_M NAME M after each; exits with a message when gasp-simulate fails.
simulate_moved_cases() {
  local build=$1 out=$2 callback=$3
  shift 3
  local c m mv name scene dir words args
  for c in "${moved_cases[@]}"; do
    read -ra words <<< "$c"
    name=${words[0]} scene=${words[1]}
    for m in "${moved_frames[@]}"; do
      # The person appears at frame 38: only at 52 does every straddling pair (from frame 37 on at
      # skip 15, every 3rd frame: 39 on) see it before the move as well as after.
      if [ "$name" = person ] && [ "$m" -lt 52 ]; then continue; fi
      dir="$out/${name}_$m"
      args=()
      for mv in "${words[@]:2}"; do args+=(--move "$mv@$m"); done
      echo "$name moved at frame $m" >&2
      "$build/bin/gasp-simulate" --scene "$scene" "$@" "${args[@]}" --out "$dir" > "$dir.sim.txt" \
        || { echo "error: gasp-simulate failed for $name at $m (see $dir.sim.txt)" >&2; exit 1; }
      "$callback" "$dir" "$name" "$m"
    done
  done
}
