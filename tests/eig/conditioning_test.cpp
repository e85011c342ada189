// The scaling diagnosis that replaces "a mechanism without mass" when a model is only badly
// scaled (a 'rigid' 1e30 N/m spring, a near-zero density).
#include "geardyn/eig/conditioning.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace geardyn::eig {
namespace {

Eigen::SparseMatrix<double> diagonal(const std::vector<double>& d) {
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(d.size()),
                                static_cast<Eigen::Index>(d.size()));
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] != 0.0) a.insert(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) = d[i];
  return a;
}

TEST(ScalingDiagnosis, APhysicalModelIsUnremarkable) {
  // A steel shaft on 1e7 N/m bearings: K_ii / M_ii within ~1e10.
  EXPECT_EQ(scaling_diagnosis(diagonal({1e7, 2e8, 5e5}), diagonal({10.0, 3.0, 0.1})), "");
}

TEST(ScalingDiagnosis, ARigidSpringIsNamed) {
  const std::string d = scaling_diagnosis(diagonal({1e30, 1e7, 1e7}), diagonal({1, 1, 1}));
  EXPECT_NE(d.find("1.0e+23"), std::string::npos) << d;
  EXPECT_NE(d.find("'rigid' spring"), std::string::npos) << d;
}

TEST(ScalingDiagnosis, ANearZeroMassIsNamed) {
  const std::string d = scaling_diagnosis(diagonal({1e7, 1e7}), diagonal({1.0, 1e-300}));
  EXPECT_NE(d.find("density or mass far below"), std::string::npos) << d;
}

TEST(ScalingDiagnosis, AMassThatOverflowsTheRatioIsNamed) {
  // density = 1e-300: every K_ii / M_ii overflows to infinity.
  const std::string d = scaling_diagnosis(diagonal({1e9, 1e9}), diagonal({1e-305, 1e-305}));
  EXPECT_NE(d.find("vanishingly small"), std::string::npos) << d;
}

TEST(ScalingDiagnosis, StiffnessSpreadWithoutMassIsNamed) {
  // Massless DOFs (rotations of a lumped model) still show a 1e30 spring by the stiffness alone.
  const std::string d = scaling_diagnosis(diagonal({1e30, 1e7, 1e7}), diagonal({0, 1, 1}));
  EXPECT_NE(d.find("stiffness values span"), std::string::npos) << d;
}

}  // namespace
}  // namespace geardyn::eig
