// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/contact/held_contact_status.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <tuple>

namespace grainmpm
{
  template <int dim>
  bool
  HeldContactStatus<dim>::Entry::operator<(const Entry &other) const
  {
    return std::tie(node, grain, face) <
           std::tie(other.node, other.grain, other.face);
  }



  template <int dim>
  void
  HeldContactStatus<dim>::record(const ContactStatus<dim>    &status,
                                 const GrainFieldLayout<dim> &layout,
                                 const BackgroundGrid<dim>   &grid)
  {
    entries.clear();
    for (unsigned int s = 0; s < status.slot_state.size(); ++s)
      if (status.slot_state[s] != ContactState::free)
        entries.push_back({grid.node_lattice_index(layout.node(s)),
                           layout.field(s),
                           contact_face,
                           status.slot_state[s],
                           status.slip_directions[s]});
    for (unsigned int w = 0; w < status.wall_slots.size(); ++w)
      if (status.wall_state[w] != ContactState::free)
        {
          const unsigned int s = status.wall_slots[w];
          entries.push_back({grid.node_lattice_index(layout.node(s)),
                             layout.field(s),
                             status.wall_faces[w],
                             status.wall_state[w],
                             status.wall_slip_directions[w]});
        }
    const MPI_Comm communicator = layout.get_communicator();
    if (Utilities::MPI::n_mpi_processes(communicator) > 1)
      {
        const std::vector<std::vector<Entry>> all =
          Utilities::MPI::all_gather(communicator, entries);
        entries.clear();
        for (const std::vector<Entry> &part : all)
          entries.insert(entries.end(), part.begin(), part.end());
      }
    std::sort(entries.begin(), entries.end());
  }



  template <int dim>
  void
  HeldContactStatus<dim>::apply(ContactStatus<dim>          &status,
                                const GrainFieldLayout<dim> &layout,
                                const BackgroundGrid<dim>   &grid) const
  {
    // Without a held entry there is no status to start from: the step
    // decides afresh, on the velocities the momentum balance asks for. (A
    // grain that hits another after a free flight is caught so, as in the
    // first step of a run.)
    if (entries.empty())
      return;
    // The entry of (slot, face), if kept.
    const auto find = [&](const unsigned int  slot,
                          const unsigned char face) -> const Entry * {
      Entry key;
      key.node         = grid.node_lattice_index(layout.node(slot));
      key.grain        = layout.field(slot);
      key.face         = face;
      const auto found = std::lower_bound(entries.begin(), entries.end(), key);
      return (found != entries.end() && !(key < *found)) ? &*found : nullptr;
    };
    bool any_active = false;
    for (unsigned int s = 0; s < status.slot_state.size(); ++s)
      if (const Entry *entry = find(s, contact_face))
        {
          status.slot_state[s]      = entry->state;
          status.slip_directions[s] = entry->slip_direction;
          any_active                = true;
        }
    for (unsigned int w = 0; w < status.wall_slots.size(); ++w)
      if (const Entry *entry = find(status.wall_slots[w], status.wall_faces[w]))
        {
          status.wall_state[w]           = entry->state;
          status.wall_slip_directions[w] = entry->slip_direction;
          any_active                     = true;
        }
    status.any_active = any_active;
    status.decided    = true;
  }



  template class HeldContactStatus<2>;
  template class HeldContactStatus<3>;
} // namespace grainmpm
