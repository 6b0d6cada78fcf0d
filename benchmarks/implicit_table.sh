#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The implicit-solver table of
# doc/notes/2026-11-26-implicit-solver-single-grain.md, from the shipped
# cases: for the single grain between walls
# (prm/single_grain_rebound_implicit.prm) at CFL 1, 2.5, 5 and 10, and the
# two-disk collision (prm/two_disks_implicit.prm) at CFL 2.5, with the
# probed Jacobi preconditioner and without: Newton iterations per step,
# Krylov (GMRES) iterations per Newton iteration, residual evaluations per
# step, energies at the end relative to the start and the two shares of
# the energy change (the theta step on the grid with the contact pass on
# v^n, and the grid-to-particle transfers), rebound speeds of the grain in
# its flights, and the explicit CFL 0.25 baseline for the spurious elastic
# energy, from each run's summary.csv and grains.csv. Not a test: it
# prints figures (about 2 minutes).
#
# Usage: benchmarks/implicit_table.sh [build directory=build]
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

# solver_columns NAME: the columns from Newton/step to the transfer share.
solver_columns() {
  local quantity columns=""
  for quantity in newton_iterations_per_step linear_iterations_per_newton_iteration \
    residual_evaluations_per_step rejected_steps total_energy_end elastic_energy_end \
    grid_energy_change transfer_work; do
    columns="$columns${columns:+ | }$(figure "$1" $quantity)"
  done
  echo "$columns"
}

echo "| case | CFL | preconditioner | steps | Newton/step | GMRES/Newton | residual evaluations/step | rejected | E_total(end)/E0 | E_el(end)/E0 | grid step share | transfer share | |v_x| in flights 1-5 |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for cfl in 1 2.5 5 10; do
  for preconditioner in "probed Jacobi" "none"; do
    name="grain_${cfl}_${preconditioner// /_}"
    run "$name" single_grain_rebound_implicit \
      "subsection Time stepping\n  set CFL number = $cfl\n  set Maximum CFL number = 0\nend\nsubsection Linear solver\n  set Preconditioner = $preconditioner\n  set Maximum linear iterations = 1000\nend"
    echo "| single grain | $cfl | $preconditioner | $(exact "$name" steps) | $(solver_columns "$name") | $(speeds "$name") |"
  done
done
for preconditioner in "probed Jacobi" "none"; do
  name="disks_${preconditioner// /_}"
  run "$name" two_disks_implicit \
    "subsection Linear solver\n  set Preconditioner = $preconditioner\n  set Maximum linear iterations = 1000\nend"
  echo "| two disks | 2.5 | $preconditioner | $(exact "$name" steps) | $(solver_columns "$name") | |"
done

run explicit single_grain_rebound_explicit ""
echo
echo "Explicit baseline (single grain, CFL 0.25, $(exact explicit steps) steps): E_total(end)/E0 = $(figure explicit total_energy_end), E_el(end)/E0 = $(figure explicit elastic_energy_end), |v_x| in flights 1-5: $(speeds explicit)"
