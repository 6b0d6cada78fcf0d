// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/transfer/shape_functions.h>
#include <grainmpm/transfer/transfer_cache.h>

#include <algorithm>
#include <cmath>

namespace grainmpm
{
  namespace
  {
    /**
     * The GIMP weights along one axis, in units of the cell size: a
     * particle whose interval is [a, b] (cut at the box faces; b - a <= 1
     * and a < 1, b > 0, as the half-width is at most half a cell and the
     * particle is in its cell) and the nodes at offsets -1, 0, 1, 2 from the
     * lower vertex of its cell. Keeps the nodes with a positive weight:
     * their offsets, values S = (Phi(b - o) - Phi(a - o)) / (b - a) and
     * derivatives (N(b - o) - N(a - o)) / (b - a) (per unit of the cell
     * size).
     *
     * The interval lies inside the cell, reaches below it (a < 0: nodes
     * -1, 0, 1) or above it (b > 1: nodes 0, 1, 2), never both. In each
     * case it is known on which piece of Phi every end falls (or that it
     * lies beyond the hat), so Phi is evaluated without tests.
     */
    struct AxisWeights
    {
      unsigned int n = 0;
      int          offsets[3];
      double       values[3];
      double       derivatives[3];

      void
      compute(const double a, const double b, const double inverse_h)
      {
        Assert(b - a <= 1. + 1e-12 && !(a < 0. && b > 1.), ExcInternalError());
        const double inverse_length = 1. / (b - a);
        n                           = 0;
        const auto keep             = [&](const int    offset,
                              const double phi_b,
                              const double phi_a) {
          const double value = (phi_b - phi_a) * inverse_length;
          if (value > 0.)
            {
              offsets[n] = offset;
              values[n]  = value;
              derivatives[n] =
                (HatKernel::value(b - offset) - HatKernel::value(a - offset)) *
                inverse_length * inverse_h;
              ++n;
            }
        };
        if (a < 0.)
          {
            // b < 1: b + 1 is beyond the hat of node -1, a - 1 before that
            // of node 1.
            keep(-1, 1., HatKernel::falling_integral(a + 1.));
            keep(0,
                 HatKernel::falling_integral(b),
                 HatKernel::rising_integral(a));
            keep(1, HatKernel::rising_integral(b - 1.), 0.);
          }
        else if (b > 1.)
          {
            keep(0, 1., HatKernel::falling_integral(a));
            keep(1,
                 HatKernel::falling_integral(b - 1.),
                 HatKernel::rising_integral(a - 1.));
            keep(2, HatKernel::rising_integral(b - 2.), 0.);
          }
        else
          {
            keep(0,
                 HatKernel::falling_integral(b),
                 HatKernel::falling_integral(a));
            keep(1,
                 HatKernel::rising_integral(b - 1.),
                 HatKernel::rising_integral(a - 1.));
          }
      }
    };



    /**
     * Bring the velocity field of the particle at place @p p of the fill
     * order up to date. A point's grain never changes, so its property
     * memory is read only if @p read_all_fields or another particle (by
     * id) held place @p p at the last fill; @p differs records a change.
     */
    template <int dim, typename ParticleIteratorType>
    inline void
    update_field(const std::size_t                   p,
                 const ParticleIteratorType         &particle,
                 const std::vector<unsigned int>    &field_of_grain,
                 const bool                          read_all_fields,
                 std::vector<unsigned int>          &fields,
                 std::vector<types::particle_index> &ids,
                 bool                               &differs)
    {
      if (const types::particle_index id = particle->get_id();
          read_all_fields || ids[p] != id)
        {
          const unsigned int field =
            field_of_grain[MaterialPointLayout<dim>::get_grain(
              particle->get_properties())];
          differs |= fields[p] != field;
          fields[p] = field;
          ids[p]    = id;
        }
    }
  } // namespace



  template <int dim>
  void
  TransferCache<dim>::reinit(
    const BackgroundGrid<dim>             &grid,
    const Particles::ParticleHandler<dim> &particle_handler,
    const std::vector<unsigned int>       &field_of_grain,
    const ShapeFunctions                   shape_functions,
    const Tensor<1, dim>                  &half_width)
  {
    const std::size_t n = particle_handler.n_locally_owned_particles();
    // The entries count as changed unless the fill below finds each one as
    // it was (nodes, first entries and fields, compared as they are
    // written).
    // (At first update_cells() finds the cells: changed.)
    changed = update_cells(grid, particle_handler) || n != fields.size() ||
              shape_functions != this->shape_functions;
    this->shape_functions = shape_functions;
    const unsigned int per_particle =
      shape_functions == ShapeFunctions::linear ? (1U << dim) :
                                                  max_nodes_per_particle;
    // The arrays only grow (resizing them down to the entries used and up
    // again every step would clear them every step).
    first_entry.resize(n + 1);
    if (nodes.size() < n * per_particle)
      {
        changed = true;
        nodes.resize(n * per_particle);
        shape_values.resize(n * per_particle);
        shape_gradients.resize(n * per_particle);
        slots.resize(n * per_particle);
      }
    fields.resize(n);
    ids.resize(n);

    // With another number of points or other cells every field is read.
    const unsigned int n_entries =
      shape_functions == ShapeFunctions::linear ?
        fill_linear(grid, particle_handler, field_of_grain, changed) :
        fill_gimp(grid, particle_handler, field_of_grain, half_width, changed);
    changed        = changed || first_entry[n] != n_entries;
    first_entry[n] = n_entries;
  }



  template <int dim>
  unsigned int
  TransferCache<dim>::fill_linear(
    const BackgroundGrid<dim>             &grid,
    const Particles::ParticleHandler<dim> &particle_handler,
    const std::vector<unsigned int>       &field_of_grain,
    const bool                             read_all_fields)
  {
    Tensor<1, dim> inverse_h;
    for (unsigned int d = 0; d < dim; ++d)
      inverse_h[d] = 1. / grid.cell_size()[d];
    std::size_t  p       = 0;
    unsigned int entry   = 0;
    bool         differs = false;
    // Loop over cells, then over the particles in each cell: the node
    // table entry is looked up once per cell.
    for_each_particle(
      particle_handler, [&](const auto &cell, const auto &particle) {
        const unsigned int *cell_nodes =
          grid.cell_nodes(cell->active_cell_index());
        const Point<dim> xi = particle->get_reference_location();
        // Q1: S = prod_d N_d, N_d = xi_d (vertex bit 1) or 1 - xi_d.
        double one_d_values[dim][2];
        for (unsigned int d = 0; d < dim; ++d)
          {
            one_d_values[d][0] = 1. - xi[d];
            one_d_values[d][1] = xi[d];
          }
        first_entry[p]                    = entry;
        constexpr unsigned int n_vertices = 1U << dim;
        for (unsigned int v = 0; v < n_vertices; ++v, ++entry)
          {
            double         value = 1.;
            Tensor<1, dim> gradient;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const unsigned int bit = (v >> d) & 1U;
                value *= one_d_values[d][bit];
                double derivative = (bit ? 1. : -1.) * inverse_h[d];
                for (unsigned int e = 0; e < dim; ++e)
                  if (e != d)
                    derivative *= one_d_values[e][(v >> e) & 1U];
                gradient[d] = derivative;
              }
            differs |= nodes[entry] != cell_nodes[v];
            nodes[entry]           = cell_nodes[v];
            shape_values[entry]    = value;
            shape_gradients[entry] = gradient;
          }
        update_field<dim>(
          p, particle, field_of_grain, read_all_fields, fields, ids, differs);
        ++p;
      });
    AssertDimension(p, particle_handler.n_locally_owned_particles());
    changed = changed || differs;
    return entry;
  }



  template <int dim>
  unsigned int
  TransferCache<dim>::fill_gimp(
    const BackgroundGrid<dim>             &grid,
    const Particles::ParticleHandler<dim> &particle_handler,
    const std::vector<unsigned int>       &field_of_grain,
    const Tensor<1, dim>                  &half_width,
    const bool                             read_all_fields)
  {
    using Layout = MaterialPointLayout<dim>;
    Tensor<1, dim> inverse_h;
    for (unsigned int d = 0; d < dim; ++d)
      inverse_h[d] = 1. / grid.cell_size()[d];
    std::size_t  p       = 0;
    unsigned int entry   = 0;
    bool         differs = false;
    // Half-widths in units of the cell size, at most half a cell so
    // that a particle touches at most 3 nodes per axis.
    Tensor<1, dim> initial_width;
    for (unsigned int d = 0; d < dim; ++d)
      initial_width[d] = std::min(0.5, half_width[d] * inverse_h[d]);
    const std::vector<unsigned int> &n_cells = grid.n_cells();
    // The lattice index of the lower vertex of the cell of the last
    // particle.
    std::array<int, dim> cell_index;
    unsigned int         last_cell = numbers::invalid_unsigned_int;
    for_each_particle(
      particle_handler, [&](const auto &cell, const auto &particle) {
        if (cell->active_cell_index() != last_cell)
          {
            last_cell  = cell->active_cell_index();
            cell_index = grid.node_lattice_index(
              grid.cell_nodes(cell->active_cell_index())[0]);
          }
        // The particle's interval per axis in cell units, cut at the
        // box.
        const Point<dim> xi    = particle->get_reference_location();
        Tensor<1, dim>   width = initial_width;
        if (shape_functions == ShapeFunctions::cpgimp)
          {
            const Tensor<2, dim> F =
              Layout::get_deformation_gradient(particle->get_properties());
            // Half-width along axis d: l_0 sqrt((F F^T)_dd), the length
            // of row d of F, unchanged by rotations; kept above 1e-6
            // cells so that (Phi(b) - Phi(a)) / (b - a) stays accurate.
            for (unsigned int d = 0; d < dim; ++d)
              width[d] = std::min(0.5, std::max(1e-6, width[d] * F[d].norm()));
          }
        // Per axis the nodes with a positive weight: their values,
        // derivatives and parts of the lattice position.
        AxisWeights axes[dim];
        std::size_t parts[dim][3];
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double a = std::max(xi[d] - width[d], -1. * cell_index[d]);
            const double b =
              std::min(xi[d] + width[d],
                       static_cast<double>(n_cells[d]) - cell_index[d]);
            axes[d].compute(a, b, inverse_h[d]);
            for (unsigned int k = 0; k < axes[d].n; ++k)
              parts[d][k] =
                grid.lattice_part(d, cell_index[d] + axes[d].offsets[k]);
          }
        // Their tensor products, counting through the axes like an
        // odometer.
        differs |= first_entry[p] != entry;
        first_entry[p]        = entry;
        unsigned int at[dim]  = {};
        bool         finished = false;
        while (!finished)
          {
            double         value    = 1.;
            std::size_t    position = 0;
            Tensor<1, dim> gradient;
            for (unsigned int d = 0; d < dim; ++d)
              {
                value *= axes[d].values[at[d]];
                position += parts[d][at[d]];
                double derivative = axes[d].derivatives[at[d]];
                for (unsigned int e = 0; e < dim; ++e)
                  if (e != d)
                    derivative *= axes[e].values[at[e]];
                gradient[d] = derivative;
              }
            AssertIndexRange(entry, nodes.size());
            const unsigned int node = grid.lattice_node(position);
            differs |= nodes[entry] != node;
            nodes[entry] = node;
            Assert(nodes[entry] != numbers::invalid_unsigned_int,
                   ExcInternalError());
            shape_values[entry]    = value;
            shape_gradients[entry] = gradient;
            ++entry;
            finished = true;
            for (unsigned int d = 0; d < dim; ++d)
              if (++at[d] < axes[d].n)
                {
                  finished = false;
                  break;
                }
              else
                at[d] = 0;
          }
        update_field<dim>(
          p, particle, field_of_grain, read_all_fields, fields, ids, differs);
        ++p;
      });
    AssertDimension(p, particle_handler.n_locally_owned_particles());
    changed = changed || differs;
    return entry;
  }



  template <int dim>
  bool
  TransferCache<dim>::update_cells(
    const BackgroundGrid<dim>             &grid,
    const Particles::ParticleHandler<dim> &particle_handler)
  {
    const Triangulation<dim> &triangulation = grid.get_triangulation();
    if (watched_triangulation != &triangulation)
      {
        watched_triangulation = &triangulation;
        cells_valid           = false;
        const auto invalidate = [this]() { cells_valid = false; };
        triangulation_changed[0] =
          triangulation.signals.any_change.connect(invalidate);
        triangulation_changed[1] =
          triangulation.signals.post_distributed_repartition.connect(
            invalidate);
        triangulation_changed[2] =
          triangulation.signals.post_distributed_load.connect(invalidate);
      }

    if (cells_valid)
      {
        // Drop the cells that were emptied or handed to another rank, and
        // count the particles in the others.
        std::size_t n_found = 0;
        auto        kept    = cells.begin();
        for (const auto &cell : cells)
          if (cell->is_locally_owned())
            if (const auto n = particle_handler.n_particles_in_cell(cell);
                n > 0)
              {
                n_found += n;
                *kept++ = cell;
              }
        cells.erase(kept, cells.end());
        if (n_found == particle_handler.n_locally_owned_particles())
          return false;
      }

    cells.clear();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() &&
          particle_handler.n_particles_in_cell(cell) > 0)
        cells.push_back(cell);
    cells_valid = true;
    return true;
  }



  template class TransferCache<2>;
  template class TransferCache<3>;
} // namespace grainmpm
