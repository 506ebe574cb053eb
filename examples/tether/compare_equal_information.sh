#!/usr/bin/env bash
# The winch controllers at equal information (docs/results.md, Tether control): seeds
# 1-5 over the shipped trajectories, for an obedient and a less obedient miniUGV
# (examples/tether/less_obedient_ugv.yaml's lag and slip), each without a plan preview
# and with the preview for both controllers (the baseline latency-compensates with
# it). Prints one markdown row per trajectory and setting: the ratio of the five-seed
# means of the winch-reachable slack RMS (MPC / baseline), the worst per-seed ratio,
# both controllers' ranges in millimetres, over-tension events summed over the seeds
# (MPC / baseline) and the MPC's cycles with l_t > L; then whether the targets hold
# (ratio of means <= 0.8 obedient, <= 1.0 less obedient, 0 MPC events and cycles).
#   examples/tether/compare_equal_information.sh [FERRET_BINARY] [MPC_SECTION] [LESS_OBEDIENT_CONTROL] [LESS_OBEDIENT_SIM]
# MPC_SECTION is a YAML flow map added to every run's config as `mpc:`, e.g.
#   examples/tether/compare_equal_information.sh build/release/apps/ferret '{ugv_velocity_error_mps: 0}'
# LESS_OBEDIENT_CONTROL is one added as `control:` (both controllers) to the less obedient
# settings only, e.g. the robot's true lag as a model: '{}' '{ugv_velocity_lag_s: 0.15}'.
# LESS_OBEDIENT_SIM replaces the less obedient robot's `sim:` keys (the inside of the flow
# map), e.g. another robot: '{}' '{}' 'ugv_velocity_lag_s: 0.25, ugv_tracking_time_s: 0.7'.
set -euo pipefail
ferret=${1:-build/release/apps/ferret}
mpc=${2:-"{}"}
less_control=${3:-"{}"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
less_obedient=${4:-"ugv_velocity_lag_s: 0.15, ugv_slip_noise_mps: 0.02, ugv_slip_time_s: 0.5, ugv_tracking_time_s: 1.0"}
write_config() {  # name, sim keys, baseline keys, control section
  printf 'sim: {%s}\nbaseline: {%s}\nmpc: %s\ncontrol: %s\n' "$2" "$3" "$mpc" "$4" >"$out/$1.yaml"
}
write_config obedient "" "" "{}"
write_config obedient_preview "ugv_preview_s: 0.5" "use_preview: true" "{}"
write_config less_obedient "$less_obedient" "" "$less_control"
write_config less_obedient_preview "$less_obedient, ugv_preview_s: 0.5" "use_preview: true" "$less_control"

echo "| setting | trajectory | reachable slack RMS ratio of means (mpc / baseline) | worst seed ratio | mpc reachable RMS [mm] | baseline reachable RMS [mm] | over-tension events (mpc / baseline) | mpc cycles l_t > L |"
echo "|---|---|---|---|---|---|---|---|"
for setting in obedient obedient_preview less_obedient less_obedient_preview; do
  for t in default.yaml corner_snag.yaml fast_back_and_forth.csv reach_limit.csv; do
    for c in mpc baseline; do
      for seed in 1 2 3 4 5; do
        "$ferret" --log-level warn tether-sim --trajectory "examples/trajectories/$t" \
          --controller "$c" --seed "$seed" --sim-config "$out/$setting.yaml" --out "$out/run" |
          awk -v c="$c" -v s="$seed" '/^reachable_slack_rms_m:/{r=$2} /^over_tension_events:/{e=$2}
                                      /^cycles_above_L:/{l=$2} END{print c, s, r, e, l}'
      done
    done | awk -v t="$t" -v setting="$setting" -v missed="$out/missed" '
      { r[$1, $2] = $3; s[$1] += $3; if (!($1 in lo) || $3 < lo[$1]) lo[$1] = $3; if ($3 > hi[$1]) hi[$1] = $3;
        ev[$1] += $4; if ($1 == "mpc") over += $5 }
      END {
        worst = 0; for (k = 1; k <= 5; ++k) if (r["mpc", k] / r["baseline", k] > worst) worst = r["mpc", k] / r["baseline", k]
        ratio = s["mpc"] / s["baseline"]
        printf "| %s | %s | %.2f | %.2f | %.2f–%.2f | %.2f–%.2f | %d / %d | %d |\n", setting, t, ratio, worst,
               1e3 * lo["mpc"], 1e3 * hi["mpc"], 1e3 * lo["baseline"], 1e3 * hi["baseline"], ev["mpc"], ev["baseline"], over
        limit = setting ~ /^less_obedient/ ? 1.0 : 0.8
        if (ratio > limit + 1e-9 || ev["mpc"] > 0 || over > 0) print "- " setting " " t >> missed
      }'
  done
done
if [ -s "$out/missed" ]; then
  echo
  echo "targets missed:"
  cat "$out/missed"
else
  echo
  echo "targets met: ratio of means <= 0.8 (obedient), <= 1.0 (less obedient), 0 MPC over-tension events, 0 MPC cycles l_t > L"
fi
