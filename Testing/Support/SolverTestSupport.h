// Helpers shared by the solver's tests (header-only, not installed).
#ifndef SolverTestSupport_h
#define SolverTestSupport_h

#include "HexahedralMesh.h"
#include "ThinTissueError.h"

#include <gtest/gtest.h>

#include <string>

namespace thintissue::testing
{

/// A block of nx x ny x nz hexahedra of 1 mm, fixed at x = 0 (the fem
/// benchmark's blocks).
inline HexahedralMesh fixedBlock(int nx, int ny, int nz)
{
  HexahedralMesh mesh =
    HexahedralMesh::makeRegularGrid(Vector3::Zero(), Vector3::Ones(), nx, ny, nz);
  mesh.fixLowestNodes(0, 1e-12);
  return mesh;
}

/// `make` throws InvalidInputError and its message names `problem`.
template <typename Make>
void expectRefusedNaming(Make&& make, const std::string& problem)
{
  try
  {
    make();
    ADD_FAILURE() << "no error for " << problem;
  }
  catch (const InvalidInputError& error)
  {
    EXPECT_NE(std::string(error.what()).find(problem), std::string::npos) << error.what();
  }
}

} // namespace thintissue::testing

#endif
