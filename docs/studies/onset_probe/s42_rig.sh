#!/usr/bin/env bash
# Session 42: session 32's nearest onset variant re-run on the session-41 rig (the 1e5 N/m motor coupling, the
# worn fit of session 41: T_w 2.93 N m, growth 200 rad, C_rib 2363 N s/m), docs/calibration.md "Session 42".
# The 13 kg thrust disk (session 32's 240.3 mm annulus, thicker; inside its bound) puts 64.5 N more on the DE sleeve
# (238.3 -> 302.8 N, modefit.static_support_loads), and the worn torque is scaled with it (T_w / W kept: 3.73 N m).
# 16 drops per backward variant, 8 per forward one, from the 5 um circle; about 30 s each on 2 cores.
set -euo pipefail
OUT=${1:-${OUT:-onset_probe_out}}
run() { tag=$1; S=$2; n=$3; shift 3; python docs/studies/ensemble.py "$S" "$n" "$@" --out "$OUT" --tag "$tag"; }
B=scenarios/paper/backward_whirl_landing.toml
D13="rotor.disks.2.mass=13 rotor.disks.2.polar_inertia=0.09793 rotor.disks.2.transverse_inertia=0.05054"
run s42_base $B 16
run s42_nodrag $B 16 effects.worn_bearing_drag=false
run s42_td13_bw $B 16 $D13 bearings.DE.worn_drag_torque=3.73
run s42_td13_bw015 $B 16 $D13 bearings.DE.worn_drag_torque=3.73 contact.mu_rad=0.15
run s42_td13_fw7000 scenarios/paper/forward_whirl_landing.toml 8 $D13
