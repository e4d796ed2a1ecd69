// Association of line features with line landmarks (landmark_association.hpp): the nearest
// within the gates, and the repeated-structure rule that keeps a drifted revisit of a row of
// fence posts from landing on a post's neighbour.
#include "localization/landmarks/landmark_association.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace flat2d::localization::landmarks {
namespace {

maps::features3d::LineFeature VerticalLineAt(double x, double y) {
  maps::features3d::LineFeature line;
  line.point = Eigen::Vector3d(x, y, 0.6);
  line.direction = Eigen::Vector3d::UnitZ();
  line.half_length_m = 0.6;
  return line;
}

// Posts 2.5 m apart along x, started at travel 0, and a street light 40 m away.
std::vector<LineTrack> FenceAndLight(const AssociationGates& gates) {
  std::vector<LineTrack> tracks;
  for (int k = 0; k < 4; ++k) AddLineTrack(StartLineTrack(VerticalLineAt(2.5 * k, 10.0)), 0.0, gates, tracks);
  AddLineTrack(StartLineTrack(VerticalLineAt(40.0, 10.0)), 0.0, gates, tracks);
  return tracks;
}

TEST(LineAssociation, PostsInARowAreRepeatedALoneLightIsNot) {
  const AssociationGates gates;
  const auto tracks = FenceAndLight(gates);
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(tracks[static_cast<std::size_t>(k)].repeated) << "post " << k;
  EXPECT_FALSE(tracks[4].repeated);
}

TEST(LineAssociation, NearestWithinTheGatesWhileRecent) {
  const AssociationGates gates;
  const auto tracks = FenceAndLight(gates);
  EXPECT_EQ(AssociateLine(tracks, VerticalLineAt(5.2, 10.1), gates, 10.0), 2);
  EXPECT_EQ(AssociateLine(tracks, VerticalLineAt(3.6, 10.0), gates, 10.0), std::nullopt);  // between two posts
  EXPECT_EQ(AssociateLine(tracks, VerticalLineAt(40.3, 9.8), gates, 10.0), 4);
}

// Back after 500 m with 2 m of drift along the fence: post 1 is seen where post 2 was
// mapped, 0.5 m from it. The posts are not met again; the lone light still is.
TEST(LineAssociation, ARevisitDoesNotMeetRepeatedStructure) {
  const AssociationGates gates;
  const auto tracks = FenceAndLight(gates);
  EXPECT_EQ(AssociateLine(tracks, VerticalLineAt(4.5, 10.0), gates, 500.0), std::nullopt);
  EXPECT_EQ(AssociateLine(tracks, VerticalLineAt(41.5, 10.3), gates, 500.0), std::nullopt);  // beyond the gate
  EXPECT_EQ(AssociateLine(tracks, VerticalLineAt(40.5, 10.3), gates, 500.0), 4);

  AssociationGates without = gates;
  without.line_revisit_travel_m = 0.0;
  EXPECT_EQ(AssociateLine(tracks, VerticalLineAt(4.5, 10.0), without, 500.0), 2);  // the alias
}

}  // namespace
}  // namespace flat2d::localization::landmarks
