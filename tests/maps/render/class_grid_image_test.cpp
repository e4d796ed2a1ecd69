#include "maps/render/class_grid_image.hpp"

#include <gtest/gtest.h>

namespace flat2d::maps {
namespace {

TEST(ClassGridImage, ThesisColoursNorthUp) {
  ClassGrid grid(GridGeometry{.width = 4, .height = 3, .resolution_m = 1.0, .origin = Eigen::Vector2d::Zero()});
  grid.Mark(CellIndex{0, 0}, CellClass::kSlammable);  // lowest row: the image's last row
  grid.Mark(CellIndex{3, 2}, CellClass::kHazard);     // highest row: the image's first row
  grid.Mark(CellIndex{1, 1}, CellClass::kFree);
  const RgbImage image = RenderClassGrid(grid);
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 3);
  EXPECT_EQ(image.At(0, 2), (Rgb{0, 0, 0}));
  EXPECT_EQ(image.At(3, 0), (Rgb{220, 30, 30}));
  EXPECT_EQ(image.At(1, 1), (Rgb{255, 255, 255}));
  EXPECT_EQ(image.At(2, 1), (Rgb{200, 200, 200}));
}

}  // namespace
}  // namespace flat2d::maps
