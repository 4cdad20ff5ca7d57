#include "WrinkleGenerator.h"

#include "CollisionScene.h"
#include "ThinTissueError.h"

#include <algorithm>
#include <limits>

namespace thintissue
{

void checkWrinkleParameters(const WrinkleParameters& p)
{
  const auto require = [](bool ok, const std::string& what)
  {
    if (!ok)
    {
      throw InvalidInputError("wrinkle parameters: " + what);
    }
  };
  require(std::isfinite(p.frequency) && p.frequency > 0.0,
    "theta^d (frequency) " + std::to_string(p.frequency) + " must be positive");
  require(std::isfinite(p.scale) && p.scale >= 0.0,
    "scale s " + std::to_string(p.scale) + " must not be negative");
  require(std::isfinite(p.magnitudeBound),
    "magnitude bound m^up " + std::to_string(p.magnitudeBound) + " must be finite");
  require(std::isfinite(p.cutOffThickness) && p.cutOffThickness >= 0.0,
    "cut-off thickness r^c " + std::to_string(p.cutOffThickness) + " must not be negative");
  require(
    p.windowSize >= 2, "window size e - s " + std::to_string(p.windowSize) + " must be at least 2");
  require(std::isfinite(p.reversalThreshold),
    "reversal threshold N_c " + std::to_string(p.reversalThreshold) + " must be finite");
  require(p.refreshMonitorsPerUpdate >= 0,
    "refresh monitors per update " + std::to_string(p.refreshMonitorsPerUpdate) +
      " must not be negative");
  require(p.startContacts >= 0 && p.endContacts >= 0,
    "contact thresholds N_s " + std::to_string(p.startContacts) + " and N_e " +
      std::to_string(p.endContacts) + " must not be negative");
}

WrinkleContactState wrinkleContactState(const CollisionScene& scene, int tissue)
{
  WrinkleContactState state;
  double deepest = -std::numeric_limits<double>::infinity();
  for (const SceneContact& c : scene.contacts())
  {
    const bool onFirst = c.first.kind == SceneBodyKind::Tissue && c.first.index == tissue;
    const bool onSecond = c.second.kind == SceneBodyKind::Tissue && c.second.index == tissue;
    if (!onFirst && !onSecond)
    {
      continue;
    }
    const SceneBody& other = onFirst ? c.second : c.first;
    if (other.kind == SceneBodyKind::Tool)
    {
      state.instrumentTouches = true;
      if (c.depth > deepest)
      {
        deepest = c.depth;
        state.instrumentContact = onFirst ? c.pointOnFirst : c.pointOnSecond;
      }
    }
    else if ((onFirst ? c.sideOnFirst : c.sideOnSecond) < 0)
    {
      ++state.lowerSurfaceContacts;
    }
  }
  return state;
}

WrinkleGenerator::WrinkleGenerator(MonitorPointSet monitors,
  const HexahedralMesh& mesh,
  const TriangleMesh& surfaceRest,
  const WrinkleParameters& parameters,
  const WrinkleInfluenceSettings& influence)
  : Monitors(std::move(monitors))
  , InfluenceSettings(influence)
{
  if (Monitors.size() == 0)
  {
    throw InvalidInputError("wrinkles: no monitor point");
  }
  checkWrinkleParameters(parameters);
  Parameters = parameters;
  Embedding.embed(mesh, Monitors.monitorPoints);
  Influence =
    WrinkleInfluence(Monitors, surfaceRest.positions, surfaceRest.triangles, InfluenceSettings);
  Current.resize(Monitors.size());
  Previous.resize(Monitors.size());
  Reference.reserve(Monitors.size());
  const std::size_t window = static_cast<std::size_t>(std::max(2, parameters.windowSize));
  Direction.reserve(window);
  Wrinkle.reserve(window);
  WrinklePoints.reserve(window);
  Displaced.reserve(Influence.affectedPoints().size());
  Displacements.reserve(Influence.affectedPoints().size());
  SlotOfPoint.assign(surfaceRest.vertexCount(), -1);
  ShownTriangles.assign(surfaceRest.triangleCount(), 1);
}

void WrinkleGenerator::setParameters(const WrinkleParameters& parameters)
{
  checkWrinkleParameters(parameters);
  Parameters = parameters;
}

void WrinkleGenerator::update(const std::vector<Vector3>& nodePositions,
  const WrinkleContactState& contacts)
{
  Embedding.mapPositions(nodePositions, Current);
  if (!HasPrevious)
  {
    std::copy(Current.begin(), Current.end(), Previous.begin());
    HasPrevious = true;
  }
  if (contacts.instrumentTouches)
  {
    selectWindow(contacts.instrumentContact);
  }
  updateReference(contacts);
  if (Influence.refreshPending() && !RefreshDeferredThisStep)
  {
    // A time-sliced refresh after a cut (WrinkleParameters): the wrinkles
    // of the steps until it ends move what the monitor points near the cut
    // moved before it (the new rim follows a few steps late).
    Influence.continueRefresh(static_cast<std::size_t>(Parameters.refreshMonitorsPerUpdate));
  }
  RefreshDeferredThisStep = false;
  for (const int j : Displaced)
  {
    SlotOfPoint[j] = -1;
  }
  Displaced.clear();
  Displacements.clear();
  if (NeedWrinkles && WindowEnd > WindowBegin)
  {
    computeWrinklePoints();
    propagate();
  }
  std::copy(Current.begin(), Current.end(), Previous.begin());
}

void WrinkleGenerator::selectWindow(const Vector3& contact)
{
  if (Current.empty()) // every monitor point was cut away
  {
    WindowBegin = WindowEnd = 0;
    return;
  }
  std::size_t nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < Current.size(); ++i)
  {
    const double d = (Current[i] - contact).squaredNorm();
    if (d < best)
    {
      best = d;
      nearest = i;
    }
  }
  const int curve = Monitors.curveOf(nearest);
  const int first = Monitors.curveStarts[curve];
  const int last = Monitors.curveStarts[curve + 1];
  const int size = std::min(Parameters.windowSize, last - first);
  WindowBegin = std::clamp(static_cast<int>(nearest) - size / 2, first, last - size);
  WindowEnd = WindowBegin + size;
}

int WrinkleGenerator::countReversals() const
{
  int count = 0;
  for (int k = WindowBegin; k < WindowEnd; ++k)
  {
    const Vector3 fromRest = Current[k] - Monitors.monitorPoints[k]; // V^c
    const Vector3 fromLast = Current[k] - Previous[k];               // V^l
    if (fromRest.dot(fromLast) < 0.0)
    {
      ++count;
    }
  }
  return count;
}

// The pseudo-code of 4.4.1.
void WrinkleGenerator::updateReference(const WrinkleContactState& contacts)
{
  if (contacts.lowerSurfaceContacts > Parameters.startContacts && contacts.instrumentTouches &&
      !NeedWrinkles && WindowEnd > WindowBegin)
  {
    LastReversals = countReversals();
    const double threshold = Parameters.reversalThreshold >= 0.0 ? Parameters.reversalThreshold
                                                                 : 0.5 * (WindowEnd - WindowBegin);
    if (LastReversals > threshold)
    {
      NeedWrinkles = true;
      Reference.assign(Previous.begin(), Previous.end());
    }
  }
  if (contacts.lowerSurfaceContacts < Parameters.endContacts && !contacts.instrumentTouches)
  {
    NeedWrinkles = false;
    Reference.clear();
  }
}

// Formula 4-16 over the window.
void WrinkleGenerator::computeWrinklePoints()
{
  const int size = WindowEnd - WindowBegin;
  Direction.resize(size);
  Wrinkle.resize(size);
  WrinklePoints.resize(size);
  // D(k) = sin(theta_k), theta over the reference's accumulated chord length.
  double chord = 0.0;
  Direction[0] = 0.0;
  for (int k = 1; k < size; ++k)
  {
    chord += (Reference[WindowBegin + k] - Reference[WindowBegin + k - 1]).norm();
    Direction[k] = chord; // accumulated, turned into sin(theta) below
  }
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  double thinnest = std::numeric_limits<double>::infinity(), thickest = 0.0;
  for (int k = WindowBegin; k < WindowEnd; ++k)
  {
    const double m = (Current[k] - Reference[k]).norm();
    smallest = std::min(smallest, m);
    largest = std::max(largest, m);
    thinnest = std::min(thinnest, Monitors.thickness[k]);
    thickest = std::max(thickest, Monitors.thickness[k]);
  }
  // M(k) = delta(k) eta(s m^d).
  double magnitude = Parameters.scale * 0.5 * (largest + smallest);
  if (Parameters.magnitudeBound > 0.0)
  {
    magnitude = std::min(magnitude, Parameters.magnitudeBound);
  }
  for (int k = 0; k < size; ++k)
  {
    const int i = WindowBegin + k;
    const double theta = chord > 0.0 ? Parameters.frequency * Direction[k] / chord : 0.0;
    Direction[k] = std::sin(theta);
    const double r = Monitors.thickness[i];
    const double ratio = thickest > thinnest ? 1.0 - (r - thinnest) / (thickest - thinnest) : 1.0;
    const double delta = r < Parameters.cutOffThickness ? 0.0 : ratio;
    Wrinkle[k] = Direction[k] * delta * magnitude;
    const Vector3 motion = Current[i] - Reference[i];
    const double m = motion.norm();
    const Vector3 offset = m > 0.0 ? Vector3(Wrinkle[k] / m * motion) : Vector3::Zero();
    WrinklePoints[k] =
      (Parameters.anchor == WrinkleAnchor::Reference ? Reference[i] : Current[i]) + offset;
  }
}

void WrinkleGenerator::propagate()
{
  for (int k = 0; k < WindowEnd - WindowBegin; ++k)
  {
    const int i = WindowBegin + k;
    const Vector3 d = WrinklePoints[k] - Current[i];
    for (int e = Influence.affectedBegin(i); e < Influence.affectedEnd(i); ++e)
    {
      const int j = Influence.point(e);
      int& slot = SlotOfPoint[j];
      if (slot < 0)
      {
        slot = static_cast<int>(Displaced.size());
        Displaced.push_back(j);
        Displacements.push_back(Vector3::Zero());
      }
      Displacements[slot] += Influence.factor(e) * d;
    }
  }
}

void WrinkleGenerator::applyTo(std::vector<Vector3>& positions) const
{
  for (std::size_t s = 0; s < Displaced.size(); ++s)
  {
    positions[Displaced[s]] += Displacements[s];
  }
}

} // namespace thintissue
