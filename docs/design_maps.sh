#!/bin/sh
# The figures of the README section "Designing against stiction" (design maps): a sigma sweep
# through the paper's four Table-1 surfaces, and a sigma x w map with the adhesion-map regimes.
# Run from the repository root: sh docs/design_maps.sh (a few minutes on 2 cores).
# Any failed point (recorded in the file's `error` variable, exit status 1) stops the script.
set -e
sweep() { mcsim sweep "$@" --overwrite --quiet; }
mkdir -p runs
sweep --surface smooth --law auto --vary sigma=0.3nm:20nm:40:log --vary tau=100MPa \
    --mc --area 100um^2 --realizations 10 --seed 1 --out runs/design_sigma.h5
mcsim plot runs/design_sigma.h5 --out docs/design_sigma.png --overwrite
sweep --surface smooth --law auto --vary sigma=0.3nm:100nm:25:log --vary gamma=0.002:5:13:log \
    --out runs/design_map.h5
mcsim plot runs/design_map.h5 --out docs/design_map.png --overwrite
