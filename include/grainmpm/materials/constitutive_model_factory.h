// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_materials_constitutive_model_factory_h
#define grainmpm_materials_constitutive_model_factory_h

#include <grainmpm/materials/constitutive_model.h>
#include <grainmpm/materials/material_parameters.h>

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace grainmpm
{
  /**
   * The constitutive models by name. A model registers itself in its own
   * source file with GRAINMPM_REGISTER_CONSTITUTIVE_MODEL; the entry
   * `Materials/NAME/Constitutive model`, its documentation and the entries
   * of each model come from here, so that a new model is its own files
   * (and their line in source/CMakeLists.txt) and nothing else.
   */
  namespace ConstitutiveModelFactory
  {
    /** What makes a model of dimension @p dim from a material. */
    template <int dim>
    using Creator = std::function<std::unique_ptr<ConstitutiveModel<dim>>(
      const MaterialParameters &material,
      const TwoDimensionalModel two_dimensional_model)>;

    /** A registered model. */
    struct Model
    {
      /** Its name in `Constitutive model`. */
      std::string name;
      /** What it is, for the documentation of `Constitutive model`. */
      std::string description;
      /** A new object of the model's own entries, with their defaults. */
      std::function<std::shared_ptr<ConstitutiveModelParameters>()>
                 make_parameters;
      Creator<2> create_2d;
      Creator<3> create_3d;
    };

    /**
     * Register @p model; returns true (for the static object of the
     * registration macro). Two models of one name are an internal error.
     */
    bool
    register_model(const Model &model);

    /** The registered models, by name. */
    const std::map<std::string, Model> &
    models();

    /** The names of the models as a Patterns::Selection: "a|b|c". */
    std::string
    selection();

    /**
     * The documentation of `Constitutive model`: each model with its
     * description.
     */
    std::string
    documentation();

    /**
     * The model of @p material for the two-dimensional idealisation
     * @p two_dimensional_model (ignored in 3D).
     */
    template <int dim>
    std::unique_ptr<ConstitutiveModel<dim>>
    create(const MaterialParameters &material,
           const TwoDimensionalModel two_dimensional_model);
  } // namespace ConstitutiveModelFactory
} // namespace grainmpm

/**
 * Register the model class template @p classname (a ConstitutiveModel<dim>
 * with a constructor from a MaterialParameters and a TwoDimensionalModel)
 * under @p name, with its entries @p parameters_class (a
 * ConstitutiveModelParameters) and the documentation @p description. Use
 * once, inside namespace grainmpm in the model's .cc file.
 */
#define GRAINMPM_REGISTER_CONSTITUTIVE_MODEL(classname,          \
                                             parameters_class,   \
                                             name,               \
                                             description)        \
  namespace                                                      \
  {                                                              \
    [[maybe_unused]] const bool classname##_registered =         \
      ConstitutiveModelFactory::register_model(                  \
        {name,                                                   \
         description,                                            \
         []() { return std::make_shared<parameters_class>(); },  \
         [](const MaterialParameters &material,                  \
            const TwoDimensionalModel two_dimensional_model) {   \
           return std::unique_ptr<ConstitutiveModel<2>>(         \
             new classname<2>(material, two_dimensional_model)); \
         },                                                      \
         [](const MaterialParameters &material,                  \
            const TwoDimensionalModel two_dimensional_model) {   \
           return std::unique_ptr<ConstitutiveModel<3>>(         \
             new classname<3>(material, two_dimensional_model)); \
         }});                                                    \
  }

#endif
