// `hofem choices`: every registry, printed from the registries themselves - the
// user's answer to "what can I name here?" and the list ctest
// registries.lists_agree holds the schema, SCENE_FORMAT.md, --help and the
// docs against.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "basis/element_orders.hpp"
#include "commands.hpp"
#include "dynamics/integrator.hpp"
#include "linalg/boomeramg_variants.hpp"
#include "material/material_registry.hpp"
#include "solver/solver_registry.hpp"

namespace hofem::cli {

namespace {

nlohmann::json choices_json() {
  using nlohmann::json;
  json j;
  for (const MaterialEntry& e : material_registry())
    j["materials"].push_back({{"name", e.name}, {"description", e.description}});
  for (const IntegratorEntry& e : integrator_registry())
    j["integrators"].push_back(
        {{"name", e.name},
         {"description", e.description},
         {"order", e.order},
         {"explicit", e.is_explicit},
         {"stability_limit", std::isinf(e.stability_limit) ? json(nullptr) : json(e.stability_limit)}});
  for (const LinearSolverEntry& e : linear_solver_registry())
    j["linear_solver_methods"].push_back(
        {{"name", method_name(e.method)}, {"description", e.description}, {"preconditioners", e.preconditioners}});
  j["linear_solvers"] = linear_solver_names();
  j["linear_solvers"].insert(j["linear_solvers"].begin(), "auto");
  for (const PreconditionerEntry& e : preconditioner_registry())
    j["preconditioners"].push_back(
        {{"name", e.name}, {"description", e.description}, {"needs_mesh", e.needs_mesh_view}});
  for (const BoomerAmgVariant& v : boomeramg_variants())
    j["boomeramg_variants"].push_back({{"name", v.name}, {"description", v.description}});
  for (CellType cell : {CellType::Tetrahedron, CellType::Hexahedron}) {
    json families = json::array();
    for (int order = 1; order <= 3 && supports_order(cell, order); ++order)
      families.push_back(element_family_name(cell, order));
    j["cells"].push_back({{"cell", name(cell)}, {"orders", supported_orders(cell)}, {"families", families}});
  }
  return j;
}

void print_section(const char* title, const nlohmann::json& rows) {
  fmt::print("{}:\n", title);
  for (const auto& r : rows)
    fmt::print("  {:<18} {}\n", r.at("name").get<std::string>(), r.at("description").get<std::string>());
}

}  // namespace

int run_choices(const ChoicesOptions& o) {
  const nlohmann::json j = choices_json();
  if (o.json) {
    fmt::print("{}\n", j.dump(1));
    return 0;
  }
  print_section("materials (material.model, mms --problem)", j["materials"]);
  print_section("integrators (integrator)", j["integrators"]);
  print_section("linear solver methods (solver.linear: METHOD or METHOD+PRECONDITIONER)", j["linear_solver_methods"]);
  print_section("preconditioners", j["preconditioners"]);
  print_section("BoomerAMG variants (solver.distributed.amg)", j["boomeramg_variants"]);
  fmt::print("element orders (mesh.cell, mesh.order):\n");
  for (const auto& c : j["cells"])
    fmt::print("  {:<18} {} ({})\n", c["cell"].get<std::string>(), c["orders"].get<std::string>(),
               fmt::join(c["families"].get<std::vector<std::string>>(), ", "));
  return 0;
}

}  // namespace hofem::cli
