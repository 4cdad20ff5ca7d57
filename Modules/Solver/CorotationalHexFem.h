// Co-rotational linear FEM on hexahedra with implicit (backward) Euler
// integration: the deformation model of the thesis (section 4.2, equations
// 4-14 to 4-16), after Nesme et al. / SOFA's HexahedronFEMForceField.
//
// Each hexahedron keeps its rest stiffness K_e (2x2x2 Gauss); at every step
// its rotation R is the polar decomposition of the deformation gradient at
// its centre, the elastic force is f_e = R K_e (R^T x_e - X_e) and the
// stiffness R K_e R^T. One linear system per step:
//   (M + h D + h^2 K) dv = h (f_ext - f_int - D v - h K v),
//   D = alpha M + beta K (Rayleigh), v += dv, x += h v,
// on the free degrees of freedom (fixed nodes are Dirichlet and excluded).
// The sparsity pattern is analysed once and again only after a topology
// change (addHexahedron, removeHexahedron, replaceHexahedronNodes), which
// touches just the affected elements: what cutting (5.3) needs.
#ifndef CorotationalHexFem_h
#define CorotationalHexFem_h

#include "HexahedralMesh.h"
#include "HexahedronElement.h"
#include "SmoothedAggregation.h"
#include "ThinTissueSolverModule.h"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace thintissue
{

enum class LinearSolverKind
{
  /// Sparse Cholesky (CHOLMOD), pattern analysed once, refactorized every
  /// step: simplicial LDL^T below CorotationalHexFemSettings::
  /// supernodalThreshold unknowns, supernodal LL^T (dense BLAS blocks) above.
  Cholmod,
  /// Conjugate gradient with a nodal block-Jacobi preconditioner (the 3x3
  /// diagonal block of each node inverted), warm-started from the previous
  /// step's velocity change.
  ConjugateGradient,
  /// Conjugate gradient preconditioned by a CHOLMOD factorization of an
  /// earlier step's matrix, refactorized only when the iterations exceed
  /// `refactorizationIterations`: the rotations change little from step to
  /// step, so a stale exact factor converges in a few iterations and the
  /// factorization cost is paid rarely. From
  /// `backgroundRefactorizationThreshold` unknowns the refactorization runs
  /// on a worker thread while the steps go on (see the settings).
  StaleFactorConjugateGradient,
  /// Conjugate gradient preconditioned by one V-cycle of a smoothed-
  /// aggregation multigrid (SmoothedAggregation: rigid-motion near-null
  /// space, Chebyshev smoothing, CHOLMOD-free). The hierarchy is built from
  /// an earlier step's matrix and turned with the nodal rotations like the
  /// stale factor (Q M_f^-1 Q^T); it is rebuilt at the step after a solve
  /// needed more than `multigridRebuildIterations`, and at once after a
  /// topology change or when a solve does not converge. For meshes whose
  /// factor is too big or too slow to refresh.
  MultigridConjugateGradient,
  /// StaleFactorConjugateGradient up to AutomaticDirectLimit degrees of
  /// freedom, MultigridConjugateGradient beyond, where factors grow too big
  /// to refresh. The default.
  Automatic
};

/// Degrees of freedom up to which Automatic factorizes (stale factor), with
/// multigrid CG beyond. Measured (issue 20, `ThinTissueBench --suite fem`,
/// 2 cores shared with other work, OpenBLAS on one thread), stale factor
/// against multigrid, step time (stepping thread's CPU): block 40x20x5
/// (14,500 unknowns) 56 (46) ms, 4 iterations, against 316 (304) ms, 36;
/// block 40x25x7 (25,272) 323 (214, plus the background refreshes) ms, 12,
/// against 251 (243) ms, 21: about even; the 10,000 block (35,670) 664 ms,
/// 23, against 400-460 ms, 19; block-Jacobi CG 1,963 ms, 891. The
/// 100,000 block (320K unknowns): multigrid 5.1 s, 21 iterations, where
/// block-Jacobi does not converge in 1,000 iterations. Those ran on
/// OpenBLAS's SSE3 kernels. Measured again on its AVX-512 ones (seventeenth
/// session; 40 x 25 x nz blocks, the fem bench's load, medians over 25-35
/// steps; stale factor against multigrid): 22,386 unknowns 192-214 against
/// 240-260 ms; 25,584: 209 against 282-314 ms; 28,782: 259 against 244 ms;
/// 31,980 (the bench's 10,000 block): 224 against 264 ms over 30 steps, but
/// 296 against 219 ms in the bench. Hence 28,000: the faster factorization
/// moved the even point up by about a tenth.
constexpr int AutomaticDirectLimit = 28000;

/// Unknowns up to which the factor bridges a topology change
/// (CorotationalHexFemSettings::bridgeTopologyChanges). Measured (issue 20
/// item 6, 2 cores, an ASan build on the other): the punch replay
/// (meniscus, 504-576 unknowns, 5 bites) needs 4-13 bridged iterations a
/// step and no factorization in a step after a bite (in-step
/// factorizations per 1,000 steps 1.45 -> 0.24, FEM step after a bite
/// 2.29 -> 1.99 ms); the 64-hexahedra block slit by 12 copied nodes 18-27
/// (fresh factor 18-23: the slit swings), first step 3.6 -> 2.4 ms. The
/// 1,000 block (4,158) slit by 33-77 copied nodes needs 15-27 against 5
/// with a fresh factor: four bridged steps cost 3 times the factorization
/// they avoid (first step 37-68 ms against 37-45), so larger systems
/// factorize in the step after a change. Growing the touched set by rings
/// of neighbours cut 26 iterations to 19 / 16 / 14 (1 / 2 / 3 rings) at a
/// higher price per step.
constexpr int BridgeUnknownLimit = 2000;

/// The most steps a background refactorization is given before it is
/// swapped in (CorotationalHexFem::refreshLagAfter): a factor
/// that takes longer waits at its due step rather than go on staler.
constexpr int MaximumRefactorizationLag = 16;

/// Fraction of the unknowns above which a topology change is not bridged:
/// the touched block's exact solve then costs about what the whole
/// factorization does, at every iteration of every bridged step. Measured
/// (issue 20 item 6, callgrind, the meniscus of 324-564 unknowns cut after
/// 20 steps, the eight steps after the cut, instructions): touched 18 %
/// bridged 13.6 M (first step 4.2 M) against 11.1 M factorized in the
/// first step (5.8 M); 42 %: 20.2 M (6.6 M) against 11.9 M (6.2 M); 65 %:
/// 53.7 M against 14.0 M; 86 % (a cut across): 110 M (32 M, then 24 M a
/// step) against 17.0 M (8.2 M). Only a small touched block lowers the
/// first step (a punch bite touches 11-29 %).
constexpr double BridgeTouchedFraction = 0.25;

/// Fill-reducing ordering of the CHOLMOD factor.
enum class FactorOrdering
{
  /// Approximate minimum degree.
  MinimumDegree,
  /// METIS nested dissection.
  Metis,
  /// CHOLMOD's nested dissection (METIS bisections, constrained minimum
  /// degree on the parts).
  NestedDissection,
  /// CHOLMOD's default: minimum degree, METIS as well when its fill is high,
  /// keeping the better.
  CholmodDefault,
  /// MinimumDegree below AutomaticMetisLimit unknowns, Metis from there.
  Automatic
};

/// Unknowns from which FactorOrdering::Automatic orders with METIS. Measured
/// (`ThinTissueBench --suite fem`, CPU time, one BLAS thread): METIS and
/// nested dissection factor the 1,000-hexahedra block in 22 ms against 25
/// for minimum degree, the 10,000 block in 0.69 s against 1.1 s; below a
/// few thousand unknowns the factors cost the same and minimum degree
/// analyses faster (72 hexahedra: 8.4 ms against 10.0 for the first step),
/// which counts after every cut.
constexpr int AutomaticMetisLimit = 3000;

struct CorotationalHexFemSettings
{
  double timeStep = 0.01;
  /// Rayleigh damping D = alpha M + beta K.
  double rayleighMass = 0.1;
  double rayleighStiffness = 0.01;
  Vector3 gravity = Vector3::Zero();
  /// false: plain linear FEM (R = I), for comparison.
  bool corotational = true;
  LinearSolverKind solver = LinearSolverKind::Automatic;
  /// Relative residual at which conjugate gradients stop.
  double conjugateGradientTolerance = 1e-8;
  int conjugateGradientMaxIterations = 1000;
  /// StaleFactorConjugateGradient refactorizes when a solve needed more.
  int refactorizationIterations = 6;
  /// ... and when the iterations beyond the first, summed over the steps
  /// since the last factorization, exceed this: a factor that keeps
  /// costing a few extra iterations every step (contacts coming and going)
  /// is renewed once the extra iterations would have paid for it. Measured
  /// on the knee of table 6-2 (meniscus, 360 unknowns): without it about 6
  /// iterations per step, with 20 about 2.
  int staleFactorIterationBudget = 20;
  /// Unknowns from which CHOLMOD factorizes supernodally (LL^T on dense
  /// BLAS blocks) instead of simplicial LDL^T. Not negative. Chosen on a
  /// step's cost, a factorization shared by the steps it serves (10-20 at
  /// thesis sizes, ~3 solves each) plus the solves: callgrind instructions
  /// of 205 stale-factor steps (issue 20, OpenBLAS), supernodal against
  /// simplicial: meniscus (312 unknowns) 271 M against 261 M (solves 88.5
  /// against 66.0 M, factorizations 17.7 against 29.9 M); steak (474) 768
  /// against 1,115 M; sheet (480) 615 against 781 M; 125-hexahedra block
  /// (540) 516 against 891 M; 250 (1,080) 1.34 against 3.51 G; over 1,005
  /// steps meniscus 1.05 against 0.98 G, steak 2.10 against 2.49 G, sheet
  /// 1.99 against 2.20 G. CPU per factorization at 4,158 (1,000
  /// hexahedra) 22 against 97 ms. Since the supernodal factor is solved
  /// by our own loops rather than cholmod_solve2's BLAS call per supernode
  /// (2026-11-28), its solves cost less too: replays of the meniscus
  /// examination (312 unknowns) 2.99 G simplicial against 2.95 G
  /// supernodal, cartilage palpation (70 nodes) 389 M against 395 M; hence
  /// 250 (was 400).
  int supernodalThreshold = 250;
  FactorOrdering factorOrdering = FactorOrdering::Automatic;
  /// Unknowns from which StaleFactorConjugateGradient refactorizes on a
  /// worker thread instead of inside the step. Not negative. At the
  /// 1,000-hexahedra block (4,158 unknowns) a factorization costs ~22 ms of
  /// CPU, several stale steps. At thesis sizes it costs 0.3-0.6 ms, 2-4
  /// steps, and the steps that paid it set the simulator's 99th percentile:
  /// refactorized in the step, 2-9 % of the replays' steps did (punch,
  /// contouring, sheet), in the background none but the first and those
  /// after cuts (`ThinTissueBench --suite simulator`, "factorizations
  /// inside steps per 1,000 steps"; 99th percentile on a quiet machine
  /// 0.52-1.43 ms against 0.44-1.05 ms).
  int backgroundRefactorizationThreshold = 0;
  /// Deterministic background refresh: a refactorization started at step k
  /// (of step k's matrix) is swapped in at step k + lag, waiting for it if
  /// it has not finished -- never "whenever it is ready", so that replays
  /// are exact. The lag is fixed when the refactorization starts, from the
  /// factor's size and step k's iterations (a bigger factor takes more
  /// steps to make), and is at least this. At least 1.
  int backgroundRefactorizationLag = 4;
  /// With a background refresh, the iterations a stale factor may take
  /// before the step gives it up and refactorizes synchronously. At least 1.
  int staleFactorIterationCap = 40;
  /// The stale factor follows the tissue's rotations: it preconditions with
  /// Q A_f^-1 Q^T, Q the per-node rotation since the factor's step, since
  /// the co-rotational matrix turns with the material (A ~ Q A_f Q^T). A
  /// factor then stays good through large rotations and is renewed for
  /// what rotations do not explain (stretch, contacts).
  bool rotateStaleFactor = true;
  /// After a topology change (a cut), the previous pattern's factor keeps
  /// preconditioning the new system until the new pattern's factor,
  /// analysed and refreshed in the background, lands (issue 20 item 6):
  /// the old factor solves the glued system (copies summed into the nodes
  /// they were copied from), and an exact solve on the nodes the change
  /// touched corrects it there, symmetrically before and after. The step
  /// after a cut then factorizes nothing; it does only if that solve needs
  /// more than staleFactorIterationCap iterations. Only with a background
  /// refresh (StaleFactorConjugateGradient at any size by default) and up
  /// to BridgeUnknownLimit unknowns, for changes that touch at most
  /// BridgeTouchedFraction of them.
  bool bridgeTopologyChanges = true;
  /// The hierarchy of MultigridConjugateGradient (checked like the rest).
  SmoothedAggregationSettings multigrid;
  /// MultigridConjugateGradient rebuilds its hierarchy (from that step's
  /// matrix, at the start of the next solve: deterministic) after a solve
  /// that needed more iterations than this. At least 1.
  int multigridRebuildIterations = 40;
  /// Conjugate gradients start from the combination of the last
  /// `warmStartSolutions` step solutions that is closest to the new one in
  /// the energy norm (SolutionHistory.h: one product with the matrix per
  /// solution); 1 starts from the last solution alone. From 1 to 4.
  /// Measured in SolutionHistory.h.
  int warmStartSolutions = 3;
  /// ... after a solve that needed at least this many iterations (a
  /// transient); after fewer, from the last solution alone. Not negative.
  int warmStartIterations = 3;
  /// Threads of the element assembly (rotations, forces, rotated
  /// stiffness): 0 for all cores (TBB's default), 1 for the calling thread
  /// only. Not negative. The results are the same bits for any count (the
  /// elements are coloured; see ParallelAssemblyMinimumElements).
  int assemblyThreads = 0;
};

/// Active hexahedra from which the assembly runs on several threads.
/// Elements of one colour share no node, so each colour is assembled in
/// parallel and the colours in order. Below a few hundred elements a
/// colour holds too few elements to pay for waking threads (the thesis
/// sizes, 42-81, stay serial). Measured (issue 20, `ThinTissueBench --suite
/// fem`, 2 cores at load 2): the 1,000 block steps in 4.07 ms against 5.03
/// on one thread; at 10,000 the solves (23 stale-factor iterations, ~60%
/// of a step) hide it (0.46 s against 0.44 s, 10 steps).
constexpr int ParallelAssemblyMinimumElements = 256;
/// Colours (bits of a node's mask) of the parallel assembly; elements that
/// need more go to one last colour assembled serially.
constexpr int ParallelColourLimit = 64;

/// A penalty contact on a point embedded in a hexahedron (thesis 5.1,
/// response): the point x_p = sum_a w_a x_a, moving at v_p relative to the
/// other body's surface (v_r = v_p - surfaceVelocity), is pushed along
/// `normal` by
///   F_n = stiffness * depth * n - (h * stiffness + damping) (n . v_r) n,
/// and, with friction mu > 0, held by the regularised Coulomb force
///   F_t = -c_t (I - n n^T) v_r,  c_t = mu |F_n| / max(|v_t|, slipVelocity),
/// |F_n| and c_t taken at the start of the step: below `slipVelocity` the
/// tissue sticks (a stiff viscous tie), above it slides under a force of
/// magnitude mu |F_n|. Both are linearised into the implicit step (their
/// matrix w_a w_b h [(h k + c) n n^T + c_t (I - n n^T)] enters the system),
/// so that stiff contact and sticking friction stay stable at large time
/// steps. Weights come from the collision-simulation embedding (trilinear,
/// HexahedralEmbedding); F goes up with H^T.
struct EmbeddedContact
{
  std::size_t hexahedron = 0;
  /// Trilinear local coordinates of the point in the hexahedron.
  Vector3 local = Vector3::Constant(0.5);
  /// Unit direction the tissue is pushed (away from the other body).
  Vector3 normal = Vector3::UnitZ();
  /// Penetration at the current positions (> 0 pushes).
  double depth = 0.0;
  double stiffness = 0.0;
  double damping = 0.0;
  /// Velocity of the other body's surface at the contact (a moving tool,
  /// another tissue); zero for a static obstacle.
  Vector3 surfaceVelocity = Vector3::Zero();
  /// Coulomb friction coefficient mu (0: frictionless).
  double friction = 0.0;
  /// Regularisation of the Coulomb cone: tangential speed below which the
  /// contact sticks viscously (in the model's units, e.g. mm/s). Positive.
  double slipVelocity = 1.0;
};

/// Outcome of a step or a static solve. On failure the state is the last
/// good one and `message` says what went wrong.
struct SolverResult
{
  bool ok = true;
  std::string message;
  /// Linear solver iterations (CG) or Newton iterations (static solve).
  int iterations = 0;
};

class THINTISSUESOLVER_EXPORT CorotationalHexFem
{
public:
  /// Takes the mesh's nodes as rest and current positions and its fixed
  /// nodes. Throws InvalidInputError on a bad mesh (index out of range,
  /// inverted or degenerate hexahedron), material or settings.
  CorotationalHexFem(const HexahedralMesh& mesh,
    const LinearMaterial& material,
    const CorotationalHexFemSettings& settings = {});
  ~CorotationalHexFem();
  CorotationalHexFem(CorotationalHexFem&&) noexcept;
  CorotationalHexFem& operator=(CorotationalHexFem&&) noexcept;
  CorotationalHexFem(const CorotationalHexFem&) = delete;
  CorotationalHexFem& operator=(const CorotationalHexFem&) = delete;

  // --- State -------------------------------------------------------------
  std::size_t nodeCount() const { return Positions.size(); }
  std::size_t hexahedronCount() const { return Elements.size(); }
  std::size_t activeHexahedronCount() const;
  const std::vector<Vector3>& restPositions() const { return RestPositions; }
  const std::vector<Vector3>& positions() const { return Positions; }
  const std::vector<Vector3>& velocities() const { return Velocities; }
  /// Throws InvalidInputError on a wrong size or a non-finite value.
  void setPositions(const std::vector<Vector3>& positions);
  void setVelocities(const std::vector<Vector3>& velocities);
  /// Lumped nodal masses (density times the shape-function integrals).
  const std::vector<double>& nodeMasses() const { return NodeMasses; }
  double kineticEnergy() const;

  // --- Loads and constraints ---------------------------------------------
  /// Throws InvalidInputError on an index out of range or a non-finite force.
  void setExternalForce(std::size_t node, const Vector3& force);
  void clearExternalForces();
  const std::vector<Vector3>& externalForces() const { return ExternalForces; }
  /// Fixed nodes keep their position (Dirichlet).
  void setFixed(std::size_t node, bool fixed);
  bool isFixed(std::size_t node) const { return Fixed[node] != 0; }
  const CorotationalHexFemSettings& settings() const { return Settings; }
  void setSettings(const CorotationalHexFemSettings& settings);
  /// Per-hexahedron material (recomputes only that element).
  void setMaterial(std::size_t hexahedron, const LinearMaterial& material);

  /// Contacts for the next step (replacing the previous ones). Throws
  /// InvalidInputError on a hexahedron out of range, a non-unit normal, a
  /// negative stiffness or damping, or non-finite values.
  void setContacts(const std::vector<EmbeddedContact>& contacts);
  const std::vector<EmbeddedContact>& contacts() const { return Contacts; }
  /// The force each contact applied in the last step (the implicit one, at
  /// the end-of-step velocity; normal and friction): equal and opposite to
  /// what the other body (a tool) receives.
  const std::vector<Vector3>& contactForces() const { return ContactForces; }

  // --- Simulation ----------------------------------------------------------
  /// One implicit Euler step of length settings().timeStep.
  SolverResult step();
  // --- Several bodies solved together (CollisionScene) ---------------------
  // step() = beginCoupledStep(), solve A dv = b, finishCoupledStep(dv). A
  // caller coupling bodies (contacts between two tissues) assembles each
  // body's system, solves the stacked one with its cross terms by
  // conjugate gradients (A_i symmetric positive definite), and finishes
  // each body with its part of the solution.
  /// The part of the next step that does not depend on the contacts: the
  /// system's pattern after topology changes, a background factor due at
  /// that step, and every element's rotation, stiffness and force. A caller
  /// may run it on another thread while it finds the contacts
  /// (CollisionScene does); beginCoupledStep() then only adds them. Any
  /// change of state in between (positions, velocities, settings, material,
  /// fixing, topology) makes beginCoupledStep assemble again. While it
  /// runs, another thread may call setContacts() and read positions() and
  /// velocities(), nothing else.
  void assembleElasticPart();
  /// Assembles this step's system (with the contacts) without solving it.
  SolverResult beginCoupledStep();
  /// Free degrees of freedom (3 per simulated, non-fixed node).
  Eigen::Index systemSize() const;
  /// First degree of freedom of a node in the system, -1 if it is fixed.
  int degreeOfFreedom(std::size_t node) const;
  const Eigen::VectorXd& systemRightHandSide() const;
  /// The last step's solution (a warm start).
  const Eigen::VectorXd& previousSystemSolution() const;
  /// y = A x.
  void multiplySystem(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// z = P^-1 r with this body's preconditioner: its (possibly stale)
  /// CHOLMOD factor, or the diagonal for the Jacobi kinds.
  bool preconditionSystem(const Eigen::VectorXd& r, Eigen::VectorXd& z, std::string& message);
  /// The next preconditionSystem refactorizes (a stale factor converged
  /// too slowly).
  void invalidateFactor();
  /// A coupled solve preconditioned by this solver's factor took
  /// `iterations`: counted against staleFactorIterationBudget.
  void chargeStaleIterations(int iterations);
  /// Applies dv (systemSize() entries): velocities, positions, contact
  /// forces. A non-finite result is refused and the last good state kept.
  SolverResult finishCoupledStep(const Eigen::VectorXd& solution);

  /// Equilibrium under the external forces and gravity (Newton iterations
  /// on the co-rotational force); contacts act in step() only. Needs at
  /// least one fixed node.
  SolverResult solveStatic(int maxIterations = 30, double relativeTolerance = 1e-10);
  /// Elastic forces f_int at the current positions (zero for a rigid motion
  /// of the rest shape), one per node.
  std::vector<Vector3> elasticForces() const;
  /// Sparse factorizations done so far (the stale-factor solver reuses one
  /// across many steps), in the step and in the background.
  int factorizationCount() const;
  /// The steps the last background refactorization was given before it is
  /// swapped in (0 if none started): CorotationalHexFemSettings::
  /// backgroundRefactorizationLag or more, for big factors.
  int lastBackgroundRefactorizationLag() const;
  /// Of those, the ones done inside a step (the first, after a topology
  /// change, and when a stale factor no longer converged).
  int synchronousFactorizationCount() const;
  /// Multigrid hierarchies built so far (MultigridConjugateGradient).
  int multigridBuildCount() const;
  /// Called on the worker thread before each background factorization: a
  /// test delays it to check that results do not depend on thread timing.
  void setBackgroundFactorizationHook(std::function<void()> hook);

  // --- Topology changes (cutting) -----------------------------------------
  /// Room for this many nodes and hexahedra, so that the topology changes
  /// of later cuts copy nothing (an element holds its 24 x 24 stiffness:
  /// growing the element table moved and faulted in all of them).
  void reserve(std::size_t nodes, std::size_t hexahedra);
  /// A new node at rest position `rest` (current position and velocity as
  /// given); returns its index. Not simulated until a hexahedron uses it.
  std::size_t addNode(const Vector3& rest, const Vector3& position, const Vector3& velocity);
  /// A copy of node `source` (rest and current position, velocity, fixed
  /// flag): the node duplication of a cut (5.3.1). Returns its index.
  std::size_t addNodeCopy(std::size_t source);
  /// A new hexahedron (VTK order); returns its index.
  std::size_t addHexahedron(const Hexahedron& nodes, const LinearMaterial& material);
  /// A copy of hexahedron h on other nodes with the same rest positions
  /// (hexahedron duplication of a cut, 5.3.1): its rest state and stiffness
  /// are copied, not recomputed, so a copy is never ill-shaped. Returns its
  /// index. Throws InvalidInputError like replaceHexahedronNodes.
  std::size_t duplicateHexahedron(std::size_t h, const Hexahedron& nodes);
  /// Removes hexahedron h from the simulation (indices stay valid).
  void removeHexahedron(std::size_t h);
  bool isActive(std::size_t h) const { return Elements[h].active; }
  /// Points hexahedron h at other nodes with the same rest positions (the
  /// duplicated nodes of a cut): its rest state is kept.
  void replaceHexahedronNodes(std::size_t h, const Hexahedron& nodes);
  const Hexahedron& hexahedronNodes(std::size_t h) const { return Elements[h].nodes; }

private:
  struct Element
  {
    Hexahedron nodes;
    LinearMaterial material;
    HexahedronRestState rest;
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    bool active = true;
  };
  struct LinearSystem;

  void checkNode(std::size_t node, const char* what) const;
  /// Throws unless `nodes` have the rest positions of hexahedron h's nodes.
  void checkSameRestNodes(std::size_t h, const Hexahedron& nodes) const;
  Element makeElement(const Hexahedron& nodes,
    const LinearMaterial& material,
    std::size_t index) const;
  void updateNodeMasses();
  /// forces += sign * R K_e (R^T (x + velocityScale v) - X).
  void accumulateElasticForce(const Element& element,
    const Eigen::Matrix3d& rotation,
    double velocityScale,
    double sign,
    std::vector<Vector3>& forces) const;
  /// The linearised contact's force at the current velocities.
  /// Velocity of the contact point relative to the other body's surface.
  Vector3 contactRelativeVelocity(const EmbeddedContact& contact) const;
  /// Normal spring and damper plus the friction damper `frictionDamping`
  /// (c_t) at the current velocities: the force the linearised step applies.
  Vector3 contactForce(const EmbeddedContact& contact, double h, double frictionDamping) const;
  /// R of the element at the current positions (identity for linear FEM).
  Eigen::Matrix3d currentRotation(const Element& element) const;
  void prepareSystem();
  /// Per simulated node, the simulated nodes it shares a hexahedron with
  /// whose DOFs are not higher (sorted, itself last).
  std::vector<std::vector<int>> blockRowsAbove() const;
  /// The upper-triangular pattern of the present numbering and where each
  /// element block, diagonal entry and nodal block lands in it.
  void buildPattern();
  /// Rotations from the current positions; elastic (+ damping-stiffness)
  /// force accumulated into `forces`; the stiffness scaled by `stiffnessScale`
  /// and the masses by `massScale` assembled into the system matrix.
  void assemble(double stiffnessScale,
    double massScale,
    double velocityStiffnessScale,
    std::vector<Vector3>& forces);
  bool solveSystem(Eigen::VectorXd& solution, int& iterations, std::string& message);
  bool factorize(std::string& message);
  bool solveWithStaleFactor(Eigen::VectorXd& solution, int& iterations, std::string& message);
  using Preconditioner = std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>;
  /// Preconditioned conjugate gradients from the previous solution, at most
  /// `limit` iterations, until |r| <= tolerance |b|; true if converged.
  bool iteratePreconditioned(Eigen::VectorXd& solution,
    int limit,
    int& iterations,
    const Preconditioner& precondition);
  /// Whether this step's stale factor is turned with the nodal rotations.
  bool tracksFactorRotations() const;
  /// Nodal rotations of this step and their change since the factor's.
  void updateNodeRotations();
  void updateRelativeRotations();
  /// z = P^-1 r with the (rotated) stale factor or multigrid hierarchy.
  void applyStaleFactor(const Eigen::VectorXd& r, Eigen::VectorXd& z);
  /// After a topology change: maps the new numbering to the factor's and
  /// sets up the exact solve on the touched nodes (see
  /// CorotationalHexFemSettings::bridgeTopologyChanges); false if the
  /// change touches too much of the system to bridge (BridgeTouchedFraction).
  bool prepareBridge();
  /// z = P^-1 r across a topology change: touched-node solve, the old
  /// factor on the glued residual, touched-node solve again.
  void applyBridgedFactor(const Eigen::VectorXd& r, Eigen::VectorXd& z);
  /// z += the old factor's correction of r (restricted to its numbering,
  /// solved, and prolonged back).
  void addGluedCorrection(const Eigen::VectorXd& r, Eigen::VectorXd& z);
  /// The touched DOFs' exact solve of the bridge's right-hand side.
  void solveTouched();
  /// The factor now in use is of the present pattern: bridge bookkeeping.
  void factorIsCurrent();
  /// Records nodes whose elements a topology change touched.
  void noteTouchedNodes(const Hexahedron& nodes);
  /// The solver Automatic stands for at this size, else Settings.solver.
  LinearSolverKind effectiveSolver() const;
  /// Builds the multigrid hierarchy of the current matrix.
  bool buildMultigrid(std::string& message);
  bool solveWithMultigrid(Eigen::VectorXd& solution, int& iterations, std::string& message);
  /// Inverts the 3x3 diagonal blocks of the current matrix.
  void invertNodalBlocks();
  /// z = (block diagonal of A)^-1 r.
  void applyNodalBlockJacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  /// Whether this step's stale factor is refreshed on a worker thread.
  bool refreshesInBackground() const;
  /// Starts refactorizing the current matrix on a worker thread, to be
  /// swapped in refreshLagAfter(...) steps later (no-op if one
  /// runs).
  void startBackgroundRefactorization();
  /// The steps until a refactorization started now is swapped in, for a
  /// step that took `iterations`.
  int refreshLagAfter(int iterations) const;
  /// At the step a background refactorization is due: waits for it and
  /// swaps it in.
  void landBackgroundRefactorization();
  /// Waits for a running background refactorization and drops it.
  void cancelBackgroundRefactorization();
  /// Groups the active elements by colour for the parallel assembly.
  void colourElements();
  /// Element e's rotation, elastic force (into `forces`) and rotated
  /// stiffness (into the matrix values).
  void assembleElement(std::size_t e,
    double stiffnessScale,
    double velocityStiffnessScale,
    std::vector<Vector3>& forces);
  /// Adds the linearised contacts to the matrix and the right-hand side.
  void assembleContacts(double h);

  std::vector<Vector3> RestPositions;
  std::vector<Vector3> Positions;
  std::vector<Vector3> Velocities;
  std::vector<Vector3> ExternalForces;
  std::vector<std::uint8_t> Fixed;
  std::vector<double> NodeMasses;
  std::vector<Element> Elements;
  std::vector<EmbeddedContact> Contacts;
  std::vector<Vector3> ContactForces;
  /// c_t of each contact, fixed at the start of the step (see EmbeddedContact).
  std::vector<double> ContactFrictionDamping;
  CorotationalHexFemSettings Settings;
  std::unique_ptr<LinearSystem> System;
  bool TopologyChanged = true;
  /// assembleElasticPart() has opened the next step (its index counted, a
  /// due background factor landed) and assembled it from the current state.
  bool StepOpened = false;
  bool ElasticPartAssembled = false;
};

} // namespace thintissue

#endif
