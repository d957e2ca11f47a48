#include "material/material_registry.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <stdexcept>

#include "material/corotated.hpp"
#include "material/linear_elastic.hpp"
#include "material/neo_hookean.hpp"
#include "material/st_venant_kirchhoff.hpp"
#include "material/stable_neo_hookean.hpp"

namespace hofem {

namespace {

template <class M>
std::unique_ptr<Material> make(LameParameters lame) {
  return std::make_unique<M>(lame);
}

}  // namespace

// Function-local, as every registry: read during other files' static initialisation.
std::span<const MaterialEntry> material_registry() {
  static const std::array<MaterialEntry, 5> materials{{
      {"linear", "small-strain linear elasticity, psi = mu eps:eps + lambda/2 tr(eps)^2", make<LinearElastic>},
      {"stvk", "St. Venant-Kirchhoff, psi = mu ||E||^2 + lambda/2 tr(E)^2 (thesis eq. 2.9)", make<StVenantKirchhoff>},
      {"corotated", "corotated linear elasticity, psi = mu ||F - R||^2 + lambda/2 tr(S - I)^2 (thesis eq. 2.11)",
       make<Corotated>},
      {"neohookean", "compressible Neo-Hookean, psi = mu/2 (I1 - 3) - mu log J + lambda/2 (log J)^2 (thesis eq. 2.13)",
       make<NeoHookean>},
      {"stable-neohookean", "Stable Neo-Hookean (Smith, de Goes, Kim 2018)", make<StableNeoHookean>},
  }};
  return materials;
}

std::vector<std::string> material_names() {
  std::vector<std::string> names;
  for (const MaterialEntry& e : material_registry()) names.emplace_back(e.name);
  return names;
}

std::unique_ptr<Material> make_material(std::string_view name, LameParameters lame) {
  for (const MaterialEntry& e : material_registry())
    if (e.name == name) {
      std::unique_ptr<Material> m = e.make(lame);
      m->name_ = std::string(e.name);
      return m;
    }
  throw std::invalid_argument(
      fmt::format("unknown material '{}' (valid: {})", name, fmt::join(material_names(), ", ")));
}

}  // namespace hofem
