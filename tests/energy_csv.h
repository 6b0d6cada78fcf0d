// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

// Whole runs of grainmpm from a test, judged by their history files.

#ifndef grainmpm_tests_energy_csv_h
#define grainmpm_tests_energy_csv_h

#include <grainmpm/simulator.h>

#include <deal.II/base/mpi.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

/** The columns of a history CSV file, by name without the unit. */
inline std::map<std::string, std::vector<double>>
read_csv(const std::string &filename)
{
  std::ifstream            file(filename);
  std::string              line;
  std::vector<std::string> names;
  std::getline(file, line);
  {
    std::istringstream header(line);
    std::string        name;
    while (std::getline(header, name, ','))
      names.push_back(name.substr(0, name.find(" [")));
  }
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(file, line))
    {
      std::istringstream row(line);
      std::string        value;
      for (unsigned int c = 0; std::getline(row, value, ','); ++c)
        columns[names[c]].push_back(std::stod(value));
    }
  return columns;
}



/** The rows of @p grains (grains.csv columns) of grain @p grain (1-based). */
inline std::map<std::string, std::vector<double>>
grain_rows(const std::map<std::string, std::vector<double>> &grains,
           const unsigned int                                grain)
{
  std::map<std::string, std::vector<double>> rows;
  for (unsigned int i = 0; i < grains.at("grain").size(); ++i)
    if (grains.at("grain")[i] == grain)
      for (const auto &[name, column] : grains)
        rows[name].push_back(column[i]);
  return rows;
}



/**
 * Time mean of @p values over the rows with time in [@p from, @p to], each
 * row weighted by its interval since the row before.
 */
inline double
time_mean(const std::vector<double> &times,
          const std::vector<double> &values,
          const double               from,
          const double               to)
{
  double sum = 0., weight = 0.;
  for (unsigned int i = 1; i < times.size(); ++i)
    if (times[i] >= from && times[i] <= to)
      {
        const double dt = times[i] - times[i - 1];
        sum += values[i] * dt;
        weight += dt;
      }
  return sum / weight;
}



/** The columns of the energy.csv in @p directory. */
inline std::map<std::string, std::vector<double>>
read_energy(const std::string &directory)
{
  return read_csv(directory + "/energy.csv");
}



/**
 * Run @p text (in @p dim dimensions, 2 unless given) as NAME.prm in test mode without particle and grid
 * output, writing into results-NAME, on every rank of MPI_COMM_WORLD;
 * return its energy.csv columns.
 */
template <int dim = 2>
std::map<std::string, std::vector<double>>
run_case(const std::string &name, const std::string &text)
{
  // One rank writes the file, the others wait for it.
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::ofstream(name + ".prm")
      << text << "\nsubsection Output\n  set Output directory = results-"
      << name << "\n  set Test mode = true\n  set Write particles = false\n"
      << "  set Write grid = false\nend\n";
  MPI_Barrier(MPI_COMM_WORLD);
  grainmpm::run<dim>(name + ".prm", MPI_COMM_WORLD);
  return read_energy("results-" + name);
}

#endif
