#!/usr/bin/env bash
# Session 32: what could delay Table 1's backward-whirl onset on the adopted rig (docs/calibration.md,
# "Session 32"). 16 drops per variant from the 5 um circle, the backward scenario with one override set each;
# about 1-2 min per variant on 2 cores. Writes OUT/<tag>.json (members and ensemble statistics).
# The velocity-weakening variants (vw*) need velocity_weakening_probe.patch applied to a scratch checkout, not
# to this one:  git worktree add /tmp/vw HEAD && (cd /tmp/vw && git apply <this dir>/velocity_weakening_probe.patch)
# then  PYTHONPATH=/tmp/vw VW_R=0.5 VW_VC=10 NUMBA_CACHE_DIR=/tmp/vwcache_<tag> python /tmp/vw/docs/studies/ensemble.py ...
# (a separate numba cache per (VW_R, VW_VC): the kernels are cached and read the two as compile-time constants).
set -euo pipefail
OUT=${1:-${OUT:-onset_probe_out}}
S=scenarios/paper/backward_whirl_landing.toml
run() { tag=$1; shift; python docs/studies/ensemble.py "$S" 16 "$@" --out "$OUT" --tag "$tag"; }
RI="bearings.DE.inner_race_inertia=2.1e-4 bearings.NDE.inner_race_inertia=2.1e-4"
run base
run nodrag effects.worn_bearing_drag=false
run e09 contact.k_visc=4.7e11
run e05 contact.k_visc=2.3e12
run vreg1e2 contact.v_reg=1e-2
run race_light bearings.DE.inner_race_inertia=1.6e-4 bearings.NDE.inner_race_inertia=1.6e-4
run ri21 $RI
run ri21_T35 $RI bearings.DE.worn_drag_torque=3.5
run ri21_e09 $RI contact.k_visc=4.7e11
run ri21_T35_e09 $RI bearings.DE.worn_drag_torque=3.5 contact.k_visc=4.7e11
