// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#ifndef grainmpm_base_config_h
#define grainmpm_base_config_h

#include <deal.II/base/config.h>

/**
 * grainmpm is written in the namespace grainmpm on top of deal.II. Every
 * grainmpm header includes this one, the one place that makes deal.II's
 * names visible in the namespace grainmpm.
 */
namespace grainmpm
{
  using namespace dealii;
} // namespace grainmpm

#endif
