// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The jammed stack of the implicit contact tests: nine disks (R = 0.1,
// 6.4 cells per radius) stacked three by three on the floor, against the
// left wall and touching each other, Coulomb friction 0.3, compressed by a
// rigid platen (grain 10) that starts 0.2 cells above the top row and
// moves down, by default at V = 0.037 (V / c = 1e-3) to t = 0.3 (0.7 cells
// of travel). The slow approach starts with the platen touching the top
// row (its contact is the rectangle's exact face, which the top disks'
// points, reaching 0.1 cells above their circles, meet at once).

#ifndef grainmpm_tests_implicit_jammed_stack_h
#define grainmpm_tests_implicit_jammed_stack_h

#include <sstream>
#include <string>

/**
 * The parameter text of the stack, with @p time_stepping (lines of the
 * subsection Time stepping) added, the platen (centred at height
 * @p platen_centre) moving down at @p platen_speed to @p end_time.
 */
inline std::string
stack_case(const std::string &time_stepping,
           const std::string &platen_speed  = "0.037",
           const std::string &end_time      = "0.3",
           const std::string &platen_centre = "0.633125")
{
  std::ostringstream prm;
  prm << "set Dimension = 2\n"
      << "subsection Background grid\n"
      << "  set Lower corner = 0, 0\n  set Upper corner = 0.625, 0.75\n"
      << "  set Number of cells = 40, 48\n"
      << "  set Boundary conditions = x-: free slip, x+: free slip, "
      << "y-: free slip, y+: open\nend\n"
      << "subsection Physics\n  set Gravity = 0, 0\nend\n"
      << "subsection Materials\n  subsection elastic\n"
      << "    set Constitutive model = linear elastic\n"
      << "    set Density = 1\n    set Young's modulus = 1000\n"
      << "    set Poisson's ratio = 0.3\n  end\nend\n"
      << "subsection Grains\n";
  unsigned int k = 0;
  for (const double y : {0.1, 0.3, 0.5})
    for (const double x : {0.1, 0.3, 0.5})
      prm << "  subsection Disk " << ++k << "\n    set Shape = disk\n"
          << "    set Centre = " << x << ", " << y << "\n"
          << "    set Radius = 0.1\n    set Material = elastic\n  end\n";
  prm << "  subsection Platen\n    set Shape = rectangle\n"
      << "    set Centre = 0.3125, " << platen_centre
      << "\n    set Size = 0.625, 0.06\n"
      << "    set Material = elastic\n    set Rigid = true\n"
      << "    set Prescribed velocity = 0; -" << platen_speed
      << "\n  end\nend\n"
      << "subsection Contact\n  set Contact model = Coulomb friction\n"
      << "  set Friction coefficient = 0.3\nend\n"
      << "subsection Time stepping\n  set End time = " << end_time << "\n"
      << time_stepping << "end\n"
      << "subsection Linear solver\n  set Preconditioner = AMG\nend\n";
  return prm.str();
}

/**
 * The slow approach of the stack: the platen, touching the top row, at
 * V / c = 1e-5 (V = 3.7e-4) to t = 1.4, 0.03 cells of travel, with
 * @p time_stepping.
 */
inline std::string
slow_stack_case(const std::string &time_stepping)
{
  return stack_case(time_stepping, "0.00037", "1.4", "0.63");
}

/** The explicit stable step of the stack at CFL 0.25, 0.25 h / c. */
constexpr double stack_explicit_step = 1.0647e-4;

/**
 * The lines of the subsection Time stepping of the explicit reference
 * runs: the leapfrog, update stress last, at CFL 0.25.
 */
inline std::string
stack_explicit_reference()
{
  return "  set Scheme = explicit leapfrog\n"
         "  set Stress update = USL\n"
         "  set CFL number = 0.25\n";
}

#endif
