// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/postprocess/contact_history.h>
#include <grainmpm/postprocess/history_file.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace grainmpm
{
  template <int dim>
  void
  PairImpulseSums<dim>::add(const typename ConstraintImpulses<dim>::Pair &pair,
                            const double                                  mu)
  {
    const double normal_part = pair.impulse * pair.normal;
    const double tangential_part =
      (pair.impulse - normal_part * pair.normal).norm();
    const double size = pair.impulse.norm();
    impulse += pair.impulse;
    normal += normal_part;
    tangential += tangential_part;
    if (mu > 0. && tangential_part >= (1. - 1e-6) * mu * normal_part)
      slipping_normal += normal_part;
    normal_direction += normal_part * pair.normal;
    moment += size * pair.position;
    weight += size;
  }



  template <int dim>
  void
  PairImpulseSums<dim>::add(const PairImpulseSums &other)
  {
    impulse += other.impulse;
    normal += other.normal;
    tangential += other.tangential;
    slipping_normal += other.slipping_normal;
    normal_direction += other.normal_direction;
    moment += other.moment;
    weight += other.weight;
  }



  template <int dim>
  ContactHistory<dim>::ContactHistory(const std::string   &filename,
                                      const double         friction_coefficient,
                                      const MPI_Comm       communicator,
                                      const std::uintmax_t resume_length)
    : friction_coefficient(friction_coefficient)
    , communicator(communicator)
    , file(filename, communicator)
  {
    const std::string force = (dim == 2 ? "M L/T^2 per L" : "M L/T^2");
    file.open(resume_length, [&](std::ofstream &out) {
      out << "time [T],grain_a [1],grain_b [1],normal_force [" << force
          << "],tangential_force [" << force << "]";
      for (unsigned int d = 0; d < dim; ++d)
        out << ",force_"
            << "xyz"[d] << " [" << force << "]";
      for (unsigned int d = 0; d < dim; ++d)
        out << ",contact_"
            << "xyz"[d] << " [L]";
      for (unsigned int d = 0; d < dim; ++d)
        out << ",normal_"
            << "xyz"[d] << " [1]";
      out << ",mobilised_friction [1],slip_share [1],sliding [1]\n"
          << std::flush;
    });
  }



  template <int dim>
  std::uintmax_t
  ContactHistory<dim>::length()
  {
    return file.length();
  }



  template <int dim>
  void
  ContactHistory<dim>::add_step(const ConstraintImpulses<dim> &impulses)
  {
    for (const auto &pair : impulses.pairs)
      local_sums[(std::uint64_t(pair.grain_a) << 32) | pair.grain_b].add(
        pair, friction_coefficient);
  }



  template <int dim>
  void
  ContactHistory<dim>::gather_sums()
  {
    std::vector<std::pair<std::uint64_t, PairImpulseSums<dim>>> mine(
      local_sums.begin(), local_sums.end());
    local_sums.clear();
    const auto merge = [this](const auto &rank_sums) {
      for (const auto &[key, pair_sums] : rank_sums)
        sums[{static_cast<unsigned int>(key >> 32),
              static_cast<unsigned int>(key & 0xffffffffU)}]
          .add(pair_sums);
    };
    if (Utilities::MPI::n_mpi_processes(communicator) == 1)
      merge(mine);
    else
      for (const auto &rank_sums :
           Utilities::MPI::gather(communicator, mine, 0))
        merge(rank_sums);
  }



  template <int dim>
  std::vector<GrainContactForce<dim>>
  ContactHistory<dim>::collect(const double time)
  {
    gather_sums();
    std::vector<GrainContactForce<dim>> forces;
    const double                        interval = time - interval_start;
    if (interval > 0.)
      for (const auto &[grains, sum] : sums)
        {
          GrainContactForce<dim> force;
          force.grain_a = grains.first;
          force.grain_b = grains.second;
          force.force   = sum.impulse / interval;
          if (sum.normal_direction.norm() > 0.)
            force.normal = sum.normal_direction / sum.normal_direction.norm();
          force.normal_force = force.force * force.normal;
          force.tangential_force =
            (force.force - force.normal_force * force.normal).norm();
          if (sum.weight > 0.)
            force.contact_point = Point<dim>(sum.moment / sum.weight);
          if (friction_coefficient > 0. && sum.normal > 0.)
            {
              force.mobilised_friction =
                sum.tangential / (friction_coefficient * sum.normal);
              force.slip_share = sum.slipping_normal / sum.normal;
            }
          forces.push_back(force);
        }
    sums.clear();
    interval_start = time;
    return forces;
  }



  template <int dim>
  void
  ContactHistory<dim>::write(const std::vector<GrainContactForce<dim>> &forces,
                             const double                               time)
  {
    if (file.is_open())
      {
        // The rows of this time in one write: a run killed meanwhile
        // leaves whole rows.
        std::ostringstream rows;
        rows << std::setprecision(9);
        for (const auto &force : forces)
          {
            rows << std::setprecision(12) << time << std::setprecision(9) << ','
                 << force.grain_a + 1 << ',' << force.grain_b + 1 << ','
                 << force.normal_force << ',' << force.tangential_force;
            for (unsigned int d = 0; d < dim; ++d)
              rows << ',' << force.force[d];
            for (unsigned int d = 0; d < dim; ++d)
              rows << ',' << force.contact_point[d];
            for (unsigned int d = 0; d < dim; ++d)
              rows << ',' << force.normal[d];
            rows << ',' << force.mobilised_friction << ',' << force.slip_share
                 << ',' << (force.slip_share > 0.5 ? 1 : 0) << '\n';
          }
        file.append(rows.str());
      }
    file.check_written();
  }



  template <int dim>
  std::vector<unsigned int>
  ContactHistory<dim>::coordination_numbers(
    const std::vector<GrainContactForce<dim>> &forces,
    const unsigned int                         n_grains)
  {
    // Fields of round-off mass (uGIMP weights of 1e-30) meet at some nodes
    // without the grains touching: their forces, many orders below the
    // others, do not count.
    double largest = 0.;
    for (const auto &force : forces)
      largest = std::max(largest, force.normal_force);
    std::vector<unsigned int> numbers(n_grains, 0);
    for (const auto &force : forces)
      if (force.normal_force > 1e-6 * largest)
        {
          ++numbers[force.grain_a];
          ++numbers[force.grain_b];
        }
    return numbers;
  }



  template struct PairImpulseSums<2>;
  template struct PairImpulseSums<3>;
  template class ContactHistory<2>;
  template class ContactHistory<3>;
} // namespace grainmpm
