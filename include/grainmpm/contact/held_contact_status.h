// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_contact_held_contact_status_h
#define grainmpm_contact_held_contact_status_h

#include <grainmpm/base/config.h>
#include <grainmpm/contact/contact_status.h>
#include <grainmpm/grid/background_grid.h>

#include <deal.II/base/tensor.h>

#include <boost/serialization/array.hpp>
#include <boost/serialization/vector.hpp>

#include <array>
#include <vector>

namespace grainmpm
{
  /**
   * The held entries of the contact status that an implicit step converged
   * to, kept for the first decision of the next step: contact slots by
   * (node, grain) and wall entries by (node, grain, face), with their
   * state and slip direction. The slots of a step are numbered anew
   * (GrainFieldLayout), so the nodes are named by their lattice index,
   * which neither the slot numbering nor a repartition of the cells
   * changes. Every rank holds all entries, in one order, so that a
   * checkpoint written by rank 0 keeps them and any partition can start
   * from them.
   */
  template <int dim>
  class HeldContactStatus
  {
  public:
    /** One held entry. */
    struct Entry
    {
      /** Lattice index of the node (BackgroundGrid::node_lattice_index()). */
      std::array<int, dim> node;
      /** The grain of the slot. */
      unsigned int grain;
      /** The closed face of a wall entry; contact_face for a contact slot. */
      unsigned char  face;
      ContactState   state;
      Tensor<1, dim> slip_direction;

      /** The order of the key (node, grain, face). */
      bool
      operator<(const Entry &other) const;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int /*version*/)
      {
        unsigned char state_number = static_cast<unsigned char>(state);
        archive &node &grain &face &state_number &slip_direction;
        state = static_cast<ContactState>(state_number);
      }
    };

    /** The face number of an entry that is a contact slot. */
    static constexpr unsigned char contact_face = 255;

    /**
     * Keep the entries of @p status that are not free (the owned slots of
     * @p layout on @p grid), from all ranks.
     */
    void
    record(const ContactStatus<dim>    &status,
           const GrainFieldLayout<dim> &layout,
           const BackgroundGrid<dim>   &grid);

    /**
     * Set the entries of @p status (sized for @p layout by
     * ContactStatus::reinit(), every entry free) that are kept here to
     * their kept state and slip direction, and mark the status decided:
     * the next decision starts from it as from one taken before in the
     * step. Without any entry kept @p status is left undecided.
     */
    void
    apply(ContactStatus<dim>          &status,
          const GrainFieldLayout<dim> &layout,
          const BackgroundGrid<dim>   &grid) const;

    /**
     * Forget the entries: the next step decides its status afresh (as the
     * first step of a run does).
     */
    void
    clear()
    {
      entries.clear();
    }

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &entries;
    }

  private:
    /** The entries, sorted by key, the same on every rank. */
    std::vector<Entry> entries;
  };
} // namespace grainmpm

#endif
