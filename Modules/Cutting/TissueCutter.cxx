#include "TissueCutter.h"

#include "CorotationalHexFem.h"
#include "ReservedVector.h"
#include "ThinTissueError.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace thintissue
{

namespace
{

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

CuttableCollisionMesh makeCuttable(const TriangleMesh& collision, const std::string& radiusName)
{
  if (!collision.pointAttributes.has(radiusName))
  {
    throw InvalidInputError(
      "collision mesh '" + collision.name + "' has no '" + radiusName + "' array");
  }
  const auto& radius = collision.pointAttributes.get(radiusName);
  if (radius.components != 1 || radius.values.size() != collision.vertexCount())
  {
    throw InvalidInputError("collision mesh '" + collision.name + "': '" + radiusName +
                            "' must have one value per vertex");
  }
  collision.checkConsistency();
  return CuttableCollisionMesh(
    collision.name, collision.positions, collision.triangles, radius.values);
}

/// The settings the cutter checks itself (the visual mesh checks its own).
void checkCutterSettings(const std::string& name, const TissueCutterSettings& settings)
{
  const std::string label = "tissue cutter for '" + name + "'";
  if (!(settings.collision.snapFraction >= 0.0 && settings.collision.snapFraction < 0.5))
  {
    throw InvalidInputError(label + ": snap fraction " +
                            std::to_string(settings.collision.snapFraction) +
                            " is not in [0, 0.5)");
  }
  if (!(settings.fragmentAreaFraction >= 0.0 && settings.fragmentAreaFraction <= 1.0))
  {
    throw InvalidInputError(label + ": fragment area fraction " +
                            std::to_string(settings.fragmentAreaFraction) + " is not in [0, 1]");
  }
}

TriangleMesh collisionOf(const VisualCollisionBinding& binding, const std::string& radiusName)
{
  TriangleMesh collision;
  collision.name = binding.visual.name + " collision";
  collision.positions = binding.collisionPositions;
  collision.triangles = binding.collisionTriangles;
  collision.pointAttributes.set(radiusName, 1, binding.collisionRadii);
  return collision;
}

} // namespace

TissueCutter::TissueCutter(const VisualCollisionBinding& binding,
  const HexahedralMesh& simulation,
  CorotationalHexFem* solver,
  const TissueCutterSettings& settings)
  : TissueCutter(collisionOf(binding, settings.radiusArrayName), simulation, solver, settings)
{
  Visual = CuttableVisualMesh(binding, settings.visual);
  HasVisual = true;
  VisualEmbedding.embed(Simulation, Visual.mesh().positions);
  // Cuts add visual vertices: room for as many as the visual mesh reserves.
  const std::size_t room = Visual.mesh().positions.capacity();
  VisualEmbedding.reserve(room);
  VisualSeen.assign(Visual.mesh().vertexCount(), 0);
  reserveTouched(VisualSeen, room);
  VisualOfHexahedron.resize(Simulation.hexahedronCount());
  VisualIndirect.assign(Visual.mesh().vertexCount(), 0);
  reserveTouched(VisualIndirect, room);
  WatchedIn.assign(Visual.mesh().vertexCount(), -1);
  reserveTouched(WatchedIn, room);
  WatchedOfHexahedron.resize(Simulation.hexahedronCount());
  for (int v = 0; v < static_cast<int>(Visual.mesh().vertexCount()); ++v)
  {
    moveToBranchCopy(v);
    VisualOfHexahedron[Branches.originalOf(VisualEmbedding.hexahedron(v))].push_back(v);
    noteRevisits(v);
  }
}

TissueCutter::TissueCutter(const TriangleMesh& collision,
  const HexahedralMesh& simulation,
  CorotationalHexFem* solver,
  const TissueCutterSettings& settings)
  : Settings(settings)
  , Collision(makeCuttable(collision, settings.radiusArrayName))
  , Simulation(simulation)
  , Solver(solver)
{
  checkCutterSettings(Collision.name(), settings);
  Simulation.checkConsistency();
  if (Simulation.hexahedronCount() == 0)
  {
    throw InvalidInputError("hexahedral mesh '" + Simulation.name + "' has no hexahedron");
  }
  if (Solver && (Solver->nodeCount() != Simulation.nodeCount() ||
                  Solver->hexahedronCount() != Simulation.hexahedronCount()))
  {
    throw InvalidInputError("tissue cutter for '" + Collision.name() +
                            "': the solver was not made from hexahedral mesh '" + Simulation.name +
                            "'");
  }
  if (Solver)
  {
    // Cuts add nodes and copies: room for four times the mesh up front.
    Solver->reserve(4 * Solver->nodeCount(), 4 * Solver->hexahedronCount());
  }
  Simulation.nodes.reserve(4 * Simulation.nodeCount());
  Simulation.hexahedra.reserve(4 * Simulation.hexahedronCount());
  Branches = HexahedralBranches(Simulation, Collision);
  // A tissue torn already (or folded back within a hexahedron) starts with
  // one copy per branch, as if its tears had been cut.
  InitialSeparation = Branches.separateAll(Collision, Simulation);
  updateSolver(InitialSeparation);
  Active.assign(Collision.triangleCount(), 1);
  for (const Triangle& t : Collision.triangles())
  {
    const auto& x = Collision.restPositions();
    InitialArea += 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
  }
  SinglePiece = activeMeshIsOnePiece();
  CollisionEmbedding.embed(Simulation, Collision.restPositions());
  for (int v = 0; v < static_cast<int>(Collision.vertexCount()); ++v)
  {
    const int h = CollisionEmbedding.hexahedron(v);
    const int holder = Branches.copyHolding(h, Collision.trianglesOfVertex(v));
    if (holder >= 0 && holder != h)
    {
      CollisionEmbedding.setPoint(v, holder, CollisionEmbedding.localCoordinates(v));
    }
  }
}

void TissueCutter::setSettings(const TissueCutterSettings& settings)
{
  requireNoVisualPending("new settings");
  checkCutterSettings(Collision.name(), settings);
  if (settings.radiusArrayName != Settings.radiusArrayName)
  {
    throw InvalidInputError("tissue cutter for '" + Collision.name() + "': radius array name '" +
                            settings.radiusArrayName + "' (the cutter was made with '" +
                            Settings.radiusArrayName + "')");
  }
  if (HasVisual)
    Visual.setSettings(settings.visual); // checks before anything changes
  Settings = settings;
}

std::vector<Vector3> TissueCutter::currentVisualPositions() const
{
  std::vector<Vector3> positions;
  if (HasVisual)
    VisualEmbedding.mapPositions(Solver ? Solver->positions() : Simulation.nodes, positions);
  return positions;
}

std::vector<Vector3> TissueCutter::currentCollisionPositions() const
{
  std::vector<Vector3> positions;
  CollisionEmbedding.mapPositions(Solver ? Solver->positions() : Simulation.nodes, positions);
  return positions;
}

TriangleMesh TissueCutter::collisionMesh() const
{
  TriangleMesh mesh;
  mesh.name = Collision.name();
  mesh.positions = Collision.restPositions();
  mesh.triangles = Collision.triangles();
  mesh.pointAttributes.set(Settings.radiusArrayName, 1, Collision.radii());
  return mesh;
}

void TissueCutter::updateSolver(const HexahedronDuplicationResult& duplication)
{
  if (!Solver)
  {
    return;
  }
  for (const auto& [copy, source] : duplication.newNodes)
  {
    // Node copies may chain (a copy of a copy): the source exists already.
    const std::size_t made = Solver->addNodeCopy(static_cast<std::size_t>(source));
    if (made != static_cast<std::size_t>(copy))
    {
      throw InvalidInputError(
        "tissue cutter for '" + Collision.name() + "': the solver's nodes are out of step");
    }
  }
  for (const auto& [copy, source] : duplication.newHexahedra)
  {
    Solver->duplicateHexahedron(source, Simulation.hexahedra[copy]);
  }
  for (int h : duplication.renodedHexahedra)
  {
    Solver->replaceHexahedronNodes(h, Simulation.hexahedra[h]);
  }
}

std::vector<int> TissueCutter::reembedCollision(const TissueCutReport& report)
{
  const int firstNewVertex = static_cast<int>(CollisionEmbedding.pointCount());
  std::vector<Vector3> newRest;
  std::vector<int> candidates;
  for (int v = firstNewVertex; v < static_cast<int>(Collision.vertexCount()); ++v)
  {
    newRest.push_back(Collision.restPositions()[v]);
    for (int t : Collision.trianglesOfVertex(v))
    {
      candidates.insert(
        candidates.end(), Branches.hexahedraOf(t).begin(), Branches.hexahedraOf(t).end());
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  CollisionEmbedding.updateHexahedra(Simulation, report.simulation.renodedHexahedra);
  if (!newRest.empty())
  {
    CollisionEmbedding.appendPoints(newRest, Simulation, candidates);
  }
  // Every vertex of a touched hexahedron goes to the copy holding its fan
  // (each once: marked, not sorted, as an original's copies share most).
  CollisionSeen.resize(Collision.vertexCount(), 0);
  std::vector<int> vertices;
  auto take = [&](int v)
  {
    if (!CollisionSeen[v])
    {
      CollisionSeen[v] = 1;
      vertices.push_back(v);
    }
  };
  for (int h : report.simulation.touchedHexahedra)
    for (int copy : Branches.copiesOf(h))
      for (int t : Branches.trianglesOf(copy))
        for (int v : Collision.triangles()[t])
          take(v);
  for (int v = firstNewVertex; v < static_cast<int>(Collision.vertexCount()); ++v)
    take(v);
  for (int v : vertices)
    CollisionSeen[v] = 0;
  std::vector<int> moved;
  for (int v : vertices)
  {
    const int h = CollisionEmbedding.hexahedron(v);
    const int holder = Branches.copyHolding(h, Collision.trianglesOfVertex(v));
    if (holder >= 0 && holder != h)
    {
      CollisionEmbedding.setPoint(v, holder, CollisionEmbedding.localCoordinates(v));
      moved.push_back(v);
    }
    else if (v >= firstNewVertex)
    {
      moved.push_back(v);
    }
  }
  std::sort(moved.begin(), moved.end());
  return moved;
}

int TissueCutter::branchHolder(int v) const
{
  const int triangle = Visual.collisionTriangleOf(v, Collision);
  return triangle < 0 ? NoCollisionTriangle
                      : Branches.copyHolding(VisualEmbedding.hexahedron(v), triangle);
}

bool TissueCutter::moveToBranchCopy(int v)
{
  return moveToBranchCopy(v, branchHolder(v));
}

/// 5.3.5: a visual vertex goes to the copy of its hexahedron that holds
/// its collision triangle (`holder`, from branchHolder), or, failing that,
/// a triangle around it.
bool TissueCutter::moveToBranchCopy(int v, int holder)
{
  if (holder == NoCollisionTriangle)
    return false;
  const int h = VisualEmbedding.hexahedron(v);
  if (holder >= 0)
  {
    // The usual case: a copy of its hexahedron holds its triangle.
    if (holder == h)
      return false;
    VisualEmbedding.setPoint(v, holder, VisualEmbedding.localCoordinates(v));
    return true;
  }
  // Else a copy holding a triangle around it.
  const int triangle = Visual.collisionTriangleOf(v, Collision);
  std::vector<int> around;
  for (int corner : Collision.triangles()[triangle])
    around.insert(around.end(),
      Collision.trianglesOfVertex(corner).begin(),
      Collision.trianglesOfVertex(corner).end());
  holder = Branches.copyHolding(h, around);
  if (holder >= 0 && !VisualIndirect[v])
  {
    VisualIndirect[v] = 1;
    IndirectVisual.push_back(v);
  }
  if (holder < 0)
  {
    // No copy of its hexahedron holds its triangle or one around it (a
    // path or rim vertex beyond the triangles' radius boxes, on the steak):
    // it goes to the nearest hexahedron holding its triangle, extrapolated,
    // so that it follows its own piece rather than whatever lies under it.
    const std::vector<int>& holders = Branches.hexahedraOf(triangle);
    if (holders.empty())
      return false;
    VisualEmbedding.reembed({ v }, { Visual.mesh().positions[v] }, Simulation, holders);
    // Listed under its new original hexahedron, so that the cuts that copy
    // that one revisit it (at construction it is listed afterwards).
    const int before = Branches.originalOf(h);
    const int after = Branches.originalOf(VisualEmbedding.hexahedron(v));
    if (before != after && before < static_cast<int>(VisualOfHexahedron.size()))
    {
      auto& listed = VisualOfHexahedron[before];
      const auto found = std::find(listed.begin(), listed.end(), v);
      if (found != listed.end())
      {
        listed.erase(found);
        VisualOfHexahedron[after].push_back(v);
      }
    }
    return VisualEmbedding.hexahedron(v) != h;
  }
  if (holder == h)
    return false;
  VisualEmbedding.setPoint(v, holder, VisualEmbedding.localCoordinates(v));
  return true;
}

void TissueCutter::noteRevisits(int v)
{
  if (Visual.bindingKind(v) == BindingKind::CollisionTriangle)
    return;
  const int original = Branches.originalOf(VisualEmbedding.hexahedron(v));
  if (WatchedIn[v] != original)
  {
    WatchedIn[v] = original;
    WatchedOfHexahedron[original].push_back(v);
  }
}

void TissueCutter::takeRevisits(const TissueCutReport& report, std::vector<int>& vertices)
{
  vertices.insert(vertices.end(), IndirectVisual.begin(), IndirectVisual.end());
  for (int v : IndirectVisual)
    VisualIndirect[v] = 0;
  IndirectVisual.clear();
  std::vector<int> touched;
  for (int h : report.simulation.touchedHexahedra)
    touched.push_back(Branches.originalOf(h));
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  for (int original : touched)
  {
    for (int v : WatchedOfHexahedron[original])
    {
      if (WatchedIn[v] != original)
        continue; // listed again elsewhere since
      WatchedIn[v] = -1;
      vertices.push_back(v);
    }
    WatchedOfHexahedron[original].clear();
  }
}

std::vector<int> TissueCutter::reembedVisual(const TissueCutReport& report)
{
  VisualEmbedding.updateHexahedra(Simulation, report.simulation.renodedHexahedra);
  VisualOfHexahedron.resize(Simulation.hexahedronCount());
  const int firstNew = static_cast<int>(VisualEmbedding.pointCount());
  const auto& rest = Visual.mesh().positions;
  if (static_cast<int>(rest.size()) > firstNew)
  {
    // Each new vertex tried first in the copy holding its collision
    // triangle whose centre is nearest (most are inside it: one inversion,
    // no search structure), the others searched among all those copies.
    std::vector<int> candidates;
    std::vector<Vector3> centres; // per candidate
    std::vector<int> firstTry;
    firstTry.reserve(rest.size() - firstNew);
    CandidateSlot.resize(Simulation.hexahedronCount(), 0);
    for (int v = firstNew; v < static_cast<int>(rest.size()); ++v)
    {
      const int t = Visual.collisionTriangleOf(v, Collision);
      int nearest = -1;
      double nearestDistance = std::numeric_limits<double>::infinity();
      static const std::vector<int> none;
      for (const int h : t >= 0 ? Branches.hexahedraOf(t) : none)
      {
        // Each candidate once, its centre too (the new vertices of a
        // triangle share its hexahedra: 8 node sums per vertex had cost
        // more than the embedding's first tries).
        if (!CandidateSlot[h])
        {
          candidates.push_back(h);
          CandidateSlot[h] = static_cast<int>(candidates.size());
          Vector3 centre = Vector3::Zero();
          for (const int node : Simulation.hexahedra[h])
            centre += Simulation.nodes[node];
          centres.push_back(centre / 8.0);
        }
        const double distance = (centres[CandidateSlot[h] - 1] - rest[v]).squaredNorm();
        if (distance < nearestDistance)
        {
          nearest = h;
          nearestDistance = distance;
        }
      }
      firstTry.push_back(nearest);
    }
    for (int h : candidates)
      CandidateSlot[h] = 0;
    std::sort(candidates.begin(), candidates.end());
    VisualEmbedding.appendPoints(
      std::vector<Vector3>(rest.begin() + firstNew, rest.end()), firstTry, Simulation, candidates);
    for (int v = firstNew; v < static_cast<int>(rest.size()); ++v)
      VisualOfHexahedron[Branches.originalOf(VisualEmbedding.hexahedron(v))].push_back(v);
  }
  // The vertices rebound by the cut, and those of hexahedra that got a new
  // copy (a touched hexahedron that was not split keeps one branch, and its
  // vertices bound to a triangle of it and not rebound keep their place).
  std::vector<int> vertices = report.visual.reboundVertices;
  std::vector<int> split;
  for (const auto& [copy, source] : report.simulation.newHexahedra)
    split.push_back(Branches.originalOf(source));
  std::sort(split.begin(), split.end());
  split.erase(std::unique(split.begin(), split.end()), split.end());
  for (int original : split)
  {
    const auto& inside = VisualOfHexahedron[original];
    vertices.insert(vertices.end(), inside.begin(), inside.end());
  }
  // And those whose collision triangle the cut may have changed without
  // copying their hexahedron (takeRevisits).
  takeRevisits(report, vertices);
  // Each once (marked, not sorted: the list is as long as the regions cut).
  VisualSeen.resize(rest.size(), 0);
  VisualIndirect.resize(rest.size(), 0);
  WatchedIn.resize(rest.size(), -1);
  WatchedOfHexahedron.resize(VisualOfHexahedron.size());
  std::vector<int> unique;
  unique.reserve(vertices.size());
  for (int v : vertices)
  {
    if (!VisualSeen[v])
    {
      VisualSeen[v] = 1;
      unique.push_back(v);
    }
  }
  // The copy holding each one's triangle only reads the binding and the
  // branches: found on several threads when there are many; moving them
  // stays serial (a few take the slow way, which edits shared lists).
  std::vector<int> holders(unique.size());
  const auto findHolders = [&](std::size_t from, std::size_t to)
  {
    for (std::size_t i = from; i < to; ++i)
      holders[i] = branchHolder(unique[i]);
  };
  if (unique.size() < Settings.visual.parallelRegionTriangles)
    findHolders(0, unique.size());
  else
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, unique.size(), 1024),
      [&](const tbb::blocked_range<std::size_t>& range)
      { findHolders(range.begin(), range.end()); });
  std::vector<int> moved;
  for (std::size_t i = 0; i < unique.size(); ++i)
    if (moveToBranchCopy(unique[i], holders[i]) || unique[i] >= firstNew)
      moved.push_back(unique[i]);
  followLeftToHistory(report, moved);
  for (int v : vertices)
  {
    VisualSeen[v] = 0;
    noteRevisits(v);
  }
  return moved;
}

// The vertices the visual cut left to the split history (lazy binding)
// and has not revisited above: each goes to the copy of its hexahedron
// holding the triangle its binding resolves to. The vertices of a piece
// share a few hexahedra: each (hexahedron, triangle) holder is found once.
void TissueCutter::followLeftToHistory(const TissueCutReport& report, std::vector<int>& moved)
{
  std::array<int, 3> last{ { -1, -1, -1 } }; // hexahedron, triangle, holder
  std::vector<std::array<int, 3>> found;
  for (const auto& [v, triangle] : report.visual.leftToHistory)
  {
    if (VisualSeen[v])
      continue;
    const int h = VisualEmbedding.hexahedron(v);
    if (last[0] != h || last[1] != triangle)
    {
      const auto known = std::find_if(found.begin(),
        found.end(),
        [&](const std::array<int, 3>& f) { return f[0] == h && f[1] == triangle; });
      if (known != found.end())
        last = *known;
      else
      {
        last = { { h, triangle, Branches.copyHolding(h, triangle) } };
        found.push_back(last);
      }
    }
    if (moveToBranchCopy(v, last[2]))
      moved.push_back(v);
  }
}

TissueCutReport TissueCutter::cut(const Blade& blade)
{
  TissueCutReport report = cutCollision(blade);
  finishVisualCut(report);
  return report;
}

TissueCutReport TissueCutter::cutCollision(const Blade& blade)
{
  requireNoVisualPending("cut");
  const auto start = Clock::now();
  TissueCutReport report;
  const std::vector<Vector3> current = currentCollisionPositions();
  report.collision = Collision.cut(blade, current, Settings.collision);
  report.collisionMilliseconds = millisecondsSince(start);
  if (report.collision.changed())
  {
    followCollisionCut(report);
    const auto removalStart = Clock::now();
    handleFreePieces(report);
    report.removalMilliseconds = millisecondsSince(removalStart);
    VisualPending = HasVisual;
  }
  report.totalMilliseconds = millisecondsSince(start);
  return report;
}

void TissueCutter::finishVisualCut(TissueCutReport& report)
{
  if (!VisualPending)
    return;
  VisualPending = false;
  const auto start = Clock::now();
  // A removal that changed no collision triangle has no visual cut to
  // follow, only its pieces.
  const bool visualToCut = report.collision.changed() && !VisualFailed;
  if (!visualToCut || followWithVisualCut(report))
  {
    const auto removalStart = Clock::now();
    for (const PendingPieceVisual& pending : PendingPieces)
      pieceVisual(pending.triangles, pending.nodeCurrent, report.handedOver[pending.piece]);
    report.removalMilliseconds += millisecondsSince(removalStart);
  }
  PendingPieces.clear();
  report.totalMilliseconds += millisecondsSince(start);
}

void TissueCutter::requireNoVisualPending(const char* what) const
{
  if (VisualPending)
  {
    throw InvalidInputError("tissue cutter for '" + Collision.name() + "': " + what +
                            " while the last cut's visual half is pending (finishVisualCut)");
  }
}

void TissueCutter::followCollisionCut(TissueCutReport& report)
{
  // Pieces of a removed piece's triangles stay removed.
  Active.resize(Collision.triangleCount(), 1);
  for (const auto& split : report.collision.splits)
    for (int child : split.children)
      Active[child] = Active[split.parent];
  const auto simulationStart = Clock::now();
  report.simulation = Branches.update(Collision, report.collision, Simulation);
  updateSolver(report.simulation);
  report.simulationMilliseconds = millisecondsSince(simulationStart);
  const auto embeddingStart = Clock::now();
  report.reembeddedCollisionVertices = reembedCollision(report);
  report.embeddingMilliseconds = millisecondsSince(embeddingStart);
}

bool TissueCutter::followWithVisualCut(TissueCutReport& report)
{
  const auto visualStart = Clock::now();
  try
  {
    report.visual = Visual.cut(Collision, report.collision);
  }
  catch (const std::exception& error)
  {
    // The collision and simulation meshes are cut already: the tissue goes
    // on without its visual cut rather than stop (the visual mesh keeps its
    // last state and its embedding).
    VisualFailed = true;
    SinglePiece = false; // its pieces are looked at whole next time
    report.visualError = "visual cut of '" + Visual.mesh().name + "' failed: " + error.what() +
                         "; the visual mesh is no longer cut";
    return false;
  }
  report.visualMilliseconds = millisecondsSince(visualStart);
  const auto reembedStart = Clock::now();
  report.reembeddedVisualVertices = reembedVisual(report);
  report.visualEmbeddingMilliseconds = millisecondsSince(reembedStart);
  return true;
}

std::vector<int> TissueCutter::activeTrianglesWithin(const Vector3& centre, double radius) const
{
  if (!centre.allFinite() || !(radius > 0.0) || !std::isfinite(radius))
    throw InvalidInputError(
      "shaving: the window needs a finite centre and a positive radius (got " +
      std::to_string(radius) + ")");
  const auto& rest = Collision.restPositions();
  const auto& triangles = Collision.triangles();
  std::vector<int> held;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    const Triangle& c = triangles[t];
    const Vector3 centroid = (rest[c[0]] + rest[c[1]] + rest[c[2]]) / 3.0;
    if (Active[t] && (centroid - centre).squaredNorm() <= radius * radius)
      held.push_back(static_cast<int>(t));
  }
  return held;
}

TissueCutReport TissueCutter::removeTriangles(const std::vector<int>& triangles)
{
  TissueCutReport report = removeTrianglesCollision(triangles);
  finishVisualCut(report);
  return report;
}

TissueCutReport TissueCutter::removeTrianglesCollision(const std::vector<int>& triangles)
{
  requireNoVisualPending("removal");
  const auto start = Clock::now();
  const auto count = static_cast<int>(Collision.triangleCount());
  std::vector<int> removed;
  for (int t : triangles)
  {
    if (t < 0 || t >= count)
    {
      throw InvalidInputError("removal from collision mesh '" + Collision.name() + "': triangle " +
                              std::to_string(t) + " is not one of its " + std::to_string(count));
    }
    if (Active[t])
      removed.push_back(t);
  }
  std::sort(removed.begin(), removed.end());
  removed.erase(std::unique(removed.begin(), removed.end()), removed.end());
  TissueCutReport report;
  if (removed.empty())
    return report;
  // The border between the removed triangles and the rest opens (a cut
  // along edges: nothing is split, traced or re-meshed), so that the
  // removed ones are a piece of their own, and the rest's cut surface
  // closes the opening (6.4.3).
  std::vector<std::array<int, 2>> border;
  const auto& corners = Collision.triangles();
  for (int t : removed)
    for (int k = 0; k < 3; ++k)
    {
      const int a = corners[t][k], b = corners[t][(k + 1) % 3];
      for (int other : Collision.trianglesOfEdge(a, b))
        if (other >= 0 && Active[other] &&
            !std::binary_search(removed.begin(), removed.end(), other))
          border.push_back({ { std::min(a, b), std::max(a, b) } });
    }
  std::sort(border.begin(), border.end());
  border.erase(std::unique(border.begin(), border.end()), border.end());
  report.collision = Collision.cutAlongEdges(border);
  report.collisionMilliseconds = millisecondsSince(start);
  if (report.collision.changed())
    followCollisionCut(report);
  const auto removalStart = Clock::now();
  if (Settings.freePieces == FreePieceHandling::HandOver)
    handOver(removed, report);
  removePiece(removed, report);
  ++report.removedPieces;
  // What the removal left apart from the rest (a bridge shaved through).
  if (report.collision.changed())
    handleFreePieces(report);
  report.removalMilliseconds = millisecondsSince(removalStart);
  // The visual half (the opening, its cut surface, the pieces' visual
  // parts; a piece with no new collision vertex needs only those).
  VisualPending = HasVisual;
  report.totalMilliseconds = millisecondsSince(start);
  return report;
}

} // namespace thintissue
