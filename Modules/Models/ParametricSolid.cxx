#include "ParametricSolid.h"

#include "UnionFind.h"

#include "ThinTissueError.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace thintissue
{

namespace
{
constexpr double ParameterTolerance = 1e-12;

bool isSameParameter(double a, double b)
{
  return std::abs(a - b) <= ParameterTolerance;
}

/// The two axes spanning a crack plane, increasing.
std::array<int, 2> inPlaneAxes(int normalAxis)
{
  return normalAxis == 0   ? std::array<int, 2>{ 1, 2 }
         : normalAxis == 1 ? std::array<int, 2>{ 0, 2 }
                           : std::array<int, 2>{ 0, 1 };
}

bool isInsideOpen(double x, const std::array<double, 2>& range)
{
  return x > range[0] + ParameterTolerance && x < range[1] - ParameterTolerance;
}

bool isInsideClosed(double x, const std::array<double, 2>& range)
{
  return x >= range[0] - ParameterTolerance && x <= range[1] + ParameterTolerance;
}

/// Opening of `crack` at the in-plane position of p: full at mouths, a
/// sine that closes at fronts, zero outside the crack.
double openingProfile(const ParametricCrack& crack, const ParameterPoint& p)
{
  const auto axes = inPlaneAxes(crack.normalAxis);
  double opening = crack.opening;
  for (int r = 0; r < 2; ++r)
  {
    const auto& range = crack.ranges[r];
    const double x = p[axes[r]];
    if (!isInsideClosed(x, range))
    {
      return 0.0;
    }
    const double t = std::clamp((x - range[0]) / (range[1] - range[0]), 0.0, 1.0);
    const bool lowIsMouth = range[0] <= ParameterTolerance;
    const bool highIsMouth = range[1] >= 1.0 - ParameterTolerance;
    if (lowIsMouth && highIsMouth)
    {
      continue;
    }
    opening *= lowIsMouth    ? std::cos(0.5 * M_PI * t)
               : highIsMouth ? std::sin(0.5 * M_PI * t)
                             : std::sin(M_PI * t);
  }
  return opening;
}

/// A 3-D grid of parameter cells with lines on every crack.
struct CellGrid
{
  std::array<std::vector<double>, 3> lines;
  std::array<int, 3> cells{ 0, 0, 0 };

  int nodeIndex(int i, int j, int k) const { return i + (cells[0] + 1) * (j + (cells[1] + 1) * k); }
  int cellIndex(int i, int j, int k) const { return i + cells[0] * (j + cells[1] * k); }
  int cellCount() const { return cells[0] * cells[1] * cells[2]; }
  ParameterPoint nodeParameter(const std::array<int, 3>& n) const
  {
    return ParameterPoint(lines[0][n[0]], lines[1][n[1]], lines[2][n[2]]);
  }
};

/// One copy of a grid node: the node and which of its (up to 8) incident
/// cells, by octant bit mask (bit a set = the cell lies on the + side of the
/// node along axis a), share it.
struct NodeCopy
{
  std::array<int, 3> node;
  std::vector<int> octants;
};

/// Corner c of a cell (bit a of c = +1 along axis a) in VTK hexahedron order.
constexpr int VtkCornerOfBits[8] = { 0, 1, 3, 2, 4, 5, 7, 6 };

} // namespace

ParametricSolid::ParametricSolid(std::string name, ParametricMap map)
  : Name(std::move(name))
  , Map(std::move(map))
{
  if (!Map)
  {
    throw InvalidInputError("parametric solid '" + Name + "': no map");
  }
}

void ParametricSolid::addCrack(const ParametricCrack& crack)
{
  std::ostringstream problem;
  if (crack.normalAxis < 0 || crack.normalAxis > 2)
  {
    problem << "normal axis " << crack.normalAxis << " is not 0, 1 or 2";
  }
  else if (!(crack.position > 0.0 && crack.position < 1.0))
  {
    problem << "plane at " << crack.position << " is not strictly inside (0, 1)";
  }
  else if (!(crack.opening >= 0.0) || !(crack.influence > 0.0) ||
           !(crack.positiveShare >= 0.0 && crack.positiveShare <= 1.0))
  {
    problem << "opening " << crack.opening << ", influence " << crack.influence << " or share "
            << crack.positiveShare << " out of range";
  }
  for (const auto& range : crack.ranges)
  {
    if (problem.tellp() == 0 && !(range[0] >= 0.0 && range[1] <= 1.0 && range[1] > range[0]))
    {
      problem << "range [" << range[0] << ", " << range[1] << "] is empty or outside [0, 1]";
    }
  }
  if (problem.tellp() != 0)
  {
    throw InvalidInputError("parametric solid '" + Name + "', tear: " + problem.str());
  }
  Cracks.push_back(crack);
}

Vector3 ParametricSolid::direction(const ParameterPoint& p, int axis) const
{
  const double step = 1e-5;
  ParameterPoint low = p;
  ParameterPoint high = p;
  low[axis] = std::max(0.0, p[axis] - step);
  high[axis] = std::min(1.0, p[axis] + step);
  return (Map(high) - Map(low)).normalized();
}

double ParametricSolid::thickness(double s, double u) const
{
  return (Map(ParameterPoint(s, u, 1.0)) - Map(ParameterPoint(s, u, 0.0))).norm();
}

std::vector<double> ParametricSolid::gridLines(int axis, int cells) const
{
  std::vector<double> required{ 0.0, 1.0 };
  for (const auto& crack : Cracks)
  {
    if (crack.normalAxis == axis)
    {
      required.push_back(crack.position);
      continue;
    }
    const auto axes = inPlaneAxes(crack.normalAxis);
    const auto& range = crack.ranges[axes[0] == axis ? 0 : 1];
    required.push_back(range[0]);
    required.push_back(range[1]);
  }
  std::sort(required.begin(), required.end());
  required.erase(std::unique(required.begin(), required.end(), isSameParameter), required.end());
  const int intervals = static_cast<int>(required.size()) - 1;
  if (cells < intervals)
  {
    std::ostringstream message;
    message << "parametric solid '" << Name << "': " << cells << " cells along axis " << axis
            << " cannot hold the " << intervals << " intervals its tears need";
    throw InvalidInputError(message.str());
  }
  // Cells per interval: proportional to its length, at least one each.
  std::vector<int> counts(intervals);
  std::vector<double> ideal(intervals);
  int total = 0;
  for (int i = 0; i < intervals; ++i)
  {
    ideal[i] = cells * (required[i + 1] - required[i]);
    counts[i] = std::max(1, static_cast<int>(std::floor(ideal[i])));
    total += counts[i];
  }
  while (total != cells)
  {
    int best = -1;
    double bestScore = -1e300;
    for (int i = 0; i < intervals; ++i)
    {
      const double score = total < cells ? ideal[i] - counts[i] : counts[i] - ideal[i];
      if ((total < cells || counts[i] > 1) && score > bestScore)
      {
        bestScore = score;
        best = i;
      }
    }
    counts[best] += total < cells ? 1 : -1;
    total += total < cells ? 1 : -1;
  }
  std::vector<double> lines;
  lines.reserve(cells + 1);
  for (int i = 0; i < intervals; ++i)
  {
    for (int k = 0; k < counts[i]; ++k)
    {
      lines.push_back(required[i] + (required[i + 1] - required[i]) * k / counts[i]);
    }
  }
  lines.push_back(1.0);
  return lines;
}

Vector3 ParametricSolid::openedPoint(const ParameterPoint& p, const std::vector<int>& sides) const
{
  Vector3 point = Map(p);
  for (std::size_t c = 0; c < Cracks.size(); ++c)
  {
    const auto& crack = Cracks[c];
    const double offset = p[crack.normalAxis] - crack.position;
    if (std::abs(offset) >= crack.influence)
    {
      continue;
    }
    const int side = std::abs(offset) > ParameterTolerance ? (offset > 0.0 ? 1 : -1)
                                                           : (c < sides.size() ? sides[c] : 0);
    if (side == 0)
    {
      continue;
    }
    const double opening = openingProfile(crack, p);
    if (opening <= 0.0)
    {
      continue;
    }
    const double fade = 1.0 - std::abs(offset) / crack.influence;
    // A tear through the thickness opens across it, the same at every depth,
    // so that the columns of material stay as they were (their thickness,
    // hence the collision radius, is kept); a horizontal tear opens along w.
    Vector3 opensAlong = direction(p, crack.normalAxis);
    if (crack.normalAxis != 2)
    {
      const Vector3 through = direction(p, 2);
      opensAlong = (opensAlong - opensAlong.dot(through) * through).normalized();
    }
    const double share = side > 0 ? crack.positiveShare : 1.0 - crack.positiveShare;
    point += (side * share * opening * fade) * opensAlong;
  }
  return point;
}

namespace
{

/// Is the face on the plane {axis = lines[axis][line]} whose centre has
/// parameters `centre` (the normal coordinate is ignored) a crack face?
bool isCrackFace(const std::vector<ParametricCrack>& cracks,
  int axis,
  double plane,
  const ParameterPoint& centre)
{
  for (const auto& crack : cracks)
  {
    if (crack.normalAxis != axis || !isSameParameter(crack.position, plane))
    {
      continue;
    }
    const auto axes = inPlaneAxes(axis);
    if (isInsideOpen(centre[axes[0]], crack.ranges[0]) &&
        isInsideOpen(centre[axes[1]], crack.ranges[1]))
    {
      return true;
    }
  }
  return false;
}

/// Is p on the crack's rectangle (its plane, ranges closed)?
bool isOnCrack(const ParametricCrack& crack, const ParameterPoint& p)
{
  const auto axes = inPlaneAxes(crack.normalAxis);
  return isSameParameter(p[crack.normalAxis], crack.position) &&
         isInsideClosed(p[axes[0]], crack.ranges[0]) && isInsideClosed(p[axes[1]], crack.ranges[1]);
}

bool touchesCrack(const std::vector<ParametricCrack>& cracks, const ParameterPoint& p)
{
  return std::any_of(
    cracks.begin(), cracks.end(), [&p](const ParametricCrack& c) { return isOnCrack(c, p); });
}

/// Node-level branch analysis (thesis 5.3.3) on a 3-D cell grid: every node
/// gets one copy per group of incident cells connected through faces that
/// are not cracks. Fills `cellCorners` (per cell, 8 copies indexed by corner
/// bits) and returns the copies.
std::vector<NodeCopy> assignNodeCopies(const CellGrid& grid,
  const std::vector<ParametricCrack>& cracks,
  std::vector<std::array<int, 8>>& cellCorners)
{
  std::vector<NodeCopy> copies;
  cellCorners.assign(grid.cellCount(), std::array<int, 8>{});
  const auto& n = grid.cells;
  for (int k = 0; k <= n[2]; ++k)
  {
    for (int j = 0; j <= n[1]; ++j)
    {
      for (int i = 0; i <= n[0]; ++i)
      {
        const std::array<int, 3> node{ i, j, k };
        // Incident cells by octant (bit a set: the cell is on the + side).
        std::array<int, 8> cellOfOctant;
        for (int o = 0; o < 8; ++o)
        {
          std::array<int, 3> c;
          bool valid = true;
          for (int a = 0; a < 3; ++a)
          {
            c[a] = node[a] - 1 + ((o >> a) & 1);
            valid = valid && c[a] >= 0 && c[a] < n[a];
          }
          cellOfOctant[o] = valid ? grid.cellIndex(c[0], c[1], c[2]) : -1;
        }
        UnionFind groups(8);
        const bool onCrack = touchesCrack(cracks, grid.nodeParameter(node));
        for (int o = 0; o < 8; ++o)
        {
          for (int a = 0; a < 3; ++a)
          {
            const int neighbour = o | (1 << a);
            if ((o >> a) & 1 || cellOfOctant[o] < 0 || cellOfOctant[neighbour] < 0)
            {
              continue;
            }
            bool connected = true;
            if (onCrack)
            {
              ParameterPoint centre;
              for (int b = 0; b < 3; ++b)
              {
                const int cell = node[b] - 1 + ((o >> b) & 1);
                centre[b] = b == a ? grid.lines[a][node[a]]
                                   : 0.5 * (grid.lines[b][cell] + grid.lines[b][cell + 1]);
              }
              connected = !isCrackFace(cracks, a, grid.lines[a][node[a]], centre);
            }
            if (connected)
            {
              groups.unite(o, neighbour);
            }
          }
        }
        std::array<int, 8> copyOfRoot;
        copyOfRoot.fill(-1);
        for (int o = 0; o < 8; ++o)
        {
          if (cellOfOctant[o] < 0)
          {
            continue;
          }
          const int root = groups.find(o);
          if (copyOfRoot[root] < 0)
          {
            copyOfRoot[root] = static_cast<int>(copies.size());
            copies.push_back(NodeCopy{ node, {} });
          }
          const int copy = copyOfRoot[root];
          copies[copy].octants.push_back(o);
          // Seen from the cell, this node is the corner opposite the octant.
          cellCorners[cellOfOctant[o]][7 - o] = copy;
        }
      }
    }
  }
  return copies;
}

/// Side of each crack that a node copy lies on: +1 / -1 when all its cells
/// are on one side of a crack plane through the node, 0 otherwise.
std::vector<int> copySides(const std::vector<ParametricCrack>& cracks,
  const ParameterPoint& p,
  const std::vector<int>& octants)
{
  std::vector<int> sides(cracks.size(), 0);
  for (std::size_t c = 0; c < cracks.size(); ++c)
  {
    const int axis = cracks[c].normalAxis;
    if (!isSameParameter(p[axis], cracks[c].position))
    {
      continue;
    }
    bool anyLow = false;
    bool anyHigh = false;
    for (int o : octants)
    {
      ((o >> axis) & 1 ? anyHigh : anyLow) = true;
    }
    sides[c] = anyHigh && !anyLow ? 1 : anyLow && !anyHigh ? -1 : 0;
  }
  return sides;
}

/// A copy on a crack that keeps cells of both of its sides (`sides` 0): a
/// tear front. On a mid-surface (w = 1/2) a horizontal crack is tested at
/// its own plane.
bool isTearFront(const std::vector<ParametricCrack>& cracks,
  const std::vector<int>& sides,
  const ParameterPoint& p,
  bool onMidSurface)
{
  for (std::size_t c = 0; c < cracks.size(); ++c)
  {
    ParameterPoint q = p;
    if (onMidSurface && cracks[c].normalAxis == 2)
    {
      q[2] = cracks[c].position;
    }
    if (sides[c] == 0 && isOnCrack(cracks[c], q))
    {
      return true;
    }
  }
  return false;
}

/// Appends the two triangles of quad (a, b, c, d) (counter-clockwise seen
/// from outside), split along its shorter diagonal, except that a diagonal
/// joining two tear-front vertices is avoided: both lips of the tear would
/// use it and make it non-manifold.
void appendQuad(std::vector<Triangle>& triangles,
  const std::vector<Vector3>& positions,
  const std::array<int, 4>& q,
  const std::vector<bool>& isFrontVertex)
{
  const bool frontDiagonal02 = isFrontVertex[q[0]] && isFrontVertex[q[2]];
  const bool frontDiagonal13 = isFrontVertex[q[1]] && isFrontVertex[q[3]];
  const bool shorter02 = (positions[q[0]] - positions[q[2]]).squaredNorm() <=
                         (positions[q[1]] - positions[q[3]]).squaredNorm();
  if (frontDiagonal13 || (!frontDiagonal02 && shorter02))
  {
    triangles.push_back({ q[0], q[1], q[2] });
    triangles.push_back({ q[0], q[2], q[3] });
  }
  else
  {
    triangles.push_back({ q[0], q[1], q[3] });
    triangles.push_back({ q[1], q[2], q[3] });
  }
}

} // namespace

TriangleMesh ParametricSolid::boundarySurface(const ParametricResolution& resolution,
  double textureScale) const
{
  CellGrid grid;
  for (int a = 0; a < 3; ++a)
  {
    grid.cells[a] = resolution[a];
    grid.lines[a] = gridLines(a, resolution[a]);
  }
  if (!(textureScale > 0.0))
  {
    throw InvalidInputError("parametric solid '" + Name + "': texture scale must be positive");
  }
  std::vector<std::array<int, 8>> cellCorners;
  const auto copies = assignNodeCopies(grid, Cracks, cellCorners);

  // Characteristic length of each axis (through the centre) for textures.
  std::array<double, 3> axisLength{ 0.0, 0.0, 0.0 };
  for (int a = 0; a < 3; ++a)
  {
    ParameterPoint p(0.5, 0.5, 0.5);
    Vector3 previous;
    for (int step = 0; step <= 32; ++step)
    {
      p[a] = step / 32.0;
      const Vector3 x = Map(p);
      axisLength[a] += step > 0 ? (x - previous).norm() : 0.0;
      previous = x;
    }
  }

  TriangleMesh mesh;
  mesh.name = Name;
  std::vector<int> vertexOfCopy(copies.size(), -1);
  std::vector<bool> isFrontVertex;
  std::unordered_map<long long, int> textureOfCopyAndChart;
  auto vertexOf = [&](int copy)
  {
    if (vertexOfCopy[copy] < 0)
    {
      const ParameterPoint p = grid.nodeParameter(copies[copy].node);
      vertexOfCopy[copy] = static_cast<int>(mesh.positions.size());
      mesh.positions.push_back(openedPoint(p, copySides(Cracks, p, copies[copy].octants)));
      isFrontVertex.push_back(
        touchesCrack(Cracks, p) &&
        isTearFront(Cracks, copySides(Cracks, p, copies[copy].octants), p, false));
    }
    return vertexOfCopy[copy];
  };
  // Chart = outward face direction (2 * axis + (positive ? 1 : 0)).
  auto textureOf = [&](int copy, int chart)
  {
    const long long key = static_cast<long long>(copy) * 6 + chart;
    const auto found = textureOfCopyAndChart.find(key);
    if (found != textureOfCopyAndChart.end())
    {
      return found->second;
    }
    const int axis = chart / 2;
    const int b = (axis + 1) % 3;
    const int c = (axis + 2) % 3;
    const ParameterPoint p = grid.nodeParameter(copies[copy].node);
    const int index = static_cast<int>(mesh.textureCoordinates.size());
    mesh.textureCoordinates.emplace_back(
      p[b] * axisLength[b] / textureScale, p[c] * axisLength[c] / textureScale);
    textureOfCopyAndChart.emplace(key, index);
    return index;
  };

  const auto& n = grid.cells;
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        const std::array<int, 3> cell{ i, j, k };
        const auto& corners = cellCorners[grid.cellIndex(i, j, k)];
        for (int a = 0; a < 3; ++a)
        {
          for (int positive = 0; positive < 2; ++positive)
          {
            const int neighbour = cell[a] + (positive ? 1 : -1);
            bool isBoundary = neighbour < 0 || neighbour >= n[a];
            if (!isBoundary)
            {
              ParameterPoint centre;
              for (int b = 0; b < 3; ++b)
              {
                centre[b] = b == a ? grid.lines[a][cell[a] + positive]
                                   : 0.5 * (grid.lines[b][cell[b]] + grid.lines[b][cell[b] + 1]);
              }
              isBoundary = isCrackFace(Cracks, a, centre[a], centre);
            }
            if (!isBoundary)
            {
              continue;
            }
            // Corners of the face in counter-clockwise order around +a
            // (e_b x e_c = e_a for the cyclic successors b, c).
            const int b = (a + 1) % 3;
            const int c = (a + 2) % 3;
            const int bitsA = positive << a;
            std::array<int, 4> bits{
              bitsA, bitsA | (1 << b), bitsA | (1 << b) | (1 << c), bitsA | (1 << c)
            };
            if (!positive)
            {
              std::swap(bits[1], bits[3]);
            }
            std::array<int, 4> quad;
            std::array<int, 4> texture;
            for (int q = 0; q < 4; ++q)
            {
              quad[q] = vertexOf(corners[bits[q]]);
              texture[q] = textureOf(corners[bits[q]], 2 * a + positive);
            }
            const std::size_t before = mesh.triangles.size();
            appendQuad(mesh.triangles, mesh.positions, quad, isFrontVertex);
            for (std::size_t t = before; t < mesh.triangles.size(); ++t)
            {
              Triangle corner;
              for (int q = 0; q < 3; ++q)
              {
                corner[q] =
                  texture[std::find(quad.begin(), quad.end(), mesh.triangles[t][q]) - quad.begin()];
              }
              mesh.textureCorners.push_back(corner);
            }
          }
        }
      }
    }
  }
  if (!(mesh.signedVolume() > 0.0))
  {
    throw InvalidInputError(
      "parametric solid '" + Name +
      "': the map is not right-handed (the surface encloses a negative volume)");
  }
  mesh.computeVertexNormals();
  return mesh;
}

namespace
{

/// The mid-surface of a parametric solid (ParametricSolid::midSurface):
/// per (s, u) cell its leaves (the cell's w extent split by horizontal
/// cracks), one quad per leaf; per grid node one vertex per group of leaves
/// joined around it (leaves of neighbouring cells that overlap in w and are
/// not parted by a crack face).
class MidSurfaceBuilder
{
public:
  MidSurfaceBuilder(const ParametricSolid& solid, int along, int across)
    : Solid(solid)
    , Along(along)
    , Across(across)
    , LineS(solid.gridLines(0, along))
    , LineU(solid.gridLines(1, across))
  {
    Mesh.name = solid.name() + " collision";
  }

  TriangleMesh build()
  {
    splitCellsIntoLeaves();
    for (int j = 0; j <= Across; ++j)
      for (int i = 0; i <= Along; ++i)
        addNodeVertices(i, j);
    for (const Leaf& leaf : Leaves)
      appendQuad(Mesh.triangles, Mesh.positions, leaf.corners, IsFrontVertex);
    Mesh.pointAttributes.set("Radius", 1, std::move(Radii));
    Mesh.computeVertexNormals();
    return std::move(Mesh);
  }

private:
  struct Leaf
  {
    int i, j;
    double low, high;
    std::array<int, 4> corners{ { -1, -1, -1, -1 } }; // (0,0) (1,0) (1,1) (0,1)
  };
  /// A leaf around a node, the corner the node is for it and the quadrant
  /// bits (bit 0: cell on the + side in s, bit 1: in u).
  struct Incident
  {
    int leaf, corner, quadrant;
  };

  void splitCellsIntoLeaves()
  {
    LeavesOfCell.resize(static_cast<std::size_t>(Along) * Across);
    for (int j = 0; j < Across; ++j)
      for (int i = 0; i < Along; ++i)
      {
        const double s = 0.5 * (LineS[i] + LineS[i + 1]);
        const double u = 0.5 * (LineU[j] + LineU[j + 1]);
        std::vector<double> cuts{ 0.0, 1.0 };
        for (const auto& crack : Solid.cracks())
          if (crack.normalAxis == 2 && isInsideOpen(s, crack.ranges[0]) &&
              isInsideOpen(u, crack.ranges[1]))
            cuts.push_back(crack.position);
        std::sort(cuts.begin(), cuts.end());
        cuts.erase(std::unique(cuts.begin(), cuts.end(), isSameParameter), cuts.end());
        for (std::size_t c = 0; c + 1 < cuts.size(); ++c)
        {
          LeavesOfCell[i + Along * j].push_back(static_cast<int>(Leaves.size()));
          Leaves.push_back(Leaf{ i, j, cuts[c], cuts[c + 1] });
        }
      }
  }

  std::vector<Incident> incidentLeaves(int i, int j) const
  {
    std::vector<Incident> incident;
    for (int quadrant = 0; quadrant < 4; ++quadrant)
    {
      const int ci = i - 1 + (quadrant & 1);
      const int cj = j - 1 + ((quadrant >> 1) & 1);
      if (ci < 0 || cj < 0 || ci >= Along || cj >= Across)
        continue;
      // Corner of the cell at this node, counter-clockwise from (0,0).
      static const int cornerOfQuadrant[4] = { 2, 3, 1, 0 };
      for (int leaf : LeavesOfCell[ci + Along * cj])
        incident.push_back({ leaf, cornerOfQuadrant[quadrant], quadrant });
    }
    return incident;
  }

  /// Whether two leaves of cells beside each other around node (i, j)
  /// overlap in w and are not parted by a crack face.
  bool joined(int i, int j, const Incident& x, const Incident& y) const
  {
    const int differing = x.quadrant ^ y.quadrant;
    if (differing != 1 && differing != 2)
      return false; // same cell (distinct leaves) or diagonal neighbours
    const Leaf& a = Leaves[x.leaf];
    const Leaf& b = Leaves[y.leaf];
    const double low = std::max(a.low, b.low);
    const double high = std::min(a.high, b.high);
    if (high - low <= ParameterTolerance)
      return false;
    const int axis = differing == 1 ? 0 : 1;
    ParameterPoint centre;
    centre[axis] = axis == 0 ? LineS[i] : LineU[j];
    centre[1 - axis] =
      axis == 1 ? 0.5 * (LineS[a.i] + LineS[a.i + 1]) : 0.5 * (LineU[a.j] + LineU[a.j + 1]);
    centre[2] = 0.5 * (low + high);
    return !isCrackFace(Solid.cracks(), axis, centre[axis], centre);
  }

  void addNodeVertices(int i, int j)
  {
    const std::vector<Incident> incident = incidentLeaves(i, j);
    UnionFind groups(incident.size());
    for (std::size_t x = 0; x < incident.size(); ++x)
      for (std::size_t y = x + 1; y < incident.size(); ++y)
        if (joined(i, j, incident[x], incident[y]))
          groups.unite(static_cast<int>(x), static_cast<int>(y));
    std::vector<int> vertexOfRoot(incident.size(), -1);
    for (std::size_t x = 0; x < incident.size(); ++x)
    {
      const int root = groups.find(static_cast<int>(x));
      if (vertexOfRoot[root] < 0)
        vertexOfRoot[root] = addGroupVertex(i, j, incident, groups, root);
      Leaves[incident[x].leaf].corners[incident[x].corner] = vertexOfRoot[root];
    }
  }

  /// The vertex of one group of leaves around node (i, j): at the middle of
  /// the group's w extent, on the crack sides the group lies on, with half
  /// the extent's thickness as its radius.
  int addGroupVertex(int i,
    int j,
    const std::vector<Incident>& incident,
    UnionFind& groups,
    int root)
  {
    double low = 1.0;
    double high = 0.0;
    std::vector<int> octants;
    for (std::size_t y = 0; y < incident.size(); ++y)
    {
      if (groups.find(static_cast<int>(y)) != root)
        continue;
      const Leaf& leaf = Leaves[incident[y].leaf];
      low = std::min(low, leaf.low);
      high = std::max(high, leaf.high);
      // Octant bits as in 3-D: w bit set for leaves above w = 1/2.
      const bool above = leaf.low >= 0.5 - ParameterTolerance;
      const bool below = leaf.high <= 0.5 + ParameterTolerance;
      for (int wBit = 0; wBit < 2; ++wBit)
        if ((wBit == 1 && !below) || (wBit == 0 && !above))
          octants.push_back(incident[y].quadrant | (wBit << 2));
    }
    const auto& cracks = Solid.cracks();
    const ParameterPoint nodeParameter(LineS[i], LineU[j], 0.5);
    std::vector<int> sides = copySides(cracks, nodeParameter, octants);
    // Horizontal cracks: the leaf's side is whether it is above.
    for (std::size_t c = 0; c < cracks.size(); ++c)
      if (cracks[c].normalAxis == 2)
        sides[c] = low >= cracks[c].position - ParameterTolerance    ? 1
                   : high <= cracks[c].position + ParameterTolerance ? -1
                                                                     : 0;
    const ParameterPoint mid(LineS[i], LineU[j], 0.5 * (low + high));
    Mesh.positions.push_back(Solid.openedPoint(mid, sides));
    IsFrontVertex.push_back(isTearFront(cracks, sides, nodeParameter, true));
    Radii.push_back(0.5 * (Solid.point(ParameterPoint(LineS[i], LineU[j], high)) -
                            Solid.point(ParameterPoint(LineS[i], LineU[j], low)))
                            .norm());
    return static_cast<int>(Mesh.positions.size()) - 1;
  }

  const ParametricSolid& Solid;
  const int Along, Across;
  const std::vector<double> LineS, LineU;
  std::vector<Leaf> Leaves;
  std::vector<std::vector<int>> LeavesOfCell;
  TriangleMesh Mesh;
  std::vector<double> Radii;
  std::vector<bool> IsFrontVertex;
};

} // namespace

TriangleMesh ParametricSolid::midSurface(int along, int across) const
{
  return MidSurfaceBuilder(*this, along, across).build();
}

HexahedralMesh ParametricSolid::hexahedra(const ParametricResolution& resolution,
  const std::array<double, 3>& margin,
  const FixedNodePredicate& isFixed) const
{
  CellGrid grid;
  for (int a = 0; a < 3; ++a)
  {
    grid.cells[a] = resolution[a];
    grid.lines[a] = gridLines(a, resolution[a]);
  }
  std::vector<std::array<int, 8>> cellCorners;
  const auto copies = assignNodeCopies(grid, Cracks, cellCorners);
  HexahedralMesh mesh;
  mesh.name = Name + " hexahedra";
  mesh.nodes.reserve(copies.size());
  mesh.fixedNodes.reserve(copies.size());
  for (const auto& copy : copies)
  {
    const ParameterPoint p = grid.nodeParameter(copy.node);
    Vector3 x = openedPoint(p, copySides(Cracks, p, copy.octants));
    for (int a = 0; a < 3; ++a)
    {
      if (copy.node[a] == 0)
      {
        x -= margin[a] * direction(p, a);
      }
      else if (copy.node[a] == grid.cells[a])
      {
        x += margin[a] * direction(p, a);
      }
    }
    mesh.nodes.push_back(x);
    mesh.fixedNodes.push_back(isFixed && isFixed(p) ? 1 : 0);
  }
  mesh.hexahedra.reserve(grid.cellCount());
  for (const auto& corners : cellCorners)
  {
    Hexahedron hexahedron;
    for (int bits = 0; bits < 8; ++bits)
    {
      hexahedron[VtkCornerOfBits[bits]] = corners[bits];
    }
    mesh.hexahedra.push_back(hexahedron);
  }
  return mesh;
}

} // namespace thintissue
