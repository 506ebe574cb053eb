#!/usr/bin/env bash
# Grid search of the winch controllers' settings over the shipped trajectories, as
# used to choose the defaults (docs/tether.md, "The baseline"). Every setting runs
# `ferret tether-sim --sim-config` on all four shipped trajectories at seed 1. The score
# is the sum of the slack RMS of default, fast_back_and_forth and reach_limit
# (corner_snag's slack behind the snag is beyond any controller, so it only counts
# for over-tension); only settings with no over-tension event on any of the four
# qualify. Prints the five best of each controller; writes all rows to OUT/grid.csv.
#   examples/tether/tune_controllers.sh [FERRET_BINARY] [OUT_DIR]
# Takes about a quarter of an hour (441 settings x 4 runs of a fraction of a second).
set -euo pipefail
ferret=${1:-build/release/apps/ferret}
out=${2:-out/tether_tuning}
mkdir -p "$out"
trajectories=(default.yaml fast_back_and_forth.csv reach_limit.csv corner_snag.yaml)
csv="$out/grid.csv"
echo "controller,setting,score,over_tension_events,$(IFS=,; echo "${trajectories[*]}")" >"$csv"

run_setting() {  # controller label yaml
  local controller=$1 label=$2 yaml=$3 score=0 events=0 per=()
  printf '%s\n' "$yaml" >"$out/config.yaml"
  for t in "${trajectories[@]}"; do
    local res
    res=$("$ferret" --log-level warn tether-sim --trajectory "examples/trajectories/$t" --controller "$controller" \
      --sim-config "$out/config.yaml" --seed 1 --out "$out/run")
    local rms ev
    rms=$(awk '/^slack_rms_m:/{print $2}' <<<"$res")
    ev=$(awk '/^over_tension_events:/{print $2}' <<<"$res")
    per+=("$rms")
    [[ $t == corner_snag.yaml ]] || score=$(awk -v a="$score" -v b="$rms" 'BEGIN{printf "%.4f", a + b}')
    events=$((events + ev))
  done
  echo "$controller,\"$label\",$score,$events,$(IFS=,; echo "${per[*]}")" >>"$csv"
}

for g in 1.0 0.2 0.05; do
  for sref in 0.0 0.005 0.01; do
    for kp in 6 10 16 24; do
      for ki in 0 16 64 128 256; do
        for kd in 0 0.05; do
          run_setting baseline "g=$g sref=$sref kp=$kp ki=$ki kd=$kd" \
            "control: {pose_filter_gain: $g, slack_reference_m: $sref}
baseline: {kp_per_s: $kp, ki_per_s2: $ki, kd: $kd}"
        done
      done
    done
    for wr in 0.1 0.5 2; do
      for ta in 0 0.1 0.3; do
        run_setting mpc "g=$g sref=$sref weight_command_rate=$wr acceleration_time_s=$ta" \
          "control: {pose_filter_gain: $g, slack_reference_m: $sref}
mpc: {weight_command_rate: $wr, acceleration_time_s: $ta}"
      done
    done
  done
done

for controller in baseline mpc; do
  echo "best $controller settings (score = sum of slack RMS [m], no over-tension event):"
  awk -F, -v c="$controller" 'NR > 1 && $1 == c && $4 == 0' "$csv" | sort -t, -k3,3g | sed -n 1,5p
done
