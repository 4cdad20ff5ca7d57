// Embeddings and sparse hexahedral grids of the real tissue shapes (thesis
// 4.3): the visual and collision meshes of the meniscus and the thin sheet
// in their simulation meshes, and sparse grids made from their surfaces.
#include "HexahedralEmbedding.h"
#include "MeniscusModel.h"
#include "SparseHexahedralGrid.h"
#include "ThinSheetModel.h"

#include <gtest/gtest.h>

using namespace thintissue;

namespace
{

double maximumError(const std::vector<Vector3>& a, const std::vector<Vector3>& b)
{
  double error = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    error = std::max(error, (a[i] - b[i]).norm());
  }
  return error;
}

// Embeds `points` in `mesh`; the rest shape must come back (to 1e-12 of the
// model's size) unless a point had to be clamped.
void expectRestShapeReproduced(const HexahedralMesh& mesh,
  const std::vector<Vector3>& points,
  const std::string& what)
{
  const HexahedralEmbedding embedding(mesh, points);
  EXPECT_EQ(embedding.clampedPointCount(), 0u) << what;
  std::vector<Vector3> mapped;
  embedding.mapPositions(mesh.nodes, mapped);
  const double size = boundingBoxOf(points).diagonal().norm();
  EXPECT_LT(maximumError(mapped, points), 1e-12 * size) << what;
}

// The sparse grid covers every vertex; returns the fraction of the full
// grid's cells it keeps.
double expectSparseGridCovers(const TriangleMesh& surface, int cells, const std::string& what)
{
  const SparseHexahedralGrid grid =
    SparseHexahedralGrid::fromSurface(surface, SparseHexahedralGridSettings{ cells, 0.0 });
  EXPECT_NO_THROW(grid.mesh.checkConsistency()) << what;
  EXPECT_GT(grid.mesh.hexahedronCount(), 0u) << what;
  const std::size_t full =
    static_cast<std::size_t>(grid.cellCounts[0]) * grid.cellCounts[1] * grid.cellCounts[2];
  const HexahedralEmbedding embedding(grid.mesh, surface.positions);
  EXPECT_EQ(embedding.outsidePointCount(), 0u) << what;
  return static_cast<double>(grid.mesh.hexahedronCount()) / static_cast<double>(full);
}

} // namespace

TEST(EmbeddingOfModels, MeniscusMeshesInItsSimulationMesh)
{
  const MeniscusModel meniscus = makeMeniscus();
  expectRestShapeReproduced(meniscus.simulation, meniscus.visual.positions, "meniscus visual");
  expectRestShapeReproduced(
    meniscus.simulation, meniscus.collision.positions, "meniscus collision");
  // The C-shaped meniscus fills a small part of its bounding box.
  EXPECT_LT(expectSparseGridCovers(meniscus.visual, 20, "meniscus sparse grid"), 0.5);
}

TEST(EmbeddingOfModels, ThinSheetMeshesInItsSimulationMesh)
{
  const TissueModel sheet = makeThinSheet(ThinSheetParameters{});
  expectRestShapeReproduced(sheet.simulation, sheet.visual.positions, "sheet visual");
  expectRestShapeReproduced(sheet.simulation, sheet.collision.positions, "sheet collision");
  EXPECT_EQ(expectSparseGridCovers(sheet.visual, 20, "sheet sparse grid"), 1.0);
  // A single layer of cells through the 2 mm sheet at 5 mm cells.
  const SparseHexahedralGrid grid =
    SparseHexahedralGrid::fromSurface(sheet.visual, SparseHexahedralGridSettings{ 20, 0.0 });
  EXPECT_EQ(grid.cellCounts[2], 1);
  EXPECT_EQ(grid.mesh.hexahedronCount(), 20u * 20u);
}
