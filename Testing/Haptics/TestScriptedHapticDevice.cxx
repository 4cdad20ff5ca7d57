// Recorded trajectories: replay interpolation, exact file round trip,
// recording from another device, bad files named.
#include "ScriptedHapticDevice.h"
#include "ThinTissueError.h"
#include "ThinTissueTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace thintissue;

namespace
{

HapticTrajectory wobble()
{
  HapticTrajectory t;
  t.name = "wobble";
  for (int k = 0; k < 50; ++k)
  {
    const double time = 0.0137 * k + 1e-7 * k * k;
    t.samples.push_back(HapticSample{ time,
      Vector3(std::sin(time) * 30.0, std::cos(3.0 * time) / 3.0, 1.0 / (k + 3.0)),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * k, Vector3(1.0, 2.0, 0.5).normalized())),
      static_cast<unsigned>(k % 4) });
  }
  return t;
}

} // namespace

TEST(ScriptedHapticDevice, ReplaysByInterpolation)
{
  const HapticTrajectory t = wobble();
  ScriptedHapticDevice device(t);
  const HapticSample& a = t.samples[10];
  const HapticSample& b = t.samples[11];
  const double middle = 0.5 * (a.time + b.time);
  const HapticDeviceState s = device.read(middle);
  EXPECT_LT((s.position - 0.5 * (a.position + b.position)).norm(), 1e-12);
  EXPECT_LT((s.velocity - (b.position - a.position) / (b.time - a.time)).norm(), 1e-9);
  EXPECT_EQ(s.buttons, a.buttons);
  const Eigen::Matrix3d halfway = a.orientation.slerp(0.5, b.orientation).toRotationMatrix();
  EXPECT_LT((s.orientation - halfway).norm(), 1e-12);
  // At a sample exactly; before the start and after the end, held.
  EXPECT_EQ(device.read(b.time).position, b.position);
  EXPECT_EQ(device.read(-1.0).position, t.samples.front().position);
  EXPECT_EQ(device.read(100.0).position, t.samples.back().position);
  EXPECT_EQ(device.read(100.0).velocity, Vector3::Zero());
  // Reading backwards in time works too.
  EXPECT_EQ(device.read(a.time).position, a.position);
}

TEST(ScriptedHapticDevice, FileRoundTripIsExactAndRecordingReplaysTheSame)
{
  const HapticTrajectory t = wobble();
  const std::string path = (thintissue::testing::temporaryDirectory() / "wobble.json").string();
  writeHapticTrajectory(path, t);
  const HapticTrajectory back = readHapticTrajectory(path);
  EXPECT_EQ(back.name, "wobble");
  ASSERT_EQ(back.samples.size(), t.samples.size());
  for (std::size_t k = 0; k < t.samples.size(); ++k)
  {
    EXPECT_TRUE(back.samples[k] == t.samples[k]) << "sample " << k;
  }
  // Record a replay tick by tick, replay the recording: the same states.
  ScriptedHapticDevice source(t);
  RecordingHapticDevice recorder(source, 1000);
  std::vector<HapticDeviceState> seen;
  for (int k = 0; k < 600; ++k)
  {
    seen.push_back(recorder.read(0.001 * k));
  }
  ScriptedHapticDevice replay(recorder.trajectory());
  for (int k = 0; k < 600; ++k)
  {
    const HapticDeviceState s = replay.read(0.001 * k);
    EXPECT_EQ(s.position, seen[k].position) << k;
    EXPECT_EQ(s.buttons, seen[k].buttons) << k;
    EXPECT_LT((s.orientation - seen[k].orientation).norm(), 1e-12) << k;
  }
}

TEST(ScriptedHapticDevice, BadTrajectoriesAreRefusedWithTheirName)
{
  EXPECT_THROW(ScriptedHapticDevice(HapticTrajectory{}), InvalidInputError);
  HapticTrajectory backwards = wobble();
  std::swap(backwards.samples[3], backwards.samples[4]);
  EXPECT_THROW(ScriptedHapticDevice{ backwards }, InvalidInputError);
  const std::string path =
    (thintissue::testing::temporaryDirectory() / "not-a-trajectory.json").string();
  std::ofstream(path) << "{\"name\": \"x\", \"samples\": [{\"t\": 0}]}";
  try
  {
    readHapticTrajectory(path);
    FAIL() << "a sample without position was read";
  }
  catch (const InvalidInputError& e)
  {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(readHapticTrajectory(path + ".missing"), FileError);
}
