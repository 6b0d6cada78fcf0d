// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_particles_grain_generator_h
#define grainmpm_particles_grain_generator_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/grid/background_grid.h>

#include <deal.II/base/function_parser.h>

#include <deal.II/lac/vector.h>

#include <deal.II/particles/particle_handler.h>

#include <memory>
#include <string>
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
    /**
     * Mean position of the material points at creation (a rigid grain that
     * has only been translated is where the points' mean has moved to from
     * here: RigidGrainMotion::locate()).
     */
    Point<dim> centroid;
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
    /** A regular position in a cell of the box claimed by a grain. */
    struct Candidate
    {
      /** Index (i,j,k) of the cell in the box, and of the position in it. */
      unsigned int cell;
      unsigned int sub_point;
      unsigned int grain;
    };

    /** The expressions that set a grain's points at creation. */
    struct GrainFunctions
    {
      std::shared_ptr<FunctionParser<dim>> initial_velocity;
      /** The grain's initial stress, else its material's, else none. */
      std::shared_ptr<FunctionParser<dim>> initial_stress;
      /** The entry that gave the initial stress, for the messages. */
      std::string stress_entry;
    };

    /**
     * The initial stress of grain @p g (its own, else its material's, else
     * none) and in @p entry the entry that gave it. Throws InputError for
     * a stress on a rigid grain or a wrong number of expressions.
     */
    std::shared_ptr<FunctionParser<dim>>
    parse_initial_stress(const unsigned int g, std::string &entry) const;

    /**
     * The regular positions of the locally owned @p cells (by box index)
     * that lie inside a grain, grain by grain; in @p overlap the message
     * for the first position claimed by two grains.
     */
    std::vector<Candidate>
    find_candidates(
      const BackgroundGrid<dim> &grid,
      const std::vector<typename Triangulation<dim>::active_cell_iterator>
                  &cells,
      std::string &overlap) const;

    /**
     * The properties of a new point of grain @p g at @p point with
     * @p volume: mass, volume, grain, initial velocity and stress, F = I.
     * @p velocity is scratch space of size dim. Returns what is wrong with
     * the initial values there, or nothing.
     */
    std::string
    point_properties(const unsigned int    g,
                     const GrainFunctions &functions,
                     const Point<dim>     &point,
                     const double          volume,
                     Vector<double>       &velocity,
                     std::vector<double>  &properties) const;

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
