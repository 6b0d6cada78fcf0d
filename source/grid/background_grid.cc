// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/grid/background_grid.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/grid/grid_generator.h>

#include <numeric>

namespace grainmpm
{
  template <int dim>
  BackgroundGrid<dim>::BackgroundGrid(
    const BackgroundGridParameters<dim> &parameters,
    const MPI_Comm                       communicator)
    : parameters(parameters)
    , triangulation(communicator)
    , fe(1)
    , dof_handler(triangulation)
  {
    GridGenerator::subdivided_hyper_rectangle(triangulation,
                                              parameters.n_cells,
                                              parameters.lower_corner,
                                              parameters.upper_corner,
                                              /*colorize=*/true);
    setup_node_tables();
  }



  template <int dim>
  void
  BackgroundGrid<dim>::setup_node_tables()
  {
    dof_handler.distribute_dofs(fe);
    locally_relevant_dofs.clear();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);

    for (unsigned int d = 0; d < dim; ++d)
      cell_extent[d] =
        (parameters.upper_corner[d] - parameters.lower_corner[d]) /
        parameters.n_cells[d];

    // Flat tables: local node numbers per active cell (the FE_Q(1) DoFs are
    // numbered like the vertices), node positions and the faces each node
    // lies on.
    cell_node_table.assign(nodes_per_cell * triangulation.n_active_cells(),
                           numbers::invalid_unsigned_int);
    node_positions.resize(locally_relevant_dofs.n_elements());
    node_face_masks.assign(locally_relevant_dofs.n_elements(), 0U);
    std::vector<types::global_dof_index> dof_indices(nodes_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dof_indices);
          for (unsigned int v = 0; v < nodes_per_cell; ++v)
            {
              const unsigned int node =
                locally_relevant_dofs.index_within_set(dof_indices[v]);
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
                    const unsigned int node =
                      locally_relevant_dofs.index_within_set(
                        cell->face(f)->vertex_dof_index(v, 0));
                    node_face_masks[node] |= (1U << face);
                  }
              }
        }
    boundary_node_list.clear();
    for (unsigned int node = 0; node < node_face_masks.size(); ++node)
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
    return locally_relevant_dofs.n_elements();
  }



  template <int dim>
  const Point<dim> &
  BackgroundGrid<dim>::node_position(const unsigned int node) const
  {
    return node_positions[node];
  }



  template <int dim>
  unsigned int
  BackgroundGrid<dim>::node_faces(const unsigned int node) const
  {
    return node_face_masks[node];
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
  const IndexSet &
  BackgroundGrid<dim>::locally_relevant_nodes() const
  {
    return locally_relevant_dofs;
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
