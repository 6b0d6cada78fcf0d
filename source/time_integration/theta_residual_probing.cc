// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The probed diagonal of the theta residual's Jacobian (the matrix-free
// weighted Jacobi preconditioner of Cummins & Brackbill; doc/theory.md
// section 11): the unknowns coloured by their node's index modulo 3 in each
// direction and by component, one finite-difference probe per colour.

#include <grainmpm/time_integration/theta_residual.h>

#include <deal.II/base/mpi.h>

#include <cmath>

namespace grainmpm
{
  template <int dim>
  void
  ThetaResidual<dim>::jacobian_diagonal(const VectorType   &x,
                                        const StepFunction &step,
                                        VectorType         &diagonal)
  {
    VectorType simplified_residual;
    simplified_residual.reinit(x, true);
    evaluate(x, simplified_residual, true);
    probe_diagonal(x, simplified_residual, diagonal, step);
  }



  template <int dim>
  unsigned int
  ThetaResidual<dim>::colour(const unsigned int dof) const
  {
    const unsigned int    slot     = dof / dim;
    const Point<dim>      position = grid.node_position(layout->node(slot));
    const Point<dim>     &lower    = grid.lower_corner();
    const Tensor<1, dim> &h        = grid.cell_size();
    unsigned int          c        = 0;
    unsigned int          factor   = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const long index = std::lround((position[d] - lower[d]) / h[d]);
        c += factor * static_cast<unsigned int>(index % 3);
        factor *= 3;
      }
    return c + factor * (dof % dim);
  }



  template <int dim>
  void
  ThetaResidual<dim>::probe_diagonal(const VectorType   &velocities,
                                     const VectorType   &residual,
                                     VectorType         &diagonal,
                                     const StepFunction &step) const
  {
    diagonal.reinit(residual, true);
    diagonal = 1.;
    VectorType direction, perturbed, probed;
    direction.reinit(residual, true);
    perturbed.reinit(residual, true);
    probed.reinit(residual, true);
    std::vector<unsigned int> dof_colours(residual.locally_owned_size());
    for (unsigned int k = 0; k < dof_colours.size(); ++k)
      dof_colours[k] = colour(k);
    for (unsigned int c = 0; c < n_colours; ++c)
      {
        direction = 0.;
        bool any  = false;
        for (unsigned int k = 0; k < dof_colours.size(); ++k)
          if (dof_colours[k] == c && slot_active[k / dim] &&
              !slot_rigid[k / dim])
            {
              direction.local_element(k) = 1.;
              any                        = true;
            }
        if (Utilities::MPI::max(any ? 1U : 0U, communicator()) == 0)
          continue;
        const double eps = step(velocities, direction);
        perturbed        = velocities;
        perturbed.add(eps, direction);
        evaluate(perturbed, probed, true);
        for (unsigned int k = 0; k < dof_colours.size(); ++k)
          if (direction.local_element(k) != 0.)
            diagonal.local_element(k) =
              (probed.local_element(k) - residual.local_element(k)) / eps;
      }
  }



  // The class itself is instantiated in theta_residual.cc; here only the
  // members defined in this file.
  template void
  ThetaResidual<2>::jacobian_diagonal(const VectorType &,
                                      const StepFunction &,
                                      VectorType &);
  template unsigned int
  ThetaResidual<2>::colour(const unsigned int) const;
  template void
  ThetaResidual<2>::probe_diagonal(const VectorType &,
                                   const VectorType &,
                                   VectorType &,
                                   const StepFunction &) const;
  template void
  ThetaResidual<3>::jacobian_diagonal(const VectorType &,
                                      const StepFunction &,
                                      VectorType &);
  template unsigned int
  ThetaResidual<3>::colour(const unsigned int) const;
  template void
  ThetaResidual<3>::probe_diagonal(const VectorType &,
                                   const VectorType &,
                                   VectorType &,
                                   const StepFunction &) const;
} // namespace grainmpm
