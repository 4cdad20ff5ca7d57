#include "CollisionScene.h"

#include "ContactKernels.h"
#include "ThinTissueError.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_group.h>

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
    /// A tissue against an obstacle: its candidates (temporal coherence).
    contact_kernels::StaticPairCandidates* candidates = nullptr;
    double margin = 0.0;
    std::vector<FeatureContact> contacts;
    contact_kernels::MeshMeshWorkspace workspace;
  };
  /// Per tissue and obstacle: the features that may touch (kept between
  /// steps while the tissue moves less than the margin).
  std::vector<std::vector<contact_kernels::StaticPairCandidates>> obstacleCandidates;
  /// Per tissue: the candidate margin and the collision mesh it is for.
  std::vector<std::pair<std::uint64_t, double>> candidateMargins;
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

  // --- Detection (CollisionScene::detectContacts), in passes over the body
  // pairs: the first queues the thick mesh pairs, whose narrow phases then
  // run (in parallel when large), the second adds every contact in the
  // order of the body pairs (the same contacts, in the same order, as one
  // thread would find).
  enum class Pass
  {
    QueueMeshPairs,
    AddContacts
  };
  struct Detection
  {
    std::vector<SceneContact>& contacts;
    const CollisionSceneParameters& parameters;
    CollisionStatistics& statistics;
    Pass pass = Pass::QueueMeshPairs;
    std::size_t nextMeshPair = 0;
  };

  /// Empties last step's contacts and springs; maps the collision meshes.
  void startDetection(std::vector<SceneContact>& contacts)
  {
    contacts.clear();
    features.clear();
    links.clear();
    linkEntries.clear();
    for (auto& t : tissues)
    {
      t.collision->update(t.fem->positions());
    }
    for (auto& springs : solverSprings)
    {
      springs.clear();
    }
    meshPairCount = 0;
    obstacleCandidates.resize(tissues.size());
    for (auto& candidates : obstacleCandidates)
    {
      candidates.resize(obstacles.size());
    }
    candidateMargins.resize(tissues.size(), { 0, 0.0 });
  }

  int candidateSearches() const
  {
    int searches = 0;
    for (const auto& ofTissue : obstacleCandidates)
    {
      for (const auto& candidates : ofTissue)
      {
        searches += candidates.searches;
      }
    }
    return searches;
  }

  /// Tissue i's candidate margin: `perRadius` times its largest radius
  /// (found again when its collision mesh changes).
  double candidateMargin(int i, double perRadius)
  {
    const DeformableCollisionMesh& mesh = *tissues[i].collision;
    auto& [identity, margin] = candidateMargins[i];
    if (identity != mesh.identity())
    {
      identity = mesh.identity();
      const auto& radii = mesh.radii();
      margin = radii.empty() ? 0.0 : *std::max_element(radii.begin(), radii.end());
      margin += mesh.contactDistance();
    }
    return perRadius * margin;
  }

  /// Broad phase of one body pair (counted in the first pass only).
  bool overlapping(Detection& d, const BoundingBox& x, const BoundingBox& y) const
  {
    const bool overlap = !x.isEmpty() && !y.isEmpty() && x.intersects(y);
    if (d.pass == Pass::QueueMeshPairs)
    {
      ++d.statistics.bodyPairs;
      d.statistics.overlappingBodyPairs += overlap ? 1 : 0;
    }
    return overlap;
  }

  void addContact(Detection& d, const SceneContact& contact, const ContactFeatures& contactFeatures)
  {
    d.contacts.push_back(contact);
    features.push_back(contactFeatures);
  }

  /// Thick meshes a and b: queued in the first pass, their contacts added
  /// in the second. `shareGroup`: see ContactFeatures.
  void meshPair(Detection& d,
    const ThickMeshView& a,
    const ThickMeshView& b,
    SceneBody first,
    SceneBody second,
    double stiffness,
    int shareGroup,
    contact_kernels::StaticPairCandidates* candidates = nullptr,
    double margin = 0.0)
  {
    if (d.pass == Pass::QueueMeshPairs)
    {
      if (meshPairs.size() == meshPairCount)
      {
        meshPairs.emplace_back();
      }
      MeshPairJob& job = meshPairs[meshPairCount++];
      job.a = a;
      job.b = b;
      job.candidates = candidates;
      job.margin = margin;
      return;
    }
    for (const FeatureContact& f : meshPairs[d.nextMeshPair++].contacts)
    {
      SceneContact c = sceneContactOf(f, first, second);
      c.stiffness = stiffness;
      ContactFeatures contactFeatures = featuresOf(f);
      contactFeatures.shareGroup = shareGroup;
      addContact(d, c, contactFeatures);
    }
  }

  /// The deepest contact of one tool primitive with a mesh's triangle
  /// `triangle`: the tool is `second` when it touches a tissue (the tissue
  /// is pushed) and `first` against an obstacle.
  template <typename PrimitiveContact>
  void primitiveContact(Detection& d,
    const PrimitiveContact& contact,
    const Vector3& toolPoint,
    const Triangle& triangle,
    SceneBody toolBody,
    SceneBody meshBody,
    bool toolIsFirst,
    double stiffness)
  {
    SceneContact c;
    ContactFeatures contactFeatures;
    c.stiffness = stiffness;
    c.depth = contact.depth;
    const std::array<int, 3> vertices{ { triangle[0], triangle[1], triangle[2] } };
    if (toolIsFirst)
    {
      c.first = toolBody;
      c.second = meshBody;
      c.pointOnFirst = toolPoint;
      c.pointOnSecond = contact.trianglePoint;
      c.normal = contact.normal;
      c.sideOnSecond = contact.side;
      contactFeatures.verticesOfSecond = vertices;
      contactFeatures.weightsOfSecond = contact.barycentric;
    }
    else
    {
      c.first = meshBody;
      c.second = toolBody;
      c.pointOnFirst = contact.trianglePoint;
      c.pointOnSecond = toolPoint;
      c.normal = -contact.normal;
      c.sideOnFirst = contact.side;
      contactFeatures.verticesOfFirst = vertices;
      contactFeatures.weightsOfFirst = contact.barycentric;
    }
    addContact(d, c, contactFeatures);
  }

  /// A tool's spheres and capsules against a thick mesh (second pass only).
  void toolPrimitives(Detection& d,
    const RigidTool& tool,
    const ThickMeshView& mesh,
    SceneBody toolBody,
    SceneBody meshBody,
    bool toolIsFirst,
    double stiffness)
  {
    if (d.pass == Pass::QueueMeshPairs)
    {
      return;
    }
    for (const ToolSphere& sphere : tool.spheres())
    {
      const auto deepest =
        contact_kernels::deepestSphereContact(sphere.centre, sphere.radius, mesh);
      if (deepest.triangle >= 0)
      {
        primitiveContact(d,
          deepest.contact,
          sphere.centre,
          (*mesh.triangles)[deepest.triangle],
          toolBody,
          meshBody,
          toolIsFirst,
          stiffness);
      }
    }
    for (const ToolCapsule& capsule : tool.capsules())
    {
      const auto deepest = contact_kernels::deepestCapsuleContact(capsule, mesh);
      if (deepest.triangle >= 0)
      {
        primitiveContact(d,
          deepest.contact,
          deepest.contact.segmentPoint,
          (*mesh.triangles)[deepest.triangle],
          toolBody,
          meshBody,
          toolIsFirst,
          stiffness);
      }
    }
  }

  /// Tissue i against the tools, the obstacles and the tissues after it.
  void tissuePairs(Detection& d, int i)
  {
    const BoundingBox tissueBox = tissues[i].collision->bvh().bounds();
    const ThickMeshView tissueView = contact_kernels::viewOf(*tissues[i].collision);
    const SceneBody tissueBody{ SceneBodyKind::Tissue, i };
    const CollisionSceneParameters& p = d.parameters;
    for (int u = 0; u < static_cast<int>(tools.size()); ++u)
    {
      const RigidTool& tool = *tools[u];
      if (!overlapping(d, tissueBox, tool.bounds()))
      {
        continue;
      }
      const SceneBody toolBody{ SceneBodyKind::Tool, u };
      toolPrimitives(d, tool, tissueView, toolBody, tissueBody, false, p.toolTissue.stiffness);
      if (tool.hasMesh())
      {
        meshPair(
          d, tissueView, toolMeshView(tool), tissueBody, toolBody, p.toolTissue.stiffness, 2 * u);
      }
    }
    for (int o = 0; o < static_cast<int>(obstacles.size()); ++o)
    {
      if (overlapping(d, tissueBox, obstacles[o]->bvh().bounds()))
      {
        meshPair(d,
          tissueView,
          contact_kernels::viewOf(*obstacles[o]),
          tissueBody,
          SceneBody{ SceneBodyKind::Obstacle, o },
          p.tissueObstacle.stiffness,
          -1,
          &obstacleCandidates[i][o],
          candidateMargin(i, p.candidateMarginPerRadius));
      }
    }
    for (int j = i + 1; j < static_cast<int>(tissues.size()); ++j)
    {
      if (overlapping(d, tissueBox, tissues[j].collision->bvh().bounds()))
      {
        meshPair(d,
          tissueView,
          contact_kernels::viewOf(*tissues[j].collision),
          tissueBody,
          SceneBody{ SceneBodyKind::Tissue, j },
          p.tissueTissue.stiffness,
          -1);
      }
    }
  }

  /// Each tool against the obstacles (acts on the tool only).
  void toolObstaclePairs(Detection& d)
  {
    const double stiffness = d.parameters.toolObstacle.stiffness;
    for (int u = 0; u < static_cast<int>(tools.size()); ++u)
    {
      const RigidTool& tool = *tools[u];
      const BoundingBox toolBox = tool.bounds();
      const SceneBody toolBody{ SceneBodyKind::Tool, u };
      for (int o = 0; o < static_cast<int>(obstacles.size()); ++o)
      {
        if (!overlapping(d, toolBox, obstacles[o]->bvh().bounds()))
        {
          continue;
        }
        const ThickMeshView obstacleView = contact_kernels::viewOf(*obstacles[o]);
        const SceneBody obstacleBody{ SceneBodyKind::Obstacle, o };
        toolPrimitives(d, tool, obstacleView, toolBody, obstacleBody, true, stiffness);
        if (tool.hasMesh())
        {
          meshPair(
            d, toolMeshView(tool), obstacleView, toolBody, obstacleBody, stiffness, 2 * u + 1);
        }
      }
    }
  }

  void bodyPairs(Detection& d)
  {
    for (int i = 0; i < static_cast<int>(tissues.size()); ++i)
    {
      tissuePairs(d, i);
    }
    toolObstaclePairs(d);
  }

  /// The queued mesh pairs' narrow phases; each job writes only its own
  /// buffers. Threads pay from a few thousand triangles on; the knee's
  /// reduced meshes (~500 triangles in all) are faster on one thread.
  void runMeshPairJobs()
  {
    auto runJob = [&](std::size_t k)
    {
      MeshPairJob& job = meshPairs[k];
      job.contacts.clear();
      if (job.candidates)
      {
        contact_kernels::meshStaticContacts(
          job.a, job.b, job.margin, *job.candidates, job.workspace, job.contacts);
        return;
      }
      contact_kernels::meshMeshContacts(job.a, job.b, job.workspace, job.contacts);
    };
    std::size_t triangles = 0;
    for (std::size_t k = 0; k < meshPairCount; ++k)
    {
      triangles += meshPairs[k].a.triangles->size() + meshPairs[k].b.triangles->size();
    }
    if (meshPairCount > 1 && triangles >= ParallelNarrowPhaseTriangles)
    {
      // One job per task, so that the threads balance jobs of very
      // different sizes (the femur's 11,752 triangles beside a tool's).
      tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, meshPairCount, 1),
        [&](const tbb::blocked_range<std::size_t>& range)
        {
          for (std::size_t k = range.begin(); k != range.end(); ++k)
          {
            runJob(k);
          }
        },
        tbb::simple_partitioner());
      return;
    }
    for (std::size_t k = 0; k < meshPairCount; ++k)
    {
      runJob(k);
    }
  }

  /// A tool mesh's contacts share its stiffness by depth (k_i = k d_i / sum d).
  void shareToolMeshStiffness(std::vector<SceneContact>& contacts)
  {
    shareDepthSums.assign(2 * tools.size(), 0.0);
    for (std::size_t k = 0; k < contacts.size(); ++k)
    {
      if (features[k].shareGroup >= 0)
      {
        shareDepthSums[features[k].shareGroup] += contacts[k].depth;
      }
    }
    for (std::size_t k = 0; k < contacts.size(); ++k)
    {
      const int group = features[k].shareGroup;
      if (group >= 0)
      {
        contacts[k].stiffness *= contacts[k].depth / shareDepthSums[group];
      }
    }
  }

  /// Two tissues: a spring on each side with the other's start-of-step
  /// velocity, coupled through the cross terms of the joint solve.
  void addTissueTissueSprings(const SceneContact& c,
    ContactFeatures& f,
    const ContactParameters& parameters)
  {
    const Vector3 velocityOfFirst =
      tissueVelocity(c.first.index, f.verticesOfFirst, f.weightsOfFirst);
    const Vector3 velocityOfSecond =
      tissueVelocity(c.second.index, f.verticesOfSecond, f.weightsOfSecond);
    f.springs[0] = addSprings(c.first.index,
      f.verticesOfFirst,
      f.weightsOfFirst,
      c.normal,
      c.depth,
      c.stiffness,
      parameters,
      velocityOfSecond);
    f.springs[1] = addSprings(c.second.index,
      f.verticesOfSecond,
      f.weightsOfSecond,
      -c.normal,
      c.depth,
      c.stiffness,
      parameters,
      velocityOfFirst);
    addLink(c.first.index,
      f.verticesOfFirst,
      f.weightsOfFirst,
      c.second.index,
      f.verticesOfSecond,
      f.weightsOfSecond,
      c.normal,
      c.stiffness,
      parameters.damping);
  }

  /// Response: springs on the tissues (tool-obstacle contacts give the
  /// tool's reaction only).
  void addContactSprings(const std::vector<SceneContact>& contacts,
    const CollisionSceneParameters& parameters)
  {
    for (std::size_t k = 0; k < contacts.size(); ++k)
    {
      const SceneContact& c = contacts[k];
      ContactFeatures& f = features[k];
      if (c.first.kind != SceneBodyKind::Tissue)
      {
        continue;
      }
      if (c.second.kind == SceneBodyKind::Tissue)
      {
        addTissueTissueSprings(c, f, parameters.tissueTissue);
        continue;
      }
      const bool tool = c.second.kind == SceneBodyKind::Tool;
      f.springs[0] = addSprings(c.first.index,
        f.verticesOfFirst,
        f.weightsOfFirst,
        c.normal,
        c.depth,
        c.stiffness,
        tool ? parameters.toolTissue : parameters.tissueObstacle,
        tool ? tools[c.second.index]->velocityAt(c.pointOnSecond) : Vector3::Zero());
    }
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
  if (!(parameters.candidateMarginPerRadius >= 0.0) ||
      !std::isfinite(parameters.candidateMarginPerRadius))
  {
    throw InvalidInputError("collision scene: candidateMarginPerRadius must be finite and >= 0");
  }
  Parameters = parameters;
}

void CollisionScene::detectContacts()
{
  Implementation& in = *Internal;
  in.startDetection(Contacts);
  Statistics = CollisionStatistics();
  Implementation::Detection detection{ Contacts, Parameters, Statistics };
  in.bodyPairs(detection);
  const int searchesBefore = in.candidateSearches();
  in.runMeshPairJobs();
  Statistics.candidateSearches = in.candidateSearches() - searchesBefore;
  detection.pass = Implementation::Pass::AddContacts;
  in.bodyPairs(detection);
  in.shareToolMeshStiffness(Contacts);
  in.addContactSprings(Contacts, Parameters);
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
  Implementation& in = *Internal;
  assembleWhileDetecting();
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

void CollisionScene::assembleWhileDetecting()
{
  // The elastic part of each solver's step (rotations, element stiffness
  // and forces) does not depend on the contacts, and the contacts do not
  // depend on it: it is assembled on another thread while they are found,
  // the same bits on any thread.
  Implementation& in = *Internal;
  tbb::task_group elastic;
  elastic.run(
    [&in]
    {
      for (auto& solver : in.solvers)
      {
        solver->assembleElasticPart();
      }
    });
  try
  {
    detectContacts();
  }
  catch (...)
  {
    elastic.wait(); // the task uses the solvers: never left running
    throw;
  }
  elastic.wait();
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
  while (iterations < settings.conjugateGradientMaxIterations && in.residual.norm() > target)
  {
    in.multiply(in.direction, in.product);
    const double step = rho / in.direction.dot(in.product);
    in.x += step * in.direction;
    in.residual -= step * in.product;
    ++iterations;
    if (in.residual.norm() <= target || iterations == settings.conjugateGradientMaxIterations)
    {
      break; // no preconditioner solve for a direction never taken
    }
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
