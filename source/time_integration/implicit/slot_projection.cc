// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/time_integration/implicit/slot_projection.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <utility>

namespace grainmpm
{
  template <int dim>
  void
  SlotProjection<dim>::reinit_groups(const GrainFieldLayout<dim> &layout)
  {
    const unsigned int n_owned = layout.n_slots();
    const unsigned int n_local = layout.n_local_slots();
    VectorType         index;
    layout.reinit_vector(index, 1);
    unsigned int largest = 0;
    for (unsigned int node = 0; node < layout.n_nodes(); ++node)
      {
        const unsigned int begin = layout.node_slots_begin(node);
        const unsigned int end   = layout.node_slots_end(node);
        largest                  = std::max(largest, end - begin);
        for (unsigned int s = begin; s < end; ++s)
          index.local_element(s) = s - begin;
      }
    slots_per_node = Utilities::MPI::max(largest, layout.get_communicator());
    index.update_ghost_values();
    slot_places.resize(n_local);
    for (unsigned int s = 0; s < n_local; ++s)
      slot_places[s] = static_cast<unsigned int>(index.local_element(s));

    // Ghost slots grouped by node.
    std::vector<std::pair<unsigned int, unsigned int>> ghosts;
    for (unsigned int s = n_owned; s < n_local; ++s)
      ghosts.emplace_back(layout.node(s), s);
    std::sort(ghosts.begin(), ghosts.end());
    group_start.assign(n_local + 1, 0);
    groups.clear();
    for (unsigned int s = 0; s < n_owned; ++s)
      {
        const unsigned int node = layout.node(s);
        for (unsigned int t = layout.node_slots_begin(node);
             t < layout.node_slots_end(node);
             ++t)
          groups.push_back(t);
        group_start[s + 1] = groups.size();
      }
    for (unsigned int s = n_owned; s < n_local; ++s)
      {
        const auto first = std::lower_bound(ghosts.begin(),
                                            ghosts.end(),
                                            std::make_pair(layout.node(s), 0U));
        for (auto g = first; g != ghosts.end() && g->first == layout.node(s);
             ++g)
          groups.push_back(g->second);
        group_start[s + 1] = groups.size();
      }
  }



  template <int dim>
  void
  SlotProjection<dim>::probe(const GrainFieldLayout<dim> &layout,
                             const std::vector<bool>     &unknown,
                             const LinearMap             &linear_projection,
                             VectorType                  &probe)
  {
    const unsigned int          n_local = layout.n_local_slots();
    std::vector<Tensor<2, dim>> columns(n_local * slots_per_node);
    std::vector<bool>           seen(n_local * slots_per_node, false);
    for (unsigned int j = 0; j < slots_per_node; ++j)
      for (unsigned int d = 0; d < dim; ++d)
        {
          probe = 0.;
          for (unsigned int node = 0; node < layout.n_nodes(); ++node)
            {
              const unsigned int s = layout.node_slots_begin(node) + j;
              if (s < layout.node_slots_end(node) && unknown[s])
                probe.local_element(s * dim + d) = 1.;
            }
          linear_projection(probe);
          probe.update_ghost_values();
          for (unsigned int s = 0; s < n_local; ++s)
            for (unsigned int i = 0; i < dim; ++i)
              {
                const double value = probe.local_element(s * dim + i);
                columns[s * slots_per_node + j][i][d] = value;
                if (value != 0.)
                  seen[s * slots_per_node + j] = true;
              }
          probe.zero_out_ghost_values();
        }
    start.assign(n_local + 1, 0);
    partners.clear();
    blocks.clear();
    for (unsigned int s = 0; s < n_local; ++s)
      {
        if (unknown[s])
          for (unsigned int k = group_start[s]; k < group_start[s + 1]; ++k)
            {
              const unsigned int t = groups[k];
              const unsigned int j = slot_places[t];
              if (unknown[t] && seen[s * slots_per_node + j])
                {
                  partners.push_back(t);
                  blocks.push_back(columns[s * slots_per_node + j]);
                }
            }
        start[s + 1] = partners.size();
      }
  }



  template class SlotProjection<2>;
  template class SlotProjection<3>;
} // namespace grainmpm
