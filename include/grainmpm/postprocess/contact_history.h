// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_postprocess_contact_history_h
#define grainmpm_postprocess_contact_history_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/grain_contact.h>
#include <grainmpm/postprocess/history_file.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <boost/serialization/map.hpp>
#include <boost/serialization/utility.hpp>

#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace grainmpm
{
  /**
   * The contact between two grains over an output interval: the sums of
   * the nodal contact impulses of every step (ConstraintImpulses::Pair).
   */
  template <int dim>
  struct PairImpulseSums
  {
    /** Sum of the impulses on grain_b from grain_a. */
    Tensor<1, dim> impulse;
    /** Sum of the normal parts J . n (> 0: the grains press). */
    double normal = 0.;
    /** Sum of the magnitudes of the tangential parts |J - (J . n) n|. */
    double tangential = 0.;
    /**
     * Sum of the normal parts at the nodes that slip, where the tangential
     * part reaches mu times the normal part (Coulomb's bound).
     */
    double slipping_normal = 0.;
    /** Sum of (J . n) n: the direction of the contact normal. */
    Tensor<1, dim> normal_direction;
    /** Sums of |J| x and |J|: the contact point. */
    Tensor<1, dim> moment;
    double         weight = 0.;

    /** Add the impulse of one node, with friction coefficient @p mu. */
    void
    add(const typename ConstraintImpulses<dim>::Pair &pair, const double mu);

    /** Add the sums of @p other. */
    void
    add(const PairImpulseSums &other);

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &impulse &normal &tangential &slipping_normal &normal_direction
        &moment &weight;
    }
  };



  /**
   * The mean contact force between two grains over an output interval,
   * what `contacts.csv` and the force-chain output show.
   */
  template <int dim>
  struct GrainContactForce
  {
    unsigned int grain_a = 0;
    unsigned int grain_b = 0;
    /** Mean force on grain_b from grain_a. */
    Tensor<1, dim> force;
    /** Unit contact normal, out of grain_a. */
    Tensor<1, dim> normal;
    /** Normal part of the force (> 0: compression) and tangential size. */
    double normal_force     = 0.;
    double tangential_force = 0.;
    /** Impulse-weighted node position. */
    Point<dim> contact_point;
    /**
     * sum |J_t| / (mu sum J . n) over the nodes and steps: 1 where every
     * node slips (Coulomb's bound is reached), below 1 where nodes stick;
     * 0 without friction.
     */
    double mobilised_friction = 0.;
    /**
     * The share of the normal impulse carried by slipping nodes: the
     * contact slips if it is above 1/2 (0 without friction).
     */
    double slip_share = 0.;
  };



  /**
   * Sums the contact impulses between grains over each output interval and
   * writes `contacts.csv`: per output time and pair of grains that touched
   * in the interval, the mean contact force (impulse over the interval),
   * its normal and tangential parts, the contact point, the contact normal,
   * the mobilised friction, the share of the normal impulse at slipping
   * nodes and whether the contact slips. The time
   * integral of the force is exact: the sum over the intervals of force
   * times interval is the impulse the pair exchanged.
   */
  template <int dim>
  class ContactHistory
  {
  public:
    /**
     * @p friction_coefficient is Coulomb's mu of the contact law (0
     * without friction). Collective.
     */
    ContactHistory(const std::string   &filename,
                   const double         friction_coefficient,
                   const MPI_Comm       communicator,
                   const std::uintmax_t resume_length = 0);

    /** The length of the file so far (for a checkpoint). */
    std::uintmax_t
    length();

    /** Add the contact impulses of one step of this rank. */
    void
    add_step(const ConstraintImpulses<dim> &impulses);

    /**
     * The mean contact forces since the last call (or since the start of
     * the run), on rank 0 (empty elsewhere); starts the next interval at
     * @p time. Collective.
     */
    std::vector<GrainContactForce<dim>>
    collect(const double time);

    /**
     * Append the rows of @p forces at @p time (rank 0). Stops every rank
     * with a message naming the file if a write has failed. Collective.
     */
    void
    write(const std::vector<GrainContactForce<dim>> &forces, const double time);

    /**
     * Number of partners each of @p n_grains grains pressed against in
     * @p forces (normal force above 1e-6 of the largest): the coordination
     * number.
     */
    static std::vector<unsigned int>
    coordination_numbers(const std::vector<GrainContactForce<dim>> &forces,
                         const unsigned int                         n_grains);

    /**
     * Checkpoint the sums of the interval so far: they are gathered on
     * rank 0 first (gather_sums()), which writes them (#local_sums is then
     * empty).
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &sums &interval_start;
      // Every rank reads the state: the sums stay on rank 0 only.
      if (Archive::is_loading::value &&
          Utilities::MPI::this_mpi_process(communicator) != 0)
        sums.clear();
    }

    /** Move the sums of every rank to rank 0. Collective. */
    void
    gather_sums();

  private:
    const double   friction_coefficient;
    const MPI_Comm communicator;
    HistoryFile    file;
    /** Sums per pair (grain_a, grain_b) of this rank since the interval start.
     */
    /**
     * Sums per pair (grain_a, grain_b) since the interval start: of every
     * rank, gathered on rank 0 (gather_sums()), and what this rank added
     * since, keyed by grain_a * 2^32 + grain_b.
     */
    std::map<std::pair<unsigned int, unsigned int>, PairImpulseSums<dim>> sums;
    std::unordered_map<std::uint64_t, PairImpulseSums<dim>> local_sums;
    double                                                  interval_start = 0.;
  };
} // namespace grainmpm

#endif
