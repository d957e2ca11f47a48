#pragma once
// The one table of hofem's materials (material_registry.cpp): each name as
// scene files and `hofem mms --problem` spell it, the law it implements with
// its source, and its factory. material_names() and make_material()
// (material.hpp) read it; so do the scene schema test, --help and the
// manufactured-solution problems. Adding a material: its class (one file),
// one row in material_registry.cpp, and its law in verification/symbolic.
#include "material/material.hpp"

#include <memory>
#include <span>
#include <string_view>

namespace hofem {

struct MaterialEntry {
  std::string_view name;
  std::string_view description;  ///< the energy density and where it is from
  std::unique_ptr<Material> (*make)(LameParameters lame);
};

/// Every material, in the order material_names() lists them.
std::span<const MaterialEntry> material_registry();

}  // namespace hofem
