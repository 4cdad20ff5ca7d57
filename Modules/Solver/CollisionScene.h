// Collision detection and contact response for a scene of tissues, rigid
// tools and static obstacles (thesis 5.1, 5.4.3, 5.4.4, 6.3).
//
// Per physics step:
//  1. Update: each tissue's collision mesh is mapped from its hexahedra and
//     its BVH refitted (the tools were placed by RigidTool::setPose/moveTo).
//  2. Broad phase: the world boxes of every pair of bodies that can touch
//     (tissue-tool, tissue-obstacle, tissue-tissue, tool-obstacle) are
//     compared; all pairs are tested, which is what a scene of a few tens of
//     bodies needs (sweep and prune pays only for many more).
//  3. Narrow phase, per overlapping pair, on thick triangles (radii):
//     - tool spheres and capsules: the deepest contact of each with the
//       other body's triangles (one contact per primitive, so the force does
//       not grow with the mesh resolution);
//     - triangle meshes (a tool's mesh, obstacles, tissues): vertex-face
//       contacts both ways (the deepest per vertex) and edge-edge crossings.
//  4. Response: every contact becomes penalty springs on the tissue's
//     collision vertices (spread by the contact's barycentric weights, then
//     to the hexahedra by H^T), linearised into the tissue's implicit step,
//     with damping on the relative velocity and optional regularised Coulomb
//     friction (EmbeddedContact). A tissue-tissue contact is one spring
//     between the two contact points: each side's part goes to its solver
//     and the cross terms couple the solvers, so that every step in which
//     tissues touch solves all solvers' systems as one (conjugate gradients
//     preconditioned by each solver's own factor). Friction between tissues
//     is linearised on each side only (its cross terms are left out to keep
//     the joint matrix symmetric). Tool-obstacle contacts act on the tool
//     only.
//  5. Reaction: after the tissues' steps each tool gets the net force and
//     torque, equal and opposite to what the tissues received, and every
//     contact keeps the data (point, normal, depth, stiffness) that a 1 kHz
//     haptic loop needs to extrapolate the force between physics steps.
//
// Stiffness: a tool primitive's contact has the full tool-tissue stiffness;
// the contacts of a tool's triangle mesh share it in proportion to their
// depths (k_i = k d_i / sum d), so that the tool's total stiffness stays k
// -- a haptic device's stability bound -- however many vertices touch, and
// changes continuously as contacts appear. Obstacle and tissue-tissue
// contacts have the full stiffness each (vertex springs, 5.4.4).
#ifndef CollisionScene_h
#define CollisionScene_h

#include "CorotationalHexFem.h"
#include "RigidTool.h"
#include "ThinTissueSolverModule.h"
#include "ToolContacts.h"

#include <memory>
#include <string>
#include <vector>

namespace thintissue
{

/// Penalty and friction parameters of one kind of contact.
struct ContactParameters
{
  double stiffness = 50.0; ///< force per unit depth (N/mm in mm models)
  double damping = 0.01;   ///< force per unit normal speed
  double friction = 0.0;   ///< Coulomb coefficient mu
  /// Tangential speed below which friction sticks viscously (mm/s).
  double slipVelocity = 1.0;
};

struct CollisionSceneParameters
{
  ContactParameters toolTissue;
  ContactParameters tissueObstacle;
  ContactParameters tissueTissue;
  /// Tool against bone: acts on the tool only (what the haptic device shows).
  ContactParameters toolObstacle;
  /// Temporal coherence against obstacles (they never move): a tissue's
  /// feature pairs that may touch an obstacle are searched with this
  /// margin, in multiples of the tissue's largest radius, and reused while
  /// none of its collision vertices has moved further than the margin.
  /// The contacts are the same, bit for bit, for any value; it only trades
  /// the searches against the candidates tested each step. 0: search every
  /// step (no candidates kept). Measured (callgrind, the first 3 s of the
  /// replays, 0.25 -> 0.1): punch 2,434 -> 2,330 M instructions, shaver
  /// 2,086 -> 2,049, examination 1,759 -> 1,723, contouring 2,360 -> 2,338;
  /// 0.05 and 0.02 gain nothing more (the punch's features near the tibia
  /// are tested every step whatever the margin).
  double candidateMarginPerRadius = 0.1;
};

enum class SceneBodyKind
{
  Tissue,
  Tool,
  Obstacle
};

struct SceneBody
{
  SceneBodyKind kind = SceneBodyKind::Tissue;
  int index = -1; ///< among the scene's tissues, tools or obstacles
  bool operator==(const SceneBody& o) const { return kind == o.kind && index == o.index; }
};

/// One contact. `first` is the tissue when a tissue is involved (the tool
/// for tool-obstacle contacts); `normal` pushes `first` out of `second`.
struct SceneContact
{
  SceneBody first;
  SceneBody second;
  Vector3 pointOnFirst = Vector3::Zero();  ///< on first's mid-surface / centre line
  Vector3 pointOnSecond = Vector3::Zero(); ///< on second's (the tool's, for haptics)
  Vector3 normal = Vector3::UnitZ();       ///< unit, from second toward first
  double depth = 0.0;                      ///< overlap of the radii
  double stiffness = 0.0;
  /// Side of first's collision surface that second touches (a tissue's
  /// lower surface: -1; the wrinkles count those, 4.4); likewise for second.
  int sideOnFirst = 1;
  int sideOnSecond = 1;
  /// Force on `first` as the last step applied it (normal and friction);
  /// `second` received minus this.
  Vector3 force = Vector3::Zero();
};

/// What the last detection did (for tests and benchmarks).
struct CollisionStatistics
{
  int bodyPairs = 0;            ///< pairs that can touch
  int overlappingBodyPairs = 0; ///< passed the broad phase
  int contacts = 0;
  int springs = 0; ///< EmbeddedContacts given to the solvers
  /// Tissue-obstacle pairs whose candidates were searched again this step
  /// (CollisionSceneParameters::candidateMarginPerRadius).
  int candidateSearches = 0;
  /// Conjugate-gradient iterations of the last joint solve (tissues in
  /// contact with each other), 0 when every solver stepped alone.
  int jointIterations = 0;
};

class THINTISSUESOLVER_EXPORT CollisionScene
{
public:
  CollisionScene();
  ~CollisionScene();
  CollisionScene(const CollisionScene&) = delete;
  CollisionScene& operator=(const CollisionScene&) = delete;

  /// The scene refers to the bodies (it does not own them): they must
  /// outlive it. `collision` must be embedded in `fem`'s hexahedra. Each
  /// returns the body's index among its kind.
  int addTissue(CorotationalHexFem& fem, DeformableCollisionMesh& collision);
  int addTool(RigidTool& tool);
  int addObstacle(const StaticObstacle& obstacle);

  void setParameters(const CollisionSceneParameters& parameters);
  const CollisionSceneParameters& parameters() const { return Parameters; }

  /// Steps 1-4: collision meshes from the current node positions, contacts,
  /// springs handed to each tissue's solver (CorotationalHexFem::setContacts).
  void detectContacts();
  /// Step 5, after the tissues' solvers stepped: contact forces, tool
  /// reactions (force and torque).
  void collectReactions();
  /// detectContacts, one step of every tissue's solver, collectReactions.
  /// Stops at the first solver that fails (its message names the tissue);
  /// failed solvers keep their last good state.
  SolverResult step();

  const std::vector<SceneContact>& contacts() const { return Contacts; }
  /// Contacts on the given side (-1: lower) of a tissue's collision surface.
  int contactCountOnSide(int tissue, int side) const;
  const CollisionStatistics& statistics() const { return Statistics; }

  std::size_t tissueCount() const;
  std::size_t toolCount() const;
  std::size_t obstacleCount() const;

private:
  /// detectContacts() with the solvers' elastic parts assembled alongside.
  void assembleWhileDetecting();
  bool solveJointly(SolverResult& result);

  struct Implementation;
  std::unique_ptr<Implementation> Internal;
  CollisionSceneParameters Parameters;
  std::vector<SceneContact> Contacts;
  CollisionStatistics Statistics;
};

} // namespace thintissue

#endif
