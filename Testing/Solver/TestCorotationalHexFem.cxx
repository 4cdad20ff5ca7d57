// Co-rotational hexahedral FEM with implicit Euler (thesis 4.2): the
// validation list of the solver issue.
#include "CorotationalHexFem.h"
#include "MeniscusModel.h"
#include "ThinTissueError.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace thintissue;

namespace
{

HexahedralMesh beam(int nx, int ny, int nz, double length, double height)
{
  return HexahedralMesh::makeRegularGrid(
    Vector3::Zero(), Vector3(length / nx, height / ny, height / nz), nx, ny, nz);
}

/// Fixes the nodes at x = 0.
void clampLeftEnd(CorotationalHexFem& fem)
{
  for (std::size_t n = 0; n < fem.nodeCount(); ++n)
  {
    if (fem.restPositions()[n].x() < 1e-12)
    {
      fem.setFixed(n, true);
    }
  }
}

/// Spreads `force` evenly over the nodes at x = length.
void loadRightEnd(CorotationalHexFem& fem, double length, const Vector3& force)
{
  std::vector<std::size_t> tip;
  for (std::size_t n = 0; n < fem.nodeCount(); ++n)
  {
    if (std::abs(fem.restPositions()[n].x() - length) < 1e-9)
    {
      tip.push_back(n);
    }
  }
  for (auto n : tip)
  {
    fem.setExternalForce(n, force / static_cast<double>(tip.size()));
  }
}

double meanTipDeflection(const CorotationalHexFem& fem, double length)
{
  double sum = 0.0;
  int count = 0;
  for (std::size_t n = 0; n < fem.nodeCount(); ++n)
  {
    if (std::abs(fem.restPositions()[n].x() - length) < 1e-9)
    {
      sum += fem.positions()[n].z() - fem.restPositions()[n].z();
      ++count;
    }
  }
  return sum / count;
}

double currentVolume(const CorotationalHexFem& fem)
{
  double volume = 0.0;
  for (std::size_t h = 0; h < fem.hexahedronCount(); ++h)
  {
    HexahedronCorners corners;
    for (int k = 0; k < 8; ++k)
    {
      corners[k] = fem.positions()[fem.hexahedronNodes(h)[k]];
    }
    volume += computeHexahedronRestState(corners, LinearMaterial{}, "volume").volume;
  }
  return volume;
}

double maxNorm(const std::vector<Vector3>& vectors)
{
  double largest = 0.0;
  for (const auto& v : vectors)
  {
    largest = std::max(largest, v.norm());
  }
  return largest;
}

LinearMaterial material(double E, double nu, double density = 1.0)
{
  LinearMaterial m;
  m.youngModulus = E;
  m.poissonRatio = nu;
  m.density = density;
  return m;
}

} // namespace

TEST(CorotationalHexFem, RigidRotationGivesNoForceAndStretchRotatesWithIt)
{
  const HexahedralMesh cube = beam(1, 1, 1, 1.0, 1.0);
  CorotationalHexFem fem(cube, material(1000.0, 0.3));
  // A small stretch: the reference force.
  std::vector<Vector3> stretched = cube.nodes;
  for (auto& p : stretched)
  {
    p.x() *= 1.1;
  }
  fem.setPositions(stretched);
  const std::vector<Vector3> reference = fem.elasticForces();
  const double scale = maxNorm(reference);
  ASSERT_GT(scale, 1.0);
  for (const Vector3& axis :
    std::vector<Vector3>{
      Vector3::UnitX(), Vector3::UnitY(), Vector3::UnitZ(), Vector3(1.0, 2.0, -1.0).normalized() })
  {
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(M_PI / 2.0, axis).toRotationMatrix();
    const Vector3 shift(0.3, -2.0, 5.0);
    std::vector<Vector3> moved = cube.nodes;
    for (auto& p : moved)
    {
      p = rotation * p + shift;
    }
    fem.setPositions(moved);
    EXPECT_LT(maxNorm(fem.elasticForces()), 1e-12 * scale) << "axis " << axis.transpose();
    for (std::size_t n = 0; n < moved.size(); ++n)
    {
      moved[n] = rotation * stretched[n] + shift;
    }
    fem.setPositions(moved);
    const auto forces = fem.elasticForces();
    for (std::size_t n = 0; n < forces.size(); ++n)
    {
      EXPECT_LT((forces[n] - rotation * reference[n]).norm(), 1e-10 * scale);
    }
  }
}

TEST(CorotationalHexFem, PolarRotationByNewtonIsTheSvdsRotation)
{
  // F = R S over rotations and stretches from near-rigid to strongly
  // anisotropic: the Newton iteration must give the SVD's proper rotation;
  // inverted and flat F must give exactly the SVD's convention.
  std::mt19937 random(20);
  const auto uniform = [&random](double low, double high)
  { return std::uniform_real_distribution<double>(low, high)(random); };
  int checked = 0;
  for (const double spread : { 1e-6, 1e-3, 0.1, 0.5, 0.9 })
  {
    for (int k = 0; k < 200; ++k)
    {
      const Eigen::Matrix3d rotation = Eigen::AngleAxisd(
        uniform(-M_PI, M_PI), Vector3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)).normalized())
                                         .toRotationMatrix();
      const Eigen::Matrix3d frame =
        Eigen::AngleAxisd(uniform(-M_PI, M_PI), Vector3(1.0, uniform(-1, 1), 0.5).normalized())
          .toRotationMatrix();
      const Vector3 stretches(
        1.0 + uniform(-spread, spread), 1.0 + uniform(-spread, spread), 1.0 / (1.0 + spread));
      const Eigen::Matrix3d gradient =
        rotation * frame * stretches.asDiagonal() * frame.transpose();
      const Eigen::Matrix3d newton = polarRotation(gradient);
      EXPECT_LT((newton - polarRotationBySvd(gradient)).norm(), 1e-12) << gradient;
      EXPECT_LT((newton - rotation).norm(), 1e-12) << gradient;
      EXPECT_LT((newton.transpose() * newton - Eigen::Matrix3d::Identity()).norm(), 1e-14);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 1000);
  const Eigen::Matrix3d turn =
    Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d inverted = turn * Vector3(1.2, 0.9, -0.3).asDiagonal();
  const Eigen::Matrix3d flat = turn * Vector3(1.2, 0.9, 1e-7).asDiagonal();
  for (const Eigen::Matrix3d& gradient : { inverted, flat })
  {
    EXPECT_EQ(polarRotation(gradient), polarRotationBySvd(gradient)) << gradient;
    EXPECT_NEAR(polarRotation(gradient).determinant(), 1.0, 1e-12);
  }
}

TEST(CorotationalHexFem, PatchTestUniformTensionGivesUniformStrain)
{
  // 3 x 3 x 3 hexahedra with the interior nodes moved: non-parallelepiped
  // cells. Boundary nodes follow a uniform strain; the interior must too.
  HexahedralMesh mesh = beam(3, 3, 3, 3.0, 3.0);
  for (auto& p : mesh.nodes)
  {
    const bool interior = (p.array() > 1e-9).all() && (p.array() < 3.0 - 1e-9).all();
    if (interior)
    {
      p += Vector3(
        0.13 * std::sin(7.0 * p.y()), -0.11 * std::cos(5.0 * p.z()), 0.09 * std::sin(3.0 * p.x()));
    }
  }
  const Eigen::Matrix3d strain =
    (Eigen::Matrix3d() << 0.02, 0.004, 0.0, 0.004, -0.006, 0.001, 0.0, 0.001, -0.006).finished();
  CorotationalHexFem fem(mesh, material(2.0e4, 0.3));
  std::vector<Vector3> positions = mesh.nodes;
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    const Vector3& p = mesh.nodes[n];
    const bool boundary = (p.array() < 1e-9).any() || (p.array() > 3.0 - 1e-9).any();
    if (boundary)
    {
      positions[n] = p + strain * p;
      fem.setFixed(n, true);
    }
  }
  fem.setPositions(positions);
  const SolverResult result = fem.solveStatic(50, 1e-14);
  ASSERT_TRUE(result.ok) << result.message;
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    const Vector3 expected = mesh.nodes[n] + strain * mesh.nodes[n];
    EXPECT_LT((fem.positions()[n] - expected).norm(), 1e-11) << "node " << n;
  }
  EXPECT_LT(maxNorm(fem.elasticForces()) * 0.0, 1.0); // forces only at the boundary
}

TEST(CorotationalHexFem, CantileverMatchesEulerBernoulliAndConverges)
{
  // L = 10, square section 1 x 1, nu = 0: delta = P L^3 / (3 E I).
  const double length = 10.0;
  const double E = 1.0e5;
  const double P = 0.01;
  const double inertia = 1.0 / 12.0;
  const double exact = P * length * length * length / (3.0 * E * inertia);
  double previousError = 1e300;
  double finestError = 1e300;
  for (const auto& [nx, nyz] : { std::pair<int, int>{ 20, 2 }, { 40, 3 }, { 120, 4 } })
  {
    CorotationalHexFem fem(beam(nx, nyz, nyz, length, 1.0), material(E, 0.0));
    clampLeftEnd(fem);
    loadRightEnd(fem, length, Vector3(0.0, 0.0, -P));
    const SolverResult result = fem.solveStatic();
    ASSERT_TRUE(result.ok) << result.message;
    const double error = std::abs(-meanTipDeflection(fem, length) - exact) / exact;
    EXPECT_LT(error, previousError) << nx << " x " << nyz;
    previousError = error;
    finestError = error;
  }
  EXPECT_LT(finestError, 0.05);
}

TEST(CorotationalHexFem, LargeLoadKeepsLengthAndVolumeWhereLinearFemInflates)
{
  const double length = 10.0;
  const HexahedralMesh mesh = beam(40, 2, 2, length, 1.0);
  const double restVolume = 10.0;
  std::vector<double> lengths;
  auto solve = [&](bool corotational)
  {
    CorotationalHexFemSettings settings;
    settings.corotational = corotational;
    CorotationalHexFem fem(mesh, material(1.0e5, 0.3), settings);
    clampLeftEnd(fem);
    loadRightEnd(fem, length, Vector3(0.0, 0.0, -150.0)); // tip deflection ~ L/2 linearly
    // Load in increments, as a user would for a large load.
    SolverResult result;
    for (int k = 1; k <= 10; ++k)
    {
      loadRightEnd(fem, length, Vector3(0.0, 0.0, -15.0 * k));
      result = fem.solveStatic(100, 1e-9);
      if (!result.ok)
      {
        break;
      }
    }
    EXPECT_TRUE(result.ok) << result.message;
    // Length of the deformed centre line (nodes at y = z = 1/2, by x).
    std::vector<std::pair<double, Vector3>> centre;
    for (std::size_t n = 0; n < fem.nodeCount(); ++n)
    {
      const Vector3& rest = fem.restPositions()[n];
      if (std::abs(rest.y() - 0.5) < 1e-9 && std::abs(rest.z() - 0.5) < 1e-9)
      {
        centre.emplace_back(rest.x(), fem.positions()[n]);
      }
    }
    std::sort(
      centre.begin(), centre.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    double centreLength = 0.0;
    for (std::size_t k = 1; k < centre.size(); ++k)
    {
      centreLength += (centre[k].second - centre[k - 1].second).norm();
    }
    lengths.push_back(centreLength);
    return std::pair<double, double>(currentVolume(fem), -meanTipDeflection(fem, length));
  };
  const auto [corotationalVolume, corotationalDeflection] = solve(true);
  const auto [linearVolume, linearDeflection] = solve(false);
  EXPECT_NEAR(lengths[0], length, 0.02 * length); // co-rotational keeps its length
  EXPECT_GT(lengths[1], 1.05 * length);           // linear FEM stretches
  EXPECT_GT(linearDeflection, 0.3 * length);
  EXPECT_GT(corotationalDeflection, 0.1 * length);
  EXPECT_LT(corotationalDeflection, linearDeflection); // no spurious stretch
  EXPECT_NEAR(corotationalVolume, restVolume, 0.03 * restVolume);
  EXPECT_GT(linearVolume, 1.05 * restVolume); // linear FEM inflates
}

TEST(CorotationalHexFem, StaysAtRestAndDampingDissipates)
{
  const HexahedralMesh mesh = beam(6, 2, 2, 6.0, 1.0);
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.01;
  settings.rayleighMass = 1.0;
  CorotationalHexFem fem(mesh, material(1.0e4, 0.3, 1.0), settings);
  clampLeftEnd(fem);
  for (int k = 0; k < 50; ++k)
  {
    ASSERT_TRUE(fem.step().ok);
  }
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    EXPECT_LT((fem.positions()[n] - mesh.nodes[n]).norm(), 1e-12);
  }
  // Pluck it: initial velocity, then free vibration with damping.
  std::vector<Vector3> velocities(mesh.nodeCount(), Vector3::Zero());
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    if (!fem.isFixed(n))
    {
      velocities[n] = Vector3(0.0, 0.0, 0.5 * mesh.nodes[n].x());
    }
  }
  fem.setVelocities(velocities);
  const double initial = fem.kineticEnergy();
  ASSERT_GT(initial, 0.0);
  double peakLate = 0.0;
  for (int k = 0; k < 600; ++k)
  {
    ASSERT_TRUE(fem.step().ok);
    if (k >= 500)
    {
      peakLate = std::max(peakLate, fem.kineticEnergy());
    }
  }
  EXPECT_LT(peakLate, 0.05 * initial);
}

TEST(CorotationalHexFem, MeniscusMaterialIsStableFor10000Steps)
{
  // Thesis 4.5: meniscus E = 150 MPa, nu = 0.49. Units mm, N, s: E in MPa,
  // density 1.1e-9 t/mm^3. dt = 20 ms, 10 N on the inner edge.
  const MeniscusModel meniscus = makeMeniscus();
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.02;
  CorotationalHexFem fem(meniscus.simulation, material(150.0, 0.49, 1.1e-9), settings);
  std::size_t loaded = 0;
  double best = 1e300;
  const Vector3 innerEdge =
    makeMeniscusSolid(MeniscusParameters{}).point(ParameterPoint(0.5, 0.0, 1.0));
  for (std::size_t n = 0; n < fem.nodeCount(); ++n)
  {
    const double d = (fem.restPositions()[n] - innerEdge).norm();
    if (d < best && !fem.isFixed(n))
    {
      best = d;
      loaded = n;
    }
  }
  fem.setExternalForce(loaded, Vector3(0.0, 0.0, -10.0));
  double largest = 0.0;
  for (int k = 0; k < 10000; ++k)
  {
    const SolverResult result = fem.step();
    ASSERT_TRUE(result.ok) << "step " << k << ": " << result.message;
    largest = std::max(largest, (fem.positions()[loaded] - fem.restPositions()[loaded]).norm());
  }
  for (const auto& p : fem.positions())
  {
    ASSERT_TRUE(p.allFinite());
  }
  EXPECT_GT(largest, 1e-3); // it does deform
  EXPECT_LT(largest, 20.0); // and stays bounded
}

TEST(CorotationalHexFem, AllLinearSolversAgreeAndTheStaleFactorIsReused)
{
  const HexahedralMesh mesh = beam(8, 2, 2, 8.0, 1.0);
  std::vector<CorotationalHexFem> fems;
  for (auto kind : { LinearSolverKind::Cholmod,
         LinearSolverKind::ConjugateGradient,
         LinearSolverKind::StaleFactorConjugateGradient,
         LinearSolverKind::Automatic })
  {
    CorotationalHexFemSettings settings;
    settings.solver = kind;
    fems.emplace_back(mesh, material(1.0e4, 0.3), settings);
  }
  const int steps = 40;
  for (auto& fem : fems)
  {
    clampLeftEnd(fem);
    loadRightEnd(fem, 8.0, Vector3(0.0, 0.0, -20.0));
    for (int k = 0; k < steps; ++k)
    {
      ASSERT_TRUE(fem.step().ok);
    }
  }
  for (std::size_t f = 1; f < fems.size(); ++f)
  {
    for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
    {
      EXPECT_LT((fems[0].positions()[n] - fems[f].positions()[n]).norm(), 1e-6) << "solver " << f;
    }
  }
  EXPECT_EQ(fems[0].factorizationCount(), steps);
  EXPECT_LT(fems[2].factorizationCount(), steps / 2); // reused across steps
}

TEST(CorotationalHexFem, TheElasticPartAssembledAheadGivesTheSameStep)
{
  // assembleElasticPart() ahead of the step (what CollisionScene runs while
  // it finds the contacts) changes nothing in the step; a change of state
  // in between is assembled again, and a topology change too.
  const HexahedralMesh mesh = beam(6, 2, 2, 6.0, 1.0);
  auto make = [&]
  {
    CorotationalHexFem fem(mesh, material(1.0e4, 0.3));
    clampLeftEnd(fem);
    loadRightEnd(fem, 6.0, Vector3(0.0, 0.0, -30.0));
    return fem;
  };
  CorotationalHexFem plain = make();
  CorotationalHexFem ahead = make();
  const std::vector<Vector3> nudge = [&]
  {
    std::vector<Vector3> v(mesh.nodeCount(), Vector3::Zero());
    v.back() = Vector3(0.0, 0.01, 0.0);
    return v;
  }();
  for (int k = 0; k < 30; ++k)
  {
    ahead.assembleElasticPart();
    if (k % 3 == 1)
    {
      ahead.assembleElasticPart(); // twice: the step is counted once
    }
    if (k % 10 == 5)
    {
      // Between the elastic part and the step: must be assembled again.
      ahead.setVelocities(nudge);
      plain.setVelocities(nudge);
    }
    ASSERT_TRUE(plain.step().ok);
    ASSERT_TRUE(ahead.step().ok);
    for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
    {
      ASSERT_EQ(plain.positions()[n], ahead.positions()[n]) << "step " << k << " node " << n;
    }
  }
  EXPECT_EQ(plain.factorizationCount(), ahead.factorizationCount());
  // A hexahedron removed after the elastic part: the step runs on the new
  // topology (a background factor due at that step may have landed before
  // the change rather than after it, so equal within the solve's tolerance).
  ahead.assembleElasticPart();
  ahead.removeHexahedron(5);
  plain.removeHexahedron(5);
  ASSERT_TRUE(plain.step().ok);
  ASSERT_TRUE(ahead.step().ok);
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    EXPECT_LT((plain.positions()[n] - ahead.positions()[n]).norm(), 1e-9) << "node " << n;
  }
}

TEST(CorotationalHexFem, StaleFactorIsRenewedOnceItsExtraIterationsAddUp)
{
  // The beam swinging under a load: every step's matrix differs, so a
  // stale factor costs a few extra iterations each step. With no budget
  // it is kept until a solve exceeds refactorizationIterations; with a
  // small budget it is renewed more often and the steps need fewer
  // iterations. Results agree either way.
  const HexahedralMesh mesh = beam(8, 2, 2, 8.0, 1.0);
  auto run = [&](int budget, int& factorizations, double& iterationsPerStep)
  {
    CorotationalHexFemSettings settings;
    settings.solver = LinearSolverKind::StaleFactorConjugateGradient;
    settings.staleFactorIterationBudget = budget;
    CorotationalHexFem fem(mesh, material(1.0e4, 0.3), settings);
    clampLeftEnd(fem);
    loadRightEnd(fem, 8.0, Vector3(0.0, 0.0, -20.0));
    int iterations = 0;
    const int steps = 60;
    for (int k = 0; k < steps; ++k)
    {
      const SolverResult result = fem.step();
      EXPECT_TRUE(result.ok) << result.message;
      iterations += result.iterations;
    }
    factorizations = fem.factorizationCount();
    iterationsPerStep = static_cast<double>(iterations) / steps;
    return fem.positions();
  };
  int unlimitedFactorizations = 0;
  int budgetFactorizations = 0;
  double unlimitedIterations = 0.0;
  double budgetIterations = 0.0;
  const auto unlimited = run(1 << 30, unlimitedFactorizations, unlimitedIterations);
  const auto budgeted = run(4, budgetFactorizations, budgetIterations);
  EXPECT_GT(budgetFactorizations, unlimitedFactorizations);
  EXPECT_LT(budgetIterations, unlimitedIterations);
  for (std::size_t n = 0; n < unlimited.size(); ++n)
  {
    EXPECT_LT((unlimited[n] - budgeted[n]).norm(), 1e-6);
  }
  CorotationalHexFemSettings negative;
  negative.staleFactorIterationBudget = -1;
  EXPECT_THROW(CorotationalHexFem(mesh, material(1.0e4, 0.3), negative), InvalidInputError);
}

TEST(CorotationalHexFem, FreeBodyIsLegalAndStable)
{
  CorotationalHexFem fem(beam(3, 1, 1, 3.0, 1.0), material(1.0e4, 0.3));
  fem.setExternalForce(0, Vector3(1.0, 0.0, 0.0));
  for (int k = 0; k < 200; ++k)
  {
    ASSERT_TRUE(fem.step().ok);
  }
  for (const auto& p : fem.positions())
  {
    EXPECT_TRUE(p.allFinite());
  }
  EXPECT_FALSE(fem.solveStatic().ok); // no unique equilibrium, reported
}

TEST(CorotationalHexFem, TopologyChangesSeparateDuplicatedNodes)
{
  // Two hexahedra side by side; give the right one its own copies of the
  // shared face (a cut), then pull the halves apart.
  const HexahedralMesh mesh = beam(2, 1, 1, 2.0, 1.0);
  CorotationalHexFem fem(mesh, material(1.0e4, 0.3));
  Hexahedron right = fem.hexahedronNodes(1);
  for (int k = 0; k < 8; ++k)
  {
    const Vector3 rest = fem.restPositions()[right[k]];
    if (std::abs(rest.x() - 1.0) < 1e-12)
    {
      right[k] = static_cast<int>(fem.addNode(rest, fem.positions()[right[k]], Vector3::Zero()));
    }
  }
  fem.replaceHexahedronNodes(1, right);
  for (std::size_t n = 0; n < fem.nodeCount(); ++n)
  {
    const double x = fem.restPositions()[n].x();
    if (x < 1e-12 || x > 2.0 - 1e-12)
    {
      fem.setFixed(n, true);
    }
    if (std::abs(x - 1.0) < 1e-12)
    {
      fem.setExternalForce(n, Vector3(n < mesh.nodeCount() ? -50.0 : 50.0, 0.0, 0.0));
    }
  }
  ASSERT_TRUE(fem.solveStatic().ok);
  double gap = 1e300;
  for (std::size_t a = 0; a < mesh.nodeCount(); ++a)
  {
    for (std::size_t b = mesh.nodeCount(); b < fem.nodeCount(); ++b)
    {
      gap = std::min(gap, (fem.positions()[a] - fem.positions()[b]).norm());
    }
  }
  EXPECT_GT(gap, 1e-3);
  const double massBefore = [&]
  {
    double m = 0.0;
    for (double x : fem.nodeMasses())
      m += x;
    return m;
  }();
  fem.removeHexahedron(1);
  EXPECT_EQ(fem.activeHexahedronCount(), 1u);
  double massAfter = 0.0;
  for (double x : fem.nodeMasses())
  {
    massAfter += x;
  }
  EXPECT_NEAR(massAfter, 0.5 * massBefore, 1e-12);
  EXPECT_TRUE(fem.step().ok);
  const std::size_t added = fem.addHexahedron(right, material(1.0e4, 0.3));
  EXPECT_EQ(added, 2u);
  EXPECT_TRUE(fem.step().ok);
}

TEST(CorotationalHexFem, BadInputIsRejectedClearly)
{
  const HexahedralMesh good = beam(1, 1, 1, 1.0, 1.0);
  HexahedralMesh inverted = good;
  std::swap(inverted.hexahedra[0][0], inverted.hexahedra[0][1]);
  std::swap(inverted.hexahedra[0][3], inverted.hexahedra[0][2]);
  std::swap(inverted.hexahedra[0][4], inverted.hexahedra[0][5]);
  std::swap(inverted.hexahedra[0][7], inverted.hexahedra[0][6]);
  auto expectError = [](auto&& make, const std::string& word)
  {
    try
    {
      make();
      ADD_FAILURE() << "no error for " << word;
    }
    catch (const InvalidInputError& error)
    {
      EXPECT_NE(std::string(error.what()).find(word), std::string::npos) << error.what();
    }
  };
  expectError([&] { CorotationalHexFem fem(inverted, material(1.0, 0.3)); }, "inverted");
  expectError([&] { CorotationalHexFem fem(good, material(1.0, 0.5)); }, "Poisson");
  expectError([&] { CorotationalHexFem fem(good, material(1.0, -1.0)); }, "Poisson");
  expectError([&] { CorotationalHexFem fem(good, material(0.0, 0.3)); }, "Young");
  CorotationalHexFemSettings settings;
  settings.timeStep = 0.0;
  expectError([&] { CorotationalHexFem fem(good, material(1.0, 0.3), settings); }, "time step");
  CorotationalHexFem fem(good, material(1.0, 0.3));
  expectError([&] { fem.setFixed(100, true); }, "node 100");
  expectError([&] { fem.setExternalForce(0, Vector3(std::nan(""), 0.0, 0.0)); }, "not finite");

  // A state that overflows is reported and the last good state kept.
  std::vector<Vector3> huge = good.nodes;
  huge[6] = Vector3(1.79e308, -1.79e308, 1.79e308);
  fem.setPositions(huge);
  std::vector<Vector3> fast(good.nodeCount(), Vector3::Zero());
  fast[6] = Vector3(1e308, -1e308, 1e308);
  fem.setVelocities(fast);
  const std::vector<Vector3> before = fem.positions();
  const SolverResult result = fem.step();
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("last good state"), std::string::npos) << result.message;
  EXPECT_EQ(fem.positions(), before);
  for (const auto& p : fem.positions())
  {
    EXPECT_TRUE(p.allFinite());
  }
}
