// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_parsing.h>
#include <grainmpm/time_integration/time_stepping_parameters.h>

#include <deal.II/base/patterns.h>

#include <limits>
#include <sstream>

namespace grainmpm
{
  // ------------------------------------------------------- time stepping

  void
  TimeSteppingParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    prm.add_parameter(
      "Scheme",
      scheme_text,
      "The time integration scheme: 'explicit leapfrog' (eqs. 7-10 of "
      "Cummins & Brackbill) or 'implicit theta' (eqs. 11-20: theta-centred "
      "stress and volume, solved by Jacobian-free Newton-Krylov; see the "
      "subsections Nonlinear solver and Linear solver). Dimensionless.",
      Patterns::Selection("explicit leapfrog|implicit theta"));
    prm.add_parameter(
      "Theta",
      theta,
      "Centring of the implicit scheme: stress and volume at t + theta dt. "
      "1/2 conserves the energy of linear elastic motion, larger values "
      "damp the highest frequencies, 1 is backward Euler. Dimensionless.",
      Patterns::Double(0.5, 1.));
    prm.add_parameter(
      "Mass scaling",
      mass_scaling,
      "Mass (density) scaling for slow, quasi-static loading: the density "
      "of every material is multiplied by this factor alpha and gravity is "
      "divided by it, so that weights and stresses at equilibrium are "
      "unchanged while the wave speed falls by sqrt(alpha) and the CFL "
      "step grows by sqrt(alpha). The inertia forces grow by alpha: the "
      "results stay those of the physical material only while the loading "
      "stays quasi-static with the scaled density, i.e. while the inertial "
      "number I = (strain rate) d / sqrt(P / (alpha rho)) written in "
      "walls.csv for each moving rigid grain stays below about 1e-3 "
      "(doc/theory.md). The masses, momenta and kinetic energies written "
      "are those of the scaled densities. A run resumed from a checkpoint "
      "may use another factor than the checkpoint's: the points' masses "
      "are then multiplied by the ratio, their velocities kept or scaled "
      "(Checkpoint/Scale velocities with the mass), and the ledger's "
      "reference moves with the kinetic energy that changes. 1 means no "
      "scaling. Dimensionless.",
      Patterns::Double(1.));
    prm.add_parameter(
      "Minimum time step",
      minimum_time_step,
      "Implicit scheme: a step whose Newton solve fails is retried with "
      "half the time step, down to this value; below it the run stops. "
      "Zero means 1/1024 of the first time step. Units: time.",
      Patterns::Double(0.));
    prm.add_parameter(
      "Adaptive time stepping",
      adaptive_time_stepping,
      "Implicit scheme: halve the time step when a Newton solve fails, "
      "and grow a cut step back by min(2, N_t / N) (up to the step given "
      "by Time step or CFL number) after Steps before growth consecutive "
      "steps that needed N <= N_t Newton iterations, N_t half of Maximum "
      "Newton iterations. If false, a failed solve stops the run.");
    prm.add_parameter(
      "Steps before growth",
      steps_before_growth,
      "Implicit scheme: consecutive steps that converge in at most half of "
      "Maximum Newton iterations before a cut time step grows. "
      "Dimensionless.",
      Patterns::Integer(1));
    prm.add_parameter(
      "Maximum time step",
      maximum_time_step,
      "Implicit scheme with Adaptive time stepping: the steps grow beyond "
      "the step of Time step or CFL number (the nominal step), up to this "
      "value, by the same rule as a cut step grows back (min(2, N_t / N) "
      "after Steps before growth easy steps), as long as no material point "
      "moves more than Maximum displacement per step in a step and the "
      "step error stays within Step error tolerance; a grown step that "
      "creates more than Energy error per step, or loses more than it to "
      "the normal contact reactions, or fails, is halved. For slow, "
      "quasi-static loading, where the nominal step of the wave speed is "
      "far smaller than what the loading needs (doc/theory.md section 12). "
      "Zero means Maximum CFL number times h / c. Units: time.",
      Patterns::Double(0.));
    prm.add_parameter(
      "Maximum CFL number",
      maximum_cfl_number,
      "Implicit scheme with Adaptive time stepping and Maximum time step = "
      "0: the largest step is this number times h / c (h the smallest cell "
      "size, c the largest dilatational wave speed of the materials), "
      "i.e. this number times the stability limit of the explicit "
      "leapfrog with the material at rest. The bounds of Maximum time step "
      "size the steps below it: they stay at the nominal step (Time step, "
      "or CFL number) while grains move fast or vibrate, and grow where the "
      "loading is slow. The default, 250, allows a thousand explicit steps "
      "at CFL 0.25 in one implicit step. 0, or a value at most the CFL "
      "number, means no growth: every step is the nominal one unless a "
      "failed solve cuts it. Dimensionless.",
      Patterns::Double(0.));
    prm.add_parameter(
      "Maximum displacement per step",
      maximum_displacement,
      "Implicit scheme, steps grown beyond the nominal step (Maximum CFL "
      "number, Maximum time step): no step is larger than this fraction of "
      "the smallest cell size divided by the largest speed of the grains "
      "at the end of the previous step, so that the steps shrink again, "
      "though never below the nominal step, while grains move fast (a "
      "slip, an impact, a grain falling); where this allows less than "
      "twice the nominal step, the step is the nominal one. The speed of a "
      "grain is that of its rigid-body motion, as grains.csv gives it: "
      "the speed of its centre of mass plus its angular speed times the "
      "largest distance of its points from the centre; the vibration "
      "within a grain does not count. Zero means no such limit. "
      "Dimensionless.",
      Patterns::Double(0.));
    prm.add_parameter(
      "Energy error per step",
      energy_error,
      "Implicit scheme with steps grown beyond the nominal one (Maximum "
      "CFL number, Maximum time step): a step longer than the nominal one (that of Time step, or of CFL number with the material "
      "at rest) whose grid step creates more energy than this fraction of "
      "the grid energy (the "
      "change of the kinetic plus elastic energy of the deformable grains "
      "on the grid, plus the friction and plastic work, minus the work of "
      "rigid grains and walls; theta = 1/2 conserves it for elastic motion "
      "with contact that holds), or whose normal contact reactions take "
      "more than this fraction out of it (a step that stops a whole impact "
      "at once), is rejected and retried with half the step, as a step "
      "whose Newton solve fails. Large steps over a change of the contacts "
      "can create energy that the Newton tolerance does not see, and steps "
      "longer than a collision make it inelastic; this check makes the "
      "steps shrink there. Zero means no such check. Dimensionless.",
      Patterns::Double(0.));
    prm.add_parameter(
      "Step error tolerance",
      step_error_tolerance,
      "Implicit scheme with steps grown beyond the nominal one (Maximum "
      "CFL number, Maximum time step): the relative error per step "
      "that sizes the grown steps. The error of a step is estimated from "
      "how the accelerations of the material points change from one step "
      "to the next (Zienkiewicz & Xie 1991: dt^2 / 12 times the change, "
      "against the displacement of the step, mass-weighted over the "
      "deformable points), and the next step is dt sqrt(tolerance / "
      "error), between half and twice dt, never below the nominal step, "
      "besides the other bounds. The steps then stay short where grains "
      "vibrate or hit and grow where the loading is slow and smooth; "
      "smaller values follow the dynamics more closely (doc/theory.md "
      "section 12). Zero means no such bound. Dimensionless.",
      Patterns::Double(0., 1.));
    prm.add_parameter(
      "Quasi-static theta",
      quasi_static_theta,
      "Implicit scheme with steps grown beyond the nominal one (Maximum "
      "CFL number, Maximum time step): the centring of a step that follows "
      "a quasi-static step, one whose grid kinetic energy is at most 1 % of "
      "the elastic energy of the deformable grains at both of its ends; "
      "such a step uses the larger of Theta and this value. At Theta = 1/2 "
      "the grains of a slowly loaded packing keep vibrating on their "
      "contacts, which holds the steps near the period of that vibration "
      "and lets long steps create energy; the damping of theta above 1/2 "
      "takes that vibration out where the loading is slow, so that the "
      "steps grow, while impacts, free flight and every step that is not "
      "quasi-static keep Theta (doc/theory.md section 12). The energy the "
      "damping takes out is the time integrator's loss, a negative balance "
      "residual of the energy ledger; the column theta of energy.csv gives "
      "the centring of each step. 0, or a value at most Theta, means Theta "
      "in every step. Dimensionless.",
      Patterns::Double(0., 1.));
    prm.add_parameter(
      "Explicit fallback",
      explicit_fallback,
      "Implicit scheme with Adaptive time stepping: a step whose Newton "
      "solve still fails when halving it would take it below the stable "
      "step of the explicit leapfrog, h / (c + max |v_p|), or below "
      "Minimum time step, is advanced by explicit leapfrog sub-steps "
      "(a step grown beyond the nominal step, Maximum CFL number, is "
      "retried implicitly at half its length first) "
      "(Stress update = USL, lumped mass, a quarter of the stable step "
      "each, the same contact law) over the interval of the failed step, "
      "and the implicit steps resume from there, grown back as after a "
      "cut step. The implicit run then gets through every event the "
      "explicit one gets through. If false, such a step stops the run.");
    prm.add_parameter(
      "Stress update",
      stress_update_text,
      "Where in the explicit step the stress is updated: 'USF' (update "
      "stress first, from the grid velocity of the particle-to-grid "
      "transfer, as in eqs. 8-9 of Cummins & Brackbill), 'MUSL' (after "
      "the particle update, from the grid velocity remapped from the new "
      "particle momenta) or 'USL' (after the grid update, from the "
      "contact- and wall-constrained new grid velocity, the one that also "
      "moves the particles: a contact or wall reaction then does no work "
      "on the strain, and grains in sustained contact do not gain energy, "
      "which they do with USF and MUSL; doc/validation.md). Dimensionless.",
      Patterns::Selection("USF|MUSL|USL"));
    prm.add_parameter("End time",
                      end_time,
                      "The time at which the run stops. Units: time.",
                      Patterns::Double(0.));
    prm.add_parameter("Time step",
                      time_step,
                      "A fixed time step. If zero, the step is chosen every "
                      "step from the CFL number. For the explicit leapfrog "
                      "at most h / c (see CFL number). Units: time.",
                      Patterns::Double(0.));
    prm.add_parameter(
      "CFL number",
      cfl_number,
      "Used when Time step is zero: dt = CFL h / (c + max |v_p|) with h the "
      "smallest cell size, c the largest dilatational wave speed of the "
      "materials in use and v_p the particle velocities. At most 1 for the "
      "explicit leapfrog (its stability limit; 0.25 is typical). "
      "Dimensionless.",
      Patterns::Double(0., 10.));
    prm.add_parameter(
      "Particle velocity update",
      velocity_update_text,
      "How particles get their new velocity from the grid: 'FLIP' (add the "
      "grid velocity change), 'PIC' (take the grid velocity) or 'blend' "
      "(FLIP fraction alpha of FLIP, 1 - alpha of PIC). Dimensionless.",
      Patterns::Selection("FLIP|PIC|blend"));
    prm.add_parameter("FLIP fraction",
                      flip_fraction,
                      "The FLIP weight alpha of the 'blend' update. "
                      "Dimensionless.",
                      Patterns::Double(0., 1.));
    prm.add_parameter(
      "Mass matrix",
      mass_matrix_text,
      "The grid mass matrix M of the momentum balance, of the "
      "particle-to-grid velocity (M v = p) and of the kinetic energy "
      "1/2 v.M v. 'lumped': the diagonal m_i = sum_p m_p S_ip; 'blended' "
      "(implicit scheme only): (1 - alpha) lumped + alpha consistent, the "
      "consistent mass being sum_p m_p S_ip S_jp (applied matrix-free), "
      "alpha = Consistent mass fraction; it keeps most of the energy that "
      "the lumped mass loses between particles and grid at every step "
      "(doc/theory.md). 'automatic': blended for the implicit scheme, "
      "lumped for the explicit one. Dimensionless.",
      Patterns::Selection("automatic|lumped|blended"));
    prm.add_parameter(
      "Consistent mass fraction",
      consistent_mass_fraction,
      "alpha of the blended mass matrix. The grid-scale modes keep the mass "
      "1 - alpha, and the GMRES iterations per Newton step grow as alpha "
      "approaches 1 (doc/validation.md), so at most 0.95 is offered. "
      "Dimensionless.",
      Patterns::Double(0., 0.95));
    prm.add_parameter("Maximum number of steps",
                      maximum_number_of_steps,
                      "The run stops after this many steps even if End time "
                      "is not reached. Dimensionless.",
                      Patterns::Integer(1));
    prm.leave_subsection();
  }



  void
  TimeSteppingParameters::check()
  {
    scheme = parse_choice<TimeSteppingScheme>(
      "Time stepping/Scheme = " + scheme_text,
      scheme_text,
      {{"explicit leapfrog", TimeSteppingScheme::explicit_leapfrog},
       {"implicit theta", TimeSteppingScheme::implicit_theta}});
    stress_update =
      parse_choice<StressUpdate>("Time stepping/Stress update = " +
                                   stress_update_text,
                                 stress_update_text,
                                 {{"USF", StressUpdate::usf},
                                  {"MUSL", StressUpdate::musl},
                                  {"USL", StressUpdate::usl}});
    if (scheme == TimeSteppingScheme::implicit_theta &&
        stress_update != StressUpdate::usf)
      throw InputError("Time stepping/Stress update = " + stress_update_text,
                       "applies to the explicit scheme only; the implicit "
                       "scheme uses the theta-centred stress of eqs. 12-13. "
                       "Remove the entry or set it to USF.");
    velocity_update =
      parse_choice<VelocityUpdate>("Time stepping/Particle velocity update = " +
                                     velocity_update_text,
                                   velocity_update_text,
                                   {{"FLIP", VelocityUpdate::flip},
                                    {"PIC", VelocityUpdate::pic},
                                    {"blend", VelocityUpdate::blend}});
    if (velocity_update == VelocityUpdate::flip)
      flip_fraction = 1.;
    else if (velocity_update == VelocityUpdate::pic)
      flip_fraction = 0.;
    mass_matrix = parse_choice<MassMatrixType>(
      "Time stepping/Mass matrix = " + mass_matrix_text,
      mass_matrix_text,
      {{"automatic",
        scheme == TimeSteppingScheme::implicit_theta ? MassMatrixType::blended :
                                                       MassMatrixType::lumped},
       {"lumped", MassMatrixType::lumped},
       {"blended", MassMatrixType::blended}});
    if (scheme == TimeSteppingScheme::explicit_leapfrog &&
        mass_matrix == MassMatrixType::blended)
      throw InputError("Time stepping/Mass matrix = blended",
                       "applies to the implicit scheme only; the explicit "
                       "leapfrog uses the lumped mass. Remove the entry or "
                       "set Scheme = implicit theta.");
    if (mass_matrix == MassMatrixType::lumped)
      consistent_mass_fraction = 0.;
    if (maximum_time_step > 0. &&
        (scheme != TimeSteppingScheme::implicit_theta ||
         !adaptive_time_stepping))
      {
        std::ostringstream entry;
        entry << "Time stepping/Maximum time step = " << maximum_time_step;
        throw InputError(entry.str(),
                         "applies to the implicit scheme with Adaptive "
                         "time stepping = true only: the explicit leapfrog "
                         "is bound to its stable step, and without adaptive "
                         "steps the step is fixed. Remove the entry, or set "
                         "Scheme = implicit theta and Adaptive time stepping "
                         "= true.");
      }
    if (maximum_time_step > 0. && maximum_time_step < time_step)
      {
        std::ostringstream entry, message;
        entry << "Time stepping/Maximum time step = " << maximum_time_step;
        message << "is below Time step = " << time_step
                << ", the step it lets grow. Set it above the time step, or "
                   "set it to 0 and Maximum CFL number = 0 for no growth.";
        throw InputError(entry.str(), message.str());
      }
    if (time_step == 0. && cfl_number == 0.)
      throw InputError("Time stepping/CFL number",
                       "must be positive when Time step is zero.");
    if (scheme == TimeSteppingScheme::explicit_leapfrog && time_step == 0. &&
        cfl_number > 1.)
      {
        std::ostringstream entry;
        entry << "Time stepping/CFL number = " << cfl_number;
        throw InputError(entry.str(),
                         "is above 1, the stability limit of the explicit "
                         "leapfrog: its energy grows without bound. Use at "
                         "most 1 (0.25 is typical), or Scheme = implicit "
                         "theta for larger steps.");
      }
  }



  double
  TimeSteppingParameters::largest_time_step(const double minimum_cell_size,
                                            const double wave_speed) const
  {
    if (scheme != TimeSteppingScheme::implicit_theta || !adaptive_time_stepping)
      return 0.;
    if (maximum_time_step > 0.)
      return maximum_time_step;
    return maximum_cfl_number * minimum_cell_size / wave_speed;
  }
} // namespace grainmpm
