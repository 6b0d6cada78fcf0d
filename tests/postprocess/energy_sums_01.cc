// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// The explicit update-stress-first step gathers the sums of energy.csv
// (kinetic and elastic energy, momentum, first moment) in its last pass
// over the particles, instead of a separate pass: they must equal what
// EnergyHistory::compute() finds by visiting the particles after the step.
// A disk shot through the open top face (points removed while the sums are
// gathered; on 2 ranks by one rank only, which made the removal hang
// before it was made collective), a disk thrown at the frictional floor and
// a free-slip side wall, with gravity and Coulomb contact, on 1 and 2 ranks.

#include <grainmpm/postprocess/energy_history.h>
#include <grainmpm/time_integration/explicit_leapfrog.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>

#include "../tests.h"

#include "../implicit/elastic_block.h"
#include "../implicit_fixture.h"

using namespace grainmpm;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_root();

  const std::string      text = R"(
set Dimension = 2
subsection Background grid
  set Number of cells     = 20, 20
  set Boundary conditions = x-: free slip, x+: free slip, y-: friction 0.3, y+: open
end
subsection Physics
  set Gravity = 0, -10
end
subsection Materials
  subsection elastic
    set Density         = 1
    set Young's modulus = 1000
    set Poisson's ratio = 0.3
  end
end
subsection Grains
  subsection Grain 1
    set Shape            = disk
    set Centre           = 0.5, 0.82
    set Radius           = 0.1
    set Material         = elastic
    set Initial velocity = 1; 20
  end
  subsection Grain 2
    set Shape            = disk
    set Centre           = 0.88, 0.2
    set Radius           = 0.12
    set Material         = elastic
    set Initial velocity = 4; -5
  end
end
subsection Contact
  set Contact model        = Coulomb friction
  set Friction coefficient = 0.3
end
subsection Time stepping
  set Scheme        = explicit leapfrog
  set Stress update = USF
end
)";
  ImplicitFixture<2>     fixture(text, "energy_sums_01");
  ExplicitLeapfrog<2>    stepper(fixture.parameters,
                              *fixture.grid,
                              fixture.grains,
                              fixture.materials);
  EnergyHistory<2>       history("energy_sums_01.csv",
                           fixture.grains,
                           fixture.materials,
                           fixture.parameters.physics.gravity,
                           MPI_COMM_WORLD);
  const EnergySummary<2> initial = history.compute(*fixture.particle_handler);
  const double           scale   = initial.kinetic;
  const double dt = 0.25 * fixture.grid->minimum_cell_size() / (36.69 + 20.);

  double             worst = 0., worst_momentum = 0.;
  unsigned int       n_with_sums = 0, n_removed = 0;
  const unsigned int n_steps = 120;
  for (unsigned int step = 0; step < n_steps; ++step)
    {
      const StepStatistics statistics =
        stepper.advance(*fixture.particle_handler, step * dt, dt);
      n_removed += statistics.events.n_removed;
      if (!statistics.sums.has_particle_sums)
        continue;
      ++n_with_sums;
      const EnergySummary<2> gathered = history.summarize(statistics);
      const EnergySummary<2> visited =
        history.compute(*fixture.particle_handler);
      worst = std::max({worst,
                        std::abs(gathered.kinetic - visited.kinetic),
                        std::abs(gathered.elastic - visited.elastic),
                        std::abs(gathered.gravity - visited.gravity)});
      worst_momentum =
        std::max(worst_momentum, (gathered.momentum - visited.momentum).norm());
    }
  deallog << "steps with gathered sums: " << n_with_sums << " of " << n_steps
          << std::endl;
  deallog << "points removed through the open face: "
          << (n_removed > 0 ? "some" : "none") << std::endl;
  deallog << "gathered sums = visited sums (1e-12 of the initial kinetic "
             "energy): "
          << (worst <= 1e-12 * scale ? "yes" : "no") << std::endl;
  deallog << "gathered momentum = visited momentum (1e-12 of the initial): "
          << (worst_momentum <= 1e-12 * initial.momentum.norm() ? "yes" : "no")
          << std::endl;
}
