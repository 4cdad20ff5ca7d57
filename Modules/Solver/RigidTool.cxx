#include "RigidTool.h"

#include "ThinTissueError.h"

#include <cmath>

namespace thintissue
{

RigidTool::RigidTool(std::string name)
  : Name(std::move(name))
{
}

void RigidTool::addSphere(const Vector3& centre, double radius)
{
  if (!centre.allFinite() || !(radius >= 0.0) || !std::isfinite(radius))
  {
    throw InvalidInputError("tool '" + Name + "': sphere " + std::to_string(Spheres.size()) +
                            " needs a finite centre and a finite radius >= 0");
  }
  Spheres.push_back({ centre, radius });
  WorldSpheres.push_back({ Pose * centre, radius });
}

void RigidTool::addCapsule(const Vector3& handleSide, const Vector3& tipSide, double radius)
{
  if (!handleSide.allFinite() || !tipSide.allFinite() || !(radius >= 0.0) || !std::isfinite(radius))
  {
    throw InvalidInputError("tool '" + Name + "': capsule " + std::to_string(Capsules.size()) +
                            " needs finite end points and a finite radius >= 0");
  }
  Capsules.push_back({ handleSide, tipSide, radius });
  WorldCapsules.push_back({ Pose * handleSide, Pose * tipSide, radius });
}

void RigidTool::setMesh(const TriangleMesh& mesh, double contactDistance)
{
  mesh.checkConsistency();
  std::vector<double> radii = mesh.pointAttributes.has("Radius")
                                ? mesh.pointAttributes.get("Radius").values
                                : std::vector<double>(mesh.vertexCount(), 0.0);
  for (std::size_t v = 0; v < radii.size(); ++v)
  {
    if (!(radii[v] >= 0.0) || !std::isfinite(radii[v]))
    {
      throw InvalidInputError("tool '" + Name + "', mesh '" + mesh.name + "': vertex " +
                              std::to_string(v) + " has a negative or non-finite radius");
    }
  }
  if (!(contactDistance >= 0.0))
  {
    throw InvalidInputError("tool '" + Name + "': negative contact distance");
  }
  MeshPositions = mesh.positions;
  MeshTriangles = mesh.triangles;
  MeshRadii = std::move(radii);
  MeshContactDistance = contactDistance;
  WorldMeshPositions.resize(MeshPositions.size());
  for (std::size_t v = 0; v < MeshPositions.size(); ++v)
  {
    WorldMeshPositions[v] = Pose * MeshPositions[v];
  }
  MeshBvh.build(WorldMeshPositions, MeshTriangles, MeshRadii, MeshContactDistance);
}

void RigidTool::setPose(const RigidPose& pose,
  const Vector3& linearVelocity,
  const Vector3& angularVelocity)
{
  if (!pose.rotation.allFinite() || !pose.translation.allFinite() || !linearVelocity.allFinite() ||
      !angularVelocity.allFinite() ||
      !(pose.rotation.transpose() * pose.rotation).isIdentity(1e-6) ||
      !(pose.rotation.determinant() > 0.0))
  {
    throw InvalidInputError("tool '" + Name +
                            "': the pose needs a finite rotation matrix (orthonormal, "
                            "determinant +1), a finite translation and finite velocities");
  }
  Pose = pose;
  Posed = true;
  LinearVelocity = linearVelocity;
  AngularVelocity = angularVelocity;
  updateWorldGeometry();
}

void RigidTool::moveTo(const RigidPose& pose, double timeStep)
{
  Vector3 linear = Vector3::Zero();
  Vector3 angular = Vector3::Zero();
  if (Posed && timeStep > 0.0)
  {
    linear = (pose.translation - Pose.translation) / timeStep;
    // Angular velocity of the relative rotation R_new R_old^T over the step.
    const Eigen::AngleAxisd turn(pose.rotation * Pose.rotation.transpose());
    angular = turn.axis() * (turn.angle() / timeStep);
  }
  setPose(pose, linear, angular);
}

void RigidTool::updateWorldGeometry()
{
  for (std::size_t k = 0; k < Spheres.size(); ++k)
  {
    WorldSpheres[k].centre = Pose * Spheres[k].centre;
  }
  for (std::size_t k = 0; k < Capsules.size(); ++k)
  {
    WorldCapsules[k].start = Pose * Capsules[k].start;
    WorldCapsules[k].end = Pose * Capsules[k].end;
  }
  if (!MeshPositions.empty())
  {
    for (std::size_t v = 0; v < MeshPositions.size(); ++v)
    {
      WorldMeshPositions[v] = Pose * MeshPositions[v];
    }
    MeshBvh.refit(WorldMeshPositions, MeshRadii);
  }
}

BoundingBox RigidTool::bounds() const
{
  BoundingBox box;
  for (const ToolSphere& s : WorldSpheres)
  {
    box.extend(s.centre - Vector3::Constant(s.radius));
    box.extend(s.centre + Vector3::Constant(s.radius));
  }
  for (const ToolCapsule& c : WorldCapsules)
  {
    for (const Vector3& p : { c.start, c.end })
    {
      box.extend(p - Vector3::Constant(c.radius));
      box.extend(p + Vector3::Constant(c.radius));
    }
  }
  if (hasMesh())
  {
    box.extend(MeshBvh.bounds());
  }
  return box;
}

} // namespace thintissue
