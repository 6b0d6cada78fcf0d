// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_grid_background_grid_h
#define grainmpm_grid_background_grid_h

#include <grainmpm/base/config.h>
#include <grainmpm/base/parameters.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/partitioner.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <deal.II/particles/particle_handler.h>

#include <array>
#include <vector>

namespace grainmpm
{
  /**
   * The background grid of the material point method: a box of equal,
   * axis-aligned cells on a `parallel::distributed::Triangulation`, the
   * Q1 shape functions of an `FE_Q<dim>(1)` on a `DoFHandler`, and the
   * flat tables the transfers need: the node numbers of each active cell,
   * and for each node the box faces it lies on.
   *
   * Nodes are numbered like the entries of a ghosted
   * `LinearAlgebra::distributed::Vector` on the DoFs: the locally owned
   * nodes first (0 .. n_owned_nodes() - 1, in the order of their global
   * DoF index), then the ghost nodes (locally relevant, owned by another
   * rank) in the order of their global DoF index. All per-node arrays are
   * plain vectors; on one rank the local number is the global DoF index.
   */
  template <int dim>
  class BackgroundGrid
  {
  public:
    /** Number of nodes of a cell. */
    static constexpr unsigned int nodes_per_cell = 1U << dim;

    BackgroundGrid(const BackgroundGridParameters<dim> &parameters,
                   const MPI_Comm                       communicator);

    /** The triangulation (boundary ids 0..2dim-1 are x-, x+, y-, ...). */
    const parallel::distributed::Triangulation<dim> &
    get_triangulation() const;

    /**
     * Load the cells and their attached data (material points) written by
     * Triangulation::save() to @p filename (a checkpoint); the coarse mesh,
     * and so every node and DoF, stays the same.
     */
    void
    load(const std::string &filename);

    /** The DoF handler of the scalar Q1 element: one DoF per node. */
    const DoFHandler<dim> &
    get_dof_handler() const;

    /** The mapping used by the particle handler. */
    const Mapping<dim> &
    get_mapping() const;

    /** Number of locally relevant nodes (owned and ghost). */
    unsigned int
    n_nodes() const;

    /** Number of locally owned nodes: the local nodes 0 .. this - 1. */
    unsigned int
    n_owned_nodes() const;

    /** The global DoF index of local node @p node. */
    types::global_dof_index
    node_global_index(const unsigned int node) const;

    /**
     * The partitioner of the node DoFs (owned, ghosts = locally relevant),
     * whose local numbering is the node numbering above.
     */
    const std::shared_ptr<const Utilities::MPI::Partitioner> &
    node_partitioner() const;

    /**
     * Repartition the cells so that every rank carries about the same
     * weight, where a cell weighs 1 plus @p particle_weight times its
     * number of material points in @p particle_handler, which moves with
     * its cells. The node tables are rebuilt.
     */
    void
    repartition(Particles::ParticleHandler<dim> &particle_handler,
                const unsigned int               particle_weight);

    /**
     * The local node numbers of the vertices of the active cell with index
     * @p active_cell_index, in deal.II vertex order.
     */
    const unsigned int *
    cell_nodes(const unsigned int active_cell_index) const;

    /** Position of local node @p node. */
    const Point<dim> &
    node_position(const unsigned int node) const;

    /**
     * The lattice index of local node @p node: its integer coordinates
     * (x - lower corner) / cell size, from 0 to the number of cells.
     */
    std::array<int, dim>
    node_lattice_index(const unsigned int node) const;

    /**
     * The local node at lattice index (i_0, .., i_{dim-1}) is
     * lattice_node(sum_d lattice_part(d, i_d)), for the indices of locally
     * relevant nodes (no range checks: for the inner loops of the
     * transfer). The nodes of the cells next to a locally owned cell are
     * all locally relevant: the kernels that reach one cell further use
     * this.
     */
    std::size_t
    lattice_part(const unsigned int d, const int index) const
    {
      return lattice_strides[d] * (index - lattice_origin[d]);
    }

    /** See lattice_part(). */
    unsigned int
    lattice_node(const std::size_t position) const
    {
      return lattice_nodes[position];
    }

    /** Number of cells in each direction. */
    const std::vector<unsigned int> &
    n_cells() const;

    /**
     * A bit mask of the box faces local node @p node lies on: bit f is set
     * for face f (x-, x+, y-, y+, z-, z+).
     */
    unsigned int
    node_faces(const unsigned int node) const
    {
      return node_face_masks[node];
    }

    /** The locally owned nodes on the boundary of the box. */
    const std::vector<unsigned int> &
    boundary_nodes() const;

    /** Cell size in each direction. */
    const Tensor<1, dim> &
    cell_size() const;

    /** The smallest cell size. */
    double
    minimum_cell_size() const;

    /** The box corners. */
    const Point<dim> &
    lower_corner() const;
    const Point<dim> &
    upper_corner() const;

    /** The condition on face @p face. */
    const BoundaryCondition &
    boundary_condition(const unsigned int face) const;

  private:
    /**
     * Refuse (InputError on every rank) a grid that cannot fit in the
     * memory of the machine, before making it. Collective.
     */
    void
    check_memory(const MPI_Comm communicator) const;

    const BackgroundGridParameters<dim>      &parameters;
    parallel::distributed::Triangulation<dim> triangulation;
    /**
     * Distribute the DoFs and fill the node tables below from the current
     * cells (after construction and after load()).
     */
    void
    setup_node_tables();

    FE_Q<dim>                                          fe;
    DoFHandler<dim>                                    dof_handler;
    MappingCartesian<dim>                              mapping;
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
    Tensor<1, dim>                                     cell_extent;
    std::vector<unsigned int>                          cell_node_table;
    std::vector<Point<dim>>                            node_positions;
    std::vector<unsigned int>                          node_face_masks;
    std::vector<unsigned int>                          boundary_node_list;
    std::vector<types::global_dof_index>               node_global_indices;
    /**
     * The locally relevant nodes on the lattice of the box: the smallest
     * index range holding them (origin and extent) and the local node at
     * each lattice point of it (numbers::invalid_unsigned_int if none).
     */
    std::array<int, dim>         lattice_origin;
    std::array<int, dim>         lattice_extent;
    std::array<std::size_t, dim> lattice_strides;
    std::vector<unsigned int>    lattice_nodes;
  };



  template <int dim>
  inline const unsigned int *
  BackgroundGrid<dim>::cell_nodes(const unsigned int active_cell_index) const
  {
    return cell_node_table.data() + nodes_per_cell * active_cell_index;
  }
} // namespace grainmpm

#endif
