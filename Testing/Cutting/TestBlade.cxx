// Blades of the simulation phase (thesis 5.1): scalpel sweep, bite outline,
// scissors, and the refusal of bad blades.
#include "Blade.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace thintissue;

namespace
{
double area(const Blade& blade)
{
  double sum = 0.0;
  for (const auto& t : blade.triangles)
  {
    const Vector3& a = blade.points[t[0]];
    sum += 0.5 * (blade.points[t[1]] - a).cross(blade.points[t[2]] - a).norm();
  }
  return sum;
}
} // namespace

TEST(Blade, SweptSegmentIsTheQuadBetweenThePoses)
{
  const Blade blade =
    Blade::sweptSegment(Vector3(0, 0, -1), Vector3(0, 0, 1), Vector3(0, 3, -1), Vector3(0, 3, 1));
  EXPECT_EQ(blade.triangles.size(), 2u);
  EXPECT_NEAR(area(blade), 6.0, 1e-12);
  EXPECT_NO_THROW(blade.validate("test"));
}

TEST(Blade, BiteOutlineSweepsABand)
{
  std::vector<Vector3> low, high;
  for (int i = 0; i < 16; ++i)
  {
    const double a = 2.0 * M_PI * i / 16.0;
    low.emplace_back(std::cos(a), std::sin(a), -1.0);
    high.emplace_back(std::cos(a), std::sin(a), 1.0);
  }
  const Blade blade = Blade::sweptOutline(low, high);
  EXPECT_EQ(blade.triangles.size(), 32u);
  // Lateral area of the 16-gon prism of height 2.
  EXPECT_NEAR(area(blade), 16.0 * 2.0 * 2.0 * std::sin(M_PI / 16.0), 1e-9);
  EXPECT_THROW(Blade::sweptOutline(low, std::vector<Vector3>(high.begin(), high.end() - 1)),
    InvalidInputError);
}

TEST(Blade, ScissorsCutOnlyWhereTheBladesHaveClosed)
{
  ScissorsPose open;
  open.length = 10.0;
  open.maximumOpeningAngle = 0.4;
  open.openingAngle = 0.4;
  open.halfHeight = 2.0;
  ScissorsPose half = open;
  half.openingAngle = 0.2;
  EXPECT_DOUBLE_EQ(open.closedLength(), 0.0);
  EXPECT_DOUBLE_EQ(half.closedLength(), 5.0);
  EXPECT_TRUE(scissorsBlade(open, open).empty());
  const Blade closing = scissorsBlade(open, half);
  ASSERT_FALSE(closing.empty());
  // The closed part of the middle line, 5 long and 4 high.
  EXPECT_NEAR(closing.boundingBox().sizes().x(), 5.0, 1e-12);
  EXPECT_NEAR(closing.boundingBox().sizes().z(), 4.0, 1e-12);
  ScissorsPose bad = half;
  bad.opening = bad.direction;
  EXPECT_THROW(scissorsBlade(open, bad), InvalidInputError);
}

TEST(Blade, BadBladesAreRefusedByName)
{
  Blade empty;
  try
  {
    empty.validate("my cut");
    FAIL();
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("my cut"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("no triangle"), std::string::npos);
  }
  Blade nan = Blade::sweptSegment(Vector3::Zero(),
    Vector3::UnitZ(),
    Vector3::UnitY(),
    Vector3(0, 1, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_THROW(nan.validate("nan"), InvalidInputError);
  const Blade still =
    Blade::sweptSegment(Vector3::Zero(), Vector3::UnitZ(), Vector3::Zero(), Vector3::UnitZ());
  EXPECT_THROW(still.validate("zero-length sweep"), InvalidInputError);
  Blade outOfRange =
    Blade::sweptSegment(Vector3::Zero(), Vector3::UnitZ(), Vector3::UnitY(), Vector3(0, 1, 1));
  outOfRange.triangles[1][2] = 7;
  EXPECT_THROW(outOfRange.validate("index"), InvalidInputError);
}
