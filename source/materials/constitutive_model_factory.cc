// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/materials/constitutive_model_factory.h>

namespace grainmpm
{
  namespace ConstitutiveModelFactory
  {
    namespace
    {
      /** The registry: a function's static object, made on first use. */
      std::map<std::string, Model> &
      registry()
      {
        static std::map<std::string, Model> models;
        return models;
      }
    } // namespace



    bool
    register_model(const Model &model)
    {
      AssertThrow(registry().count(model.name) == 0,
                  ExcMessage("Two constitutive models are registered as '" +
                             model.name + "'."));
      registry()[model.name] = model;
      return true;
    }



    const std::map<std::string, Model> &
    models()
    {
      return registry();
    }



    std::string
    selection()
    {
      std::string names;
      for (const auto &[name, model] : models())
        names += (names.empty() ? "" : "|") + name;
      return names;
    }



    std::string
    documentation()
    {
      std::string  text = "The stress update of this material: ";
      unsigned int i    = 0;
      for (const auto &[name, model] : models())
        {
          text += std::string(i == 0                  ? "" :
                              i + 1 < models().size() ? ", " :
                                                        " or ") +
                  "'" + name + "' (" + model.description + ")";
          ++i;
        }
      return text + ". Dimensionless.";
    }



    template <int dim>
    std::unique_ptr<ConstitutiveModel<dim>>
    create(const MaterialParameters &material,
           const TwoDimensionalModel two_dimensional_model)
    {
      const Model &model = models().at(material.constitutive_model);
      if constexpr (dim == 2)
        return model.create_2d(material, two_dimensional_model);
      else
        return model.create_3d(material, two_dimensional_model);
    }



    template std::unique_ptr<ConstitutiveModel<2>>
    create<2>(const MaterialParameters &, const TwoDimensionalModel);
    template std::unique_ptr<ConstitutiveModel<3>>
    create<3>(const MaterialParameters &, const TwoDimensionalModel);
  } // namespace ConstitutiveModelFactory
} // namespace grainmpm
