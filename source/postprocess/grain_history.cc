// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/postprocess/grain_history.h>
#include <grainmpm/postprocess/history_file.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace grainmpm
{
  template <int dim>
  GrainHistory<dim>::GrainHistory(const std::string       &filename,
                                  const std::vector<bool> &rigid,
                                  const MPI_Comm           communicator,
                                  const std::uintmax_t     resume_length)
    : rigid(rigid)
    , n_grains(rigid.size())
    , communicator(communicator)
    , file(filename, communicator)
    , rotations(rigid.size())
    , last_angular_velocities(rigid.size())
  {
    file.open(resume_length, [&](std::ofstream &out) {
      out << "time [T],grain [1],mass [M]";
      for (unsigned int d = 0; d < dim; ++d)
        out << ",centre_"
            << "xyz"[d] << " [L]";
      for (unsigned int d = 0; d < dim; ++d)
        out << ",velocity_"
            << "xyz"[d] << " [L/T]";
      if (dim == 2)
        out << ",angular_velocity_z [1/T]";
      else
        out << ",angular_velocity_x [1/T],angular_velocity_y "
               "[1/T],angular_velocity_z [1/T]";
      out << ",max_distance [L]";
      if (dim == 2)
        out << ",rotation_z [1]";
      else
        out << ",rotation_x [1],rotation_y [1],rotation_z [1]";
      out << ",coordination_number [1]\n" << std::flush;
    });
  }



  template <int dim>
  void
  GrainHistory<dim>::check_written() const
  {
    file.check_written();
  }



  template <int dim>
  std::uintmax_t
  GrainHistory<dim>::length()
  {
    return file.length();
  }



  template <int dim>
  std::vector<GrainMotion<dim>>
  GrainHistory<dim>::compute(
    const Particles::ParticleHandler<dim> &particle_handler) const
  {
    using Layout = MaterialPointLayout<dim>;
    // First moments: mass, m x, m v, m F.
    const unsigned int  n_first = 1 + 2 * dim + dim * dim;
    std::vector<double> sums(n_grains * n_first, 0.);
    for (const auto &particle : particle_handler)
      {
        const auto         properties = particle.get_properties();
        const unsigned int g          = Layout::get_grain(properties);
        const double       mass       = properties[Layout::mass];
        double            *sum        = &sums[g * n_first];
        sum[0] += mass;
        for (unsigned int d = 0; d < dim; ++d)
          {
            sum[1 + d] += mass * particle.get_location()[d];
            sum[1 + dim + d] += mass * properties[Layout::velocity + d];
          }
        for (unsigned int k = 0; k < dim * dim; ++k)
          sum[1 + 2 * dim + k] +=
            mass * properties[Layout::deformation_gradient + k];
      }
    Utilities::MPI::sum(sums, communicator, sums);
    std::vector<GrainMotion<dim>> motions(n_grains);
    for (unsigned int g = 0; g < n_grains; ++g)
      {
        const double *sum = &sums[g * n_first];
        motions[g].mass   = sum[0];
        if (sum[0] > 0.)
          {
            for (unsigned int d = 0; d < dim; ++d)
              {
                motions[g].centre_of_mass[d] = sum[1 + d] / sum[0];
                motions[g].velocity[d]       = sum[1 + dim + d] / sum[0];
              }
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                motions[g].deformation_gradient[i][j] =
                  sum[1 + 2 * dim + dim * i + j] / sum[0];
          }
      }

    // Second moments about the centre of mass: angular momentum L and the
    // inertia tensor I (3D) or polar moment (2D).
    const unsigned int  n_second = (dim == 2 ? 2 : 3 + 9);
    std::vector<double> second(n_grains * n_second, 0.);
    for (const auto &particle : particle_handler)
      {
        const auto           properties = particle.get_properties();
        const unsigned int   g          = Layout::get_grain(properties);
        const double         mass       = properties[Layout::mass];
        const Tensor<1, dim> r =
          particle.get_location() - motions[g].centre_of_mass;
        const Tensor<1, dim> v =
          Layout::get_velocity(properties) - motions[g].velocity;
        motions[g].max_distance = std::max(motions[g].max_distance, r.norm());
        double *sum             = &second[g * n_second];
        if (dim == 2)
          {
            sum[0] += mass * (r[0] * v[1] - r[1] * v[0]);
            sum[1] += mass * r.norm_square();
          }
        else
          {
            const Tensor<1, 3> r3({r[0], r[1], r[dim - 1]});
            const Tensor<1, 3> v3({v[0], v[1], v[dim - 1]});
            const Tensor<1, 3> l = cross_product_3d(r3, v3);
            for (unsigned int d = 0; d < 3; ++d)
              sum[d] += mass * l[d];
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int b = 0; b < 3; ++b)
                sum[3 + 3 * a + b] +=
                  mass * ((a == b ? r3.norm_square() : 0.) - r3[a] * r3[b]);
          }
      }
    Utilities::MPI::sum(second, communicator, second);
    // One collective for all grains (not one per grain: an output of
    // 10,000 grains would make 10,000 calls).
    std::vector<double> max_distances(n_grains);
    for (unsigned int g = 0; g < n_grains; ++g)
      max_distances[g] = motions[g].max_distance;
    Utilities::MPI::max(max_distances, communicator, max_distances);
    for (unsigned int g = 0; g < n_grains; ++g)
      motions[g].max_distance = max_distances[g];
    for (unsigned int g = 0; g < n_grains; ++g)
      {
        const double *sum = &second[g * n_second];
        if (dim == 2)
          {
            if (sum[1] > 0.)
              motions[g].angular_velocity[0] = sum[0] / sum[1];
          }
        else
          {
            Tensor<2, 3> inertia;
            Tensor<1, 3> angular_momentum;
            for (unsigned int a = 0; a < 3; ++a)
              {
                angular_momentum[a] = sum[a];
                for (unsigned int b = 0; b < 3; ++b)
                  inertia[a][b] = sum[3 + 3 * a + b];
              }
            if (determinant(inertia) > 0.)
              {
                const Tensor<1, 3> omega = invert(inertia) * angular_momentum;
                for (unsigned int d = 0; d < 3; ++d)
                  motions[g].angular_velocity[d] = omega[d];
              }
          }
      }
    return motions;
  }



  namespace
  {
    /** @p angle moved by whole turns to within half a turn of @p target. */
    double
    nearest_turn(const double angle, const double target)
    {
      const double turn = 2. * numbers::PI;
      return angle + turn * std::round((target - angle) / turn);
    }



    /** The rotation vector (axis times angle) of the rotation part of F. */
    Tensor<1, 3>
    rotation_vector(const Tensor<2, 3> &F)
    {
      // Polar decomposition by the iteration R <- (R + R^{-T}) / 2.
      Tensor<2, 3> R = F;
      for (unsigned int k = 0; k < 50 && determinant(R) > 0.; ++k)
        {
          const Tensor<2, 3> next   = 0.5 * (R + transpose(invert(R)));
          const double       change = (next - R).norm();
          R                         = next;
          if (change < 1e-14)
            break;
        }
      const Tensor<1, 3> axis(
        {R[2][1] - R[1][2], R[0][2] - R[2][0], R[1][0] - R[0][1]});
      const double cosine = std::max(-1., std::min(1., 0.5 * (trace(R) - 1.)));
      const double angle  = std::acos(cosine);
      const double sine   = std::sin(angle);
      return sine > 1e-12 ? (angle / (2. * sine)) * axis : 0.5 * axis;
    }
  } // namespace



  template <int dim>
  void
  GrainHistory<dim>::update_rotations(
    const std::vector<GrainMotion<dim>> &motions,
    const double                         time)
  {
    const double interval = have_last ? time - last_time : 0.;
    for (unsigned int g = 0; g < n_grains; ++g)
      {
        const Rotation &omega = motions[g].angular_velocity;
        const Rotation  predicted =
          rotations[g] + 0.5 * interval * (last_angular_velocities[g] + omega);
        const Tensor<2, dim> &F = motions[g].deformation_gradient;
        if (rigid[g] || motions[g].mass <= 0.)
          rotations[g] = predicted;
        else if constexpr (dim == 2)
          rotations[g][0] =
            nearest_turn(std::atan2(F[1][0] - F[0][1], F[0][0] + F[1][1]),
                         predicted[0]);
        else
          rotations[g] = rotation_vector(F);
        last_angular_velocities[g] = omega;
      }
    last_time = time;
    have_last = true;
  }



  template <int dim>
  void
  GrainHistory<dim>::write(
    const std::vector<GrainMotion<dim>> &motions,
    const std::vector<unsigned int>     &coordination_numbers,
    const double                         time,
    const bool                           write_rows)
  {
    update_rotations(motions, time);
    if (!file.is_open() || !write_rows)
      return;
    // The rows of this time in one write: a run killed meanwhile leaves
    // whole rows.
    std::ostringstream rows;
    rows << std::setprecision(12);
    for (unsigned int g = 0; g < n_grains; ++g)
      {
        rows << time << ',' << g + 1 << ',' << motions[g].mass;
        for (unsigned int d = 0; d < dim; ++d)
          rows << ',' << motions[g].centre_of_mass[d];
        for (unsigned int d = 0; d < dim; ++d)
          rows << ',' << motions[g].velocity[d];
        for (unsigned int d = 0; d < (dim == 2 ? 1 : 3); ++d)
          rows << ',' << motions[g].angular_velocity[d];
        rows << ',' << motions[g].max_distance;
        for (unsigned int d = 0; d < (dim == 2 ? 1 : 3); ++d)
          rows << ',' << rotations[g][d];
        rows << ',' << coordination_numbers[g] << '\n';
      }
    file.append(rows.str());
  }



  template class GrainHistory<2>;
  template class GrainHistory<3>;
} // namespace grainmpm
