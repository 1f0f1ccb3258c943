#!/usr/bin/env bash
# Session 32 (docs/studies/onset_probe/README.md): run from the repository root; OUT=dir to choose the output.
set -euo pipefail
SETS=$(cat docs/studies/onset_probe/screen_2_796.sets)
run() { tag=$1; S=$2; n=$3; shift 3; python docs/studies/ensemble.py $S $n $SETS "$@" --out ${OUT:-onset_probe_out} --tag $tag ; }
run c7_bw scenarios/paper/backward_whirl_landing.toml 16 bearings.DE.worn_drag_torque=4.24
run c7_bw015 scenarios/paper/backward_whirl_landing.toml 16 bearings.DE.worn_drag_torque=4.24 contact.mu_rad=0.15
run c7_fw7000 scenarios/paper/forward_whirl_landing.toml 8
run c7_fw10000 scenarios/paper/forward_whirl_10000rpm.toml 8
run c7_fw3000 scenarios/paper/forward_whirl_3000rpm.toml 8
