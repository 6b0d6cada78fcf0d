// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/grid/background_grid.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/grid/grid_generator.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>

namespace grainmpm
{
  template <int dim>
  void
  BackgroundGrid<dim>::check_memory(const MPI_Comm communicator) const
  {
    // Measured with grainmpm 0.4 on deal.II 9.4 (cells, p4est, DoFs and
    // node tables): 0.9 KiB per cell in 2D and 2.2 KiB in 3D. A lower
    // bound: the material points and vectors come on top.
    double n_cells = 1.;
    for (const unsigned int n : parameters.n_cells)
      n_cells *= n;
    const double bytes_per_cell = (dim == 2 ? 0.8 : 2.) * 1024.;
    const double bytes          = n_cells * bytes_per_cell;

    // What this node has available, shared by the ranks on it.
    MPI_Comm node;
    MPI_Comm_split_type(communicator,
                        MPI_COMM_TYPE_SHARED,
                        Utilities::MPI::this_mpi_process(communicator),
                        MPI_INFO_NULL,
                        &node);
    const unsigned int ranks_on_node = Utilities::MPI::n_mpi_processes(node);
    MPI_Comm_free(&node);
    const double node_bytes =
      bytes / Utilities::MPI::n_mpi_processes(communicator) * ranks_on_node;
    double        available = -1.;
    std::ifstream meminfo("/proc/meminfo");
    std::string   key;
    double        value = 0.;
    while (meminfo >> key >> value)
      {
        if (key == "MemAvailable:")
          {
            available = value * 1024.;
            break;
          }
        meminfo.ignore(256, '\n');
      }

    std::string error;
    if (available > 0. && node_bytes > available)
      {
        std::ostringstream entry, message;
        entry << "Background grid/Number of cells = ";
        for (unsigned int d = 0; d < dim; ++d)
          entry << (d > 0 ? ", " : "") << parameters.n_cells[d];
        const double gib = 1024. * 1024. * 1024.;
        message << n_cells << " cells need at least " << node_bytes / gib
                << " GiB of memory on this machine (about "
                << bytes_per_cell / 1024. << " KiB per cell in " << dim
                << "D, material points not counted), more than it has "
                   "available (MemAvailable in /proc/meminfo). Use fewer "
                   "cells, or more machines.";
        error = InputError(entry.str(), message.str()).what();
      }
    throw_on_all_ranks(error, communicator);
  }



  template <int dim>
  BackgroundGrid<dim>::BackgroundGrid(
    const BackgroundGridParameters<dim> &parameters,
    const MPI_Comm                       communicator)
    : parameters(parameters)
    , triangulation(communicator)
    , fe(1)
    , dof_handler(triangulation)
  {
    // p4est keeps the coarse mesh on every rank: make it coarse (at most
    // 65536 cells, about 25 MB, where the numbers of cells allow it) and
    // refine it globally to the requested cells, as large parallel runs
    // need. (The refined cells are visited in z-order: on one rank the
    // explicit step then costs 5 % more than on the same cells in rows,
    // measured on 512 x 512 cells; 10 % with 16384 coarse cells.)
    check_memory(communicator);

    std::vector<unsigned int> coarse_cells  = parameters.n_cells;
    unsigned int              n_refinements = 0;
    const auto                n_coarse      = [&coarse_cells]() {
      std::size_t n = 1;
      for (const unsigned int c : coarse_cells)
        n *= c;
      return n;
    };
    while (n_coarse() > 65536 &&
           std::all_of(coarse_cells.begin(),
                       coarse_cells.end(),
                       [](const unsigned int c) { return c % 2 == 0; }))
      {
        for (unsigned int &c : coarse_cells)
          c /= 2;
        ++n_refinements;
      }
    GridGenerator::subdivided_hyper_rectangle(triangulation,
                                              coarse_cells,
                                              parameters.lower_corner,
                                              parameters.upper_corner,
                                              /*colorize=*/true);
    triangulation.refine_global(n_refinements);
    setup_node_tables();
  }



  template <int dim>
  void
  BackgroundGrid<dim>::setup_node_tables()
  {
    dof_handler.distribute_dofs(fe);
    IndexSet locally_relevant_dofs;
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);
    const IndexSet &locally_owned_dofs = dof_handler.locally_owned_dofs();
    IndexSet        ghost_dofs         = locally_relevant_dofs;
    ghost_dofs.subtract_set(locally_owned_dofs);
    partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      locally_owned_dofs, ghost_dofs, triangulation.get_communicator());
    const unsigned int n_local_nodes = locally_relevant_dofs.n_elements();
    node_global_indices.resize(n_local_nodes);
    for (unsigned int node = 0; node < n_local_nodes; ++node)
      node_global_indices[node] = partitioner->local_to_global(node);

    for (unsigned int d = 0; d < dim; ++d)
      cell_extent[d] =
        (parameters.upper_corner[d] - parameters.lower_corner[d]) /
        parameters.n_cells[d];

    // Flat tables: local node numbers per active cell (the FE_Q(1) DoFs are
    // numbered like the vertices), node positions and the faces each node
    // lies on.
    cell_node_table.assign(nodes_per_cell * triangulation.n_active_cells(),
                           numbers::invalid_unsigned_int);
    node_positions.resize(n_local_nodes);
    node_face_masks.assign(n_local_nodes, 0U);
    std::vector<types::global_dof_index> dof_indices(nodes_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dof_indices);
          for (unsigned int v = 0; v < nodes_per_cell; ++v)
            {
              const unsigned int node =
                partitioner->global_to_local(dof_indices[v]);
              cell_node_table[nodes_per_cell * cell->active_cell_index() + v] =
                node;
              node_positions[node] = cell->vertex(v);
            }
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const unsigned int face = cell->face(f)->boundary_id();
                for (const unsigned int v : cell->face(f)->vertex_indices())
                  {
                    const unsigned int node = partitioner->global_to_local(
                      cell->face(f)->vertex_dof_index(v, 0));
                    node_face_masks[node] |= (1U << face);
                  }
              }
        }
    // The lattice of the locally relevant nodes.
    for (unsigned int d = 0; d < dim; ++d)
      {
        lattice_origin[d] = std::numeric_limits<int>::max();
        lattice_extent[d] = 0;
      }
    std::array<int, dim> upper_index;
    upper_index.fill(std::numeric_limits<int>::min());
    for (unsigned int node = 0; node < n_local_nodes; ++node)
      {
        const std::array<int, dim> index = node_lattice_index(node);
        for (unsigned int d = 0; d < dim; ++d)
          {
            lattice_origin[d] = std::min(lattice_origin[d], index[d]);
            upper_index[d]    = std::max(upper_index[d], index[d]);
          }
      }
    if (n_local_nodes == 0)
      lattice_origin.fill(0);
    std::size_t n_lattice_points = (n_local_nodes > 0 ? 1 : 0);
    for (unsigned int d = 0; d < dim; ++d)
      if (n_local_nodes > 0)
        {
          lattice_extent[d] = upper_index[d] - lattice_origin[d] + 1;
          n_lattice_points *= lattice_extent[d];
        }
    for (unsigned int d = 0; d < dim; ++d)
      lattice_strides[d] =
        (d == 0 ? 1 : lattice_strides[d - 1] * lattice_extent[d - 1]);
    lattice_nodes.assign(n_lattice_points, numbers::invalid_unsigned_int);
    for (unsigned int node = 0; node < n_local_nodes; ++node)
      {
        const std::array<int, dim> index    = node_lattice_index(node);
        std::size_t                position = 0;
        std::size_t                stride   = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            position += stride * (index[d] - lattice_origin[d]);
            stride *= lattice_extent[d];
          }
        lattice_nodes[position] = node;
      }

    // Walls act on the slots of owned nodes (their owner applies them).
    boundary_node_list.clear();
    for (unsigned int node = 0; node < n_owned_nodes(); ++node)
      if (node_face_masks[node] != 0)
        boundary_node_list.push_back(node);
  }



  template <int dim>
  const std::vector<unsigned int> &
  BackgroundGrid<dim>::boundary_nodes() const
  {
    return boundary_node_list;
  }



  template <int dim>
  const parallel::distributed::Triangulation<dim> &
  BackgroundGrid<dim>::get_triangulation() const
  {
    return triangulation;
  }



  template <int dim>
  const DoFHandler<dim> &
  BackgroundGrid<dim>::get_dof_handler() const
  {
    return dof_handler;
  }



  template <int dim>
  const Mapping<dim> &
  BackgroundGrid<dim>::get_mapping() const
  {
    return mapping;
  }



  template <int dim>
  unsigned int
  BackgroundGrid<dim>::n_nodes() const
  {
    return node_global_indices.size();
  }



  template <int dim>
  unsigned int
  BackgroundGrid<dim>::n_owned_nodes() const
  {
    return partitioner->locally_owned_size();
  }



  template <int dim>
  types::global_dof_index
  BackgroundGrid<dim>::node_global_index(const unsigned int node) const
  {
    return node_global_indices[node];
  }



  template <int dim>
  const std::shared_ptr<const Utilities::MPI::Partitioner> &
  BackgroundGrid<dim>::node_partitioner() const
  {
    return partitioner;
  }



  template <int dim>
  void
  BackgroundGrid<dim>::repartition(
    Particles::ParticleHandler<dim> &particle_handler,
    const unsigned int               particle_weight)
  {
    // The weight signal as in step-68: a cell costs 1 plus particle_weight
    // per material point.
    const auto connection = triangulation.signals.weight.connect(
      [&particle_handler,
       particle_weight](const typename Triangulation<dim>::cell_iterator &cell,
                        const typename Triangulation<dim>::CellStatus status) {
        if (status != Triangulation<dim>::CELL_PERSIST)
          return 0U;
        return static_cast<unsigned int>(
          1 + particle_weight * particle_handler.n_particles_in_cell(cell));
      });
    particle_handler.prepare_for_coarsening_and_refinement();
    triangulation.repartition();
    particle_handler.unpack_after_coarsening_and_refinement();
    // Unpacked points lie in memory in the order they arrived; sorting
    // puts them in the order of the cells the transfers loop over
    // (measured: the particle loops ran 20-25 % slower per point without).
    particle_handler.sort_particles_into_subdomains_and_cells();
    connection.disconnect();
    setup_node_tables();
  }



  template <int dim>
  const Point<dim> &
  BackgroundGrid<dim>::node_position(const unsigned int node) const
  {
    return node_positions[node];
  }



  template <int dim>
  std::array<int, dim>
  BackgroundGrid<dim>::node_lattice_index(const unsigned int node) const
  {
    std::array<int, dim> index;
    for (unsigned int d = 0; d < dim; ++d)
      index[d] = static_cast<int>(
        std::lround((node_positions[node][d] - parameters.lower_corner[d]) /
                    cell_extent[d]));
    return index;
  }



  template <int dim>
  const std::vector<unsigned int> &
  BackgroundGrid<dim>::n_cells() const
  {
    return parameters.n_cells;
  }



  template <int dim>
  const Tensor<1, dim> &
  BackgroundGrid<dim>::cell_size() const
  {
    return cell_extent;
  }



  template <int dim>
  double
  BackgroundGrid<dim>::minimum_cell_size() const
  {
    double h = cell_extent[0];
    for (unsigned int d = 1; d < dim; ++d)
      h = std::min(h, cell_extent[d]);
    return h;
  }



  template <int dim>
  const Point<dim> &
  BackgroundGrid<dim>::lower_corner() const
  {
    return parameters.lower_corner;
  }



  template <int dim>
  const Point<dim> &
  BackgroundGrid<dim>::upper_corner() const
  {
    return parameters.upper_corner;
  }



  template <int dim>
  const BoundaryCondition &
  BackgroundGrid<dim>::boundary_condition(const unsigned int face) const
  {
    return parameters.boundary_conditions[face];
  }



  template <int dim>
  void
  BackgroundGrid<dim>::load(const std::string &filename)
  {
    triangulation.load(filename);
    setup_node_tables();
  }



  template class BackgroundGrid<2>;
  template class BackgroundGrid<3>;
} // namespace grainmpm
