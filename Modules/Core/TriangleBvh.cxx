#include "TriangleBvh.h"

#include "ThinTissueError.h"
#include "TriangleMeshAdjacency.h"

#include <algorithm>
#include <array>
#include <string>

namespace thintissue
{

namespace
{

double maximumRadius(const Triangle& triangle, const std::vector<double>& radii)
{
  if (radii.empty())
  {
    return 0.0;
  }
  return std::max({ radii[triangle[0]], radii[triangle[1]], radii[triangle[2]] });
}

} // namespace

//------------------------------------------------------------------------------
BoundingBox TriangleBvh::triangleBox(const std::vector<Vector3>& positions,
  const Triangle& triangle,
  const std::vector<double>& radii,
  double contactDistance)
{
  const Vector3& a = positions[triangle[0]];
  const Vector3& b = positions[triangle[1]];
  const Vector3& c = positions[triangle[2]];
  const double inflation = maximumRadius(triangle, radii) + contactDistance;
  const Vector3 margin = Vector3::Constant(inflation);
  return BoundingBox(a.cwiseMin(b).cwiseMin(c) - margin, a.cwiseMax(b).cwiseMax(c) + margin);
}

namespace
{
/// Bit k of entry t set where triangle t is the lowest of its edge k (the
/// first side of the lowest triangle: the adjacency lists an edge's
/// triangles by increasing index).
std::vector<std::uint8_t> lowestTriangleEdges(const std::vector<Triangle>& triangles,
  int vertexCount)
{
  const TriangleMeshAdjacency adjacency(static_cast<std::size_t>(vertexCount), triangles);
  std::vector<std::uint8_t> owned(triangles.size(), 0);
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
  {
    const std::array<int, 3>& edges = adjacency.triangleEdges(t);
    for (int k = 0; k < 3; ++k)
    {
      const bool firstSide =
        std::find(edges.begin(), edges.begin() + k, edges[k]) == edges.begin() + k;
      if (firstSide && *adjacency.edgeTrianglesBegin(edges[k]) == t)
        owned[t] |= static_cast<std::uint8_t>(1u << k);
    }
  }
  return owned;
}
} // namespace

//------------------------------------------------------------------------------
void TriangleBvh::build(const std::vector<Vector3>& positions,
  const std::vector<Triangle>& triangles,
  const std::vector<double>& radii,
  double contactDistance)
{
  if (!radii.empty() && radii.size() != positions.size())
  {
    throw InvalidInputError("TriangleBvh: " + std::to_string(radii.size()) + " radii for " +
                            std::to_string(positions.size()) + " vertices");
  }
  if (!(contactDistance >= 0.0))
  {
    throw InvalidInputError("TriangleBvh: contact distance must be >= 0");
  }
  const int vertexCount = static_cast<int>(positions.size());
  for (const Triangle& t : triangles)
  {
    for (int v : t)
    {
      if (v < 0 || v >= vertexCount)
      {
        throw InvalidInputError("TriangleBvh: triangle vertex index " + std::to_string(v) +
                                " out of range [0, " + std::to_string(vertexCount) + ")");
      }
    }
  }

  this->Triangles = triangles;
  this->ContactDistance = contactDistance;
  this->OwnedEdges = lowestTriangleEdges(triangles, vertexCount);
  this->Nodes.clear();
  const int count = static_cast<int>(triangles.size());
  this->Order.resize(count);
  this->TriangleBoxes.resize(count);
  if (count == 0)
  {
    return;
  }
  std::vector<Vector3> centroids(count);
  for (int t = 0; t < count; ++t)
  {
    this->Order[t] = t;
    const Triangle& tri = triangles[t];
    centroids[t] = (positions[tri[0]] + positions[tri[1]] + positions[tri[2]]) / 3.0;
  }
  // A median-split tree with leaves of >= MaximumLeafSize / 2 triangles has
  // fewer than 2 * count / (MaximumLeafSize / 2) nodes.
  this->Nodes.reserve(2 * count);
  this->buildRange(0, count, centroids);
  this->Nodes.shrink_to_fit();
  this->refit(positions, radii);
}

//------------------------------------------------------------------------------
int TriangleBvh::buildRange(int begin, int end, std::vector<Vector3>& centroids)
{
  const int index = static_cast<int>(this->Nodes.size());
  this->Nodes.emplace_back();
  if (end - begin <= MaximumLeafSize)
  {
    Node& leaf = this->Nodes[index];
    leaf.firstTriangle = begin;
    leaf.triangleCount = end - begin;
    return index;
  }
  BoundingBox centroidBounds;
  for (int i = begin; i < end; ++i)
  {
    centroidBounds.extend(centroids[this->Order[i]]);
  }
  Eigen::Index axis = 0;
  centroidBounds.sizes().maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(this->Order.begin() + begin,
    this->Order.begin() + middle,
    this->Order.begin() + end,
    [&](int s, int t) { return centroids[s][axis] < centroids[t][axis]; });
  this->buildRange(begin, middle, centroids);
  const int right = this->buildRange(middle, end, centroids);
  this->Nodes[index].rightChild = right;
  return index;
}

//------------------------------------------------------------------------------
void TriangleBvh::refit(const std::vector<Vector3>& positions, const std::vector<double>& radii)
{
  if (!radii.empty() && radii.size() != positions.size())
  {
    throw InvalidInputError("TriangleBvh::refit: " + std::to_string(radii.size()) + " radii for " +
                            std::to_string(positions.size()) + " vertices");
  }
  // Children come after their parent in the depth-first array: one reverse
  // sweep visits every child before its parent.
  for (int index = static_cast<int>(this->Nodes.size()) - 1; index >= 0; --index)
  {
    Node& node = this->Nodes[index];
    if (node.isLeaf())
    {
      BoundingBox box;
      for (int i = node.firstTriangle; i < node.firstTriangle + node.triangleCount; ++i)
      {
        this->TriangleBoxes[i] =
          triangleBox(positions, this->Triangles[this->Order[i]], radii, this->ContactDistance);
        box.extend(this->TriangleBoxes[i]);
      }
      node.box = box;
    }
    else
    {
      node.box = this->Nodes[index + 1].box.merged(this->Nodes[node.rightChild].box);
    }
  }
}

//------------------------------------------------------------------------------
bool TriangleBvh::descendFirst(int nodeA, const TriangleBvh& other, int nodeB) const
{
  const Node& a = this->Nodes[nodeA];
  const Node& b = other.Nodes[nodeB];
  if (a.isLeaf())
  {
    return false;
  }
  if (b.isLeaf())
  {
    return true;
  }
  // Split the larger box: keeps the two boxes of a pair of similar size.
  return a.box.sizes().squaredNorm() >= b.box.sizes().squaredNorm();
}

} // namespace thintissue
