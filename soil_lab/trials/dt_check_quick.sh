#!/bin/bash
# soil_lab/trials/dt_check_quick.sh — the quick ci plates at the soil's step and at half of it
# (soil-lab --dt-check): cdt (ci.in) against epsdt (trials/ci_epsdt.in), three beds each (the
# default seed and two of plan.REPLICATE_SEEDS). ~1 min per lab on one rank. Results: README.md
# "The lab at half the time step".
cd "$(dirname "$0")/../.."   # the checkout
for soil in ci soil_lab/trials/ci_epsdt.in; do
  tag=$(basename $soil .in)
  for seed in default 67867967 86028121; do
    sv=(); [ "$seed" != default ] && sv=(--bed-var seed=$seed)
    nice -n 5 soil_lab/soil-lab run $soil --preset quick --tests plate --dt-check --np 1 --bed-hold 0.05 --build-dir build "${sv[@]}" --out runs/soil_lab/dtq/${tag}_${seed} > runs/soil_lab/dtq/${tag}_${seed}.log 2>&1
    grep "time step:" runs/soil_lab/dtq/${tag}_${seed}.log
  done
done
