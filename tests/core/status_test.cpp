// Statuses: names written to the manifest, and which one wins when outcomes are combined.
#include "geardyn/core/status.hpp"

#include <gtest/gtest.h>

namespace geardyn {
namespace {

TEST(Status, NamesAreTheManifestWords) {
  EXPECT_EQ(to_string(Status::Ok), "ok");
  EXPECT_EQ(to_string(Status::Unstable), "unstable");
  EXPECT_EQ(to_string(Status::NotConverged), "not_converged");
  EXPECT_EQ(to_string(Status::FewerModes), "fewer_modes");
  EXPECT_EQ(to_string(Status::Diverged), "diverged");
  EXPECT_EQ(to_string(Status::Singular), "singular");
  EXPECT_EQ(to_string(Status::Failed), "failed");
}

TEST(Status, TheWorseOutcomeWins) {
  // An unstable but computed response is worse than ok and better than no result at all.
  EXPECT_EQ(worse(Status::Ok, Status::Unstable), Status::Unstable);
  EXPECT_EQ(worse(Status::Unstable, Status::NotConverged), Status::NotConverged);
  EXPECT_EQ(worse(Status::Failed, Status::Unstable), Status::Failed);
  EXPECT_EQ(worse(Status::Singular, Status::Diverged), Status::Singular);
  EXPECT_EQ(worse(Status::Ok, Status::Ok), Status::Ok);
}

}  // namespace
}  // namespace geardyn
