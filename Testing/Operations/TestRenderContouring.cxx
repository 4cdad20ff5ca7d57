// Thesis fig. 6-15: contouring the edge of the meniscus. The inner border of
// the meniscus after four overlapping punch bites with a jagged cut surface
// (left), and after the small shaver in contouring mode was drawn along the
// bitten rim (right): the same rim, evened out, nothing removed. Close-up
// from above the open side.
#include "OperationSceneHelpers.h"

#include <iostream>

using namespace thintissue;
using namespace thintissue::testing;

int main(int argc, char* argv[])
{
  const BoundMeniscusModel m(MeniscusTearType::None);
  TissueCutter cutter = jaggedCutter(m, 0.45);
  punchAlongTheBorder(cutter, m.model, 4, 0.44, 0.56);
  auto jagged = remainingTissueActor(cutter);
  const double before = cutter.cutRimRoughness().rootMeanSquare;

  InstrumentActionSettings contouring;
  contouring.shaverMode = ShaverMode::Contour;
  contouring.contourStrength = 0.5;
  InstrumentAction shaver(makeSurgicalInstrument(SurgicalInstrumentType::SmallShaver), contouring);
  const MonitorCurve& border = m.model.monitorCurves.front();
  const std::size_t first = border.monitorPoints.size() * 40 / 100;
  const std::size_t last = border.monitorPoints.size() * 60 / 100;
  double time = 0.0;
  for (std::size_t i = first; i <= last; ++i)
  {
    Vector3 into = border.regionPoints[i] - border.monitorPoints[i];
    into.z() = 0.0;
    // The window against the rim left by the bites, 1-3 mm in.
    for (const double depth : { 1.0, 2.0, 3.0 })
    {
      const RigidPose pose =
        operations_test::poseAt(operations_test::centroid(shaver.instrument().biteOutline),
          border.monitorPoints[i] + depth * into.normalized(),
          -into,
          Vector3::UnitZ() - into);
      for (int pass = 0; pass < 3; ++pass, time += 0.06)
        shaver.apply(cutter, operations_test::command(time, pose, 1.0, true));
    }
  }
  const double after = cutter.cutRimRoughness().rootMeanSquare;
  std::cout << "rim roughness " << before << " mm before contouring, " << after << " after\n";
  if (!(after < 0.75 * before)) // measured: 0.60 of it
  {
    std::cerr << "contouring did not smooth the rim\n";
    return EXIT_FAILURE;
  }

  const std::size_t middle = border.monitorPoints.size() / 2;
  Vector3 into = border.regionPoints[middle] - border.monitorPoints[middle];
  into.z() = 0.0;
  const Vector3 focus = border.monitorPoints[middle] + 1.5 * into.normalized();
  const Vector3 from = focus - 12.0 * into.normalized() + Vector3(0.0, 0.0, 12.0);
  auto window = makeSceneWindow(800, 400);
  window->AddRenderer(viewport(jagged, { 0.0, 0.0, 0.5, 1.0 }, focus, from));
  window->AddRenderer(viewport(remainingTissueActor(cutter), { 0.5, 0.0, 1.0, 1.0 }, focus, from));
  return compareWithBaseline(argc, argv, window);
}
