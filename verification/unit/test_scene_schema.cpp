// The JSON Schemas of scenes and studies (core/scene/scene.schema.json,
// core/study/study.schema.json) against the parser's own lists, so that a new
// material, integrator or solver cannot be missed by the schema (the Python
// tests in verification/scene_schema/ check verdicts; this checks the names),
// and the "$schema" key both parsers accept.
#include "dynamics/integrator.hpp"
#include "material/material.hpp"
#include "scene/scene.hpp"
#include "linalg/boomeramg_variants.hpp"
#include "solver/solver_spec.hpp"
#include "study/study_file.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <vector>

namespace {

using hofem::SceneError;
using json = nlohmann::json;

json scene_schema() {
  std::ifstream in(std::string(HOFEM_SOURCE_DIR) + "/core/scene/scene.schema.json");
  return json::parse(in);
}

std::vector<std::string> enum_at(const json& schema, const std::vector<std::string>& keys) {
  const json* node = &schema;
  for (const std::string& k : keys) node = &node->at("properties").at(k);
  return node->at("enum").get<std::vector<std::string>>();
}

TEST(SceneSchema, EnumsAreTheParsersLists) {
  const json schema = scene_schema();
  EXPECT_EQ(enum_at(schema, {"material", "model"}), hofem::material_names());
  std::vector<std::string> integrators = hofem::integrator_names();
  integrators.push_back("static");
  EXPECT_EQ(enum_at(schema, {"integrator"}), integrators);
  std::vector<std::string> solvers = hofem::linear_solver_names();
  solvers.insert(solvers.begin(), "auto");
  EXPECT_EQ(enum_at(schema, {"solver", "linear"}), solvers);
  EXPECT_EQ(enum_at(schema, {"solver", "distributed", "amg"}), hofem::boomeramg_variant_names());
}

const char* kScene = R"({"$schema": SCHEMA, "mesh": {"box": {"min": [0,0,0], "max": [1,1,1], "cells": [1,1,1]}},
  "material": {"model": "linear", "young": 1, "poisson": 0.3}, "integrator": "static"})";

std::string with_schema(const std::string& value) {
  std::string text = kScene;
  return text.replace(text.find("SCHEMA"), 6, value);
}

TEST(SceneSchema, SceneAcceptsSchemaKey) {
  EXPECT_NO_THROW(hofem::parse_scene(with_schema("\"../core/scene/scene.schema.json\""), "s.json"));
  try {
    hofem::parse_scene(with_schema("5"), "s.json");
    FAIL() << "a number for $schema was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: $schema must be a string"), std::string::npos) << e.what();
  }
}

TEST(SceneSchema, StudyAcceptsSchemaKey) {
  const std::string schema = R"("../../../core/study/study.schema.json")";
  const std::string text = R"({"$schema": )" + schema + R"(, "name": "tiny",
    "scene": "scene_tiny.json", "frames": [0.1], "thresholds": [0.05],
    "reference": {"overrides": ["mesh.order=2"]}, "runs": [{"name": "a", "family": "Tet4"}]})";
  const std::string origin = std::string(HOFEM_TEST_DATA_DIR) + "/study_with_schema.json";
  EXPECT_EQ(hofem::parse_study(text, origin).name, "tiny");
  std::string bad = text;
  bad.replace(bad.find(schema), schema.size(), "[]");
  EXPECT_THROW(hofem::parse_study(bad, origin), SceneError);
}

}  // namespace
