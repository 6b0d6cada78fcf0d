// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/postprocess/history_file.h>
#include <grainmpm/postprocess/reaction_history.h>
#include <grainmpm/transfer/rigid_grain_motion.h>

#include <deal.II/base/mpi.h>

#include <deal.II/lac/vector.h>

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace grainmpm
{
  namespace
  {
    /** Number of torque components: 1 in 2D (z), 3 in 3D. */
    template <int dim>
    constexpr unsigned int n_torque = (dim == 2 ? 1 : 3);

    /** The indices of the rigid ones among @p grains. */
    template <int dim>
    std::vector<unsigned int>
    rigid_grain_indices(const std::vector<GrainInfo<dim>> &grains)
    {
      std::vector<unsigned int> rigid;
      for (unsigned int g = 0; g < grains.size(); ++g)
        if (grains[g].rigid)
          rigid.push_back(g);
      return rigid;
    }
  } // namespace



  template <int dim>
  ReactionHistory<dim>::ReactionHistory(
    const std::string                     &filename,
    const BackgroundGrid<dim>             &grid,
    const std::vector<GrainInfo<dim>>     &grains,
    const std::vector<Point<dim>>         &initial_centres,
    const Particles::ParticleHandler<dim> &particle_handler,
    const MPI_Comm                         communicator,
    const std::uintmax_t                   resume_length)
    : grid(grid)
    , grains(grains)
    , communicator(communicator)
    , file(filename, communicator)
    , rigid_grains(rigid_grain_indices(grains))
    , inertial_number(grains, rigid_grains, particle_handler, communicator)
  {
    for (unsigned int face = 0; face < 2 * dim; ++face)
      if (grid.boundary_condition(face).type != BoundaryType::open)
        faces.push_back(face);
    for (const unsigned int g : rigid_grains)
      centres.push_back(initial_centres[g]);

    const std::string force  = (dim == 2 ? "M L/T^2 per L" : "M L/T^2");
    const std::string torque = (dim == 2 ? "M L^2/T^2 per L" : "M L^2/T^2");
    file.open(resume_length, [&](std::ofstream &out) {
      out << "step,time [T],dt [T]";
      for (const unsigned int face : faces)
        for (unsigned int d = 0; d < dim; ++d)
          out << ",wall_" << face_name(face) << "_force_"
              << "xyz"[d] << " [" << force << "]";
      for (const unsigned int g : rigid_grains)
        {
          for (unsigned int d = 0; d < dim; ++d)
            out << ",grain_" << g + 1 << "_force_"
                << "xyz"[d] << " [" << force << "]";
          for (unsigned int d = 0; d < n_torque<dim>; ++d)
            out << ",grain_" << g + 1 << "_torque_"
                << (dim == 2 ? 'z' : "xyz"[d]) << " [" << torque << "]";
          out << ",grain_" << g + 1 << "_inertial_number [1]";
        }
      out << "\n" << std::flush;
    });
  }



  template <int dim>
  std::uintmax_t
  ReactionHistory<dim>::length()
  {
    return file.length();
  }



  template <int dim>
  void
  ReactionHistory<dim>::check_written() const
  {
    file.check_written();
  }



  template <int dim>
  void
  ReactionHistory<dim>::write_row(
    const unsigned int                     step,
    const double                           time,
    const double                           dt,
    const ConstraintImpulses<dim>         &impulses,
    const Particles::ParticleHandler<dim> &particle_handler)
  {
    // What the grains gave each wall and rigid grain: minus what they got.
    const unsigned int  per_rigid = dim + n_torque<dim>;
    std::vector<double> sums(faces.size() * dim +
                               rigid_grains.size() * per_rigid,
                             0.);
    for (unsigned int f = 0; f < faces.size(); ++f)
      for (unsigned int d = 0; d < dim; ++d)
        sums[f * dim + d] = -impulses.walls[faces[f]][d];
    if (!rigid_grains.empty())
      {
        std::vector<int> rigid_index(grains.size(), -1);
        for (unsigned int r = 0; r < rigid_grains.size(); ++r)
          rigid_index[rigid_grains[r]] = r;
        for (const auto &pair : impulses.pairs)
          {
            // Contact impulses only act on deformable slots: one of the two
            // grains at most is rigid.
            const int r =
              std::max(rigid_index[pair.grain_a], rigid_index[pair.grain_b]);
            if (r < 0)
              continue;
            const Tensor<1, dim> on_rigid =
              rigid_index[pair.grain_b] >= 0 ? pair.impulse : -pair.impulse;
            const Tensor<1, dim> arm = pair.position - centres[r];
            double *sum = &sums[faces.size() * dim + r * per_rigid];
            for (unsigned int d = 0; d < dim; ++d)
              sum[d] += on_rigid[d];
            if (dim == 2)
              sum[dim] += arm[0] * on_rigid[1] - arm[1] * on_rigid[0];
            else
              for (unsigned int d = 0; d < 3; ++d)
                {
                  const unsigned int e = (d + 1) % 3, f = (d + 2) % 3;
                  sum[dim + d] += arm[e] * on_rigid[f] - arm[f] * on_rigid[e];
                }
          }
      }
    if (!sums.empty())
      Utilities::MPI::sum(sums, communicator, sums);

    // The centres move as the rigid grains' points do (midpoint rule).
    for (unsigned int r = 0; r < rigid_grains.size(); ++r)
      centres[r] = RigidGrainMotion<dim>::move(grains[rigid_grains[r]],
                                               centres[r],
                                               time - 0.5 * dt,
                                               dt);

    std::vector<double> numbers;
    if (!rigid_grains.empty())
      {
        std::vector<Tensor<1, dim>> forces(rigid_grains.size());
        for (unsigned int r = 0; r < rigid_grains.size(); ++r)
          for (unsigned int d = 0; d < dim; ++d)
            forces[r][d] = sums[faces.size() * dim + r * per_rigid + d] / dt;
        numbers = inertial_number.compute(
          step, particle_handler, forces, centres, time);
      }

    if (file.is_open())
      {
        std::ostringstream row;
        row << step << ',' << std::setprecision(12) << time << ',' << dt
            << std::setprecision(9);
        // (+ 0. prints a zero without its sign.)
        for (unsigned int f = 0; f < faces.size() * dim; ++f)
          row << ',' << sums[f] / dt + 0.;
        for (unsigned int r = 0; r < rigid_grains.size(); ++r)
          {
            for (unsigned int c = 0; c < per_rigid; ++c)
              row << ','
                  << sums[faces.size() * dim + r * per_rigid + c] / dt + 0.;
            row << ',' << numbers[r];
          }
        row << '\n';
        file.append(row.str());
      }
  }



  template class ReactionHistory<2>;
  template class ReactionHistory<3>;
} // namespace grainmpm
