#!/usr/bin/env bash
# Session 34 (docs/studies/onset_probe/README.md, "Session 34"): five more rotors of the rise screen with a heavy DE
# end, landed with their drawn shaft and disk (no landing fit), as screen_2_796.sh landed one in session 32.
# Run from the repository root; SCREEN=the screen's JSON (python docs/studies/rotor_rise_screen.py --same-amb
# --margin 0.05 --top 40 --out DIR; DIR/rotor_rise_screen.json, about 6 min), OUT=dir for the ensembles.
# The worn torque keeps the rig's T_w / (r_i W_DE) = 0.38: T_w = 2.79 N m x W_DE / 248 N.
set -euo pipefail
P=docs/studies/onset_probe
for c in "1 1489 343" "1 408 330" "1 93 325" "2 496 320" "2 172 351"; do
  set -- $c
  if [ -n "${SCREEN:-}" ]; then python $P/screen_candidate_sets.py "$SCREEN" $1 $2 > $P/screen_$1_$2.sets; fi
  SETS=$(cat $P/screen_$1_$2.sets); tw=$(python -c "print(round(2.79 * $3 / 248, 3))")
  python docs/studies/ensemble.py scenarios/paper/forward_whirl_landing.toml 8 $SETS --out ${OUT:-onset_probe_out} --tag s34_s$1_$2_fw7000
  python docs/studies/ensemble.py scenarios/paper/backward_whirl_landing.toml 16 $SETS bearings.DE.worn_drag_torque=$tw \
    --out ${OUT:-onset_probe_out} --tag s34_s$1_$2_bw
done
