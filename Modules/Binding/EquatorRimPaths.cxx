#include "EquatorRimPaths.h"

#include "MeshPieces.h"
#include "ProximityQueries.h"
#include "ThinTissueError.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <string>

namespace thintissue
{

namespace
{

constexpr double Infinity = std::numeric_limits<double>::infinity();

/// Rounds of merging stray pieces and removing pinches before giving up
/// (each round settles what the last one changed; a handful suffice).
constexpr int LabelRounds = 32;

/// Start candidates of the cyclic assignment: the loop vertices nearest to
/// the first rim point.
constexpr std::size_t AssignmentStarts = 8;

std::string visualName(const EquatorInput& in)
{
  return "visual mesh '" + in.visual->name + "'";
}

/// Per collision vertex: whether it borders a hole (a border loop other
/// than the longest, the outline's).
std::vector<char> holeBorderVertices(const EquatorInput& in,
  const std::vector<std::vector<int>>& borders)
{
  std::vector<double> length(borders.size(), 0.0);
  for (std::size_t l = 0; l < borders.size(); ++l)
    for (std::size_t i = 0; i < borders[l].size(); ++i)
      length[l] += (in.collision->positions[borders[l][i]] -
                    in.collision->positions[borders[l][(i + 1) % borders[l].size()]])
                     .norm();
  const auto outline = std::max_element(length.begin(), length.end()) - length.begin();
  std::vector<char> hole(in.collision->vertexCount(), 0);
  for (std::size_t l = 0; l < borders.size(); ++l)
    for (int c : borders[l])
      hole[c] = static_cast<std::ptrdiff_t>(l) != outline ? 1 : 0;
  return hole;
}

/// Whether a point `away` from its closest point `q` on collision triangle
/// `tri` lies beyond a hole's border: q on a border edge of a hole (or at
/// a hole's border vertex) and the point off the normal there.
bool beyondHoleBorder(const Triangle& tri,
  const TriangleClosestPoint& q,
  const Vector3& away,
  const Vector3& normal,
  const std::vector<char>& holeBorder,
  const TriangleMeshAdjacency& collisionAdjacency)
{
  const double along = std::abs(away.dot(normal.normalized()));
  if (away.norm() - along <= 1e-3 * away.norm())
    return false;
  constexpr double OnEdge = 1e-9;
  for (int k = 0; k < 3; ++k)
  {
    const int a = tri[(k + 1) % 3];
    const int b = tri[(k + 2) % 3];
    if (q.barycentric[k] > OnEdge || !holeBorder[a] || !holeBorder[b])
      continue;
    if (collisionAdjacency.isBorderEdge(collisionAdjacency.findEdge(a, b)))
      return true;
  }
  return false;
}

/// Where a visual vertex lies against the collision mid-surface.
struct SideOfMidSurface
{
  std::vector<double> offset;   ///< along the interpolated collision normal
  std::vector<char> beyondHole; ///< its closest point on a hole's border, outward
};

/// Per visual vertex: its offset from the collision mid-surface, along the
/// collision normal interpolated at its closest point there (on the
/// triangles around the nearest collision vertex: the collision mesh is
/// coarse and its triangles well shaped), and whether it lies beyond the
/// border of a hole (its closest point on a border edge there, and off the
/// normal through it).
SideOfMidSurface sideOfMidSurface(const EquatorInput& in,
  const TriangleMeshAdjacency& collisionAdjacency,
  const std::vector<char>& holeBorder)
{
  const TriangleMesh& visual = *in.visual;
  const TriangleMesh& collision = *in.collision;
  const std::vector<Vector3>& normals = *in.collisionNormals;
  SideOfMidSurface side;
  side.offset.assign(visual.vertexCount(), 0.0);
  side.beyondHole.assign(visual.vertexCount(), 0);
  for (std::size_t v = 0; v < visual.vertexCount(); ++v)
  {
    const Vector3& p = visual.positions[v];
    int nearest = 0;
    double best = Infinity;
    for (std::size_t c = 0; c < collision.vertexCount(); ++c)
    {
      const double d = (collision.positions[c] - p).squaredNorm();
      if (d < best)
      {
        best = d;
        nearest = static_cast<int>(c);
      }
    }
    side.offset[v] = (p - collision.positions[nearest]).dot(normals[nearest]);
    double closest = Infinity;
    for (const int* t = collisionAdjacency.vertexTrianglesBegin(nearest);
         t != collisionAdjacency.vertexTrianglesEnd(nearest);
         ++t)
    {
      const Triangle& tri = collision.triangles[*t];
      const TriangleClosestPoint q = closestPointOnTriangleWithBarycentric(
        p, collision.positions[tri[0]], collision.positions[tri[1]], collision.positions[tri[2]]);
      const double d = (q.point - p).squaredNorm();
      if (d >= closest)
        continue;
      closest = d;
      const Vector3 n = q.barycentric[0] * normals[tri[0]] + q.barycentric[1] * normals[tri[1]] +
                        q.barycentric[2] * normals[tri[2]];
      const Vector3 away = p - q.point;
      side.offset[v] = away.dot(n);
      side.beyondHole[v] =
        beyondHoleBorder(tri, q, away, n, holeBorder, collisionAdjacency) ? 1 : 0;
    }
  }
  return side;
}

/// Per triangle +1 or -1: the side its vertices lie on, summed; the
/// triangles beyond a hole's border (two vertices there at least) are
/// negative and stay so (`fixed`): the positive half runs around the hole
/// whether the segmentation left a tunnel there or closed it.
struct TriangleLabels
{
  std::vector<std::int8_t> label;
  std::vector<char> fixed;
};

TriangleLabels sideLabels(const TriangleMesh& visual, const SideOfMidSurface& side)
{
  TriangleLabels labels;
  labels.label.resize(visual.triangleCount());
  labels.fixed.resize(visual.triangleCount());
  for (std::size_t t = 0; t < visual.triangleCount(); ++t)
  {
    const Triangle& tri = visual.triangles[t];
    const int beyond = side.beyondHole[tri[0]] + side.beyondHole[tri[1]] + side.beyondHole[tri[2]];
    labels.fixed[t] = beyond >= 2 ? 1 : 0;
    const double offset = side.offset[tri[0]] + side.offset[tri[1]] + side.offset[tri[2]];
    labels.label[t] = offset >= 0.0 && !labels.fixed[t] ? 1 : -1;
  }
  return labels;
}

int labelIndex(std::int8_t label)
{
  return label > 0 ? 0 : 1;
}

/// Per triangle its piece: triangles of one label joined across edges.
int labelPieces(const TriangleMeshAdjacency& adjacency,
  const std::vector<std::int8_t>& label,
  std::vector<int>& piece)
{
  return floodTrianglePieces(
    adjacency,
    label.size(),
    [&](int t, int k) { return label[adjacency.neighbourAcross(t, k)] == label[t]; },
    piece);
}

/// Every piece of a label but its main one (the most votes for that label,
/// then the most triangles) and those holding fixed triangles takes the
/// other label. Returns the triangles relabelled.
int mergeStrayPieces(const EquatorInput& in, TriangleLabels& labels)
{
  std::vector<std::int8_t>& label = labels.label;
  const TriangleMeshAdjacency& adjacency = *in.adjacency;
  std::vector<int> piece;
  const int pieces = labelPieces(adjacency, label, piece);
  std::vector<std::array<int, 2>> weight(static_cast<std::size_t>(pieces), { { 0, 0 } });
  std::vector<std::int8_t> pieceLabel(static_cast<std::size_t>(pieces), 0);
  std::vector<char> pieceFixed(static_cast<std::size_t>(pieces), 0);
  for (std::size_t t = 0; t < label.size(); ++t)
  {
    ++weight[piece[t]][1];
    pieceLabel[piece[t]] = label[t];
    pieceFixed[piece[t]] |= labels.fixed[t];
  }
  for (const auto& [v, side] : in.halfVotes)
  {
    const int* begin = adjacency.vertexTrianglesBegin(v);
    const int* end = adjacency.vertexTrianglesEnd(v);
    const int* t = std::find_if(begin, end, [&](int s) { return label[s] == side; });
    if (t != end)
      ++weight[piece[*t]][0];
  }
  std::array<int, 2> main{ { -1, -1 } };
  for (int p = 0; p < pieces; ++p)
  {
    int& m = main[labelIndex(pieceLabel[p])];
    m = m < 0 || weight[p] > weight[m] ? p : m;
  }
  if (main[0] < 0 || main[1] < 0)
    throw InvalidInputError(visualName(in) + ": no visual triangle lies on the " +
                            (main[0] < 0 ? "positive" : "negative") +
                            " side of the collision mid-surface");
  int relabelled = 0;
  for (std::size_t t = 0; t < label.size(); ++t)
  {
    if (piece[t] != main[labelIndex(label[t])] && !pieceFixed[piece[t]])
    {
      label[t] = static_cast<std::int8_t>(-label[t]);
      ++relabelled;
    }
  }
  return relabelled;
}

/// Per vertex: the edges around it between triangles of different labels.
std::vector<int> equatorDegrees(const EquatorInput& in, const std::vector<std::int8_t>& label)
{
  const TriangleMeshAdjacency& adjacency = *in.adjacency;
  std::vector<int> degree(in.visual->vertexCount(), 0);
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e)
  {
    const int edge = static_cast<int>(e);
    const int* t = adjacency.edgeTrianglesBegin(edge);
    if (adjacency.edgeTriangleCount(edge) == 2 && label[t[0]] != label[t[1]])
    {
      ++degree[adjacency.edge(edge)[0]];
      ++degree[adjacency.edge(edge)[1]];
    }
  }
  return degree;
}

/// Where the halves touch at a single vertex (the labels change more than
/// twice around it), the vertex's triangles take the label most of them
/// have (but the fixed ones). Returns the triangles relabelled.
int removePinches(const EquatorInput& in, TriangleLabels& labels)
{
  std::vector<std::int8_t>& label = labels.label;
  const TriangleMeshAdjacency& adjacency = *in.adjacency;
  const std::vector<int> degree = equatorDegrees(in, label);
  int relabelled = 0;
  for (std::size_t v = 0; v < degree.size(); ++v)
  {
    if (degree[v] <= 2)
      continue;
    const int* begin = adjacency.vertexTrianglesBegin(static_cast<int>(v));
    const int* end = adjacency.vertexTrianglesEnd(static_cast<int>(v));
    const auto positive = std::count_if(begin, end, [&](int t) { return label[t] > 0; });
    const std::int8_t majority = 2 * positive >= end - begin ? 1 : -1;
    for (const int* t = begin; t != end; ++t)
    {
      if (!labels.fixed[*t] && label[*t] != majority)
      {
        label[*t] = majority;
        ++relabelled;
      }
    }
  }
  return relabelled;
}

/// The labels of the triangles, each half one piece without pinches.
std::vector<std::int8_t> halfLabels(const EquatorInput& in,
  const TriangleMeshAdjacency& collisionAdjacency,
  const std::vector<std::vector<int>>& borders,
  int& relabelled)
{
  TriangleLabels labels = sideLabels(
    *in.visual, sideOfMidSurface(in, collisionAdjacency, holeBorderVertices(in, borders)));
  relabelled = 0;
  for (int round = 0; round < LabelRounds; ++round)
  {
    const int changed = mergeStrayPieces(in, labels) + removePinches(in, labels);
    relabelled += changed;
    if (changed == 0)
      return labels.label;
  }
  throw InvalidInputError(visualName(in) + ": the sides of the collision mid-surface do not " +
                          "settle into two connected halves (after " + std::to_string(LabelRounds) +
                          " rounds)");
}

/// The border between the labels as vertex loops, each run with the
/// positive half on its left (as the positive triangles run).
std::vector<std::vector<int>> equatorLoops(const EquatorInput& in,
  const std::vector<std::int8_t>& label)
{
  const TriangleMesh& visual = *in.visual;
  std::vector<int> next(visual.vertexCount(), -1);
  for (std::size_t t = 0; t < label.size(); ++t)
  {
    for (int k = 0; k < 3 && label[t] > 0; ++k)
    {
      const int across = in.adjacency->neighbourAcross(static_cast<int>(t), k);
      if (across >= 0 && label[across] < 0)
        next[visual.triangles[t][k]] = visual.triangles[t][(k + 1) % 3];
    }
  }
  std::vector<std::vector<int>> loops;
  std::vector<char> visited(visual.vertexCount(), 0);
  for (std::size_t start = 0; start < next.size(); ++start)
  {
    if (next[start] < 0 || visited[start])
      continue;
    std::vector<int>& loop = loops.emplace_back();
    for (int v = static_cast<int>(start); !visited[v]; v = next[v])
    {
      if (next[v] < 0)
        throw InvalidInputError(
          visualName(in) + ": the equator stops at visual vertex " + std::to_string(v));
      visited[v] = 1;
      loop.push_back(v);
    }
  }
  return loops;
}

/// Where on a loop the rim points go.
struct LoopPlacement
{
  double cost = Infinity;
  std::vector<int> loop;      ///< visual vertices, in the border loop's direction
  std::vector<int> positions; ///< per border vertex in order: its index in `loop`
};

/// Cyclic, strictly increasing positions on `loop` for the points in order,
/// the summed distance least (dynamic programming from each of a few start
/// candidates for the first point).
LoopPlacement placeOnLoop(const std::vector<Vector3>& points,
  const std::vector<int>& loop,
  const TriangleMesh& visual)
{
  LoopPlacement best;
  const std::size_t m = points.size();
  const std::size_t n = loop.size();
  if (n < m || m == 0)
    return best;
  std::vector<double> distance(m * n);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < n; ++j)
      distance[i * n + j] = (points[i] - visual.positions[loop[j]]).norm();
  std::vector<std::size_t> starts(n);
  for (std::size_t j = 0; j < n; ++j)
    starts[j] = j;
  const std::size_t candidates = std::min(AssignmentStarts, n);
  std::partial_sort(starts.begin(),
    starts.begin() + static_cast<std::ptrdiff_t>(candidates),
    starts.end(),
    [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; });
  std::vector<double> previous(n);
  std::vector<double> current(n);
  std::vector<int> choice(m * n, -1); // per point and offset: the previous point's offset
  for (std::size_t s = 0; s < candidates; ++s)
  {
    const std::size_t first = starts[s];
    auto cost = [&](std::size_t i, std::size_t offset)
    { return distance[i * n + (first + offset) % n]; };
    std::fill(previous.begin(), previous.end(), Infinity);
    previous[0] = cost(0, 0);
    for (std::size_t i = 1; i < m; ++i)
    {
      double runningMin = Infinity;
      int runningArg = -1;
      for (std::size_t o = 0; o < n; ++o)
      {
        current[o] = runningArg >= 0 ? runningMin + cost(i, o) : Infinity;
        choice[i * n + o] = runningArg;
        if (previous[o] < runningMin)
        {
          runningMin = previous[o];
          runningArg = static_cast<int>(o);
        }
      }
      std::swap(previous, current);
    }
    const auto last = std::min_element(previous.begin(), previous.end());
    if (*last >= best.cost)
      continue;
    best.cost = *last;
    best.positions.assign(m, 0);
    int o = static_cast<int>(last - previous.begin());
    for (std::size_t i = m; i-- > 0;)
    {
      best.positions[i] = static_cast<int>((first + static_cast<std::size_t>(o)) % n);
      o = i > 0 ? choice[i * n + static_cast<std::size_t>(o)] : 0;
    }
    best.loop = loop;
  }
  return best;
}

/// The better placement of a border loop's rim points on an equator loop,
/// run either way.
LoopPlacement placeOnLoopEitherWay(const EquatorInput& in,
  const std::vector<int>& border,
  std::vector<int> loop)
{
  std::vector<Vector3> points;
  for (int c : border)
    points.push_back(in.visual->positions[in.rimPoints[c]]);
  LoopPlacement forward = placeOnLoop(points, loop, *in.visual);
  std::reverse(loop.begin(), loop.end());
  LoopPlacement backward = placeOnLoop(points, loop, *in.visual);
  return backward.cost < forward.cost ? backward : forward;
}

/// The arc of a loop from position `from` to position `to`, onward.
std::vector<int> arcOf(const std::vector<int>& loop, int from, int to)
{
  const auto n = static_cast<int>(loop.size());
  std::vector<int> arc;
  for (int i = from;; i = (i + 1) % n)
  {
    arc.push_back(loop[i]);
    if (i == to && arc.size() > 1)
      return arc;
  }
}

} // namespace

EquatorRimPaths equatorRimPaths(const EquatorInput& in)
{
  EquatorRimPaths result;
  const TriangleMeshAdjacency collisionAdjacency(*in.collision);
  const std::vector<std::vector<int>> borders = borderLoops(
    collisionAdjacency, in.collision->vertexCount(), "collision mesh '" + in.collision->name + "'");
  const std::vector<std::int8_t> label =
    halfLabels(in, collisionAdjacency, borders, result.relabelledTriangles);
  const std::vector<std::vector<int>> loops = equatorLoops(in, label);
  if (loops.size() != borders.size())
    throw InvalidInputError(
      visualName(in) + ": the sides of the collision mid-surface meet along " +
      std::to_string(loops.size()) + " loops, its border has " + std::to_string(borders.size()));
  result.rimPoints.assign(in.collision->vertexCount(), -1);
  std::map<std::pair<int, int>, std::vector<int>> arcs; // by (border vertex, next one)
  std::vector<char> taken(loops.size(), 0);
  for (const std::vector<int>& border : borders)
  {
    LoopPlacement best;
    std::size_t bestLoop = 0;
    for (std::size_t l = 0; l < loops.size(); ++l)
    {
      LoopPlacement placement = placeOnLoopEitherWay(in, border, loops[l]);
      if (!taken[l] && placement.cost < best.cost)
      {
        best = std::move(placement);
        bestLoop = l;
      }
    }
    if (best.positions.empty())
      throw InvalidInputError(visualName(in) + ": no loop of the equator takes the " +
                              std::to_string(border.size()) + " rim points of border vertex " +
                              std::to_string(border.front()) + "'s loop");
    taken[bestLoop] = 1;
    for (std::size_t i = 0; i < border.size(); ++i)
    {
      const std::size_t j = (i + 1) % border.size();
      result.rimPoints[border[i]] = best.loop[best.positions[i]];
      arcs[{ border[i], border[j] }] = arcOf(best.loop, best.positions[i], best.positions[j]);
    }
  }
  for (const auto& edge : in.rimEdges)
  {
    auto forward = arcs.find({ edge[0], edge[1] });
    if (forward != arcs.end())
    {
      result.paths.push_back(forward->second);
      continue;
    }
    std::vector<int> arc = arcs.at({ edge[1], edge[0] });
    std::reverse(arc.begin(), arc.end());
    result.paths.push_back(std::move(arc));
  }
  return result;
}

} // namespace thintissue
