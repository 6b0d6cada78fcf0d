// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_time_integration_time_integrator_h
#define grainmpm_time_integration_time_integrator_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/step_statistics.h>
#include <grainmpm/contact/grain_contact.h>
#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/particles/grain_generator.h>
#include <grainmpm/transfer/grain_field_layout.h>
#include <grainmpm/transfer/transfer.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/particles/particle_handler.h>

#include <memory>
#include <vector>

namespace grainmpm
{
  template <int dim>
  class HeldContactStatus;
  template <int dim>
  class StepErrorEstimator;

  /**
   * The largest dilatational wave speed of the materials of the deformable
   * grains (0 if there are none).
   */
  template <int dim>
  double
  largest_wave_speed(
    const std::vector<GrainInfo<dim>>                          &grains,
    const std::vector<std::unique_ptr<ConstitutiveModel<dim>>> &materials);



  /**
   * The multi-valued grid field of one step, dim numbers per slot (one per
   * slot for the masses), in the layout of Transfer::get_layout().
   */
  template <int dim>
  struct GridState
  {
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    VectorType masses;
    /**
     * Volumes sum_p V_p S_ip and their first moments per slot (1 + dim
     * components, Transfer::particles_to_grid(); for the gap check of
     * contact).
     */
    VectorType volumes;
    /**
     * With the volumes: per field that keeps its shape, the sums over its
     * points on this process that give its strain and rigid motion
     * (Transfer::particles_to_grid()).
     */
    std::vector<double> shape_sums;
    VectorType          momenta;
    VectorType          mass_gradients;
    VectorType          normals;
    /** v^n from particle to grid (uncorrected): the FLIP reference. */
    VectorType velocities_p2g;
    /** The grid velocity at the end of the step. */
    VectorType velocities_new;
    /** 1 for nodes where contact corrected a field in the step. */
    std::vector<unsigned char> node_in_contact;
    /**
     * The impulses the contact, wall and rigid-grain constraints of the
     * step gave the deformable grains, at the nodes this rank owns: their
     * sum over the step is the change of the grains' momentum that the
     * forces and gravity do not make.
     */
    ConstraintImpulses<dim> impulses;
  };



  /**
   * The start of a step of length @p dt shared by both schemes, at the
   * positions at @p time: shape functions and slots (@p transfer),
   * particle to grid of mass, volume, momentum and mass gradient, v^n =
   * p / m with the rigid slots at their prescribed velocity, and the
   * contact normals and gaps (@p contact); no impulses recorded yet.
   */
  template <int dim>
  void
  begin_step(Transfer<dim>                   &transfer,
             GrainContact<dim>               &contact,
             Particles::ParticleHandler<dim> &particle_handler,
             const double                     time,
             const double                     dt,
             GridState<dim>                  &state);



  /**
   * The interface of a time integrator: advance() moves the particles by
   * one step; the grid of the last step is there for output.
   */
  template <int dim>
  class TimeIntegrator
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    virtual ~TimeIntegrator() = default;

    /**
     * Advance the particles of @p particle_handler from @p time by @p dt.
     * Throws InputError if a particle leaves the grid through a closed face.
     * An implicit step that fails returns `converged == false` and leaves
     * the particles untouched.
     */
    virtual StepStatistics
    advance(Particles::ParticleHandler<dim> &particle_handler,
            const double                     time,
            const double                     dt) = 0;

    /** The slot layout of the last step. */
    virtual const GrainFieldLayout<dim> &
    get_layout() const = 0;

    /** The grid field of the last step. */
    virtual const GridState<dim> &
    get_grid_state() const = 0;

    /** Slot masses of the last step. */
    const VectorType &
    get_masses() const
    {
      return get_grid_state().masses;
    }

    /** Slot velocities at the end of the last step. */
    const VectorType &
    get_velocities() const
    {
      return get_grid_state().velocities_new;
    }

    /** 1 for nodes where contact corrected a field in the last step. */
    const std::vector<unsigned char> &
    get_node_contact_flags() const
    {
      return get_grid_state().node_in_contact;
    }

    /**
     * The contact status a scheme keeps from one step to the next (the
     * implicit scheme's; HeldContactStatus), for checkpoints and to forget
     * it, or nullptr.
     */
    virtual HeldContactStatus<dim> *
    get_held_contact_status()
    {
      return nullptr;
    }

    /**
     * The error estimate of the steps that a scheme keeps from one step to
     * the next (the implicit scheme's; StepErrorEstimator), for
     * checkpoints and to forget it, or nullptr.
     */
    virtual StepErrorEstimator<dim> *
    get_step_error_estimator()
    {
      return nullptr;
    }

    /**
     * Whether a scheme's last step was quasi-static (the implicit scheme's,
     * whose next step then uses `Quasi-static theta`), for checkpoints and
     * to forget it, or nullptr.
     */
    virtual bool *
    get_quasi_static_flag()
    {
      return nullptr;
    }

    /**
     * Where the scheme's contact locates the rigid grains
     * (RigidGrainMotion::locate()), for checkpoints, or nullptr.
     */
    virtual RigidGrainMotion<dim> *
    get_rigid_grain_motion()
    {
      return nullptr;
    }

    /** The constraint impulses of the last step (this rank's nodes). */
    virtual const ConstraintImpulses<dim> &
    get_impulses() const
    {
      return get_grid_state().impulses;
    }
  };
} // namespace grainmpm

#endif
