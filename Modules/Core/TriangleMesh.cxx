#include "TriangleMesh.h"

#include "ThinTissueError.h"

#include <cmath>

namespace thintissue
{

BoundingBox boundingBoxOf(const std::vector<Vector3>& points)
{
  BoundingBox box;
  for (const Vector3& p : points)
  {
    box.extend(p);
  }
  return box;
}

BoundingBox TriangleMesh::boundingBox() const
{
  return boundingBoxOf(positions);
}

double TriangleMesh::triangleArea(std::size_t t) const
{
  const Triangle& tri = triangles[t];
  return 0.5 * (positions[tri[1]] - positions[tri[0]])
                 .cross(positions[tri[2]] - positions[tri[0]])
                 .norm();
}

Vector3 TriangleMesh::triangleNormal(std::size_t t) const
{
  const Triangle& tri = triangles[t];
  const Vector3 n =
    (positions[tri[1]] - positions[tri[0]]).cross(positions[tri[2]] - positions[tri[0]]);
  const double length = n.norm();
  return length > 0.0 ? Vector3(n / length) : Vector3::Zero();
}

double TriangleMesh::surfaceArea() const
{
  double area = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    area += triangleArea(t);
  }
  return area;
}

double TriangleMesh::signedVolume() const
{
  // Relative to the centroid of the box to limit cancellation far from 0.
  const Vector3 origin = boundingBox().center();
  double volume = 0.0;
  for (const Triangle& tri : triangles)
  {
    const Vector3 a = positions[tri[0]] - origin;
    const Vector3 b = positions[tri[1]] - origin;
    const Vector3 c = positions[tri[2]] - origin;
    volume += a.dot(b.cross(c));
  }
  return volume / 6.0;
}

void TriangleMesh::reverseOrientation()
{
  for (Triangle& tri : triangles)
  {
    std::swap(tri[1], tri[2]);
  }
  for (Triangle& corner : textureCorners)
  {
    std::swap(corner[1], corner[2]);
  }
  for (Vector3& n : normals)
  {
    n = -n;
  }
}

void TriangleMesh::computeVertexNormals()
{
  normals.assign(positions.size(), Vector3::Zero());
  for (const Triangle& tri : triangles)
  {
    // Cross product length is twice the area: area weighting for free.
    const Vector3 n =
      (positions[tri[1]] - positions[tri[0]]).cross(positions[tri[2]] - positions[tri[0]]);
    for (int v : tri)
    {
      normals[v] += n;
    }
  }
  for (Vector3& n : normals)
  {
    const double length = n.norm();
    n = length > 0.0 ? Vector3(n / length) : Vector3::UnitZ();
  }
}

void TriangleMesh::checkConsistency() const
{
  const std::string context = "mesh '" + name + "'";
  const long long n = static_cast<long long>(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    if (!positions[i].allFinite())
    {
      throw InvalidInputError(
        context + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    for (int v : triangles[t])
    {
      if (v < 0 || v >= n)
      {
        throw InvalidInputError(context + ": triangle " + std::to_string(t) + " has vertex index " +
                                std::to_string(v) + " out of range (" + std::to_string(n) +
                                " vertices)");
      }
    }
  }
  if (!normals.empty() && normals.size() != positions.size())
  {
    throw InvalidInputError(context + ": " + std::to_string(normals.size()) + " normals for " +
                            std::to_string(positions.size()) + " vertices");
  }
  if (!textureCorners.empty() && textureCorners.size() != triangles.size())
  {
    throw InvalidInputError(context + ": texture corners for " +
                            std::to_string(textureCorners.size()) + " triangles, mesh has " +
                            std::to_string(triangles.size()));
  }
  const long long nt = static_cast<long long>(textureCoordinates.size());
  for (std::size_t t = 0; t < textureCorners.size(); ++t)
  {
    for (int c : textureCorners[t])
    {
      if (c < 0 || c >= nt)
      {
        throw InvalidInputError(context + ": triangle " + std::to_string(t) +
                                " has texture coordinate index " + std::to_string(c) +
                                " out of range (" + std::to_string(nt) + " texture coordinates)");
      }
    }
  }
  pointAttributes.checkElementCount(positions.size(), context);
}

void TriangleMesh::append(const TriangleMesh& other)
{
  const int vertexOffset = static_cast<int>(positions.size());
  const int textureOffset = static_cast<int>(textureCoordinates.size());
  const bool keepTexture =
    (hasTextureCoordinates() || triangles.empty()) && other.hasTextureCoordinates();
  const bool keepNormals = (hasNormals() || positions.empty()) && other.hasNormals();
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  for (const Triangle& tri : other.triangles)
  {
    triangles.push_back({ tri[0] + vertexOffset, tri[1] + vertexOffset, tri[2] + vertexOffset });
  }
  if (keepNormals)
  {
    normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  }
  else
  {
    normals.clear();
  }
  if (keepTexture)
  {
    textureCoordinates.insert(
      textureCoordinates.end(), other.textureCoordinates.begin(), other.textureCoordinates.end());
    for (const Triangle& corner : other.textureCorners)
    {
      textureCorners.push_back(
        { corner[0] + textureOffset, corner[1] + textureOffset, corner[2] + textureOffset });
    }
  }
  else
  {
    textureCoordinates.clear();
    textureCorners.clear();
  }
  // Attributes present in both are concatenated; the others are dropped.
  for (const std::string& attributeName : pointAttributes.names())
  {
    if (!other.pointAttributes.has(attributeName) ||
        other.pointAttributes.get(attributeName).components !=
          pointAttributes.get(attributeName).components)
    {
      pointAttributes.remove(attributeName);
      continue;
    }
    AttributeArray& mine = pointAttributes.get(attributeName);
    const AttributeArray& theirs = other.pointAttributes.get(attributeName);
    mine.values.insert(mine.values.end(), theirs.values.begin(), theirs.values.end());
  }
}

} // namespace thintissue
