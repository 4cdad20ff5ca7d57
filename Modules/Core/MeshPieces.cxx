#include "MeshPieces.h"

#include "ThinTissueError.h"
#include "TriangleMeshAdjacency.h"
#include "UnionFind.h"

#include <algorithm>
#include <sstream>

namespace thintissue
{

std::vector<std::vector<int>> edgeConnectedTriangles(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency)
{
  UnionFind pieces(mesh.triangleCount());
  for (int e = 0; e < static_cast<int>(adjacency.edgeCount()); ++e)
  {
    const int* first = adjacency.edgeTrianglesBegin(e);
    for (const int* t = first + 1; t < adjacency.edgeTrianglesEnd(e); ++t)
    {
      pieces.unite(*first, *t);
    }
  }
  std::vector<std::vector<int>> groups;
  std::vector<int> groupOfRoot(mesh.triangleCount(), -1);
  for (int t = 0; t < static_cast<int>(mesh.triangleCount()); ++t)
  {
    int& group = groupOfRoot[pieces.find(t)];
    if (group < 0)
    {
      group = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[group].push_back(t);
  }
  return groups;
}

int floodTrianglePieces(const TriangleMeshAdjacency& adjacency,
  std::size_t triangleCount,
  const std::function<bool(int triangle, int edge)>& joined,
  std::vector<int>& piece)
{
  piece.assign(triangleCount, -1);
  int pieces = 0;
  std::vector<int> stack;
  for (std::size_t seed = 0; seed < triangleCount; ++seed)
  {
    if (piece[seed] >= 0)
    {
      continue;
    }
    piece[seed] = pieces;
    stack.assign(1, static_cast<int>(seed));
    while (!stack.empty())
    {
      const int t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k)
      {
        const int next = adjacency.neighbourAcross(t, k);
        if (next >= 0 && piece[next] < 0 && joined(t, k))
        {
          piece[next] = pieces;
          stack.push_back(next);
        }
      }
    }
    ++pieces;
  }
  return pieces;
}

std::vector<std::vector<int>> borderLoops(const TriangleMeshAdjacency& adjacency,
  std::size_t vertexCount,
  const std::string& meshLabel)
{
  std::vector<std::vector<int>> neighbours(vertexCount);
  for (int e = 0; e < static_cast<int>(adjacency.edgeCount()); ++e)
  {
    if (adjacency.isBorderEdge(e))
    {
      neighbours[adjacency.edge(e)[0]].push_back(adjacency.edge(e)[1]);
      neighbours[adjacency.edge(e)[1]].push_back(adjacency.edge(e)[0]);
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    if (!neighbours[v].empty() && neighbours[v].size() != 2)
    {
      throw InvalidInputError(meshLabel + ": border vertex " + std::to_string(v) + " joins " +
                              std::to_string(neighbours[v].size()) + " border edges, not 2");
    }
  }
  std::vector<std::vector<int>> loops;
  std::vector<char> visited(vertexCount, 0);
  for (std::size_t start = 0; start < vertexCount; ++start)
  {
    if (neighbours[start].empty() || visited[start])
    {
      continue;
    }
    std::vector<int>& loop = loops.emplace_back();
    int previous = -1;
    for (int v = static_cast<int>(start); !visited[v];)
    {
      visited[v] = 1;
      loop.push_back(v);
      const int following = neighbours[v][0] != previous ? neighbours[v][0] : neighbours[v][1];
      previous = v;
      v = following;
    }
  }
  return loops;
}

namespace
{

/// Copies the triangles into a mesh of their own; `localIndex` (one entry
/// per input vertex, all -1) is used as scratch and left all -1.
MeshPiece extractPiece(const TriangleMesh& mesh,
  const std::vector<int>& triangles,
  std::vector<int>& localIndex)
{
  MeshPiece piece;
  TriangleMesh& out = piece.mesh;
  for (int t : triangles)
  {
    Triangle local{};
    for (int k = 0; k < 3; ++k)
    {
      const int v = mesh.triangles[t][k];
      if (localIndex[v] < 0)
      {
        localIndex[v] = static_cast<int>(piece.originalVertices.size());
        piece.originalVertices.push_back(v);
        out.positions.push_back(mesh.positions[v]);
      }
      local[k] = localIndex[v];
    }
    out.triangles.push_back(local);
  }
  for (int v : piece.originalVertices)
  {
    localIndex[v] = -1;
    if (mesh.hasNormals())
    {
      out.normals.push_back(mesh.normals[v]);
    }
  }
  for (const std::string& name : mesh.pointAttributes.names())
  {
    const AttributeArray& array = mesh.pointAttributes.get(name);
    std::vector<double> values;
    for (int v : piece.originalVertices)
    {
      values.insert(values.end(), array.element(v), array.element(v) + array.components);
    }
    out.pointAttributes.set(name, array.components, std::move(values));
  }
  if (mesh.hasTextureCoordinates())
  {
    // Each piece keeps all texture coordinates: they are small, and the
    // corners then index them unchanged.
    out.textureCoordinates = mesh.textureCoordinates;
    for (int t : triangles)
    {
      out.textureCorners.push_back(mesh.textureCorners[t]);
    }
  }
  return piece;
}

void measure(MeshPiece& piece)
{
  const TriangleMesh& mesh = piece.mesh;
  Vector3 weighted = Vector3::Zero();
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const double area = mesh.triangleArea(t);
    const Triangle& tri = mesh.triangles[t];
    weighted +=
      area / 3.0 * (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]);
    piece.area += area;
  }
  const BoundingBox box = mesh.boundingBox();
  // A piece of zero area (degenerate triangles only) is placed at its box.
  piece.centre = piece.area > 0.0 ? Vector3(weighted / piece.area) : box.center();
  piece.largestExtent = box.sizes().maxCoeff();
}

std::string shortNumber(double value)
{
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

} // namespace

std::string MeshPiece::description() const
{
  return "piece " + std::to_string(number) + ": " + std::to_string(mesh.vertexCount()) +
         " vertices, " + std::to_string(mesh.triangleCount()) + " triangles, area " +
         shortNumber(area) + ", centre (" + shortNumber(centre.x()) + ", " +
         shortNumber(centre.y()) + ", " + shortNumber(centre.z()) + ")";
}

std::size_t countPieces(const TriangleMesh& mesh)
{
  return edgeConnectedTriangles(mesh, TriangleMeshAdjacency(mesh)).size();
}

std::vector<MeshPiece> splitIntoPieces(const TriangleMesh& mesh)
{
  std::vector<MeshPiece> pieces;
  std::vector<int> localIndex(mesh.vertexCount(), -1);
  for (const std::vector<int>& triangles :
    edgeConnectedTriangles(mesh, TriangleMeshAdjacency(mesh)))
  {
    pieces.push_back(extractPiece(mesh, triangles, localIndex));
    measure(pieces.back());
  }
  // Stable: pieces of equal area keep the order of their first triangle.
  std::stable_sort(pieces.begin(),
    pieces.end(),
    [](const MeshPiece& a, const MeshPiece& b) { return a.area > b.area; });
  const bool several = pieces.size() > 1;
  for (std::size_t i = 0; i < pieces.size(); ++i)
  {
    pieces[i].number = static_cast<int>(i) + 1;
    pieces[i].mesh.name =
      several ? mesh.name + " piece " + std::to_string(pieces[i].number) : mesh.name;
  }
  return pieces;
}

PieceSelection selectPieces(const TriangleMesh& mesh, double minimumFraction)
{
  if (!(minimumFraction >= 0.0 && minimumFraction <= 1.0))
  {
    throw InvalidInputError("mesh pieces: the minimum piece fraction must be in [0, 1], not " +
                            shortNumber(minimumFraction));
  }
  PieceSelection selection;
  std::vector<MeshPiece> pieces = splitIntoPieces(mesh);
  const double minimumArea = pieces.empty() ? 0.0 : minimumFraction * pieces.front().area;
  for (MeshPiece& piece : pieces)
  {
    // The largest piece is always kept, even when all are degenerate.
    const bool kept = piece.number == 1 || piece.area >= minimumArea;
    (kept ? selection.kept : selection.dropped).push_back(std::move(piece));
  }
  return selection;
}

} // namespace thintissue
