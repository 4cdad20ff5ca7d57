// A rigid surgical tool for collision (thesis 5.1, 6.3): collision
// primitives fixed in the tool frame -- points (spheres), centre-line
// capsules, a triangle mesh with optional radii -- moved by a pose that the
// haptic device or a script sets each physics step. The tool's world
// geometry, its velocity at any point (for contact damping and friction) and
// the reaction of the tissues and obstacles on it (net force and torque,
// filled by CollisionScene) live here.
#ifndef RigidTool_h
#define RigidTool_h

#include "ThinTissueSolverModule.h"
#include "ToolContacts.h"
#include "TriangleBvh.h"

#include <string>
#include <vector>

namespace thintissue
{

/// Rigid motion: world = rotation * tool + translation. The translation is
/// the tool origin (its tip, for the instruments of SurgicalInstruments.h),
/// about which velocities and torques are expressed.
struct RigidPose
{
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vector3 translation = Vector3::Zero();
  Vector3 operator*(const Vector3& point) const { return rotation * point + translation; }
};

/// A point primitive of a tool: every point within `radius` of `centre`.
struct ToolSphere
{
  Vector3 centre = Vector3::Zero();
  double radius = 0.0;
};

class THINTISSUESOLVER_EXPORT RigidTool
{
public:
  explicit RigidTool(std::string name = "tool");

  // --- Geometry, in the tool frame ----------------------------------------
  /// Throws InvalidInputError on a negative or non-finite radius or centre.
  void addSphere(const Vector3& centre, double radius);
  /// A segment with a radius. Where the centre line crosses a tissue's
  /// mid-surface the tissue is pushed toward the handle side (where the
  /// tool came in from). Instrument centre lines (SurgicalInstruments.h)
  /// run from the tip to the handle: pass their `end` as `handleSide`.
  /// Throws InvalidInputError on a negative or non-finite radius or point.
  void addCapsule(const Vector3& handleSide, const Vector3& tipSide, double radius);
  /// The tool's triangle mesh (its full-resolution visual mesh, or a reduced
  /// one), optional "Radius" per vertex; replaces an earlier mesh. The
  /// contact distance thickens it in every query (thesis 6.3: the distance
  /// tuned so that the visual models do not interpenetrate). Throws
  /// InvalidInputError naming the mesh on inconsistent data or negative
  /// radii.
  void setMesh(const TriangleMesh& mesh, double contactDistance = 0.0);

  // --- Motion --------------------------------------------------------------
  /// Places the tool with the given velocities (linear velocity of the tool
  /// origin, angular velocity): world geometry and the mesh BVH are updated
  /// (cost linear in the tool's primitives, no allocation).
  void setPose(const RigidPose& pose,
    const Vector3& linearVelocity = Vector3::Zero(),
    const Vector3& angularVelocity = Vector3::Zero());
  /// Places the tool and takes its velocities from the previous pose over
  /// `timeStep` (zero on the first call): what a device sampled once per
  /// physics step gives.
  void moveTo(const RigidPose& pose, double timeStep);
  const RigidPose& pose() const { return Pose; }
  const Vector3& linearVelocity() const { return LinearVelocity; }
  const Vector3& angularVelocity() const { return AngularVelocity; }
  /// Velocity of the tool's material point at `worldPoint`.
  Vector3 velocityAt(const Vector3& worldPoint) const
  {
    return LinearVelocity + AngularVelocity.cross(worldPoint - Pose.translation);
  }

  // --- World geometry at the current pose ----------------------------------
  const std::string& name() const { return Name; }
  const std::vector<ToolSphere>& spheres() const { return WorldSpheres; }
  const std::vector<ToolCapsule>& capsules() const { return WorldCapsules; }
  bool hasMesh() const { return !MeshTriangles.empty(); }
  const std::vector<Vector3>& meshPositions() const { return WorldMeshPositions; }
  const std::vector<Triangle>& meshTriangles() const { return MeshTriangles; }
  const std::vector<double>& meshRadii() const { return MeshRadii; }
  const TriangleBvh& meshBvh() const { return MeshBvh; }
  double meshContactDistance() const { return MeshContactDistance; }
  /// Box of every primitive with its radius (empty for a tool without any).
  BoundingBox bounds() const;

  // --- Reaction (set by CollisionScene after each step) --------------------
  /// Net force of the tissues and obstacles on the tool (equal and opposite
  /// to what they receive from it).
  const Vector3& force() const { return Force; }
  /// Net torque about the tool origin (pose().translation).
  const Vector3& torque() const { return Torque; }
  void setReaction(const Vector3& force, const Vector3& torque)
  {
    Force = force;
    Torque = torque;
  }

private:
  std::string Name;
  std::vector<ToolSphere> Spheres; // tool frame
  std::vector<ToolCapsule> Capsules;
  std::vector<Vector3> MeshPositions;
  std::vector<Triangle> MeshTriangles;
  std::vector<double> MeshRadii;
  double MeshContactDistance = 0.0;

  RigidPose Pose;
  bool Posed = false;
  Vector3 LinearVelocity = Vector3::Zero();
  Vector3 AngularVelocity = Vector3::Zero();
  std::vector<ToolSphere> WorldSpheres;
  std::vector<ToolCapsule> WorldCapsules;
  std::vector<Vector3> WorldMeshPositions;
  TriangleBvh MeshBvh;

  Vector3 Force = Vector3::Zero();
  Vector3 Torque = Vector3::Zero();

  void updateWorldGeometry();
};

} // namespace thintissue

#endif
