#include "ScriptedHapticDevice.h"

#include "AtomicFileWriter.h"
#include "ThinTissueError.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace thintissue
{

namespace
{

void checkTrajectory(const HapticTrajectory& t, const std::string& source)
{
  if (t.samples.empty())
  {
    throw InvalidInputError(source + ": the trajectory has no sample");
  }
  for (std::size_t k = 0; k < t.samples.size(); ++k)
  {
    const HapticSample& s = t.samples[k];
    if (!std::isfinite(s.time) || !s.position.allFinite() || !s.orientation.coeffs().allFinite() ||
        s.orientation.norm() == 0.0)
    {
      throw InvalidInputError(source + ": sample " + std::to_string(k) + " is not finite");
    }
    if (k > 0 && !(s.time > t.samples[k - 1].time))
    {
      throw InvalidInputError(source + ": sample " + std::to_string(k) +
                              " does not come after the one before (times must increase)");
    }
  }
}

nlohmann::json toJson(const HapticSample& s)
{
  const Eigen::Quaterniond& q = s.orientation;
  return { { "t", s.time },
    { "position", { s.position.x(), s.position.y(), s.position.z() } },
    { "orientation", { q.w(), q.x(), q.y(), q.z() } },
    { "buttons", s.buttons } };
}

HapticSample fromJson(const nlohmann::json& j)
{
  HapticSample s;
  s.time = j.at("t").get<double>();
  const auto& p = j.at("position");
  s.position = Vector3(p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>());
  const auto& q = j.at("orientation");
  s.orientation = Eigen::Quaterniond(
    q.at(0).get<double>(), q.at(1).get<double>(), q.at(2).get<double>(), q.at(3).get<double>());
  s.buttons = j.at("buttons").get<unsigned>();
  return s;
}

} // namespace

std::string hapticTrajectoryText(const HapticTrajectory& trajectory)
{
  nlohmann::json samples = nlohmann::json::array();
  for (const HapticSample& s : trajectory.samples)
  {
    samples.push_back(toJson(s));
  }
  const nlohmann::json document = { { "name", trajectory.name }, { "samples", samples } };
  return document.dump(1);
}

HapticTrajectory parseHapticTrajectory(const std::string& text, const std::string& source)
{
  HapticTrajectory trajectory;
  try
  {
    const nlohmann::json document = nlohmann::json::parse(text);
    trajectory.name = document.at("name").get<std::string>();
    for (const auto& sample : document.at("samples"))
    {
      trajectory.samples.push_back(fromJson(sample));
    }
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InvalidInputError(source + ": not a haptic trajectory (" + e.what() + ")");
  }
  checkTrajectory(trajectory, source);
  return trajectory;
}

void writeHapticTrajectory(const std::string& path, const HapticTrajectory& trajectory)
{
  checkTrajectory(trajectory, path);
  const std::string text = hapticTrajectoryText(trajectory);
  writeFileAtomically(path, [&](std::ostream& out) { out << text << "\n"; });
}

HapticTrajectory readHapticTrajectory(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw FileError(path, "cannot be opened for reading");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parseHapticTrajectory(text.str(), path);
}

ScriptedHapticDevice::ScriptedHapticDevice(HapticTrajectory trajectory,
  HapticDeviceInfo info,
  std::size_t forceCapacity)
  : Trajectory(std::move(trajectory))
  , Info(std::move(info))
{
  checkTrajectory(Trajectory, "scripted device '" + Info.name + "'");
  for (HapticSample& s : Trajectory.samples)
  {
    // Recorded orientations are unit already: keep their bits, so that a
    // replay reproduces the recorded run exactly.
    if (std::abs(s.orientation.squaredNorm() - 1.0) > 1e-12)
    {
      s.orientation.normalize();
    }
  }
  Forces.reserve(forceCapacity);
}

HapticDeviceState ScriptedHapticDevice::read(double time)
{
  const auto& samples = Trajectory.samples;
  HapticDeviceState state;
  if (Cursor >= samples.size() || samples[Cursor].time > time)
  {
    Cursor = 0; // a jump back in time: search from the start
  }
  while (Cursor + 1 < samples.size() && samples[Cursor + 1].time <= time)
  {
    ++Cursor;
  }
  const HapticSample& a = samples[Cursor];
  state.buttons = a.buttons;
  if (time <= a.time || Cursor + 1 == samples.size())
  {
    state.position = a.position;
    state.orientation = a.orientation.toRotationMatrix();
    return state;
  }
  const HapticSample& b = samples[Cursor + 1];
  const double span = b.time - a.time;
  const double t = (time - a.time) / span;
  state.position = a.position + t * (b.position - a.position);
  state.orientation = a.orientation.slerp(t, b.orientation).toRotationMatrix();
  state.velocity = (b.position - a.position) / span;
  return state;
}

void ScriptedHapticDevice::writeForce(const Vector3& force)
{
  if (Forces.size() < Forces.capacity())
  {
    Forces.push_back(force);
  }
}

RecordingHapticDevice::RecordingHapticDevice(HapticDevice& device, std::size_t capacity)
  : Device(device)
{
  Samples.reserve(capacity);
}

HapticDeviceState RecordingHapticDevice::read(double time)
{
  HapticDeviceState state = Device.read(time);
  // The run goes on with the orientation as the recording stores it (a unit
  // quaternion), so that replaying the recording gives the same run bit for
  // bit; velocity is what a replay gives at a sample (none).
  const Eigen::Quaterniond orientation = Eigen::Quaterniond(state.orientation).normalized();
  state.orientation = orientation.toRotationMatrix();
  state.velocity = Vector3::Zero();
  if (Samples.size() < Samples.capacity() && (Samples.empty() || time > Samples.back().time))
  {
    HapticSample s;
    s.time = time;
    s.position = state.position;
    s.orientation = orientation;
    s.buttons = state.buttons;
    Samples.push_back(s);
  }
  return state;
}

HapticTrajectory RecordingHapticDevice::trajectory() const
{
  HapticTrajectory t;
  t.name = Device.info().name;
  t.samples = Samples;
  return t;
}

} // namespace thintissue
