#include "SheetThickening.h"

#include "MeshPieces.h"
#include "ThinTissueError.h"
#include "TriangleMeshAdjacency.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

namespace thintissue
{

namespace
{

std::string meshLabel(const TriangleMesh& mesh)
{
  return "thickening of mesh '" + (mesh.name.empty() ? std::string("mesh") : mesh.name) + "'";
}

/// +1 if triangle c runs from a to b, -1 if from b to a.
int direction(const Triangle& c, int a, int b)
{
  for (int k = 0; k < 3; ++k)
  {
    if (c[k] == a && c[(k + 1) % 3] == b)
    {
      return 1;
    }
  }
  return -1;
}

/// Throws where an edge has more than two triangles or its two triangles
/// run along it the same way (the normals would not agree).
void checkEdges(const TriangleMesh& mesh, const TriangleMeshAdjacency& adjacency)
{
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    const auto [a, b] = adjacency.edge(static_cast<int>(e));
    const int count = adjacency.edgeTriangleCount(static_cast<int>(e));
    const std::string where = "edge " + std::to_string(a) + "-" + std::to_string(b);
    if (count > 2)
    {
      throw InvalidInputError(meshLabel(mesh) + ": " + where + " has " + std::to_string(count) +
                              " triangles (a non-manifold edge; --repair splits it)");
    }
    if (count == 2)
    {
      const int* t = adjacency.edgeTrianglesBegin(static_cast<int>(e));
      if (direction(mesh.triangles[t[0]], a, b) == direction(mesh.triangles[t[1]], a, b))
      {
        throw InvalidInputError(meshLabel(mesh) + ": triangles " + std::to_string(t[0]) + " and " +
                                std::to_string(t[1]) + " on " + where +
                                " are not consistently oriented (--repair orients them)");
      }
    }
  }
}

/// Per triangle its piece (MeshPieces.h: joined through shared edges).
std::vector<int> trianglePieces(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  int& pieceCount)
{
  const std::vector<std::vector<int>> pieces = edgeConnectedTriangles(mesh, adjacency);
  std::vector<int> piece(mesh.triangleCount(), -1);
  for (std::size_t p = 0; p < pieces.size(); ++p)
  {
    for (const int t : pieces[p])
    {
      piece[t] = static_cast<int>(p);
    }
  }
  pieceCount = static_cast<int>(pieces.size());
  return piece;
}

/// Per vertex its unit normal over the triangles of open pieces, weighted by
/// the triangles' angles at it (zero for the others); throws where they
/// cancel out or where a vertex joins two pieces.
std::vector<Vector3> offsetNormals(const TriangleMesh& mesh,
  const std::vector<int>& piece,
  const std::vector<char>& open)
{
  std::vector<Vector3> normals(mesh.vertexCount(), Vector3::Zero());
  std::vector<int> pieceOf(mesh.vertexCount(), -1);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const Triangle& c = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      int& owner = pieceOf[c[k]];
      if (owner >= 0 && owner != piece[t])
      {
        throw InvalidInputError(meshLabel(mesh) + ": vertex " + std::to_string(c[k]) +
                                " joins two pieces (a non-manifold vertex; --repair splits it)");
      }
      owner = piece[t];
    }
    if (!open[piece[t]])
    {
      continue;
    }
    const Vector3 unit = mesh.triangleNormal(t);
    for (int k = 0; k < 3; ++k)
    {
      const Vector3& p = mesh.positions[c[k]];
      const Vector3 u = mesh.positions[c[(k + 1) % 3]] - p;
      const Vector3 w = mesh.positions[c[(k + 2) % 3]] - p;
      normals[c[k]] += std::atan2(u.cross(w).norm(), u.dot(w)) * unit;
    }
  }
  for (std::size_t v = 0; v < normals.size(); ++v)
  {
    if (pieceOf[v] < 0 || !open[pieceOf[v]])
    {
      continue;
    }
    const double length = normals[v].norm();
    if (!(length > 1e-12))
    {
      throw InvalidInputError(meshLabel(mesh) + ": vertex " + std::to_string(v) +
                              " has no normal (its triangles cancel out)");
    }
    normals[v] /= length;
  }
  return normals;
}

/// The normals averaged with their neighbours' over about the thickness
/// (uniform weights, (thickness / mean edge)^2 passes, at most 50): a
/// segmented surface is rough at the scale of its voxels, and offsetting
/// along its own normals would fold the layers at every small bump.
std::vector<Vector3> smoothedNormals(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  std::vector<Vector3> normals,
  double thickness)
{
  double edgeSum = 0.0;
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    const auto& [a, b] = adjacency.edge(static_cast<int>(e));
    edgeSum += (mesh.positions[a] - mesh.positions[b]).norm();
  }
  const double meanEdge =
    edgeSum / static_cast<double>(std::max<std::size_t>(1, adjacency.edgeCount()));
  const double ratio = thickness / meanEdge;
  const int passes = static_cast<int>(std::min(50.0, std::ceil(ratio * ratio)));
  std::vector<Vector3> next(normals.size());
  for (int pass = 0; pass < passes; ++pass)
  {
    next = normals;
    for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
    {
      const auto& [a, b] = adjacency.edge(static_cast<int>(e));
      next[a] += normals[b];
      next[b] += normals[a];
    }
    for (std::size_t v = 0; v < normals.size(); ++v)
    {
      const double length = next[v].norm();
      normals[v] =
        normals[v].squaredNorm() > 0.0 && length > 1e-12 ? Vector3(next[v] / length) : normals[v];
    }
  }
  return normals;
}

/// The texture corner of vertex v in triangle t (-1 without texture).
int textureCornerOf(const TriangleMesh& mesh, int t, int v)
{
  if (!mesh.hasTextureCoordinates())
  {
    return -1;
  }
  const Triangle& c = mesh.triangles[t];
  return mesh.textureCorners[t][c[0] == v ? 0 : (c[1] == v ? 1 : 2)];
}

/// Throws if the upper or lower copy of triangle t turned over.
void checkNotFolded(const TriangleMesh& original,
  const TriangleMesh& result,
  std::size_t t,
  const Triangle& lower)
{
  const Triangle& c = original.triangles[t];
  auto normal = [](const std::vector<Vector3>& p, const Triangle& corners)
  { return Vector3((p[corners[1]] - p[corners[0]]).cross(p[corners[2]] - p[corners[0]])); };
  const Vector3 before = normal(original.positions, c);
  if (before.dot(normal(result.positions, c)) <= 0.0 ||
      before.dot(normal(result.positions, lower)) <= 0.0)
  {
    throw InvalidInputError(meshLabel(original) + ": the thickness folds the layers at triangle " +
                            std::to_string(t) +
                            " (thicker than about twice the surface's radius of curvature there)");
  }
}

/// The loops the border edges form (each border vertex has two of them).
int borderLoops(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<int>& borderEdges)
{
  std::vector<std::vector<int>> next(mesh.vertexCount());
  for (const int e : borderEdges)
  {
    next[adjacency.edge(e)[0]].push_back(adjacency.edge(e)[1]);
    next[adjacency.edge(e)[1]].push_back(adjacency.edge(e)[0]);
  }
  std::vector<char> seen(mesh.vertexCount(), 0);
  int loops = 0;
  std::vector<int> stack;
  for (const int e : borderEdges)
  {
    const int start = adjacency.edge(e)[0];
    if (seen[start])
    {
      continue;
    }
    ++loops;
    stack.assign(1, start);
    seen[start] = 1;
    while (!stack.empty())
    {
      const int v = stack.back();
      stack.pop_back();
      for (const int w : next[v])
      {
        if (!seen[w])
        {
          seen[w] = 1;
          stack.push_back(w);
        }
      }
    }
  }
  return loops;
}

/// A quad per border edge (a, b) as its triangle runs: upper b, upper a,
/// lower a, and upper b, lower a, lower b (the upper triangle runs a -> b,
/// the rim b -> a; the lower one b' -> a', the rim a' -> b').
void addRim(const TriangleMesh& mesh,
  const TriangleMeshAdjacency& adjacency,
  const std::vector<int>& borderEdges,
  const std::vector<int>& lowerOf,
  TriangleMesh& result)
{
  for (const int e : borderEdges)
  {
    const int t = *adjacency.edgeTrianglesBegin(e);
    auto [a, b] = adjacency.edge(e);
    if (direction(mesh.triangles[t], a, b) < 0)
    {
      std::swap(a, b);
    }
    result.triangles.push_back({ b, a, lowerOf[a] });
    result.triangles.push_back({ b, lowerOf[a], lowerOf[b] });
    if (mesh.hasTextureCoordinates())
    {
      const int ta = textureCornerOf(mesh, t, a);
      const int tb = textureCornerOf(mesh, t, b);
      result.textureCorners.push_back({ tb, ta, ta });
      result.textureCorners.push_back({ tb, ta, tb });
    }
  }
}

} // namespace

std::string SheetThickeningReport::summary(const std::string& units) const
{
  std::ostringstream out;
  out << "thickened " << thickenedPieces << " open piece" << (thickenedPieces == 1 ? "" : "s")
      << " to " << thickness << " " << units << " (" << borderLoops << " border"
      << (borderLoops == 1 ? "" : "s") << " closed by a rim; " << addedVertices << " vertices and "
      << addedTriangles << " triangles added)";
  if (closedPieces > 0)
  {
    out << "; " << closedPieces << " closed piece" << (closedPieces == 1 ? "" : "s") << " left as "
        << (closedPieces == 1 ? "it was" : "they were");
  }
  out << "\n";
  return out.str();
}

std::string SheetThickeningReport::toJson() const
{
  std::ostringstream out;
  out << "{\"thickness\": " << thickness << ", \"thickenedPieces\": " << thickenedPieces
      << ", \"closedPieces\": " << closedPieces << ", \"borderLoops\": " << borderLoops
      << ", \"addedVertices\": " << addedVertices << ", \"addedTriangles\": " << addedTriangles
      << "}";
  return out.str();
}

TriangleMesh thickenOpenSheets(const TriangleMesh& mesh,
  double thickness,
  SheetThickeningReport* report)
{
  if (!(thickness > 0.0) || !std::isfinite(thickness))
  {
    throw InvalidInputError(meshLabel(mesh) + ": the thickness must be positive and finite");
  }
  mesh.checkConsistency();
  const TriangleMeshAdjacency adjacency(mesh);
  checkEdges(mesh, adjacency);
  int pieceCount = 0;
  const std::vector<int> piece = trianglePieces(mesh, adjacency, pieceCount);
  std::vector<char> open(static_cast<std::size_t>(pieceCount), 0);
  std::vector<int> borderEdges;
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    if (adjacency.isBorderEdge(static_cast<int>(e)))
    {
      open[piece[*adjacency.edgeTrianglesBegin(static_cast<int>(e))]] = 1;
      borderEdges.push_back(static_cast<int>(e));
    }
  }
  const std::vector<Vector3> normals =
    smoothedNormals(mesh, adjacency, offsetNormals(mesh, piece, open), thickness);

  TriangleMesh result = mesh;
  const double half = 0.5 * thickness;
  std::vector<int> lowerOf(mesh.vertexCount(), -1);
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    if (normals[v].squaredNorm() > 0.0)
    {
      lowerOf[v] = static_cast<int>(result.positions.size());
      result.positions.push_back(mesh.positions[v] - half * normals[v]);
      result.positions[v] = mesh.positions[v] + half * normals[v];
      result.pointAttributes.appendCopyOf(v);
    }
  }
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    if (!open[piece[t]])
    {
      continue;
    }
    const Triangle& c = mesh.triangles[t];
    const Triangle lower = { lowerOf[c[0]], lowerOf[c[1]], lowerOf[c[2]] };
    checkNotFolded(mesh, result, t, lower);
    result.triangles.push_back({ lower[0], lower[2], lower[1] });
    if (mesh.hasTextureCoordinates())
    {
      const Triangle& corners = mesh.textureCorners[t];
      result.textureCorners.push_back({ corners[0], corners[2], corners[1] });
    }
  }
  addRim(mesh, adjacency, borderEdges, lowerOf, result);
  if (mesh.hasNormals())
  {
    result.normals.clear();
    result.computeVertexNormals();
  }

  SheetThickeningReport counts;
  counts.thickness = thickness;
  for (const char isOpen : open)
  {
    (isOpen ? counts.thickenedPieces : counts.closedPieces) += 1;
  }
  counts.addedVertices = result.vertexCount() - mesh.vertexCount();
  counts.addedTriangles = result.triangleCount() - mesh.triangleCount();
  counts.borderLoops = borderLoops(mesh, adjacency, borderEdges);
  if (report)
  {
    *report = counts;
  }
  return result;
}

} // namespace thintissue
