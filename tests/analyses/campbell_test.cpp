// Campbell analysis: optimal assignment, engine-order lines, input checks.
// (Tracking and critical speeds against closed-form results: campbell_validation_test.cpp.)
#include "geardyn/analyses/campbell.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

using C = model::Component;
constexpr double kPi = std::numbers::pi;

TEST(Campbell, AssignmentIsOptimalNotGreedy) {
  // Greedy takes (0,0) = 0.9 and is left with (1,1) = 0.1: total 1.0. Optimal: 0.8 + 0.85.
  Eigen::MatrixXd score(2, 3);
  score << 0.9, 0.8, 0.0, 0.85, 0.1, 0.0;
  EXPECT_EQ(best_assignment(score), (std::vector<int>{1, 0}));
  // Rectangular with a better spare column for the second row.
  Eigen::MatrixXd spare(2, 3);
  spare << 0.9, 0.2, 0.1, 0.9, 0.1, 0.95;
  EXPECT_EQ(best_assignment(spare), (std::vector<int>{0, 2}));
  EXPECT_THROW(best_assignment(Eigen::MatrixXd::Zero(3, 2)), std::invalid_argument);
}

TEST(Campbell, EngineOrderLinesFromShaftsAndMeshes) {
  model::Model model;
  auto shaft = [](const std::string& name, double ratio) {
    model::Shaft s;
    s.name = name;
    s.speed_ratio = ratio;
    model::ShaftElement e;
    e.length = 0.1;
    e.outer_diameter = 0.02;
    s.elements.push_back(e);
    return s;
  };
  model.shafts.push_back(shaft("input", 1.0));
  model.shafts.push_back(shaft("output", -2.5));
  model::GearMesh mesh;
  mesh.name = "stage1";
  mesh.gear1 = "input.1";
  mesh.gear2 = "output.0";
  mesh.teeth1 = 50;
  mesh.teeth2 = 20;
  model.gear_meshes.push_back(mesh);
  fe::LinearSystem system;
  system.dofs = fe::DofMap::build(model);
  analyses::CampbellSettings settings;
  settings.engine_orders = {1.0, 2.0};
  const auto lines = engine_order_lines(model, system, settings);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].order, 1.0);  // EO 1 merged with the input shaft's 1x
  EXPECT_NE(lines[0].label.find("input"), std::string::npos);
  EXPECT_EQ(lines[1].order, 2.0);
  EXPECT_EQ(lines[2].order, 2.5);   // |speed ratio| of the output shaft
  EXPECT_EQ(lines[3].order, 50.0);  // 50 teeth x 1 (= 20 x 2.5)
  settings.shaft_orders = false;
  settings.mesh_orders = false;
  EXPECT_EQ(engine_order_lines(model, system, settings).size(), 2u);
}

TEST(Campbell, InvalidSettingsThrowInputError) {
  const auto model = test::jeffcott(1.0, 1.0, 0.1);
  const auto system = assembly::build_system(model);
  analyses::CampbellSettings s;
  s.speeds = {};
  EXPECT_THROW(run_campbell(model, s, Context("campbell").with_system(&system)), InputError);
  s.speeds = {0.0, 10.0, 5.0};
  EXPECT_THROW(run_campbell(model, s, Context("campbell").with_system(&system)), InputError);
  s.speeds = {0.0, 10.0};
  s.mac_threshold = 1.5;
  EXPECT_THROW(run_campbell(model, s, Context("campbell").with_system(&system)), InputError);
}

}  // namespace
}  // namespace geardyn::analyses
