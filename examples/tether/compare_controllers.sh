#!/usr/bin/env bash
# Both winch controllers on every shipped trajectory over seeds 1-5, as in
# docs/results.md (Tether control). Prints one markdown row per trajectory: the
# range of slack RMS over the seeds for the MPC and the baseline, the ratio of the
# five-seed means (MPC / baseline), over-tension events summed over the seeds
# (MPC / baseline), the largest tension and the cycles with l_t > L.
#   examples/tether/compare_controllers.sh [FERRET_BINARY] [tether-sim options...]
# e.g. examples/tether/compare_controllers.sh build/release/apps/ferret --latency 0.15
#      examples/tether/compare_controllers.sh build/release/apps/ferret --sim-config examples/tether/plan_preview.yaml
set -euo pipefail
ferret=${1:-build/release/apps/ferret}
shift || true
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| trajectory | mpc slack RMS [m] | baseline slack RMS [m] | ratio of means | over-tension events (mpc / baseline) | max tension [N] (mpc / baseline) | cycles l_t > L |"
echo "|---|---|---|---|---|---|---|"
for t in default.yaml corner_snag.yaml fast_back_and_forth.csv reach_limit.csv; do
  for c in mpc baseline; do
    for seed in 1 2 3 4 5; do
      "$ferret" --log-level warn tether-sim --trajectory "examples/trajectories/$t" --controller "$c" \
        --seed "$seed" --out "$out/run" "$@" |
        awk -v c="$c" '/^slack_rms_m:/{r=$2} /^over_tension_events:/{e=$2} /^max_tension_n:/{m=$2}
                       /^cycles_above_L:/{l=$2} END{print c, r, e, m, l}'
    done
  done | awk -v t="$t" '
    { n[$1]++; s[$1] += $2; if (!($1 in lo) || $2 < lo[$1]) lo[$1] = $2; if ($2 > hi[$1]) hi[$1] = $2;
      ev[$1] += $3; if ($4 > mt[$1]) mt[$1] = $4; over += $5 }
    END { printf "| %s | %s–%s | %s–%s | %.2f | %d / %d | %.1f / %.1f | %d |\n", t, lo["mpc"], hi["mpc"],
          lo["baseline"], hi["baseline"], s["mpc"] / s["baseline"], ev["mpc"], ev["baseline"], mt["mpc"], mt["baseline"], over }'
done
