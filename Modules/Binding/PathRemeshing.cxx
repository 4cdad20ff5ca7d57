#include "PathRemeshing.h"

#include "ThinTissueError.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace thintissue
{

namespace
{

std::string meshLabel(const TriangleMesh& mesh)
{
  return mesh.name.empty() ? std::string("mesh") : "mesh '" + mesh.name + "'";
}

std::uint64_t edgeKey(int a, int b)
{
  if (a > b)
  {
    std::swap(a, b);
  }
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(b));
}

std::string describePoint(const SurfacePoint& point)
{
  std::ostringstream text;
  if (point.isVertex())
  {
    text << "vertex " << point.vertex;
  }
  else
  {
    text << "edge (" << point.edgeStart << ", " << point.edgeEnd << ") at parameter "
         << point.edgeParameter;
  }
  return text.str();
}

/// A mesh edge that path points lie inside. Its lists are ranges of
/// arrays shared by all edges (EdgeLists): one allocation each, not four
/// per edge.
struct PathEdge
{
  int start = 0; ///< smaller vertex index
  int end = 0;
  int firstPath = 0; ///< the first path point on it, for messages
  int firstPoint = 0;
  /// The vertices along the edge from start to end (start, the inserted
  /// vertices by increasing parameter, end), and the triangles beside it
  /// by increasing index: [begin, end) in EdgeLists::chains, ::triangles.
  int chainBegin = 0;
  int chainEnd = 0;
  int trianglesBegin = 0;
  int trianglesEnd = 0;
  int chainSize() const { return chainEnd - chainBegin; }
  int triangleCount() const { return trianglesEnd - trianglesBegin; }
};

/// The path points inside edges (per point: its edge, its parameter, the
/// vertex it became: an inserted vertex or an end of the edge), and the
/// edges' chains and triangles.
struct EdgeLists
{
  std::vector<int> pointEdge;
  std::vector<double> pointParameter;
  std::vector<int> pointVertex;
  std::vector<int> chains;
  std::vector<int> triangles;
};

/// A run of ints in one of those arrays (empty: no such edge).
struct IntRange
{
  const int* first = nullptr;
  const int* last = nullptr;
  const int* begin() const { return first; }
  const int* end() const { return last; }
  std::size_t size() const { return static_cast<std::size_t>(last - first); }
  int front() const { return *first; }
  int operator[](std::ptrdiff_t i) const { return first[i]; }
};

/// A vertex inserted inside an edge.
struct InsertedVertex
{
  int edge = 0;           ///< PathEdge index
  double parameter = 0.0; ///< from the edge's start (smaller index) to its end
  /// The first of the texture coordinates made for it (-1: none yet); the
  /// others (sides of a texture seam) follow in a list through
  /// `nextTexture`.
  int firstTexture = -1;
};

/// Where a path point lies: an input vertex, or point `index` of PathEdge
/// `edge`.
struct PointLocation
{
  int vertex = -1;
  int edge = -1;
  int index = -1;
};

/// A path segment crossing the interior of an input triangle.
struct Chord
{
  int triangle = 0;
  int from = 0; ///< output vertices
  int to = 0;
  int path = 0;
};

/// A point on the border of an affected triangle: a corner or an inserted
/// vertex inside one of its edges. Side k joins corners k and k + 1.
struct BorderPoint
{
  int vertex = 0;
  int side = 0;
  int texture = -1;
};

/// A convex piece of an affected triangle: border positions in the
/// parent's counter-clockwise order and, per edge i (from point i to point
/// i + 1), the straight line it lies on (0 to 2: the parent's sides; then
/// the chords and the diagonals added while triangulating).
struct Face
{
  std::vector<int> points;
  std::vector<int> lines;
};

/// Shape quality of a triangle: twice its area over the sum of its squared
/// edge lengths (0 for a degenerate one).
double shapeQuality(const Vector3& a, const Vector3& b, const Vector3& c)
{
  const double lengths = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return lengths > 0.0 ? (b - a).cross(c - a).norm() / lengths : 0.0;
}

/// Triangulates a convex face whose sides may hold several collinear points
/// by clipping ears: an ear at point v (neighbours p and n) is allowed when
/// v is a true corner (its two edges lie on different lines) and p and n do
/// not lie on one line of what remains (which would leave a flat polygon).
/// Such an ear exists while more than three points remain, so the triangles
/// are never degenerate; among the allowed ears the best shaped one is cut
/// first (ties: the first in the face's order). The collinearity tests are
/// combinatorial (line labels), not floating-point, so they are exact.
void triangulateFace(Face& face,
  int& nextLine,
  const std::vector<BorderPoint>& border,
  const std::vector<Vector3>& positions,
  std::vector<std::array<int, 3>>& pieces)
{
  auto position = [&](int point) -> const Vector3& { return positions[border[point].vertex]; };
  while (face.points.size() > 3)
  {
    const int m = static_cast<int>(face.points.size());
    int best = -1;
    double bestQuality = -1.0;
    for (int i = 0; i < m; ++i)
    {
      const int previous = (i + m - 1) % m;
      const int next = (i + 1) % m;
      const int beforePrevious = (i + m - 2) % m;
      if (face.lines[previous] == face.lines[i] || face.lines[beforePrevious] == face.lines[next])
      {
        continue;
      }
      const double quality = shapeQuality(
        position(face.points[previous]), position(face.points[i]), position(face.points[next]));
      if (quality > bestQuality)
      {
        bestQuality = quality;
        best = i;
      }
    }
    if (best < 0)
    {
      throw Error("path re-meshing: no ear to clip in a convex face (internal error)");
    }
    const int previous = (best + m - 1) % m;
    const int next = (best + 1) % m;
    pieces.push_back({ face.points[previous], face.points[best], face.points[next] });
    // The edge (previous, best) is replaced by the diagonal (previous, next).
    face.lines[previous] = nextLine++;
    face.points.erase(face.points.begin() + best);
    face.lines.erase(face.lines.begin() + best);
  }
  pieces.push_back({ face.points[0], face.points[1], face.points[2] });
}

/// The work of insertPaths, step by step (see there): the state the steps
/// share, and one function per step.
class PathInsertion
{
public:
  PathInsertion(const TriangleMesh& input,
    const std::vector<SurfacePath>& inputPaths,
    double tolerance,
    std::string name)
    : mesh(input)
    , paths(inputPaths)
    , mergeTolerance(tolerance)
    , label(std::move(name))
    , vertexCount(static_cast<int>(input.positions.size()))
    , triangleCount(static_cast<int>(input.triangles.size()))
    , hasTexture(input.hasTextureCoordinates())
    , inputTextureCount(static_cast<int>(input.textureCoordinates.size()))
  {
  }

  RemeshedSurface run()
  {
    locatePoints();
    gatherStars();
    placeEdgePoints();
    copyMesh();
    tracePaths();
    findAffected();
    retriangulate();
    return std::move(result);
  }

private:
  void locatePoints();
  void gatherStars();
  void placeEdgePoints();
  void copyMesh();
  void tracePaths();
  void findAffected();
  void retriangulate();
  void collectBorder(int t);
  void collectCuts(int t, std::vector<Chord>::const_iterator& chord);
  int cutIntoFaces();
  void emitPieces(int t, int nextLine);
  int textureOf(int x, int t, int corner, int otherCorner);

  void touch(int v)
  {
    if (localIndex[v] < 0)
    {
      localIndex[v] = static_cast<int>(touched.size());
      touched.push_back(v);
    }
  }
  std::vector<int>::const_iterator starBegin(int v) const
  {
    return starTriangles.begin() + starOffsets[localIndex[v]];
  }
  std::vector<int>::const_iterator starEnd(int v) const
  {
    return starTriangles.begin() + starOffsets[localIndex[v] + 1];
  }
  bool hasCorner(int t, int v) const
  {
    const Triangle& tri = mesh.triangles[t];
    return tri[0] == v || tri[1] == v || tri[2] == v;
  }
  int vertexOf(const PointLocation& location) const
  {
    return location.vertex >= 0 ? location.vertex : lists.pointVertex[location.index];
  }
  /// Whether vertex x lies on the side of `tri` joining corners k and k + 1.
  bool onSide(int x, const Triangle& tri, int k) const
  {
    const int a = tri[k];
    const int b = tri[(k + 1) % 3];
    if (x == a || x == b)
    {
      return true;
    }
    if (x < vertexCount)
    {
      return false;
    }
    const PathEdge& edge = edges[inserted[x - vertexCount].edge];
    return (edge.start == a && edge.end == b) || (edge.start == b && edge.end == a);
  }
  IntRange chainOf(int a, int b) const
  {
    const auto found = edgeIndex.find(edgeKey(a, b));
    if (found == edgeIndex.end())
    {
      return IntRange{};
    }
    const PathEdge& edge = edges[found->second];
    return IntRange{ lists.chains.data() + edge.chainBegin, lists.chains.data() + edge.chainEnd };
  }
  Face& newFace()
  {
    if (faceCount == faces.size())
    {
      faces.emplace_back();
    }
    Face& face = faces[faceCount++];
    face.points.clear();
    face.lines.clear();
    return face;
  }
  int positionOf(int vertex) const
  {
    for (std::size_t i = 0; i < border.size(); ++i)
    {
      if (border[i].vertex == vertex)
      {
        return static_cast<int>(i);
      }
    }
    throw Error(label + ": chord end not on its triangle (internal error)");
  }

  const TriangleMesh& mesh;
  const std::vector<SurfacePath>& paths;
  const double mergeTolerance;
  const std::string label;
  const int vertexCount;
  const int triangleCount;
  const bool hasTexture;
  const int inputTextureCount;
  /// Steps 1 and 2: where each path point lies, the edges holding points,
  /// the vertices touched (local index per vertex) and their triangles.
  std::vector<std::vector<PointLocation>> locations;
  std::vector<PathEdge> edges;
  EdgeLists lists;
  std::unordered_map<std::uint64_t, int> edgeIndex;
  std::vector<int> localIndex;
  std::vector<int> touched;
  std::vector<int> starOffsets;
  std::vector<int> starTriangles;
  /// Steps 3 to 7: the inserted vertices, the output, the chords, the
  /// affected triangles.
  std::vector<InsertedVertex> inserted;
  RemeshedSurface result;
  TriangleMesh& out = result.mesh;
  std::vector<Chord> chords;
  std::vector<int> affected;
  std::size_t addedTriangles = 0;
  std::vector<int> nextTexture; ///< per texture coordinate made here
  /// Scratch buffers of step 7, reused from triangle to triangle.
  std::vector<BorderPoint> border;
  std::vector<std::array<int, 3>> cuts; ///< border positions (first < second), path
  std::vector<Face> faces;              ///< the first `faceCount` are in use
  std::size_t faceCount = 0;
  Face split;
  std::vector<std::array<int, 3>> pieces;
};

/// A triangle repeating a vertex is listed once in that vertex's star.
bool firstOccurrence(const Triangle& tri, int c)
{
  return (c == 0 || tri[c] != tri[0]) && (c < 2 || tri[2] != tri[1]);
}

void PathInsertion::locatePoints()
{
  // 1. Path points: check them, gather the points inside each edge, and
  // note the vertices whose triangles are needed.
  locations.resize(paths.size());
  localIndex.assign(vertexCount, -1);
  std::size_t pointCount = 0;
  for (const SurfacePath& path : paths)
  {
    pointCount += path.points.size();
  }
  edgeIndex.reserve(pointCount);
  lists.pointEdge.reserve(pointCount);
  lists.pointParameter.reserve(pointCount);
  for (std::size_t p = 0; p < paths.size(); ++p)
  {
    const auto& points = paths[p].points;
    locations[p].resize(points.size());
    for (std::size_t k = 0; k < points.size(); ++k)
    {
      const SurfacePoint& point = points[k];
      auto where = [&]
      {
        return label + ": path " + std::to_string(p) + ", point " + std::to_string(k) + " (" +
               describePoint(point) + ")";
      };
      PointLocation& location = locations[p][k];
      if (point.isVertex())
      {
        if (point.vertex >= vertexCount)
        {
          throw InvalidInputError(
            where() + ": vertex index out of range (" + std::to_string(vertexCount) + " vertices)");
        }
        location.vertex = point.vertex;
        touch(point.vertex);
        continue;
      }
      if (point.edgeStart < 0 || point.edgeEnd >= vertexCount || point.edgeStart >= point.edgeEnd)
      {
        throw InvalidInputError(where() +
                                ": neither a vertex nor an edge (start < end) of the mesh's " +
                                std::to_string(vertexCount) + " vertices");
      }
      if (!(point.edgeParameter >= 0.0 && point.edgeParameter <= 1.0))
      {
        throw InvalidInputError(where() + ": edge parameter outside [0, 1]");
      }
      const std::uint64_t key = edgeKey(point.edgeStart, point.edgeEnd);
      auto found = edgeIndex.find(key);
      if (found == edgeIndex.end())
      {
        found = edgeIndex.emplace(key, static_cast<int>(edges.size())).first;
        PathEdge edge;
        edge.start = point.edgeStart;
        edge.end = point.edgeEnd;
        edge.firstPath = static_cast<int>(p);
        edge.firstPoint = static_cast<int>(k);
        edges.push_back(std::move(edge));
      }
      location.edge = found->second;
      location.index = static_cast<int>(lists.pointParameter.size());
      lists.pointEdge.push_back(found->second);
      lists.pointParameter.push_back(point.edgeParameter);
      touch(point.edgeStart);
      touch(point.edgeEnd);
    }
  }
}

void PathInsertion::gatherStars()
{
  // 2. The triangles around the touched vertices (one pass over the
  // triangles; each list by increasing triangle index).
  // A triangle repeating a vertex is listed once in that vertex's list.
  starOffsets.assign(touched.size() + 1, 0);
  for (const Triangle& tri : mesh.triangles)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (localIndex[tri[c]] >= 0 && firstOccurrence(tri, c))
      {
        ++starOffsets[localIndex[tri[c]] + 1];
      }
    }
  }
  std::partial_sum(starOffsets.begin(), starOffsets.end(), starOffsets.begin());
  starTriangles.assign(starOffsets.back(), 0);
  {
    std::vector<int> cursor(starOffsets.begin(), starOffsets.end() - 1);
    for (int t = 0; t < triangleCount; ++t)
    {
      const Triangle& tri = mesh.triangles[t];
      for (int c = 0; c < 3; ++c)
      {
        const int local = localIndex[tri[c]];
        if (local >= 0 && firstOccurrence(tri, c))
        {
          starTriangles[cursor[local]++] = t;
        }
      }
    }
  }
}

void PathInsertion::placeEdgePoints()
{
  // 3. The triangles beside each edge, and the vertices its points become:
  // points within the tolerance of an end are that end; the others, sorted
  // along the edge, form clusters no wider than the tolerance, each one
  // inserted vertex at its first (smallest) parameter.
  // Each edge's points (global point indices, in the order met), grouped
  // by edge.
  std::vector<int> edgePointOffsets(edges.size() + 1, 0);
  for (int e : lists.pointEdge)
  {
    ++edgePointOffsets[e + 1];
  }
  std::partial_sum(edgePointOffsets.begin(), edgePointOffsets.end(), edgePointOffsets.begin());
  std::vector<int> edgePoints(lists.pointEdge.size());
  {
    std::vector<int> cursor(edgePointOffsets.begin(), edgePointOffsets.end() - 1);
    for (std::size_t i = 0; i < lists.pointEdge.size(); ++i)
    {
      edgePoints[cursor[lists.pointEdge[i]]++] = static_cast<int>(i);
    }
  }
  lists.pointVertex.assign(lists.pointEdge.size(), -1);
  lists.chains.reserve(2 * edges.size() + lists.pointEdge.size());
  lists.triangles.reserve(2 * edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
  {
    PathEdge& edge = edges[e];
    edge.trianglesBegin = static_cast<int>(lists.triangles.size());
    for (auto t = starBegin(edge.start); t != starEnd(edge.start); ++t)
    {
      if (hasCorner(*t, edge.end))
      {
        lists.triangles.push_back(*t);
      }
    }
    edge.trianglesEnd = static_cast<int>(lists.triangles.size());
    if (edge.triangleCount() == 0)
    {
      throw InvalidInputError(label + ": path " + std::to_string(edge.firstPath) + ", point " +
                              std::to_string(edge.firstPoint) + " lies on (" +
                              std::to_string(edge.start) + ", " + std::to_string(edge.end) +
                              "), which is not an edge of the mesh");
    }
    // The edge's points by increasing parameter (ties: in the order met,
    // which is increasing point index).
    const auto order = edgePoints.begin() + edgePointOffsets[e];
    const auto orderEnd = edgePoints.begin() + edgePointOffsets[e + 1];
    std::sort(order,
      orderEnd,
      [&](int a, int b)
      {
        return lists.pointParameter[a] < lists.pointParameter[b] ||
               (lists.pointParameter[a] == lists.pointParameter[b] && a < b);
      });
    edge.chainBegin = static_cast<int>(lists.chains.size());
    lists.chains.push_back(edge.start);
    double clusterParameter = -1.0;
    for (auto i = order; i != orderEnd; ++i)
    {
      const double t = lists.pointParameter[*i];
      int& pointVertex = lists.pointVertex[*i];
      if (t <= mergeTolerance)
      {
        pointVertex = edge.start;
      }
      else if (t >= 1.0 - mergeTolerance)
      {
        pointVertex = edge.end;
      }
      else
      {
        if (clusterParameter < 0.0 || t - clusterParameter > mergeTolerance)
        {
          clusterParameter = t;
          InsertedVertex vertex;
          vertex.edge = static_cast<int>(e);
          vertex.parameter = t;
          lists.chains.push_back(vertexCount + static_cast<int>(inserted.size()));
          inserted.push_back(std::move(vertex));
        }
        pointVertex = lists.chains.back();
      }
    }
    lists.chains.push_back(edge.end);
    edge.chainEnd = static_cast<int>(lists.chains.size());
  }
}

void PathInsertion::copyMesh()
{
  // 4. The output mesh: a copy of the input plus the inserted vertices.
  out = mesh;
  const std::size_t outputVertexCount = vertexCount + inserted.size();
  out.positions.reserve(outputVertexCount);
  for (const InsertedVertex& vertex : inserted)
  {
    const PathEdge& edge = edges[vertex.edge];
    const double s = vertex.parameter;
    out.positions.emplace_back(
      (1.0 - s) * mesh.positions[edge.start] + s * mesh.positions[edge.end]);
  }
  if (mesh.hasNormals())
  {
    out.normals.reserve(outputVertexCount);
    for (const InsertedVertex& vertex : inserted)
    {
      const PathEdge& edge = edges[vertex.edge];
      const double s = vertex.parameter;
      Vector3 normal = (1.0 - s) * mesh.normals[edge.start] + s * mesh.normals[edge.end];
      const double length = normal.norm();
      if (length > 1e-12)
      {
        normal /= length;
      }
      else
      {
        // Opposite end normals: the first triangle's normal instead.
        normal = mesh.triangleNormal(lists.triangles[edge.trianglesBegin]);
        if (normal.squaredNorm() == 0.0)
        {
          normal = mesh.normals[edge.start];
        }
      }
      out.normals.push_back(normal);
    }
  }
  for (const std::string& name : out.pointAttributes.names())
  {
    AttributeArray& array = out.pointAttributes.get(name);
    const std::size_t components = static_cast<std::size_t>(array.components);
    array.values.reserve(outputVertexCount * components);
    for (const InsertedVertex& vertex : inserted)
    {
      const PathEdge& edge = edges[vertex.edge];
      const double s = vertex.parameter;
      for (std::size_t c = 0; c < components; ++c)
      {
        const double a = array.values[edge.start * components + c];
        const double b = array.values[edge.end * components + c];
        array.values.push_back((1.0 - s) * a + s * b);
      }
    }
  }
  result.inputVertex.resize(outputVertexCount, -1);
  std::iota(result.inputVertex.begin(), result.inputVertex.begin() + vertexCount, 0);
  result.insertedOn.reserve(inserted.size());
  for (const InsertedVertex& vertex : inserted)
  {
    const PathEdge& edge = edges[vertex.edge];
    result.insertedOn.push_back(SurfacePoint::onEdge(edge.start, edge.end, vertex.parameter));
  }
}

void PathInsertion::tracePaths()
{
  // 5. The path segments: along an edge (then the path visits every vertex
  // inserted on it in between) or a chord across a triangle.
  result.pathVertices.resize(paths.size());
  for (std::size_t p = 0; p < paths.size(); ++p)
  {
    std::vector<int>& vertices = result.pathVertices[p];
    auto append = [&](int v)
    {
      if (vertices.empty() || vertices.back() != v)
      {
        vertices.push_back(v);
      }
    };
    const auto& pathLocations = locations[p];
    for (std::size_t k = 0; k < pathLocations.size(); ++k)
    {
      const int to = vertexOf(pathLocations[k]);
      if (k == 0)
      {
        append(to);
        continue;
      }
      const int from = vertexOf(pathLocations[k - 1]);
      // The first triangle holding both points as the path gives them.
      std::array<int, 4> required{};
      int requiredCount = 0;
      auto require = [&](int v)
      {
        if (std::find(required.begin(), required.begin() + requiredCount, v) ==
            required.begin() + requiredCount)
        {
          required[requiredCount++] = v;
        }
      };
      for (std::size_t j = k - 1; j <= k; ++j)
      {
        const PointLocation& location = pathLocations[j];
        if (location.vertex >= 0)
        {
          require(location.vertex);
        }
        else
        {
          require(edges[location.edge].start);
          require(edges[location.edge].end);
        }
      }
      int triangle = -1;
      if (requiredCount <= 3)
      {
        for (auto t = starBegin(required[0]); t != starEnd(required[0]) && triangle < 0; ++t)
        {
          bool all = true;
          for (int r = 1; r < requiredCount; ++r)
          {
            all = all && hasCorner(*t, required[r]);
          }
          if (all)
          {
            triangle = *t;
          }
        }
      }
      if (triangle < 0)
      {
        throw InvalidInputError(
          label + ": path " + std::to_string(p) + ", points " + std::to_string(k - 1) + " (" +
          describePoint(paths[p].points[k - 1]) + ") and " + std::to_string(k) + " (" +
          describePoint(paths[p].points[k]) + ") lie on no common triangle");
      }
      if (from == to)
      {
        continue;
      }
      const Triangle& tri = mesh.triangles[triangle];
      int side = -1;
      for (int k2 = 0; k2 < 3 && side < 0; ++k2)
      {
        if (onSide(from, tri, k2) && onSide(to, tri, k2))
        {
          side = k2;
        }
      }
      if (side < 0)
      {
        chords.push_back({ triangle, from, to, static_cast<int>(p) });
        append(to);
        continue;
      }
      const int a = tri[side];
      const int b = tri[(side + 1) % 3];
      const IntRange chain = chainOf(a, b);
      if (chain.first == nullptr)
      {
        append(to);
        continue;
      }
      const auto fromAt = std::find(chain.begin(), chain.end(), from) - chain.begin();
      const auto toAt = std::find(chain.begin(), chain.end(), to) - chain.begin();
      const auto step = toAt > fromAt ? 1 : -1;
      for (auto i = fromAt + step; i != toAt; i += step)
      {
        append(chain[i]);
      }
      append(to);
    }
  }
}

void PathInsertion::findAffected()
{
  // 6. The affected triangles (those beside an edge with inserted vertices;
  // every chord ends at such a vertex), by increasing index. A triangle with
  // n inserted vertices on its sides becomes n + 1 triangles.
  for (const PathEdge& edge : edges)
  {
    if (edge.chainSize() > 2)
    {
      affected.insert(affected.end(),
        lists.triangles.begin() + edge.trianglesBegin,
        lists.triangles.begin() + edge.trianglesEnd);
      addedTriangles += static_cast<std::size_t>((edge.chainSize() - 2) * edge.triangleCount());
    }
  }
  std::sort(affected.begin(), affected.end());
  affected.erase(std::unique(affected.begin(), affected.end()), affected.end());
  std::stable_sort(chords.begin(),
    chords.end(),
    [](const Chord& a, const Chord& b) { return a.triangle < b.triangle; });
}

// Vertex x inserted on the side joining corners `corner` and `otherCorner`
// of triangle t: interpolated from t's own corners, and shared with the
// other triangles where the value is the same.
int PathInsertion::textureOf(int x, int t, int corner, int otherCorner)
{
  InsertedVertex& vertex = inserted[x - vertexCount];
  const PathEdge& edge = edges[vertex.edge];
  const Triangle& texture = mesh.textureCorners[t];
  const int startCorner = mesh.triangles[t][corner] == edge.start ? corner : otherCorner;
  const int endCorner = startCorner == corner ? otherCorner : corner;
  const double s = vertex.parameter;
  const Vector2 value = (1.0 - s) * mesh.textureCoordinates[texture[startCorner]] +
                        s * mesh.textureCoordinates[texture[endCorner]];
  int last = -1;
  for (int i = vertex.firstTexture; i >= 0; i = nextTexture[i - inputTextureCount])
  {
    const Vector2& known = out.textureCoordinates[i];
    if (known.x() == value.x() && known.y() == value.y())
    {
      return i;
    }
    last = i;
  }
  const int index = static_cast<int>(out.textureCoordinates.size());
  out.textureCoordinates.push_back(value);
  nextTexture.push_back(-1);
  (last < 0 ? vertex.firstTexture : nextTexture[last - inputTextureCount]) = index;
  return index;
}

void PathInsertion::retriangulate()
{
  // 7. Re-triangulation of each affected triangle inside its own plane.
  out.triangles.reserve(triangleCount + addedTriangles);
  if (hasTexture)
  {
    out.textureCorners.reserve(triangleCount + addedTriangles);
  }
  result.inputTriangle.reserve(triangleCount + addedTriangles);
  result.inputTriangle.resize(triangleCount);
  std::iota(result.inputTriangle.begin(), result.inputTriangle.end(), 0);
  auto chord = chords.cbegin();
  for (int t : affected)
  {
    const Triangle& tri = mesh.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
    {
      throw InvalidInputError(
        label + ": triangle " + std::to_string(t) + ", which a path crosses, repeats a vertex");
    }
    collectBorder(t);
    collectCuts(t, chord);
    emitPieces(t, cutIntoFaces());
  }
  if (chord != chords.cend())
  {
    throw Error(label + ": a chord in an unaffected triangle (internal error)");
  }
}

void PathInsertion::collectBorder(int t)
{
  const Triangle& tri = mesh.triangles[t];
  border.clear();
  for (int k = 0; k < 3; ++k)
  {
    border.push_back({ tri[k], k, hasTexture ? mesh.textureCorners[t][k] : -1 });
    const IntRange chain = chainOf(tri[k], tri[(k + 1) % 3]);
    if (chain.size() <= 2)
    {
      continue;
    }
    const bool forward = chain.front() == tri[k];
    for (std::size_t i = 1; i + 1 < chain.size(); ++i)
    {
      const int x = chain[static_cast<std::ptrdiff_t>(forward ? i : chain.size() - 1 - i)];
      border.push_back({ x, k, hasTexture ? textureOf(x, t, k, (k + 1) % 3) : -1 });
    }
  }
}

void PathInsertion::collectCuts(int t, std::vector<Chord>::const_iterator& chord)
{
  // The chords in this triangle, once each; two cross when their ends
  // alternate around the border (exact: no floating-point test).
  cuts.clear();
  for (; chord != chords.end() && chord->triangle == t; ++chord)
  {
    const int a = positionOf(chord->from);
    const int b = positionOf(chord->to);
    cuts.push_back({ std::min(a, b), std::max(a, b), chord->path });
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(),
               cuts.end(),
               [](const std::array<int, 3>& x, const std::array<int, 3>& y)
               { return x[0] == y[0] && x[1] == y[1]; }),
    cuts.end());
  for (std::size_t i = 0; i < cuts.size(); ++i)
  {
    for (std::size_t j = i + 1; j < cuts.size(); ++j)
    {
      const auto& c = cuts[i];
      const auto& d = cuts[j];
      if ((c[0] < d[0] && d[0] < c[1] && c[1] < d[1]) ||
          (d[0] < c[0] && c[0] < d[1] && d[1] < c[1]))
      {
        const int first = std::min(c[2], d[2]);
        const int second = std::max(c[2], d[2]);
        throw PathsCrossError(label + ": paths " + std::to_string(first) + " and " +
                                std::to_string(second) + " cross inside triangle " +
                                std::to_string(t) + " (paths may touch, never cross)",
          first,
          second,
          t);
      }
    }
  }
}

/// Cuts the triangle along the chords into convex faces; returns the next
/// free line label.
int PathInsertion::cutIntoFaces()
{
  faceCount = 0;
  {
    Face& whole = newFace();
    for (std::size_t i = 0; i < border.size(); ++i)
    {
      whole.points.push_back(static_cast<int>(i));
      whole.lines.push_back(border[i].side);
    }
  }
  int nextLine = 3;
  for (const auto& cut : cuts)
  {
    const int line = nextLine++;
    for (std::size_t f = 0; f < faceCount; ++f)
    {
      Face& face = faces[f];
      const auto first = std::find(face.points.begin(), face.points.end(), cut[0]);
      const auto second = std::find(face.points.begin(), face.points.end(), cut[1]);
      if (first == face.points.end() || second == face.points.end())
      {
        continue;
      }
      // Points lo..hi stay (closed by the chord from hi to lo); the rest,
      // hi..lo around the end, form the new face (closed from lo to hi).
      const auto lo = std::min(first, second) - face.points.begin();
      const auto hi = std::max(first, second) - face.points.begin();
      split.points.assign(face.points.begin() + hi, face.points.end());
      split.points.insert(split.points.end(), face.points.begin(), face.points.begin() + lo + 1);
      split.lines.assign(face.lines.begin() + hi, face.lines.end());
      split.lines.insert(split.lines.end(), face.lines.begin(), face.lines.begin() + lo);
      split.lines.push_back(line);
      face.points.erase(face.points.begin() + hi + 1, face.points.end());
      face.points.erase(face.points.begin(), face.points.begin() + lo);
      face.lines.erase(face.lines.begin() + hi, face.lines.end());
      face.lines.erase(face.lines.begin(), face.lines.begin() + lo);
      face.lines.push_back(line);
      Face& added = newFace(); // may move the faces: `face` is not used again
      std::swap(added.points, split.points);
      std::swap(added.lines, split.lines);
      break;
    }
  }
  return nextLine;
}

void PathInsertion::emitPieces(int t, int nextLine)
{
  pieces.clear();
  for (std::size_t f = 0; f < faceCount; ++f)
  {
    triangulateFace(faces[f], nextLine, border, out.positions, pieces);
  }
  for (std::size_t i = 0; i < pieces.size(); ++i)
  {
    const auto& piece = pieces[i];
    const Triangle vertices{
      border[piece[0]].vertex, border[piece[1]].vertex, border[piece[2]].vertex
    };
    const Triangle textures{
      border[piece[0]].texture, border[piece[1]].texture, border[piece[2]].texture
    };
    if (i == 0)
    {
      out.triangles[t] = vertices;
      if (hasTexture)
      {
        out.textureCorners[t] = textures;
      }
    }
    else
    {
      out.triangles.push_back(vertices);
      if (hasTexture)
      {
        out.textureCorners.push_back(textures);
      }
      result.inputTriangle.push_back(t);
    }
  }
}

} // namespace

RemeshedSurface insertPaths(const TriangleMesh& mesh,
  const std::vector<SurfacePath>& paths,
  double mergeTolerance)
{
  std::string label = "path re-meshing on " + meshLabel(mesh);
  if (!(mergeTolerance >= 0.0 && mergeTolerance < 0.5))
  {
    std::ostringstream message;
    message << label << ": merge tolerance must be at least 0 and below 0.5, got "
            << mergeTolerance;
    throw InvalidInputError(message.str());
  }
  mesh.checkConsistency();
  return PathInsertion(mesh, paths, mergeTolerance, std::move(label)).run();
}

} // namespace thintissue
