// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/particles/material_point_layout.h>
#include <grainmpm/postprocess/particle_fields.h>

#include <cmath>

namespace grainmpm
{
  template <int dim>
  double
  principal_stress_difference(const SymmetricTensor<2, 3> &stress)
  {
    if (dim == 2)
      {
        const double difference = stress[0][0] - stress[1][1];
        return std::sqrt(difference * difference +
                         4. * stress[0][1] * stress[0][1]);
      }
    const auto principal = eigenvalues(stress); // descending order
    return principal[0] - principal[2];
  }



  double
  von_mises_stress(const SymmetricTensor<2, 3> &stress)
  {
    const SymmetricTensor<2, 3> deviatoric = deviator(stress);
    return std::sqrt(1.5 * (deviatoric * deviatoric));
  }



  template <int dim>
  const std::vector<ParticleField<dim>> &
  particle_fields()
  {
    using Layout            = MaterialPointLayout<dim>;
    using Point             = MaterialPointView<dim>;
    constexpr auto scalar   = DataComponentInterpretation::component_is_scalar;
    const auto     property = [](const unsigned int index) {
      return [index](const Point &point, double *values) {
        values[0] = point.properties[index];
      };
    };

    static const std::vector<ParticleField<dim>> fields = [&]() {
      std::vector<ParticleField<dim>> table = {
        {"grain",
         1,
         scalar,
         [](const Point &point, double *values) {
           values[0] = Layout::get_grain(point.properties) + 1;
         }},
        {"id",
         1,
         scalar,
         [](const Point &point, double *values) { values[0] = point.id; }},
        {"velocity",
         dim,
         DataComponentInterpretation::component_is_part_of_vector,
         [](const Point &point, double *values) {
           for (unsigned int d = 0; d < dim; ++d)
             values[d] = point.properties[Layout::velocity + d];
         }},
        {"stress",
         dim * dim,
         DataComponentInterpretation::component_is_part_of_tensor,
         [](const Point &point, double *values) {
           for (unsigned int a = 0; a < dim; ++a)
             for (unsigned int b = 0; b < dim; ++b)
               values[a * dim + b] = point.stress[a][b];
         }}};
      if (dim == 2)
        table.push_back(
          {"stress_zz", 1, scalar, [](const Point &point, double *values) {
             values[0] = point.stress[2][2];
           }});
      table.push_back({"principal_stress_difference",
                       1,
                       scalar,
                       [](const Point &point, double *values) {
                         values[0] =
                           principal_stress_difference<dim>(point.stress);
                       }});
      table.push_back(
        {"fringe_order", 1, scalar, [](const Point &point, double *values) {
           values[0] = point.fringe_factor *
                       principal_stress_difference<dim>(point.stress);
         }});
      table.push_back(
        {"von_mises_stress", 1, scalar, [](const Point &point, double *values) {
           values[0] = von_mises_stress(point.stress);
         }});
      table.push_back({"volume", 1, scalar, property(Layout::volume)});
      table.push_back(
        {"plastic_strain", 1, scalar, property(Layout::plastic_strain)});
      return table;
    }();
    return fields;
  }



  template double
  principal_stress_difference<2>(const SymmetricTensor<2, 3> &);
  template double
  principal_stress_difference<3>(const SymmetricTensor<2, 3> &);
  template const std::vector<ParticleField<2>> &
  particle_fields<2>();
  template const std::vector<ParticleField<3>> &
  particle_fields<3>();
} // namespace grainmpm
