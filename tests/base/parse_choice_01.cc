// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// parse_choice(): every choice entry is converted to its enum by check(),
// and a text that is none of the choices (possible when the text is set in
// code, past the Patterns::Selection of the parameter file) is rejected
// with an InputError that names the entry and lists the choices, instead
// of silently becoming a default.

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/base/parameters.h>
#include <grainmpm/materials/von_mises.h>

#include <deal.II/base/mpi.h>

#include "../tests.h"

using namespace grainmpm;

template <typename SubsectionParameters>
void
check(const std::string &name, SubsectionParameters parameters)
{
  try
    {
      parameters.check();
      deallog << name << ": accepted" << std::endl;
    }
  catch (const InputError &error)
    {
      deallog << name << ": " << error.what() << std::endl;
    }
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  enum class Colour
  {
    red,
    green,
    blue
  };
  const std::vector<std::pair<std::string, Colour>> colours = {
    {"red", Colour::red}, {"green", Colour::green}, {"blue", Colour::blue}};
  deallog << "green: "
          << static_cast<int>(
               parse_choice<Colour>("Colour = green", "green", colours))
          << std::endl;
  try
    {
      parse_choice<Colour>("Colour = Green", "Green", colours);
    }
  catch (const InputError &error)
    {
      deallog << error.what() << std::endl;
    }
  try
    {
      parse_choice<Colour>("Colour = grey", "grey", colours, "not a colour.");
    }
  catch (const InputError &error)
    {
      deallog << error.what() << std::endl;
    }

  // The defaults and the other choice of every choice entry.
  {
    ContactParameters contact;
    contact.check();
    deallog << "contact model: " << static_cast<int>(contact.model);
    contact.model_text = "none";
    contact.check();
    deallog << ", " << static_cast<int>(contact.model) << std::endl;
  }
  {
    TimeSteppingParameters time_stepping;
    time_stepping.check();
    deallog << "scheme, stress update, velocity update, FLIP fraction: "
            << static_cast<int>(time_stepping.scheme) << ' '
            << static_cast<int>(time_stepping.stress_update) << ' '
            << static_cast<int>(time_stepping.velocity_update) << ' '
            << time_stepping.flip_fraction;
    time_stepping.stress_update_text   = "MUSL";
    time_stepping.velocity_update_text = "PIC";
    time_stepping.check();
    deallog << "; " << static_cast<int>(time_stepping.scheme) << ' '
            << static_cast<int>(time_stepping.stress_update) << ' '
            << static_cast<int>(time_stepping.velocity_update) << ' '
            << time_stepping.flip_fraction << std::endl;
  }
  {
    NonlinearSolverParameters nonlinear;
    nonlinear.check();
    deallog << "residual scale, forcing, differencing: "
            << static_cast<int>(nonlinear.residual_scale) << ' '
            << static_cast<int>(nonlinear.forcing) << ' '
            << nonlinear.eisenstat_walker << ' '
            << static_cast<int>(nonlinear.differencing);
    nonlinear.residual_scale_text = "physical";
    nonlinear.forcing_text        = "constant";
    nonlinear.differencing_text   = "Knoll-Keyes";
    nonlinear.check();
    deallog << "; " << static_cast<int>(nonlinear.residual_scale) << ' '
            << static_cast<int>(nonlinear.forcing) << ' '
            << nonlinear.eisenstat_walker << ' '
            << static_cast<int>(nonlinear.differencing) << std::endl;
  }
  {
    LinearSolverParameters linear;
    linear.check();
    deallog << "solver, preconditioner: " << static_cast<int>(linear.solver)
            << ' ' << linear.flexible << ' '
            << static_cast<int>(linear.preconditioner) << ' '
            << linear.probed_jacobi_at(1.) << linear.assembled_at(1.)
            << linear.probed_jacobi_at(10.) << linear.assembled_at(10.);
    linear.solver_text         = "FGMRES";
    linear.preconditioner_text = "none";
    linear.check();
    deallog << "; " << static_cast<int>(linear.solver) << ' ' << linear.flexible
            << ' ' << static_cast<int>(linear.preconditioner) << ' '
            << linear.probed_jacobi_at(1.) << linear.assembled_at(1.)
            << linear.probed_jacobi_at(10.) << linear.assembled_at(10.)
            << std::endl;
  }
  {
    PhysicsParameters<2> physics;
    physics.check();
    deallog << "two-dimensional model: "
            << static_cast<int>(physics.two_dimensional_model);
    physics.two_dimensional_model_text = "plane stress";
    physics.check();
    deallog << ", " << static_cast<int>(physics.two_dimensional_model)
            << std::endl;
  }
  {
    MaterialParameters material;
    material.name = "steel";
    material.check();
    deallog << "constitutive model: " << material.constitutive_model;
    material.constitutive_model = "von Mises";
    material.get_model_parameters<VonMisesParameters>("von Mises")
      .yield_stress = 1.;
    material.check();
    deallog << ", " << material.constitutive_model << std::endl;
  }

  // Unknown texts.
  {
    ContactParameters contact;
    contact.model_text = "sticky";
    check("contact", contact);
  }
  {
    TimeSteppingParameters time_stepping;
    time_stepping.scheme_text = "implicit Euler";
    check("scheme", time_stepping);
    time_stepping                    = TimeSteppingParameters();
    time_stepping.stress_update_text = "USLX";
    check("stress update", time_stepping);
    time_stepping                      = TimeSteppingParameters();
    time_stepping.velocity_update_text = "APIC";
    check("velocity update", time_stepping);
  }
  {
    NonlinearSolverParameters nonlinear;
    nonlinear.residual_scale_text = "relative";
    check("residual scale", nonlinear);
    nonlinear              = NonlinearSolverParameters();
    nonlinear.forcing_text = "Eisenstat Walker";
    check("forcing term", nonlinear);
    nonlinear                   = NonlinearSolverParameters();
    nonlinear.differencing_text = "Brown-Saad";
    check("differencing step", nonlinear);
  }
  {
    LinearSolverParameters linear;
    linear.solver_text = "BiCGStab";
    check("solver", linear);
    linear                     = LinearSolverParameters();
    linear.preconditioner_text = "ILU";
    check("preconditioner", linear);
  }
  {
    PhysicsParameters<2> physics;
    physics.two_dimensional_model_text = "axisymmetric";
    check("two-dimensional model", physics);
  }
  {
    MaterialParameters material;
    material.name               = "steel";
    material.constitutive_model = "Drucker-Prager";
    check("constitutive model", material);
  }
  {
    BackgroundGridParameters<2> grid;
    grid.boundary_conditions_text = "x-: sticky";
    check("boundary type", grid);
    grid.boundary_conditions_text = "z-: open";
    check("face", grid);
  }
  {
    GrainParameters<3> grain;
    grain.shape_text = "cube";
    try
      {
        grain.check("Grains/Grain 1/");
      }
    catch (const InputError &error)
      {
        deallog << "shape: " << error.what() << std::endl;
      }
  }
}
