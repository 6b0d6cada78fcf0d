// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_inertial_number_h
#define grainmpm_postprocess_inertial_number_h

#include <grainmpm/base/config.h>
#include <grainmpm/particles/grain_generator.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <vector>

namespace grainmpm
{
  /**
   * The inertial number of the loading by moving rigid grains (platens),
   * I = (strain rate) d / sqrt(P / rho), the measure of granular flow
   * that tells quasi-static loading (I below about 1e-3) from inertial
   * flow (GDR MiDi 2004; da Cruz et al. 2005). For a rigid grain moving
   * with velocity V along the unit direction u:
   * - the strain rate is |V| / H, H the distance along u from the grain's
   *   leading face (its material point farthest along u) to the far end
   *   of the deformable material (the deformable point farthest along u);
   * - P = max(0, -F.u) / A, F the force the grains exert on the rigid
   *   grain and A the extent of the deformable material across u (a
   *   length in 2D, per unit thickness; an area in 3D), taken as the
   *   bounding box of the deformable points in the coordinates other
   *   than the one u points along most;
   * - d is the mean equivalent diameter of the deformable grains and rho
   *   their mean density sum m / sum V_0 (with Mass scaling, the scaled
   *   density: I is that of the simulated loading).
   * A rigid grain at rest has I = 0; one that pushes nothing (P = 0) has
   * I = infinity. The extents (H and A) change slowly: they are measured
   * in a pass over the points every refresh_interval steps and kept in
   * between (and in checkpoints).
   */
  template <int dim>
  class InertialNumber
  {
  public:
    /**
     * For @p rigid_grains among @p grains: d and rho from the deformable
     * points of @p particle_handler. Collective.
     */
    InertialNumber(const std::vector<GrainInfo<dim>>     &grains,
                   const std::vector<unsigned int>       &rigid_grains,
                   const Particles::ParticleHandler<dim> &particle_handler,
                   const MPI_Comm                         communicator);

    /**
     * I of each rigid grain after step @p step at @p time: @p forces the
     * forces the grains exert on them, @p centres their centres (where
     * their velocity is taken). Collective.
     */
    std::vector<double>
    compute(const unsigned int                     step,
            const Particles::ParticleHandler<dim> &particle_handler,
            const std::vector<Tensor<1, dim>>     &forces,
            const std::vector<Point<dim>>         &centres,
            const double                           time);

    /** Steps between two measurements of the extents. */
    static constexpr unsigned int refresh_interval = 16;

    /** Read or write the kept extents with @p archive. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &extents;
    }

  private:
    const std::vector<GrainInfo<dim>> &grains;
    const std::vector<unsigned int>    rigid_grains;
    const MPI_Comm                     communicator;
    double                             diameter = 0.;
    double                             density  = 0.;
    /**
     * The maxima of the last measurement: the bounding box of the
     * deformable points (x_d and -x_d, 2 dim numbers), then per rigid
     * grain the largest u.x of the deformable points and of its own.
     */
    std::vector<double> extents;

    /** Measure the extents for the motion directions @p directions. */
    void
    measure(const Particles::ParticleHandler<dim> &particle_handler,
            const std::vector<Tensor<1, dim>>     &directions);
  };
} // namespace grainmpm

#endif
