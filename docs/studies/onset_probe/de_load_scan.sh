#!/usr/bin/env bash
# Session 32 (docs/studies/onset_probe/README.md): run from the repository root; OUT=dir to choose the output.
set -euo pipefail
run() { tag=$1; S=$2; n=$3; shift 3; python docs/studies/ensemble.py $S $n "$@" --out ${OUT:-onset_probe_out} --tag $tag ; }
for spec in "9 0.0678 0.03442 271" "11 0.08286 0.04239 292" "13 0.09793 0.05054 314"; do
  set -- $spec; m=$1; ip=$2; it=$3; w=$4
  tw=$(python -c "print(round(2.790095721727786*$w/247.6,3))")
  D="rotor.disks.2.mass=$m rotor.disks.2.polar_inertia=$ip rotor.disks.2.transverse_inertia=$it"
  run td${m}_bw scenarios/paper/backward_whirl_landing.toml 16 $D bearings.DE.worn_drag_torque=$tw
  run td${m}_fw7000 scenarios/paper/forward_whirl_landing.toml 8 $D
done
# a stronger worn drag on the 11 and 13 kg disks (td11_T36, td11_T40, td13_T39)
D11="rotor.disks.2.mass=11 rotor.disks.2.polar_inertia=0.08286 rotor.disks.2.transverse_inertia=0.04239"
D13="rotor.disks.2.mass=13 rotor.disks.2.polar_inertia=0.09793 rotor.disks.2.transverse_inertia=0.05054"
run td11_T36_bw scenarios/paper/backward_whirl_landing.toml 16 $D11 bearings.DE.worn_drag_torque=3.6
run td11_T40_bw scenarios/paper/backward_whirl_landing.toml 16 $D11 bearings.DE.worn_drag_torque=4.0
run td13_T39_bw scenarios/paper/backward_whirl_landing.toml 16 $D13 bearings.DE.worn_drag_torque=3.9
run td13_T39_bw015 scenarios/paper/backward_whirl_landing.toml 16 $D13 bearings.DE.worn_drag_torque=3.9 contact.mu_rad=0.15
# the heaviest variant (deheavy*, fw*_deheavy): thrust disk 14.3 kg (session 28's) and coupling hub 8.0 kg (its
# bound's top), T_w 4.1 N m:
H="rotor.disks.2.mass=14.3 rotor.disks.2.polar_inertia=0.1154 rotor.disks.2.transverse_inertia=0.0595 rotor.disks.3.mass=8.0 rotor.disks.3.polar_inertia=0.01665 rotor.disks.3.transverse_inertia=0.0110"
run deheavy scenarios/paper/backward_whirl_landing.toml 16 $H
run deheavy_nodrag scenarios/paper/backward_whirl_landing.toml 16 $H effects.worn_bearing_drag=false
run deheavy_T41 scenarios/paper/backward_whirl_landing.toml 16 $H bearings.DE.worn_drag_torque=4.1
run deheavy_T41_015 scenarios/paper/backward_whirl_landing.toml 16 $H bearings.DE.worn_drag_torque=4.1 contact.mu_rad=0.15
run fw7000_deheavy scenarios/paper/forward_whirl_landing.toml 8 $H
run fw10000_deheavy scenarios/paper/forward_whirl_10000rpm.toml 8 $H
run fw3000_deheavy scenarios/paper/forward_whirl_3000rpm.toml 8 $H
# A static DE load without mass (sl*): needs static_de_load_probe.patch in a scratch checkout (as the velocity-
# weakening probe, see the head of run.sh), then e.g.
#   PYTHONPATH=/tmp/sl SL_DE_N=115 python /tmp/sl/docs/studies/ensemble.py scenarios/paper/backward_whirl_landing.toml 16 \
#       bearings.DE.worn_drag_torque=4.08 --out $OUT --tag sl115_bw
# (sl65: 65 N, T_w 3.52; sl115: 115 N, T_w 4.08; _fw7000: the forward 7000 rpm landing, 8 drops; _bw015: mu_rad 0.15)
# Session 33: the DE ribbon's damping alone raised, on the rig and on the 13 kg thrust disk (s33_*)
for c in 1e4 2e4 4e4; do
  run s33_rig_c$c scenarios/paper/forward_whirl_landing.toml 8 bearings.DE.c_rib=$c
  run s33_td13_c$c scenarios/paper/forward_whirl_landing.toml 8 $D13 bearings.DE.c_rib=$c
done
run s33_td13_c8e4 scenarios/paper/forward_whirl_landing.toml 8 $D13 bearings.DE.c_rib=8e4
run s33_td13_c4e4_fw10000 scenarios/paper/forward_whirl_10000rpm.toml 8 $D13 bearings.DE.c_rib=4e4
run s33_td13_c4e4_fw3000 scenarios/paper/forward_whirl_3000rpm.toml 8 $D13 bearings.DE.c_rib=4e4
run s33_td13_T39_c2e4_bw scenarios/paper/backward_whirl_landing.toml 16 $D13 bearings.DE.worn_drag_torque=3.9 bearings.DE.c_rib=2e4
run s33_td13_T39_c4e4_bw scenarios/paper/backward_whirl_landing.toml 16 $D13 bearings.DE.worn_drag_torque=3.9 bearings.DE.c_rib=4e4
run s33_td13_T60_c4e4_bw scenarios/paper/backward_whirl_landing.toml 16 $D13 bearings.DE.worn_drag_torque=6.0 bearings.DE.c_rib=4e4
