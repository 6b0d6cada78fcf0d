// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/postprocess/output_writer.h>
#include <grainmpm/postprocess/particle_fields.h>

#include <deal.II/base/data_out_base.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/vector.h>

#include <deal.II/numerics/data_out.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace grainmpm
{
  namespace
  {
    /**
     * Point patches of the material points with the fields we want, in the
     * manner of Particles::DataOut but with derived quantities.
     */
    template <int dim>
    class ParticlePatches : public DataOutInterface<0, dim>
    {
    public:
      void
      build(const Particles::ParticleHandler<dim> &particle_handler,
            const std::vector<double>             &fringe_factors)
      {
        using Layout = MaterialPointLayout<dim>;
        const std::vector<ParticleField<dim>> &fields = particle_fields<dim>();
        names.clear();
        ranges.clear();
        for (const ParticleField<dim> &field : fields)
          {
            if (field.n_components > 1)
              ranges.emplace_back(names.size(),
                                  names.size() + field.n_components - 1,
                                  field.name,
                                  field.interpretation);
            for (unsigned int c = 0; c < field.n_components; ++c)
              names.push_back(field.name);
          }

        patches.clear();
        patches.resize(particle_handler.n_locally_owned_particles());
        unsigned int i = 0;
        for (const auto &particle : particle_handler)
          {
            auto &patch       = patches[i];
            patch.vertices[0] = particle.get_location();
            patch.patch_index = i;
            patch.data.reinit(names.size(), 1);
            const auto                   properties = particle.get_properties();
            const MaterialPointView<dim> point      = {
              properties,
              particle.get_id(),
              Layout::get_stress(properties),
              fringe_factors[Layout::get_grain(properties)]};
            std::vector<double> values;
            unsigned int        c = 0;
            for (const ParticleField<dim> &field : fields)
              {
                values.resize(field.n_components);
                field.evaluate(point, values.data());
                for (const double value : values)
                  patch.data(c++, 0) = value;
              }
            ++i;
          }
      }

    private:
      const std::vector<DataOutBase::Patch<0, dim>> &
      get_patches() const override
      {
        return patches;
      }

      std::vector<std::string>
      get_dataset_names() const override
      {
        return names;
      }

      std::vector<
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>>
      get_nonscalar_data_ranges() const override
      {
        return ranges;
      }

      std::vector<DataOutBase::Patch<0, dim>> patches;
      std::vector<std::string>                names;
      std::vector<
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>>
        ranges;
    };



    /**
     * Write the record file @p filename on rank 0 of @p communicator: to a
     * temporary name, renamed when complete, so that a run stopped at any
     * moment leaves the previous record intact. A failed write is an error
     * on every rank, naming the file. Collective.
     */
    void
    write_pvd(const std::string                                 &filename,
              const std::vector<std::pair<double, std::string>> &records,
              const MPI_Comm                                     communicator)
    {
      std::string error;
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          const std::string temporary = filename + ".tmp";
          bool              written   = false;
          try
            {
              std::ofstream out(temporary);
              if (out)
                {
                  // Throws ExcIO if the stream fails while writing.
                  DataOutBase::write_pvd_record(out, records);
                  out.close();
                  written = !out.fail();
                }
            }
          catch (const ExceptionBase &)
            {}
          if (!written)
            error = "could not write '" + temporary +
                    "' (disk full, or no permission?); '" + filename +
                    "' is left as it was.";
          std::error_code code;
          if (error.empty())
            std::filesystem::rename(temporary, filename, code);
          if (code)
            error = "could not rename '" + temporary + "' to '" + filename +
                    "': " + code.message() + ".";
        }
      throw_on_all_ranks(error.empty() ?
                           error :
                           InputError("Output/Output directory", error).what(),
                         communicator);
    }



    /**
     * Call @p write, which writes the .vtu files of one output (each rank
     * its own) and the .pvtu record (rank 0), and turn a failed write on
     * any rank into an error on every rank that names the files: deal.II
     * throws ExcIO, whose text does not say which file. Collective.
     */
    template <typename Write>
    std::string
    write_vtu_files(const std::string &directory,
                    const std::string &what,
                    const MPI_Comm     communicator,
                    const Write       &write)
    {
      std::string name, error;
      try
        {
          name = write();
        }
      catch (const std::exception &)
        {
          error = "could not write the " + what + " files of this output in '" +
                  directory + "' (disk full, or no permission?); the record " +
                  "file lists the outputs before it.";
        }
      throw_on_all_ranks(error.empty() ?
                           error :
                           InputError("Output/Output directory", error).what(),
                         communicator);
      return name;
    }
  } // namespace



  template <int dim>
  OutputWriter<dim>::OutputWriter(const OutputParameters    &parameters,
                                  const BackgroundGrid<dim> &grid,
                                  const std::vector<double> &fringe_factors)
    : parameters(parameters)
    , grid(grid)
    , fringe_factors(fringe_factors)
    , vector_fe(FE_Q<dim>(1), dim)
    , vector_dof_handler(grid.get_triangulation())
  {
    vector_dof_handler.distribute_dofs(vector_fe);
    const MPI_Comm communicator = grid.get_triangulation().get_communicator();
    std::string    error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      for (const std::string name : {"particles", "grid", "contacts"})
        if (name == "particles" ? parameters.write_particles :
            name == "grid"      ? parameters.write_grid :
                                  parameters.write_contacts)
          {
            const std::string path = parameters.directory + "/" + name;
            std::error_code   code;
            std::filesystem::create_directories(path, code);
            if (code || !std::filesystem::is_directory(path))
              error =
                InputError("Output/Output directory = " + parameters.directory,
                           "cannot create the directory '" + path + "' (" +
                             (code ? code.message() :
                                     std::string("a file has its name")) +
                             ").")
                  .what();
          }
    throw_on_all_ranks(error, communicator);
  }



  template <int dim>
  void
  OutputWriter<dim>::write_particles(
    const Particles::ParticleHandler<dim> &particle_handler,
    const double                           time,
    const unsigned int                     index)
  {
    ParticlePatches<dim> patches;
    patches.build(particle_handler, fringe_factors);
    DataOutBase::VtkFlags flags;
    flags.time  = time;
    flags.cycle = index;
    patches.set_flags(flags);
    const MPI_Comm communicator = grid.get_triangulation().get_communicator();
    const std::string name      = write_vtu_files(
      parameters.directory + "/particles", "particle", communicator, [&]() {
        return patches.write_vtu_with_pvtu_record(parameters.directory +
                                                    "/particles/",
                                                  "particles",
                                                  index,
                                                  communicator,
                                                  5,
                                                  8);
      });
    particle_records.emplace_back(time, "particles/" + name);
    write_pvd(parameters.directory + "/particles.pvd",
              particle_records,
              grid.get_triangulation().get_communicator());
  }



  template <int dim>
  void
  OutputWriter<dim>::write_grid(const TimeIntegrator<dim> &stepper,
                                const double               time,
                                const unsigned int         index)
  {
    const auto &layout     = stepper.get_layout();
    const auto &masses     = stepper.get_masses();
    const auto &velocities = stepper.get_velocities();
    const auto &contact    = stepper.get_node_contact_flags();
    const auto &nodes      = *grid.node_partitioner();
    using NodeVector       = LinearAlgebra::distributed::Vector<double>;

    // Nodal sums over the slots of each owned node (the owner has all the
    // slots of its nodes), then copied to the ghost nodes.
    NodeVector              nodal_mass(grid.node_partitioner());
    NodeVector              n_grains(grid.node_partitioner());
    NodeVector              contact_flag(grid.node_partitioner());
    std::vector<NodeVector> momentum(dim, nodal_mass);
    for (unsigned int node = 0; node < layout.n_nodes(); ++node)
      {
        for (unsigned int s = layout.node_slots_begin(node);
             s < layout.node_slots_end(node);
             ++s)
          {
            nodal_mass.local_element(node) += masses.local_element(s);
            for (unsigned int d = 0; d < dim; ++d)
              momentum[d].local_element(node) +=
                masses.local_element(s) * velocities.local_element(s * dim + d);
          }
        n_grains.local_element(node) =
          layout.node_slots_end(node) - layout.node_slots_begin(node);
        contact_flag.local_element(node) = contact[node];
      }
    for (NodeVector *vector : {&nodal_mass, &n_grains, &contact_flag})
      vector->update_ghost_values();
    for (auto &vector : momentum)
      vector.update_ghost_values();

    // Centre-of-mass velocity on the vector-valued Q1 DoFs of the owned
    // cells (renumbered here: the cells may have been repartitioned).
    vector_dof_handler.distribute_dofs(vector_fe);
    Vector<double> velocity(vector_dof_handler.n_dofs());
    auto           scalar_cell = grid.get_dof_handler().begin_active();
    for (const auto &cell : vector_dof_handler.active_cell_iterators())
      {
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            {
              const unsigned int node =
                nodes.global_to_local(scalar_cell->vertex_dof_index(v, 0));
              const double mass = nodal_mass.local_element(node);
              if (mass > 0.)
                for (unsigned int d = 0; d < dim; ++d)
                  velocity[cell->vertex_dof_index(v, d)] =
                    momentum[d].local_element(node) / mass;
            }
        ++scalar_cell;
      }

    DataOut<dim> data_out;
    data_out.attach_triangulation(grid.get_triangulation());
    data_out.add_data_vector(grid.get_dof_handler(), nodal_mass, "nodal_mass");
    data_out.add_data_vector(grid.get_dof_handler(),
                             n_grains,
                             "number_of_grains");
    data_out.add_data_vector(grid.get_dof_handler(), contact_flag, "contact");
    data_out.add_data_vector(
      vector_dof_handler,
      velocity,
      std::vector<std::string>(dim, "centre_of_mass_velocity"),
      std::vector<DataComponentInterpretation::DataComponentInterpretation>(
        dim, DataComponentInterpretation::component_is_part_of_vector));
    data_out.build_patches();
    DataOutBase::VtkFlags flags;
    flags.time  = time;
    flags.cycle = index;
    data_out.set_flags(flags);
    const MPI_Comm communicator = grid.get_triangulation().get_communicator();
    const std::string name      = write_vtu_files(
      parameters.directory + "/grid", "grid", communicator, [&]() {
        return data_out.write_vtu_with_pvtu_record(
          parameters.directory + "/grid/", "grid", index, communicator, 5, 8);
      });
    grid_records.emplace_back(time, "grid/" + name);
    write_pvd(parameters.directory + "/grid.pvd",
              grid_records,
              grid.get_triangulation().get_communicator());
  }



  template <int dim>
  void
  OutputWriter<dim>::write_contacts(
    const std::vector<GrainContactForce<dim>> &forces,
    const std::vector<GrainMotion<dim>>       &motions,
    const std::vector<bool>                   &rigid,
    const double                               time,
    const unsigned int                         index)
  {
    const MPI_Comm communicator = grid.get_triangulation().get_communicator();
    const std::string name =
      "contacts_" + Utilities::int_to_string(index, 5) + ".vtu";
    const std::string path = parameters.directory + "/contacts/" + name;
    write_vtu_files(
      parameters.directory + "/contacts", "contact", communicator, [&]() {
        if (Utilities::MPI::this_mpi_process(communicator) != 0)
          return name;
        // A line per contact, its forces as cell data: the
        // few numbers are written as text.
        std::ofstream out(path);
        out << std::setprecision(9)
            << "<?xml version=\"1.0\"?>\n"
               "<VTKFile type=\"UnstructuredGrid\" "
               "version=\"0.1\" byte_order=\"LittleEndian\">\n"
               "<UnstructuredGrid>\n<FieldData>\n"
               "<DataArray type=\"Float64\" Name=\"TIME\" "
               "NumberOfTuples=\"1\" format=\"ascii\">"
            << time
            << "</DataArray>\n</FieldData>\n"
               "<Piece NumberOfPoints=\""
            << 2 * forces.size() << "\" NumberOfCells=\"" << forces.size()
            << "\">\n<Points>\n<DataArray type=\"Float64\" "
               "NumberOfComponents=\"3\" format=\"ascii\">\n";
        for (const auto &force : forces)
          {
            const bool        a_rigid = rigid[force.grain_a];
            const bool        b_rigid = rigid[force.grain_b];
            const Point<dim> &start   = a_rigid ?
                                          force.contact_point :
                                          motions[force.grain_a].centre_of_mass;
            const Point<dim> &end     = b_rigid ?
                                          force.contact_point :
                                          motions[force.grain_b].centre_of_mass;
            for (const Point<dim> *p : {&start, &end})
              for (unsigned int d = 0; d < 3; ++d)
                out << (d < dim ? (*p)[d] : 0.) << (d < 2 ? ' ' : '\n');
          }
        out << "</DataArray>\n</Points>\n<Cells>\n"
               "<DataArray type=\"Int64\" Name=\"connectivity\" "
               "format=\"ascii\">\n";
        for (unsigned int c = 0; c < forces.size(); ++c)
          out << 2 * c << ' ' << 2 * c + 1 << '\n';
        out << "</DataArray>\n<DataArray type=\"Int64\" "
               "Name=\"offsets\" format=\"ascii\">\n";
        for (unsigned int c = 0; c < forces.size(); ++c)
          out << 2 * c + 2 << '\n';
        out << "</DataArray>\n<DataArray type=\"UInt8\" "
               "Name=\"types\" format=\"ascii\">\n";
        for (unsigned int c = 0; c < forces.size(); ++c)
          out << "3\n";
        out << "</DataArray>\n</Cells>\n"
               "<CellData Scalars=\"normal_force\">\n";
        const auto write_field = [&](const char *field, const auto &value) {
          out << "<DataArray type=\"Float64\" Name=\"" << field
              << "\" format=\"ascii\">\n";
          for (const auto &force : forces)
            out << value(force) << '\n';
          out << "</DataArray>\n";
        };
        using Force = GrainContactForce<dim>;
        write_field("normal_force",
                    [](const Force &f) { return f.normal_force; });
        write_field("tangential_force",
                    [](const Force &f) { return f.tangential_force; });
        write_field("force_magnitude",
                    [](const Force &f) { return f.force.norm(); });
        write_field("mobilised_friction",
                    [](const Force &f) { return f.mobilised_friction; });
        write_field("slip_share", [](const Force &f) { return f.slip_share; });
        write_field("grain_a", [](const Force &f) { return f.grain_a + 1.; });
        write_field("grain_b", [](const Force &f) { return f.grain_b + 1.; });
        out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n"
               "</VTKFile>\n";
        out.close();
        if (!out)
          throw std::runtime_error("write failed");
        return name;
      });
    contact_records.emplace_back(time, "contacts/" + name);
    write_pvd(parameters.directory + "/contacts.pvd",
              contact_records,
              communicator);
  }



  template class OutputWriter<2>;
  template class OutputWriter<3>;
} // namespace grainmpm
