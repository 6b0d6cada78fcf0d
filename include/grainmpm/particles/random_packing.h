// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_particles_random_packing_h
#define grainmpm_particles_random_packing_h

#include <grainmpm/base/parameters.h>

#include <vector>

namespace grainmpm
{
  /**
   * A random dense packing of polydisperse disks (2D) or spheres (3D) in a
   * box, by ballistic deposition: the grains, with radii drawn uniformly
   * from [Minimum radius, Maximum radius], are dropped one after the other
   * at uniformly random lateral positions and stop where they first touch
   * the floor of the box or a grain below (the vertical is the y
   * direction; gravity, if any, should point to -y). Each grain is dropped
   * at Drop attempts positions and kept at the lowest resting place, which
   * fills holes. Neighbours are found through columns of width
   * 2 Maximum radius, so the cost is linear in the number of grains. The
   * run itself then settles the grains.
   *
   * With Deposition = rolling (2D) a disk that lands on a grain then rolls
   * down over it until it rests on the floor, against a side of the box,
   * or on two grains on either side of its centre (rolling on over the
   * grain it meets while both lie on one side, falling when it rolls past
   * the level of its support's centre), as in the deposition model of
   * Visscher & Bolsterli (Nature 239, 504, 1972): every disk is held from
   * both sides, and the packing is denser. Its search over the grains met
   * on the way is linear in their number, so the packing costs
   * O(n^2) operations.
   *
   * The random numbers come from std::mt19937 with the given seed,
   * converted to doubles by hand, so a seed gives the same packing on every
   * platform.
   *
   * Throws InputError naming 'Random packing/Upper corner' when a grain
   * does not fit below the top of the box.
   */
  template <int dim>
  std::vector<GrainParameters<dim>>
  random_packing(const RandomPackingParameters<dim> &parameters);

  /**
   * Put the grains of subsection Random packing (random_packing()) at the
   * end of @p parameters.grains, in place of those of an earlier call,
   * checked like the described grains (Parameters::check_grain()), and set
   * @p parameters.n_packed_grains. Call after Parameters::parse() (or
   * check()), before the grains are used; calling it again gives the same
   * grains. Does nothing if Number of grains is 0.
   */
  template <int dim>
  void
  add_random_packing(Parameters<dim> &parameters);
} // namespace grainmpm

#endif
