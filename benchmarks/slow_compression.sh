#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The slow compression of 30 disks by a rigid platen (prm/slow_compression_
# implicit.prm and prm/slow_compression_explicit.prm) to t = 1, frictionless
# and with Coulomb friction 0.3: implicit theta = 1/2 at CFL 7.5 (the
# shipped case: 30 times the explicit step, AMG preconditioner), explicit
# at CFL 0.25 with Stress update = USL (the shipped explicit case) and with
# the default USF; without friction also explicit USL at CFL 0.125 and
# with 1 % PIC, and implicit with the lumped mass. Prints
# the platen work W, the end energy E and the ledger in units of W, the
# explicit platen work relative to the implicit one, the platen force
# curves F(t) = dW/dt / 0.037 averaged over windows of 0.1, the
# frictionless windows of the variants against explicit USL, and the
# explicit USL ledger over time. Not a test: it prints figures (about 8
# minutes).
#
# Usage: benchmarks/slow_compression.sh [build directory=build]
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

for friction in 0 0.3; do
  if [ "$friction" = 0 ]; then
    contact="subsection Contact\n  set Contact model = frictionless\nend"
  else
    contact="subsection Contact\n  set Contact model = Coulomb friction\n  set Friction coefficient = $friction\nend"
  fi
  run "implicit_$friction" slow_compression_implicit "$contact"
  run "usl_$friction" slow_compression_explicit "$contact"
  run "usf_$friction" slow_compression_explicit \
    "$contact\nsubsection Time stepping\n  set Stress update = USF\nend"
done
# The explicit ledger at half the step, frictionless.
run usl_0_half slow_compression_explicit \
  "subsection Contact\n  set Contact model = frictionless\nend\nsubsection Time stepping\n  set CFL number = 0.125\nend"
# How the frictionless force windows depend on the dissipation: explicit
# with 1 % PIC in the velocity update, implicit with the lumped mass.
run usl_0_pic slow_compression_explicit \
  "subsection Contact\n  set Contact model = frictionless\nend\nsubsection Time stepping\n  set Particle velocity update = blend\n  set FLIP fraction = 0.99\nend"
run implicit_0_lumped slow_compression_implicit \
  "subsection Contact\n  set Contact model = frictionless\nend\nsubsection Time stepping\n  set Mass matrix = lumped\nend"

python3 - "$work" <<'PYTHON'
import csv, sys
work = sys.argv[1]
speed = 0.037

def columns(name):
    rows = list(csv.reader(open(f"{work}/{name}/energy.csv")))
    header = [h.split(" [")[0] for h in rows[0]]
    return {h: [float(r[i]) for r in rows[1:]] for i, h in enumerate(header)}

def at(c, key, t):
    i = min(range(len(c["time"])), key=lambda i: abs(c["time"][i] - t))
    return c[key][i]

def window(c, t):
    """The platen work over (t - 0.1, t]."""
    return at(c, "boundary_work", t) - at(c, "boundary_work", t - 0.1)

times = [0.1 * k for k in range(1, 11)]
for friction in ["0", "0.3"]:
    runs = {s: columns(f"{s}_{friction}") for s in ["implicit", "usl", "usf"]}
    W_implicit = runs["implicit"]["boundary_work"][-1]
    print(f"\nfriction coefficient {friction}\n")
    print("| scheme | W(1) | W / W_implicit | E(1) / W | friction work / W | transfers / W | leapfrog / W | balance / W |")
    print("|---|---|---|---|---|---|---|---|")
    for s, label in [("implicit", "implicit, CFL 7.5"), ("usl", "explicit USL, CFL 0.25"),
                     ("usf", "explicit USF, CFL 0.25")]:
        c = runs[s]
        W = c["boundary_work"][-1]
        print(f"| {label} | {W:.4g} | {W / W_implicit:.3f} | {c['total_energy'][-1] / W:.3f} "
              f"| {c['friction_work'][-1] / W:.3f} | {c['transfer_work'][-1] / W:.3f} "
              f"| {c['leapfrog_work'][-1] / W:.3f} "
              f"| {c['balance_residual'][-1] / W:.3f} |")
    print("\nplaten force F = dW/dt / v over (t - 0.1, t]:\n")
    print("| t | " + " | ".join(f"{t:.1f}" for t in times) + " |")
    print("|---|" + "---|" * len(times))
    for s in ["implicit", "usl", "usf"]:
        c = runs[s]
        forces = [window(c, t) / (0.1 * speed) for t in times]
        print(f"| {s} | " + " | ".join(f"{f:.4f}" for f in forces) + " |")
print("\nfrictionless: E(1) / W and the platen force windows over those of explicit USL, CFL 0.25:\n")
print("| run | E(1) / W | W / W_USL | " + " | ".join(f"{t:.1f}" for t in times) + " |")
print("|---|---|---|" + "---|" * len(times))
usl = columns("usl_0")
for name, label in [("usl_0_half", "explicit USL, CFL 0.125"), ("usl_0_pic", "explicit USL, FLIP fraction 0.99"),
                    ("implicit_0", "implicit (blended mass)"), ("implicit_0_lumped", "implicit, lumped mass")]:
    c = columns(name)
    W = c["boundary_work"][-1]
    print(f"| {label} | {c['total_energy'][-1] / W:.3f} | {W / usl['boundary_work'][-1]:.3f} | "
          + " | ".join(f"{window(c, t) / window(usl, t):.3f}" if abs(window(usl, t)) > 1e-9 * W
                       else "-" for t in times) + " |")
print("\nexplicit USL ledger: transfers, leapfrog and balance in units of W(1), "
      "the balance at t = 0.1, ..., 1 in units of W(t):\n")
print("| friction | CFL | transfers / W | leapfrog / W | balance / W(t) at t = 0.1, 0.2, ..., 1 | largest \\|balance\\| / W(1) |")
print("|---|---|---|---|---|---|")
for name, friction, cfl in [("usl_0", "0", "0.25"), ("usl_0_half", "0", "0.125"),
                            ("usl_0.3", "0.3", "0.25")]:
    c = columns(name)
    W = c["boundary_work"][-1]
    balances = " ".join(f"{at(c, 'balance_residual', t) / at(c, 'boundary_work', t):+.4f}"
                        if at(c, 'boundary_work', t) > 0. else "-" for t in times)
    print(f"| {friction} | {cfl} | {c['transfer_work'][-1] / W:.3f} | {c['leapfrog_work'][-1] / W:.3f} "
          f"| {balances} | {max(abs(b) for b in c['balance_residual']) / W:.4f} |")
PYTHON
