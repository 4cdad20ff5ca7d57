// Thesis figs. 6-12 and 6-13/6-14: the meniscus with a longitudinal tear
// after the operations of partial meniscectomy, seen from above its open
// side. Left: five punch bites along the inner border (jagged cut surface,
// the rim uneven where bites overlap); right: the large shaver run along the
// border in six passes, each removing the collision triangles its window
// holds (6.4.3: the notch of whole triangles it leaves, closed by cut
// surface). Tissue
// pink, cut surface dark red, removed pieces gone.
#include "OperationSceneHelpers.h"

using namespace thintissue;
using namespace thintissue::testing;

namespace
{

void shaveAlongTheBorder(TissueCutter& cutter, const MeniscusModel& model, int count)
{
  const MonitorCurve& border = model.monitorCurves.front();
  InstrumentAction shaver(makeSurgicalInstrument(SurgicalInstrumentType::LargeShaver));
  for (int k = 0; k < count; ++k)
  {
    const double at = 0.35 + 0.3 * k / std::max(1, count - 1);
    const auto i = static_cast<std::size_t>(at * (border.monitorPoints.size() - 1));
    Vector3 into = border.regionPoints[i] - border.monitorPoints[i];
    into.z() = 0.0;
    // The window facing down onto the border, 1 mm in from it.
    const RigidPose pose =
      operations_test::poseAt(operations_test::centroid(shaver.instrument().biteOutline),
        border.monitorPoints[i] + into.normalized(),
        -Vector3::UnitZ(),
        -into);
    shaver.apply(cutter, operations_test::command(1.0 * k, pose, 1.0, false));
    shaver.apply(cutter, operations_test::command(1.0 * k + 0.5, pose, 1.0, true));
  }
}

} // namespace

int main(int argc, char* argv[])
{
  const BoundMeniscusModel m(MeniscusTearType::Longitudinal);
  TissueCutter punched = jaggedCutter(m, 0.25);
  punchAlongTheBorder(punched, m.model, 5);
  TissueCutter shaved = jaggedCutter(m, 0.0);
  shaveAlongTheBorder(shaved, m.model, 6);

  const MonitorCurve& border = m.model.monitorCurves.front();
  const std::size_t middle = border.monitorPoints.size() / 2;
  Vector3 into = border.regionPoints[middle] - border.monitorPoints[middle];
  into.z() = 0.0;
  const Vector3 focus = border.monitorPoints[middle] + 2.0 * into.normalized();
  const Vector3 from = focus - 34.0 * into.normalized() + Vector3(0.0, 0.0, 40.0);
  auto window = makeSceneWindow(800, 400);
  window->AddRenderer(viewport(remainingTissueActor(punched), { 0.0, 0.0, 0.5, 1.0 }, focus, from));
  window->AddRenderer(viewport(remainingTissueActor(shaved), { 0.5, 0.0, 1.0, 1.0 }, focus, from));
  return compareWithBaseline(argc, argv, window);
}
