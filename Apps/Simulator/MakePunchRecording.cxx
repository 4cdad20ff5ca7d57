// Writes Data/Recordings/meniscectomy-punch.json: the punch recording of the
// partial meniscectomy scenario, made from the scenario's own geometry so
// that it can be made again when the models change. For each of five bites
// along the bucket-handle fragment's inner border (35 % to 65 % of it): from
// 6 mm above, down to 2 mm above the bite's height beside the border, onto it with the jaws' bite
// outline centred 0.8 mm in from the border and its face 0.6 mm below the border's monitor point
// (the fixed jaw under the tissue: the portal tilts the jaws about 27 degrees, so that with the
// face 0.3 mm above the border, as first made, the tissue under the bite's proximal end lay 1.1-1.4
// mm below the face, out of the bite's reach, and the first bite's loop stayed open), the first
// button held 0.2 s (the jaws close and bite), released, and back out. The arthroscope follows the
// examination's recording. Usage: ThinTissueMakePunchRecording SCENARIO OUTPUT SCENARIO-AS-WRITTEN
// EXAMINATION-RECORDING
#include "PortalMapping.h"
#include "TrainingScene.h"

#include <iostream>

using namespace thintissue;

namespace
{

Vector3 centroid(const std::vector<Vector3>& points)
{
  Vector3 sum = Vector3::Zero();
  for (const Vector3& p : points)
    sum += p;
  return sum / static_cast<double>(points.size());
}

/// A point of the curve at `fraction` of its data points, with the unit
/// horizontal direction into the tissue there.
void borderAt(const MonitorCurve& curve, double fraction, Vector3& point, Vector3& inward)
{
  const double x = fraction * static_cast<double>(curve.monitorPoints.size() - 1);
  const std::size_t k =
    std::min<std::size_t>(static_cast<std::size_t>(x), curve.monitorPoints.size() - 2);
  const double w = x - static_cast<double>(k);
  point = (1 - w) * curve.monitorPoints[k] + w * curve.monitorPoints[k + 1];
  inward = (1 - w) * curve.regionPoints[k] + w * curve.regionPoints[k + 1] - point;
  inward.z() = 0.0;
  inward.normalize();
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 5)
  {
    std::cerr << "usage: ThinTissueMakePunchRecording SCENARIO OUTPUT SCENARIO-AS-WRITTEN "
                 "EXAMINATION-RECORDING\n";
    return 2;
  }
  const ScenarioDescription scenario = readScenario(argv[1]);
  MeniscusParameters parameters =
    scenario.examinationResolution ? examinationMeniscusParameters() : MeniscusParameters{};
  parameters.tear = defaultMeniscusTear(scenario.tear);
  const MeniscusModel meniscus = makeMeniscus(parameters);
  const SurgicalInstrumentModel punch = makeSurgicalInstrument(scenario.instrument);
  const Vector3 outline = centroid(punch.biteOutline);
  PortalSettings portal;
  portal.portal = scenario.instrumentPortal.portal;
  portal.inward = scenario.instrumentPortal.inward;
  const PortalMapping mapping(portal);
  // The stylus's +y (the jaws' opening side) turned to world +z.
  const Eigen::Quaterniond up(Eigen::AngleAxisd(M_PI / 2, Vector3::UnitX()));
  const Eigen::Matrix3d rotation = up.toRotationMatrix();

  SceneRecording recording;
  recording.scenario = argv[3];
  recording.scope = readSceneRecording(argv[4]).scope;
  recording.instrument.name = "instrument";
  const auto sample = [&](double time, const Vector3& position, unsigned buttons)
  {
    HapticSample s;
    s.time = time;
    s.position = position;
    s.orientation = up;
    s.buttons = buttons;
    recording.instrument.samples.push_back(s);
  };
  sample(0.0, Vector3::Zero(), 0);
  const MonitorCurve& border = meniscus.monitorCurves.front();
  double t = 0.8;
  for (int bite = 0; bite < 5; ++bite)
  {
    Vector3 point, inward;
    borderAt(border, 0.35 + 0.3 * bite / 4.0, point, inward);
    const Vector3 target = point + 0.8 * inward - Vector3(0.0, 0.0, 0.6);
    const Vector3 on = mapping.stylusPositionPlacing(outline, target, rotation);
    // Beside the border 2 mm above the bite's height, so that the jaws come
    // down onto the border rather than along the bare plateau (cartilage
    // contact steps 2,114 -> 1,182 over the recording, the bites unchanged).
    const Vector3 beside = mapping.stylusPositionPlacing(
      outline, target - 3.0 * inward + Vector3(0.0, 0.0, 2.0), rotation);
    const Vector3 above = mapping.stylusPositionPlacing(
      outline, target - 3.0 * inward + Vector3(0.0, 0.0, 6.0), rotation);
    sample(t, above, 0);
    sample(t += 0.3, beside, 0);
    sample(t += 0.3, on, 0);
    sample(t += 0.15, on, 1);
    sample(t += 0.2, on, 0);
    sample(t += 0.15, beside, 0);
    sample(t += 0.2, above, 0);
    t += 0.1;
  }
  sample(t + 0.5, Vector3::Zero(), 0);
  writeSceneRecording(argv[2], recording);
  std::cout << "recording of " << t + 0.5 << " s written to " << argv[2] << "\n";
  return 0;
}
