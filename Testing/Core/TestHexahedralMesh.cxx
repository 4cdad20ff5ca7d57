#include "HexahedralMesh.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

using namespace thintissue;

TEST(HexahedralMesh, RegularGridOfTheThesisSheet)
{
  // Thesis table 5-5: a 9 x 9 x 1 grid, 200 nodes, 81 hexahedra.
  const HexahedralMesh grid =
    HexahedralMesh::makeRegularGrid(Vector3(0, 0, 0), Vector3(1, 1, 0.5), 9, 9, 1);
  EXPECT_EQ(grid.nodeCount(), 200u);
  EXPECT_EQ(grid.hexahedronCount(), 81u);
  EXPECT_EQ(grid.fixedNodeCount(), 0u);
  EXPECT_NO_THROW(grid.checkConsistency());
  EXPECT_TRUE(grid.hexahedronCentre(0).isApprox(Vector3(0.5, 0.5, 0.25)));
  // VTK order: corner k of cell 0 sits at cornerOffset(k) * spacing.
  for (int k = 0; k < 8; ++k)
  {
    const auto o = HexahedralMesh::cornerOffset(k);
    EXPECT_LT((grid.nodes[grid.hexahedra[0][k]] - Vector3(o[0], o[1], 0.5 * o[2])).norm(), 1e-12);
  }
}

TEST(HexahedralMesh, FixLowestNodesClampsOneEnd)
{
  HexahedralMesh mesh =
    HexahedralMesh::makeRegularGrid(Vector3(-2.0, 1.0, 0.5), Vector3(0.5, 1.0, 2.0), 4, 2, 1);
  mesh.fixLowestNodes(1, 1e-9); // the face y = 1: 5 x 2 nodes
  EXPECT_EQ(mesh.fixedNodeCount(), 10u);
  for (std::size_t n = 0; n < mesh.nodeCount(); ++n)
  {
    EXPECT_EQ(mesh.isFixed(n), mesh.nodes[n].y() < 1.0 + 1e-9) << n;
  }
  mesh.fixLowestNodes(0, 0.6); // x = -2 and x = -1.5 now; y = 1 freed
  EXPECT_EQ(mesh.fixedNodeCount(), 12u);
  EXPECT_THROW(mesh.fixLowestNodes(3, 0.0), InvalidInputError);
  EXPECT_THROW(mesh.fixLowestNodes(0, -1.0), InvalidInputError);
}

TEST(HexahedralMesh, ConsistencyErrors)
{
  HexahedralMesh grid = HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), 1, 1, 1);
  grid.name = "cube";
  grid.hexahedra[0][3] = 8;
  EXPECT_THROW(grid.checkConsistency(), InvalidInputError);
  grid.hexahedra[0][3] = grid.hexahedra[0][2];
  EXPECT_THROW(grid.checkConsistency(), InvalidInputError);
  grid = HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), 1, 1, 1);
  grid.fixedNodes.resize(3);
  EXPECT_THROW(grid.checkConsistency(), InvalidInputError);
  EXPECT_THROW(
    HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), 0, 1, 1), InvalidInputError);
  EXPECT_THROW(HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3(1, -1, 1), 1, 1, 1),
    InvalidInputError);
}
