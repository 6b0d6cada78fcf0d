// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_particles_grain_generator_h
#define grainmpm_particles_grain_generator_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>

#include <deal.II/base/function_parser.h>

#include <deal.II/particles/particle_handler.h>

#include <memory>
#include <vector>

namespace grainmpm
{
  /**
   * What the time loop needs to know about a grain beyond its material
   * points.
   */
  template <int dim>
  struct GrainInfo
  {
    /** Index into the list of materials. */
    unsigned int material = 0;
    /** A rigid grain moves with a prescribed velocity. */
    bool rigid = false;
    /** The prescribed velocity of a rigid grain, a function of x and t. */
    std::shared_ptr<FunctionParser<dim>> prescribed_velocity;
    /** Total mass and number of material points at creation. */
    double                mass        = 0.;
    types::particle_index n_particles = 0;
  };

  /**
   * Fills grains with material points: for every cell a grain's bounding
   * box touches, `Particles per cell`^dim points at regular reference
   * positions ((i + 1/2)/n per direction), kept if they lie strictly inside
   * the grain's shape. Each point gets the mass density times its share of
   * the cell volume, the grain's initial velocity at its position, zero
   * stress and F = I. Points are inserted with their known cell, so that
   * no cell has to be searched for.
   */
  template <int dim>
  class GrainGenerator
  {
  public:
    explicit GrainGenerator(const Parameters<dim> &parameters);

    /**
     * Insert the material points of all grains into @p particle_handler and
     * return the per-grain information. Throws InputError if two grains
     * overlap, a grain receives no material point, or a velocity expression
     * does not parse.
     */
    std::vector<GrainInfo<dim>>
    generate(const BackgroundGrid<dim>       &grid,
             Particles::ParticleHandler<dim> &particle_handler) const;

  private:
    const Parameters<dim> &parameters;
  };

  /**
   * Parse @p expressions (@p n_components expressions separated by ';')
   * into a vector
   * function of x, y (, z) and, if @p time_dependent, t. Throws InputError
   * naming @p entry on a syntax error.
   */
  template <int dim>
  std::shared_ptr<FunctionParser<dim>>
  parse_vector_function(const std::string &expressions,
                        const bool         time_dependent,
                        const std::string &entry,
                        const unsigned int n_components = dim);
} // namespace grainmpm

#endif
