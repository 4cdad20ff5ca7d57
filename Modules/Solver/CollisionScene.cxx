#include "CollisionScene.h"

#include "ContactKernels.h"
#include "ThinTissueError.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <array>

namespace thintissue
{

using contact_kernels::FeatureContact;
using contact_kernels::ThickMeshView;

namespace
{

/// Mesh pairs are checked in parallel when they hold this many triangles.
constexpr std::size_t ParallelNarrowPhaseTriangles = 8192;

/// The springs one side of a contact gave to a solver.
struct SpringRange
{
  int solver = -1;
  int first = 0;
  int count = 0;
};

/// Which vertices of each body carry a contact (a tool or an obstacle side
/// has none that matter).
struct ContactFeatures
{
  std::array<int, 3> verticesOfFirst{ { -1, -1, -1 } };
  Vector3 weightsOfFirst = Vector3::Zero();
  std::array<int, 3> verticesOfSecond{ { -1, -1, -1 } };
  Vector3 weightsOfSecond = Vector3::Zero();
  /// Contacts of one tool's mesh share its stiffness (see the header):
  /// index of the sharing group, -1 for a contact with its own stiffness.
  int shareGroup = -1;
  std::array<SpringRange, 2> springs;
};

ContactFeatures featuresOf(const FeatureContact& c)
{
  ContactFeatures f;
  f.verticesOfFirst = c.verticesA;
  f.weightsOfFirst = c.weightsA;
  f.verticesOfSecond = c.verticesB;
  f.weightsOfSecond = c.weightsB;
  return f;
}

SceneContact sceneContactOf(const FeatureContact& c, SceneBody first, SceneBody second)
{
  SceneContact s;
  s.first = first;
  s.second = second;
  s.pointOnFirst = c.pointA;
  s.pointOnSecond = c.pointB;
  s.normal = c.normal;
  s.depth = c.depth;
  s.sideOnFirst = c.sideOnA;
  s.sideOnSecond = c.sideOnB;
  return s;
}

ThickMeshView toolMeshView(const RigidTool& tool)
{
  return { &tool.meshPositions(),
    &tool.meshTriangles(),
    &tool.meshRadii(),
    &tool.meshBvh(),
    nullptr,
    tool.meshContactDistance() };
}

} // namespace

struct CollisionScene::Implementation
{
  struct Tissue
  {
    CorotationalHexFem* fem = nullptr;
    DeformableCollisionMesh* collision = nullptr;
  };
  std::vector<Tissue> tissues;
  std::vector<RigidTool*> tools;
  std::vector<const StaticObstacle*> obstacles;

  // Parallel to CollisionScene::Contacts.
  std::vector<ContactFeatures> features;
  /// One pair of thick meshes the broad phase found overlapping: its
  /// narrow phase runs in parallel with the others', into its own buffers.
  struct MeshPairJob
  {
    ThickMeshView a;
    ThickMeshView b;
    std::vector<FeatureContact> contacts;
    contact_kernels::MeshMeshWorkspace workspace;
  };
  // Reused buffers (grown, never shrunk: no allocation once warm).
  std::vector<MeshPairJob> meshPairs;
  std::size_t meshPairCount = 0;
  std::vector<double> shareDepthSums;

  /// Distinct solvers (tissues may share one) and each tissue's solver.
  std::vector<CorotationalHexFem*> solvers;
  std::vector<int> solverOfTissue;
  std::vector<std::vector<EmbeddedContact>> solverSprings;

  /// A tissue-tissue contact's coupling in the joint solve: the cross
  /// terms -coefficient (sum_i w_i H_i^T n)(n^T sum_j u_j H_j) and their
  /// transpose, each side as (degree of freedom, weight) entries.
  struct Link
  {
    int tissueA = 0;
    int tissueB = 0;
    std::array<int, 3> verticesA{ { -1, -1, -1 } };
    Vector3 weightsA = Vector3::Zero();
    std::array<int, 3> verticesB{ { -1, -1, -1 } };
    Vector3 weightsB = Vector3::Zero();
    Vector3 normal = Vector3::UnitZ();
    double coefficient = 0.0; ///< h (h k + c)
    // Filled by buildLinkEntries once the systems are assembled.
    int firstEntryA = 0;
    int entryCountA = 0;
    int firstEntryB = 0;
    int entryCountB = 0;
  };
  std::vector<Link> links;
  std::vector<std::pair<int, double>> linkEntries;
  // Joint conjugate-gradient buffers.
  std::vector<Eigen::Index> solverOffsets;
  Eigen::VectorXd rhs, x, residual, preconditioned, direction, product, part, partOut;

  /// The (dof, weight) entries of a contact point given by collision
  /// vertices and weights, through the embedding (fixed nodes dropped).
  void appendEntries(int tissue, const std::array<int, 3>& vertices, const Vector3& weights)
  {
    const Tissue& t = tissues[tissue];
    const HexahedralEmbedding& embedding = t.collision->embedding();
    for (int k = 0; k < 3; ++k)
    {
      if (vertices[k] < 0 || !(weights[k] > 0.0))
      {
        continue;
      }
      const auto trilinear = embedding.weights(vertices[k]);
      const Hexahedron& nodes = embedding.nodesOf(vertices[k]);
      for (int a = 0; a < 8; ++a)
      {
        const int dof = t.fem->degreeOfFreedom(static_cast<std::size_t>(nodes[a]));
        if (dof >= 0 && trilinear[a] != 0.0)
        {
          linkEntries.emplace_back(dof, weights[k] * trilinear[a]);
        }
      }
    }
  }

  void addLink(int tissueA,
    const std::array<int, 3>& verticesA,
    const Vector3& weightsA,
    int tissueB,
    const std::array<int, 3>& verticesB,
    const Vector3& weightsB,
    const Vector3& normal,
    double stiffness,
    double damping)
  {
    Link link;
    link.tissueA = tissueA;
    link.tissueB = tissueB;
    link.verticesA = verticesA;
    link.weightsA = weightsA;
    link.verticesB = verticesB;
    link.weightsB = weightsB;
    const double h = tissues[tissueA].fem->settings().timeStep;
    link.coefficient = h * (h * stiffness + damping);
    link.normal = normal;
    links.push_back(link);
  }

  /// Degrees of freedom are known once each system is assembled.
  void buildLinkEntries()
  {
    linkEntries.clear();
    for (Link& link : links)
    {
      link.firstEntryA = static_cast<int>(linkEntries.size());
      appendEntries(link.tissueA, link.verticesA, link.weightsA);
      link.entryCountA = static_cast<int>(linkEntries.size()) - link.firstEntryA;
      link.firstEntryB = static_cast<int>(linkEntries.size());
      appendEntries(link.tissueB, link.verticesB, link.weightsB);
      link.entryCountB = static_cast<int>(linkEntries.size()) - link.firstEntryB;
    }
  }

  /// n . (sum of entries applied to the stacked vector v), per axis.
  double projected(const Eigen::VectorXd& v,
    Eigen::Index offset,
    int first,
    int count,
    const Vector3& n) const
  {
    Vector3 point = Vector3::Zero();
    for (int e = first; e < first + count; ++e)
    {
      point += linkEntries[e].second * v.segment<3>(offset + linkEntries[e].first);
    }
    return n.dot(point);
  }

  void spread(Eigen::VectorXd& y, Eigen::Index offset, int first, int count, const Vector3& f) const
  {
    for (int e = first; e < first + count; ++e)
    {
      y.segment<3>(offset + linkEntries[e].first) += linkEntries[e].second * f;
    }
  }

  /// y = (block-diagonal A + cross terms) v on the stacked vector.
  void multiply(const Eigen::VectorXd& v, Eigen::VectorXd& y)
  {
    for (std::size_t b = 0; b < solvers.size(); ++b)
    {
      const Eigen::Index n = solvers[b]->systemSize();
      part = v.segment(solverOffsets[b], n);
      solvers[b]->multiplySystem(part, partOut);
      y.segment(solverOffsets[b], n) = partOut;
    }
    for (const Link& link : links)
    {
      const Eigen::Index offsetA = solverOffsets[solverOfTissue[link.tissueA]];
      const Eigen::Index offsetB = solverOffsets[solverOfTissue[link.tissueB]];
      const double a = projected(v, offsetA, link.firstEntryA, link.entryCountA, link.normal);
      const double b = projected(v, offsetB, link.firstEntryB, link.entryCountB, link.normal);
      spread(y, offsetA, link.firstEntryA, link.entryCountA, -link.coefficient * b * link.normal);
      spread(y, offsetB, link.firstEntryB, link.entryCountB, -link.coefficient * a * link.normal);
    }
  }

  bool precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z, std::string& message)
  {
    for (std::size_t b = 0; b < solvers.size(); ++b)
    {
      const Eigen::Index n = solvers[b]->systemSize();
      part = r.segment(solverOffsets[b], n);
      if (!solvers[b]->preconditionSystem(part, partOut, message))
      {
        return false;
      }
      z.segment(solverOffsets[b], n) = partOut;
    }
    return true;
  }

  /// Velocity of a tissue's material point given by collision vertices
  /// and weights (x = H u applied to the node velocities).
  Vector3 tissueVelocity(int tissue,
    const std::array<int, 3>& vertices,
    const Vector3& weights) const
  {
    const Tissue& t = tissues[tissue];
    Vector3 velocity = Vector3::Zero();
    for (int k = 0; k < 3; ++k)
    {
      if (vertices[k] >= 0 && weights[k] != 0.0)
      {
        velocity +=
          weights[k] * t.collision->embedding().mapPosition(vertices[k], t.fem->velocities());
      }
    }
    return velocity;
  }

  /// Springs on a tissue's collision vertices for one side of a contact.
  SpringRange addSprings(int tissue,
    const std::array<int, 3>& vertices,
    const Vector3& weights,
    const Vector3& normal,
    double depth,
    double stiffness,
    const ContactParameters& parameters,
    const Vector3& surfaceVelocity)
  {
    const Tissue& t = tissues[tissue];
    std::vector<EmbeddedContact>& springs = solverSprings[solverOfTissue[tissue]];
    SpringRange range;
    range.solver = solverOfTissue[tissue];
    range.first = static_cast<int>(springs.size());
    const HexahedralEmbedding& embedding = t.collision->embedding();
    for (int k = 0; k < 3; ++k)
    {
      if (vertices[k] < 0 || !(weights[k] > 0.0))
      {
        continue;
      }
      EmbeddedContact spring;
      spring.hexahedron = static_cast<std::size_t>(embedding.hexahedron(vertices[k]));
      spring.local = embedding.localCoordinates(vertices[k]);
      spring.normal = normal;
      spring.depth = depth;
      spring.stiffness = weights[k] * stiffness;
      spring.damping = weights[k] * parameters.damping;
      spring.friction = parameters.friction;
      spring.slipVelocity = parameters.slipVelocity;
      spring.surfaceVelocity = surfaceVelocity;
      springs.push_back(spring);
    }
    range.count = static_cast<int>(springs.size()) - range.first;
    return range;
  }
};

CollisionScene::CollisionScene()
  : Internal(std::make_unique<Implementation>())
{
}

CollisionScene::~CollisionScene() = default;

int CollisionScene::addTissue(CorotationalHexFem& fem, DeformableCollisionMesh& collision)
{
  if (collision.embedding().nodeCount() != fem.positions().size())
  {
    throw InvalidInputError("collision scene: tissue " + std::to_string(Internal->tissues.size()) +
                            ": its collision mesh is embedded in " +
                            std::to_string(collision.embedding().nodeCount()) +
                            " nodes but its solver has " + std::to_string(fem.positions().size()));
  }
  Internal->tissues.push_back({ &fem, &collision });
  const auto known = std::find(Internal->solvers.begin(), Internal->solvers.end(), &fem);
  Internal->solverOfTissue.push_back(static_cast<int>(known - Internal->solvers.begin()));
  if (known == Internal->solvers.end())
  {
    Internal->solvers.push_back(&fem);
    Internal->solverSprings.emplace_back();
  }
  return static_cast<int>(Internal->tissues.size()) - 1;
}

int CollisionScene::addTool(RigidTool& tool)
{
  Internal->tools.push_back(&tool);
  return static_cast<int>(Internal->tools.size()) - 1;
}

int CollisionScene::addObstacle(const StaticObstacle& obstacle)
{
  Internal->obstacles.push_back(&obstacle);
  return static_cast<int>(Internal->obstacles.size()) - 1;
}

std::size_t CollisionScene::tissueCount() const
{
  return Internal->tissues.size();
}
std::size_t CollisionScene::toolCount() const
{
  return Internal->tools.size();
}
std::size_t CollisionScene::obstacleCount() const
{
  return Internal->obstacles.size();
}

void CollisionScene::setParameters(const CollisionSceneParameters& parameters)
{
  for (const ContactParameters* p : { &parameters.toolTissue,
         &parameters.tissueObstacle,
         &parameters.tissueTissue,
         &parameters.toolObstacle })
  {
    const bool valid = p->stiffness >= 0.0 && std::isfinite(p->stiffness) && p->damping >= 0.0 &&
                       std::isfinite(p->damping) && p->friction >= 0.0 &&
                       std::isfinite(p->friction) && p->slipVelocity > 0.0 &&
                       std::isfinite(p->slipVelocity);
    if (!valid)
    {
      throw InvalidInputError("collision scene: contact parameters need finite stiffness, damping "
                              "and friction >= 0 and a positive slip velocity");
    }
  }
  Parameters = parameters;
}

void CollisionScene::detectContacts()
{
  Implementation& in = *Internal;
  Contacts.clear();
  in.features.clear();
  in.links.clear();
  in.linkEntries.clear();
  Statistics = CollisionStatistics();
  for (auto& t : in.tissues)
  {
    t.collision->update(t.fem->positions());
  }
  for (auto& springs : in.solverSprings)
  {
    springs.clear();
  }

  // A contact of a primitive (sphere or capsule) with a thick mesh.
  auto addPrimitiveContact = [&](SceneBody first,
                               SceneBody second,
                               const Vector3& pointOnFirst,
                               const Vector3& pointOnSecond,
                               const Vector3& normal,
                               double depth,
                               int sideOnFirst,
                               int sideOnSecond,
                               double stiffness,
                               const ContactFeatures& features)
  {
    SceneContact c;
    c.first = first;
    c.second = second;
    c.pointOnFirst = pointOnFirst;
    c.pointOnSecond = pointOnSecond;
    c.normal = normal;
    c.depth = depth;
    c.stiffness = stiffness;
    c.sideOnFirst = sideOnFirst;
    c.sideOnSecond = sideOnSecond;
    Contacts.push_back(c);
    in.features.push_back(features);
  };
  // Thick mesh pairs: the first pass over the body pairs queues them, the
  // narrow phases run in parallel, the second pass adds their contacts in
  // the order of the body pairs (the same contacts, in the same order, as
  // one thread would find).
  bool collecting = true;
  std::size_t nextMeshPair = 0;
  auto addMeshContacts = [&](const ThickMeshView& a,
                           const ThickMeshView& b,
                           SceneBody first,
                           SceneBody second,
                           double stiffness,
                           int shareGroup)
  {
    if (collecting)
    {
      if (in.meshPairs.size() == in.meshPairCount)
      {
        in.meshPairs.emplace_back();
      }
      Implementation::MeshPairJob& job = in.meshPairs[in.meshPairCount++];
      job.a = a;
      job.b = b;
      return;
    }
    for (const FeatureContact& f : in.meshPairs[nextMeshPair++].contacts)
    {
      SceneContact c = sceneContactOf(f, first, second);
      c.stiffness = stiffness;
      Contacts.push_back(c);
      ContactFeatures features = featuresOf(f);
      features.shareGroup = shareGroup;
      in.features.push_back(features);
    }
  };
  // Primitives of a tool against a thick mesh; the tool is `second` when it
  // touches a tissue (the tissue is pushed) and `first` against an obstacle.
  auto addToolPrimitiveContacts = [&](const RigidTool& tool,
                                    const ThickMeshView& mesh,
                                    SceneBody toolBody,
                                    SceneBody meshBody,
                                    bool toolIsFirst,
                                    double stiffness)
  {
    if (collecting)
    {
      return;
    }
    for (const ToolSphere& sphere : tool.spheres())
    {
      const auto deepest =
        contact_kernels::deepestSphereContact(sphere.centre, sphere.radius, mesh);
      if (deepest.triangle < 0)
      {
        continue;
      }
      const Triangle& tri = (*mesh.triangles)[deepest.triangle];
      ContactFeatures features;
      const PointTriangleContact& pc = deepest.contact;
      if (toolIsFirst)
      {
        features.verticesOfSecond = { { tri[0], tri[1], tri[2] } };
        features.weightsOfSecond = pc.barycentric;
        addPrimitiveContact(toolBody,
          meshBody,
          sphere.centre,
          pc.trianglePoint,
          pc.normal,
          pc.depth,
          1,
          pc.side,
          stiffness,
          features);
      }
      else
      {
        features.verticesOfFirst = { { tri[0], tri[1], tri[2] } };
        features.weightsOfFirst = pc.barycentric;
        addPrimitiveContact(meshBody,
          toolBody,
          pc.trianglePoint,
          sphere.centre,
          -pc.normal,
          pc.depth,
          pc.side,
          1,
          stiffness,
          features);
      }
    }
    for (const ToolCapsule& capsule : tool.capsules())
    {
      const auto deepest = contact_kernels::deepestCapsuleContact(capsule, mesh);
      if (deepest.triangle < 0)
      {
        continue;
      }
      const Triangle& tri = (*mesh.triangles)[deepest.triangle];
      ContactFeatures features;
      const SegmentTriangleContact& sc = deepest.contact;
      if (toolIsFirst)
      {
        features.verticesOfSecond = { { tri[0], tri[1], tri[2] } };
        features.weightsOfSecond = sc.barycentric;
        addPrimitiveContact(toolBody,
          meshBody,
          sc.segmentPoint,
          sc.trianglePoint,
          sc.normal,
          sc.depth,
          1,
          sc.side,
          stiffness,
          features);
      }
      else
      {
        features.verticesOfFirst = { { tri[0], tri[1], tri[2] } };
        features.weightsOfFirst = sc.barycentric;
        addPrimitiveContact(meshBody,
          toolBody,
          sc.trianglePoint,
          sc.segmentPoint,
          -sc.normal,
          sc.depth,
          sc.side,
          1,
          stiffness,
          features);
      }
    }
  };

  // Broad phase: world boxes (inflated by radii and contact distances).
  const int tissueCount = static_cast<int>(in.tissues.size());
  const int toolCount = static_cast<int>(in.tools.size());
  const int obstacleCount = static_cast<int>(in.obstacles.size());
  auto overlapping = [&](const BoundingBox& x, const BoundingBox& y)
  {
    const bool overlap = !x.isEmpty() && !y.isEmpty() && x.intersects(y);
    if (collecting)
    {
      ++Statistics.bodyPairs;
      Statistics.overlappingBodyPairs += overlap ? 1 : 0;
    }
    return overlap;
  };
  in.meshPairCount = 0;
  for (int pass = 0; pass < 2; ++pass)
  {
    collecting = pass == 0;
    if (!collecting)
    {
      // Each job writes only its own buffers. Threads pay from a few
      // thousand triangles on; the knee's reduced meshes (~500 triangles
      // in all) are faster on one thread.
      auto runJob = [&](std::size_t k)
      {
        Implementation::MeshPairJob& job = in.meshPairs[k];
        job.contacts.clear();
        contact_kernels::meshMeshContacts(job.a, job.b, job.workspace, job.contacts);
      };
      std::size_t triangles = 0;
      for (std::size_t k = 0; k < in.meshPairCount; ++k)
      {
        triangles += in.meshPairs[k].a.triangles->size() + in.meshPairs[k].b.triangles->size();
      }
      if (in.meshPairCount > 1 && triangles >= ParallelNarrowPhaseTriangles)
      {
        // One job per task, so that the threads balance jobs of very
        // different sizes (the femur's 11,752 triangles beside a tool's).
        tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, in.meshPairCount, 1),
          [&](const tbb::blocked_range<std::size_t>& range)
          {
            for (std::size_t k = range.begin(); k != range.end(); ++k)
            {
              runJob(k);
            }
          },
          tbb::simple_partitioner());
      }
      else
      {
        for (std::size_t k = 0; k < in.meshPairCount; ++k)
        {
          runJob(k);
        }
      }
    }
    for (int i = 0; i < tissueCount; ++i)
    {
      const BoundingBox tissueBox = in.tissues[i].collision->bvh().bounds();
      const ThickMeshView tissueView = contact_kernels::viewOf(*in.tissues[i].collision);
      const SceneBody tissueBody{ SceneBodyKind::Tissue, i };
      for (int u = 0; u < toolCount; ++u)
      {
        const RigidTool& tool = *in.tools[u];
        if (!overlapping(tissueBox, tool.bounds()))
        {
          continue;
        }
        const SceneBody toolBody{ SceneBodyKind::Tool, u };
        addToolPrimitiveContacts(
          tool, tissueView, toolBody, tissueBody, false, Parameters.toolTissue.stiffness);
        if (tool.hasMesh())
        {
          addMeshContacts(tissueView,
            toolMeshView(tool),
            tissueBody,
            toolBody,
            Parameters.toolTissue.stiffness,
            2 * u);
        }
      }
      for (int o = 0; o < obstacleCount; ++o)
      {
        if (overlapping(tissueBox, in.obstacles[o]->bvh().bounds()))
        {
          addMeshContacts(tissueView,
            contact_kernels::viewOf(*in.obstacles[o]),
            tissueBody,
            SceneBody{ SceneBodyKind::Obstacle, o },
            Parameters.tissueObstacle.stiffness,
            -1);
        }
      }
      for (int j = i + 1; j < tissueCount; ++j)
      {
        if (overlapping(tissueBox, in.tissues[j].collision->bvh().bounds()))
        {
          addMeshContacts(tissueView,
            contact_kernels::viewOf(*in.tissues[j].collision),
            tissueBody,
            SceneBody{ SceneBodyKind::Tissue, j },
            Parameters.tissueTissue.stiffness,
            -1);
        }
      }
    }
    for (int u = 0; u < toolCount; ++u)
    {
      const RigidTool& tool = *in.tools[u];
      const BoundingBox toolBox = tool.bounds();
      const SceneBody toolBody{ SceneBodyKind::Tool, u };
      for (int o = 0; o < obstacleCount; ++o)
      {
        if (!overlapping(toolBox, in.obstacles[o]->bvh().bounds()))
        {
          continue;
        }
        const ThickMeshView obstacleView = contact_kernels::viewOf(*in.obstacles[o]);
        const SceneBody obstacleBody{ SceneBodyKind::Obstacle, o };
        addToolPrimitiveContacts(
          tool, obstacleView, toolBody, obstacleBody, true, Parameters.toolObstacle.stiffness);
        if (tool.hasMesh())
        {
          addMeshContacts(toolMeshView(tool),
            obstacleView,
            toolBody,
            obstacleBody,
            Parameters.toolObstacle.stiffness,
            2 * u + 1);
        }
      }
    }
  }

  // A tool mesh's contacts share its stiffness by depth (k_i = k d_i / sum d).
  in.shareDepthSums.assign(2 * in.tools.size(), 0.0);
  for (std::size_t k = 0; k < Contacts.size(); ++k)
  {
    if (in.features[k].shareGroup >= 0)
    {
      in.shareDepthSums[in.features[k].shareGroup] += Contacts[k].depth;
    }
  }
  for (std::size_t k = 0; k < Contacts.size(); ++k)
  {
    const int group = in.features[k].shareGroup;
    if (group >= 0)
    {
      Contacts[k].stiffness *= Contacts[k].depth / in.shareDepthSums[group];
    }
  }

  // Response: springs on the tissues.
  for (std::size_t k = 0; k < Contacts.size(); ++k)
  {
    const SceneContact& c = Contacts[k];
    ContactFeatures& f = in.features[k];
    if (c.first.kind != SceneBodyKind::Tissue)
    {
      continue; // tool-obstacle: the tool's reaction only
    }
    switch (c.second.kind)
    {
      case SceneBodyKind::Tool:
        f.springs[0] = in.addSprings(c.first.index,
          f.verticesOfFirst,
          f.weightsOfFirst,
          c.normal,
          c.depth,
          c.stiffness,
          Parameters.toolTissue,
          in.tools[c.second.index]->velocityAt(c.pointOnSecond));
        break;
      case SceneBodyKind::Obstacle:
        f.springs[0] = in.addSprings(c.first.index,
          f.verticesOfFirst,
          f.weightsOfFirst,
          c.normal,
          c.depth,
          c.stiffness,
          Parameters.tissueObstacle,
          Vector3::Zero());
        break;
      case SceneBodyKind::Tissue:
      {
        // Two tissues: a spring on each side with the other's start-of-step
        // velocity, coupled through the cross terms of the joint solve.
        const Vector3 velocityOfFirst =
          in.tissueVelocity(c.first.index, f.verticesOfFirst, f.weightsOfFirst);
        const Vector3 velocityOfSecond =
          in.tissueVelocity(c.second.index, f.verticesOfSecond, f.weightsOfSecond);
        f.springs[0] = in.addSprings(c.first.index,
          f.verticesOfFirst,
          f.weightsOfFirst,
          c.normal,
          c.depth,
          c.stiffness,
          Parameters.tissueTissue,
          velocityOfSecond);
        f.springs[1] = in.addSprings(c.second.index,
          f.verticesOfSecond,
          f.weightsOfSecond,
          -c.normal,
          c.depth,
          c.stiffness,
          Parameters.tissueTissue,
          velocityOfFirst);
        in.addLink(c.first.index,
          f.verticesOfFirst,
          f.weightsOfFirst,
          c.second.index,
          f.verticesOfSecond,
          f.weightsOfSecond,
          c.normal,
          c.stiffness,
          Parameters.tissueTissue.damping);
        break;
      }
    }
  }
  for (std::size_t b = 0; b < in.solvers.size(); ++b)
  {
    in.solvers[b]->setContacts(in.solverSprings[b]);
    Statistics.springs += static_cast<int>(in.solverSprings[b].size());
  }
  Statistics.contacts = static_cast<int>(Contacts.size());
}

void CollisionScene::collectReactions()
{
  Implementation& in = *Internal;
  std::vector<Vector3> toolForces(in.tools.size(), Vector3::Zero());
  std::vector<Vector3> toolTorques(in.tools.size(), Vector3::Zero());
  for (std::size_t k = 0; k < Contacts.size(); ++k)
  {
    SceneContact& c = Contacts[k];
    const ContactFeatures& f = in.features[k];
    if (c.first.kind == SceneBodyKind::Tool)
    {
      // Tool against an obstacle: penalty on the tool's velocity.
      const RigidTool& tool = *in.tools[c.first.index];
      const ContactParameters& p = Parameters.toolObstacle;
      const Vector3 velocity = tool.velocityAt(c.pointOnFirst);
      const double normalSpeed = c.normal.dot(velocity);
      const double normalForce = c.stiffness * c.depth - p.damping * normalSpeed;
      const Vector3 slip = velocity - normalSpeed * c.normal;
      c.force =
        normalForce * c.normal -
        (p.friction * std::max(0.0, normalForce) / std::max(slip.norm(), p.slipVelocity)) * slip;
      toolForces[c.first.index] += c.force;
      toolTorques[c.first.index] += (c.pointOnFirst - tool.pose().translation).cross(c.force);
      continue;
    }
    // Force on the tissue: what its solver's springs applied.
    const SpringRange& range = f.springs[0];
    const auto& forces = in.solvers[range.solver]->contactForces();
    c.force = Vector3::Zero();
    for (int s = range.first; s < range.first + range.count; ++s)
    {
      c.force += forces[s];
    }
    if (c.second.kind == SceneBodyKind::Tool)
    {
      const RigidTool& tool = *in.tools[c.second.index];
      toolForces[c.second.index] -= c.force;
      toolTorques[c.second.index] -= (c.pointOnSecond - tool.pose().translation).cross(c.force);
    }
  }
  for (std::size_t u = 0; u < in.tools.size(); ++u)
  {
    in.tools[u]->setReaction(toolForces[u], toolTorques[u]);
  }
}

SolverResult CollisionScene::step()
{
  detectContacts();
  Implementation& in = *Internal;
  SolverResult result;
  auto fail = [&](std::size_t solver, const std::string& message)
  {
    if (result.ok)
    {
      result.ok = false;
      result.message =
        "collision scene, solver of tissue " +
        std::to_string(
          std::find(in.solverOfTissue.begin(), in.solverOfTissue.end(), static_cast<int>(solver)) -
          in.solverOfTissue.begin()) +
        ": " + message;
    }
  };
  if (in.links.empty())
  {
    for (std::size_t b = 0; b < in.solvers.size(); ++b)
    {
      const SolverResult r = in.solvers[b]->step();
      result.iterations += r.iterations;
      if (!r.ok)
      {
        fail(b, r.message);
      }
    }
  }
  else if (solveJointly(result))
  {
    for (std::size_t b = 0; b < in.solvers.size(); ++b)
    {
      const SolverResult r = in.solvers[b]->finishCoupledStep(
        in.x.segment(in.solverOffsets[b], in.solvers[b]->systemSize()));
      if (!r.ok)
      {
        fail(b, r.message);
      }
    }
  }
  collectReactions();
  return result;
}

bool CollisionScene::solveJointly(SolverResult& result)
{
  // Tissues in contact with each other: one system for all solvers, the
  // block-diagonal part from each solver and the contacts' cross terms,
  // solved by conjugate gradients preconditioned by each solver's own
  // (stale) factor. Without the cross terms each side would resolve the
  // whole overlap against the other's extrapolated motion, which
  // overshoots and chatters (two-step cycles in the stacked-sheets test).
  Implementation& in = *Internal;
  in.solverOffsets.assign(in.solvers.size() + 1, 0);
  for (std::size_t b = 0; b < in.solvers.size(); ++b)
  {
    const SolverResult r = in.solvers[b]->beginCoupledStep();
    if (!r.ok)
    {
      result.ok = false;
      result.message = "collision scene: " + r.message;
      return false;
    }
    in.solverOffsets[b + 1] = in.solverOffsets[b] + in.solvers[b]->systemSize();
  }
  in.buildLinkEntries();
  const Eigen::Index size = in.solverOffsets.back();
  in.rhs.resize(size);
  in.x.resize(size);
  for (std::size_t b = 0; b < in.solvers.size(); ++b)
  {
    const Eigen::Index n = in.solvers[b]->systemSize();
    in.rhs.segment(in.solverOffsets[b], n) = in.solvers[b]->systemRightHandSide();
    const Eigen::VectorXd& previous = in.solvers[b]->previousSystemSolution();
    if (previous.size() == n)
    {
      in.x.segment(in.solverOffsets[b], n) = previous;
    }
    else
    {
      in.x.segment(in.solverOffsets[b], n).setZero();
    }
  }
  in.residual.resize(size);
  in.preconditioned.resize(size);
  in.product.resize(size);
  const CorotationalHexFemSettings& settings = in.solvers.front()->settings();
  const double target = settings.conjugateGradientTolerance * in.rhs.norm();
  std::string message;
  in.multiply(in.x, in.product);
  in.residual = in.rhs - in.product;
  if (!in.precondition(in.residual, in.preconditioned, message))
  {
    result.ok = false;
    result.message = "collision scene: " + message;
    return false;
  }
  in.direction = in.preconditioned;
  double rho = in.residual.dot(in.preconditioned);
  int iterations = 0;
  for (; iterations < settings.conjugateGradientMaxIterations && in.residual.norm() > target;
       ++iterations)
  {
    in.multiply(in.direction, in.product);
    const double step = rho / in.direction.dot(in.product);
    in.x += step * in.direction;
    in.residual -= step * in.product;
    if (!in.precondition(in.residual, in.preconditioned, message))
    {
      result.ok = false;
      result.message = "collision scene: " + message;
      return false;
    }
    const double next = in.residual.dot(in.preconditioned);
    in.direction = in.preconditioned + (next / rho) * in.direction;
    rho = next;
  }
  result.iterations = iterations;
  Statistics.jointIterations = iterations;
  if (in.residual.norm() > target || !in.x.allFinite())
  {
    result.ok = false;
    result.message = "collision scene: the joint solve of the tissues in contact did not converge "
                     "in " +
                     std::to_string(iterations) + " iterations; the last good state is kept";
    return false;
  }
  for (CorotationalHexFem* solver : in.solvers)
  {
    if (iterations > settings.refactorizationIterations)
    {
      solver->invalidateFactor(); // stale: refactorize at the next step
    }
    else
    {
      solver->chargeStaleIterations(iterations);
    }
  }
  return true;
}

int CollisionScene::contactCountOnSide(int tissue, int side) const
{
  int count = 0;
  for (const SceneContact& c : Contacts)
  {
    if (c.first.kind == SceneBodyKind::Tissue && c.first.index == tissue && c.sideOnFirst == side)
    {
      ++count;
    }
    if (c.second.kind == SceneBodyKind::Tissue && c.second.index == tissue &&
        c.sideOnSecond == side)
    {
      ++count;
    }
  }
  return count;
}

} // namespace thintissue
