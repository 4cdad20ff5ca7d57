// 5.3.4: the cut surface. Each opened collision edge carries a strip that
// joins its + and - visual paths (fig. 5-12); rows of vertices in between
// sit at the union of both paths' edge parameters (up-sampling), and the
// rows at the edge's ends belong to the collision vertex, so strips meeting
// there share them and the surface stays closed. A strip whose edge is cut
// again is split by comparing parameters (fig. 5-13).
#include "VisualMeshCut.h"
#include "VisualMeshCutPrivate.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace thintissue
{

namespace
{

constexpr double ColumnMerge = 1e-9; ///< of the edge's parameter

/// A point at edge parameter u on a path whose vertices have parameters
/// `at` (increasing).
Vector3 pointAt(const std::vector<Vector3>& positions,
  const std::vector<int>& path,
  const std::vector<double>& at,
  double u)
{
  std::size_t i = 0;
  while (i + 2 < path.size() && at[i + 1] <= u)
    ++i;
  const double span = at[i + 1] - at[i];
  const double s = span > 0.0 ? std::clamp((u - at[i]) / span, 0.0, 1.0) : 0.0;
  return (1.0 - s) * positions[path[i]] + s * positions[path[i + 1]];
}

/// Joins two rows running the same way along the edge (parameters
/// increasing): (a_i, a_i+1, b_j) or (a_i, b_j+1, b_j), whichever row's
/// next point comes first; triangles that repeat a vertex are left out.
void zipRows(const std::vector<int>& upper,
  const std::vector<double>& upperAt,
  const std::vector<int>& lower,
  const std::vector<double>& lowerAt,
  std::vector<Triangle>& out)
{
  std::size_t i = 0, j = 0;
  while (i + 1 < upper.size() || j + 1 < lower.size())
  {
    const bool advanceUpper =
      j + 1 >= lower.size() || (i + 1 < upper.size() && upperAt[i + 1] <= lowerAt[j + 1]);
    Triangle t = advanceUpper ? Triangle{ { upper[i], upper[i + 1], lower[j] } }
                              : Triangle{ { upper[i], lower[j + 1], lower[j] } };
    advanceUpper ? ++i : ++j;
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
      out.push_back(t);
  }
}

/// The cut surface's outward direction on collision edge (a, b): across
/// the edge in the plane of its triangle, away from the triangle's third
/// corner (rest configuration).
Vector3 outwardAcross(const CuttableCollisionMesh& collision, int a, int b)
{
  const int region = collision.trianglesOfEdge(a, b)[0];
  const Triangle& corners = collision.triangles()[region];
  const auto& rest = collision.restPositions();
  int third = corners[0];
  for (int c : corners)
    third = (c != a && c != b) ? c : third;
  const Vector3 along = rest[b] - rest[a];
  Vector3 outward = along.cross(along.cross(rest[third] - rest[a]));
  if (outward.dot(rest[third] - rest[a]) > 0.0)
    outward = -outward;
  return outward.normalized();
}

/// Where a smooth cut puts the vertex of row fraction s (0 at the + path,
/// 1 at the - path) at edge parameter u: between the two paths (5.3.4).
/// `paths` and `at`: the - path then the + path, and their parameters.
Vector3 betweenPaths(const std::vector<Vector3>& positions,
  const std::array<const std::vector<int>*, 2>& paths,
  const std::array<std::vector<double>, 2>& at,
  double u,
  double s)
{
  return (1.0 - s) * pointAt(positions, *paths[1], at[1], u) +
         s * pointAt(positions, *paths[0], at[0], u);
}

/// Entry r (0-based) of a strip's `rowCount` inner rows on a column of the
/// end (from its + paired vertex to its - one): a column with fewer entries
/// than the strip has rows (a plain vertex's, where the strip's other end
/// is a junction vertex's full one) is shared by neighbouring rows.
int columnEntry(const std::vector<int>& column, std::size_t r, std::size_t rowCount)
{
  const double at =
    static_cast<double>(r + 1) * static_cast<double>(column.size() - 1) / (rowCount + 1);
  return column[static_cast<std::size_t>(std::lround(at))];
}

} // namespace

void CuttableVisualMesh::splitStrip(std::uint64_t key,
  int a,
  int b,
  int middle,
  double at,
  CutContext& context)
{
  CutStrip strip = std::move(Strips.at(key));
  Strips.erase(key);
  for (int t : strip.triangles)
    freeTriangle(t);
  CutStrip first, second;
  first.cleft = second.cleft = strip.cleft;
  for (const auto& row : strip.rows)
  {
    std::vector<int> before, after;
    for (int w : row)
    {
      const double u = edgeParameter(w, a, b);
      if (u < at)
      {
        bindToEdge(w, a, middle, u / at, 0);
        before.push_back(w);
      }
      else
      {
        bindToEdge(w, middle, b, (u - at) / (1.0 - at), 0);
        after.push_back(w);
      }
      context.rebound.push_back(w);
    }
    std::reverse(after.begin(), after.end()); // (b, middle): from b, the lower
    first.rows.push_back(std::move(before));
    second.rows.push_back(std::move(after));
  }
  Strips[edgeKey(a, middle)] = std::move(first);
  Strips[edgeKey(b, middle)] = std::move(second);
}

std::vector<CuttableVisualMesh::StripLip> CuttableVisualMesh::stripLipsAt(
  const CuttableCollisionMesh& collision,
  int v) const
{
  std::vector<std::array<int, 2>> edges;
  for (int T : collision.trianglesOfVertex(v))
    for (int k = 0; k < 3; ++k)
    {
      const int x = collision.triangles()[T][k], y = collision.triangles()[T][(k + 1) % 3];
      if (x == v || y == v)
        edges.push_back({ { std::min(x, y), std::max(x, y) } });
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<StripLip> lips;
  for (const auto& [x, y] : edges)
  {
    StripLip lip;
    if (stripSides(collision, x, y, lip))
      lips.push_back(lip);
  }
  return lips;
}

bool CuttableVisualMesh::creaseOnTheCut(const CuttableCollisionMesh& collision, int v) const
{
  // A strip at v reaches the crease (a leaf cut there): the crease then
  // lies on the cut surface. A cut through the body alone leaves it inside
  // the cleft's walls.
  for (const StripLip& lip : stripLipsAt(collision, v))
    if (pairedSlot(v, 0, lip.cleft[0]) == CreaseSlot ||
        pairedSlot(v, 1, lip.cleft[1]) == CreaseSlot)
      return true;
  return false;
}

CuttableVisualMesh::EndColumn& CuttableVisualMesh::endColumn(const CuttableCollisionMesh& collision,
  int collisionVertex)
{
  auto [it, added] = EndColumns.emplace(collisionVertex, EndColumn{});
  EndColumn& column = it->second;
  if (!added)
    return column;
  const std::array<int, 3>& paired = Paired[collisionVertex];
  const auto rows = static_cast<std::size_t>(Settings.cutSurfaceRows);
  column.rim = paired[0] == paired[1];
  column.throughCrease = paired[CreaseSlot] >= 0 && creaseOnTheCut(collision, collisionVertex);
  if (column.rim)
    column.vertices.assign(rows, paired[1]); // on the rim both sides meet
  else if (column.throughCrease)
  {
    // + to crease, the crease, crease to -: the body's strip runs through
    // all of it, each leaf's through its half. Entries are made when a
    // strip needs them (a junction vertex left with one leaf needs half).
    column.vertices.assign(2 * rows + 1, -1);
    column.vertices[rows] = paired[CreaseSlot];
  }
  else
    column.vertices.assign(rows, -1);
  return column;
}

int CuttableVisualMesh::columnVertex(int collisionVertex, int index, const Vector3& outward)
{
  int& entry = EndColumns.at(collisionVertex).vertices[static_cast<std::size_t>(index)];
  if (entry >= 0)
    return entry;
  // 5.3.4 at a cleavage: a copy of a junction vertex that holds the lower
  // leaf alone has no + paired vertex (-1); the new vertex takes its
  // attributes from the - one.
  const std::array<int, 3>& paired = Paired[collisionVertex];
  const int w = addVertexCopy(paired[1] >= 0 ? paired[1] : paired[0]);
  Mesh.positions[w] = columnPlace(collisionVertex, index);
  Mesh.positions[w] += jaggedOffset(Mesh.positions[w], outward);
  if (Mesh.hasNormals())
    Mesh.normals[w] = outward;
  Bindings[w].kind = BindingKind::CollisionVertex;
  Bindings[w].element = collisionVertex;
  Bindings[w].side = 0;
  Bindings[w].parameters = Vector3(1.0, 0.0, 0.0);
  entry = w;
  return w;
}

bool CuttableVisualMesh::stripSides(const CuttableCollisionMesh& collision,
  int a,
  int b,
  StripLip& lip) const
{
  const auto paths = Paths.find(edgeKey(a, b));
  if (paths == Paths.end() || paths->second.rim)
    return false;
  const auto lips = collision.trianglesOfEdge(a, b);
  if (lips[0] >= 0 && lips[1] < 0)
  {
    lip = {
      lips[0], 1, { { facesCleft(collision, lips[0], 0), facesCleft(collision, lips[0], 1) } }
    };
    return true;
  }
  if (!paths->second.junction() || lips[1] < 0 || lips[2] >= 0)
    return false;
  // Two of a junction's three sheets left on the edge (a cut along it took
  // the third): the strip closes the wedge the third filled. Without the
  // body (a fold) it joins the top to the bottom in front of the crease;
  // without a leaf, the top or the bottom to the crease.
  int body = -1, upper = -1, lower = -1;
  for (int k = 0; k < 2; ++k)
  {
    const bool minusCleft = facesCleft(collision, lips[k], 0);
    const bool plusCleft = facesCleft(collision, lips[k], 1);
    (minusCleft ? upper : (plusCleft ? lower : body)) = lips[k];
  }
  if (body < 0 && upper >= 0 && lower >= 0)
    lip = { upper, 1, { { false, false } } };
  else if (upper < 0 && body >= 0 && lower >= 0)
    lip = { body, 1, { { true, false } } };
  else if (lower < 0 && body >= 0 && upper >= 0)
    lip = { upper, 0, { { false, true } } }; // its - side borders the crease
  else
    return false;
  return true;
}

bool CuttableVisualMesh::bodyColumnUsesCrease(const CuttableCollisionMesh& collision, int v) const
{
  const auto column = EndColumns.find(v);
  if (column == EndColumns.end() || !column->second.throughCrease)
    return false;
  const std::vector<bool> needed = columnNeeds(collision, v);
  return needed[static_cast<std::size_t>(Settings.cutSurfaceRows)];
}

std::vector<bool> CuttableVisualMesh::columnNeeds(const CuttableCollisionMesh& collision,
  int v) const
{
  const EndColumn& column = EndColumns.at(v);
  std::vector<bool> needed(column.vertices.size(), false);
  for (const StripLip& lip : stripLipsAt(collision, v))
  {
    // The strip spans its lip's + paired vertex to its - one.
    const auto span = columnSpan(column, v, lip.cleft);
    for (int i = span[0] + 1; i < span[1]; ++i)
      needed[static_cast<std::size_t>(i - 1)] = true;
  }
  return needed;
}

void CuttableVisualMesh::checkColumnWalls(const CuttableCollisionMesh& collision, int v)
{
  // Each segment of a junction vertex's column joins two cut walls. A bite
  // through the body and one leaf on both sides of the vertex, the other
  // leaf whole, would leave four walls on half its column; the collision
  // cut cracks the whole leaf there (notchedJunctionCut), so this is met
  // only where that leaf has no edge of its own at the vertex to crack.
  const auto inner = static_cast<int>(endColumn(collision, v).vertices.size());
  std::vector<int> walls(static_cast<std::size_t>(inner) + 1, 0);
  for (const StripLip& lip : stripLipsAt(collision, v))
  {
    const auto span = columnSpan(collision, v, lip.cleft);
    for (int p = span[0]; p < span[1]; ++p)
      walls[static_cast<std::size_t>(p)] += 1;
  }
  if (*std::max_element(walls.begin(), walls.end()) > 2)
  {
    throw Error("visual cut of '" + Mesh.name + "': more than two cut walls meet at junction " +
                "vertex " + std::to_string(v) + " (a cut through the body and one leaf on both " +
                "sides of it, the other leaf whole and without an edge of its own there to crack)");
  }
}

// A copy made by this cut takes over the column entries its root no longer
// needs and it does (the strips that used them moved to it), so that no
// cut-surface vertex is left without a triangle.
void CuttableVisualMesh::handOverColumns(const CuttableCollisionMesh& collision,
  CutContext& context)
{
  for (std::size_t i = 0; i < context.originalOf.size(); ++i)
  {
    const int root = context.originalOf[i];
    const int copy = context.firstCopy + static_cast<int>(i);
    const auto rootColumn = EndColumns.find(root);
    if (root < 0 || rootColumn == EndColumns.end() || rootColumn->second.rim ||
        collision.trianglesOfVertex(copy).empty())
      continue;
    const std::vector<bool> rootNeeds = columnNeeds(collision, root);
    EndColumn& copyColumn = endColumn(collision, copy);
    if (copyColumn.vertices.size() != rootColumn->second.vertices.size())
      continue;
    const std::vector<bool> copyNeeds = columnNeeds(collision, copy);
    for (std::size_t e = 0; e < copyNeeds.size(); ++e)
    {
      int& from = rootColumn->second.vertices[e];
      int& to = copyColumn.vertices[e];
      if (from < 0 || rootNeeds[e] || !copyNeeds[e] || to >= 0 || from == Paired[root][CreaseSlot])
        continue;
      to = from;
      from = -1;
      Bindings[to].element = copy;
      context.rebound.push_back(to);
    }
  }
}

// A junction vertex whose column was made for a cut through its body alone
// (passing the crease by), and whose leaves are cut there now: the column
// runs through the crease from now on, so the strips at the vertex get the
// rows it has grown by, and are rebuilt.
void CuttableVisualMesh::upgradeColumns(const CuttableCollisionMesh& collision,
  std::vector<std::array<int, 2>>& edges,
  CutContext& context)
{
  const std::size_t edgeCount = edges.size();
  for (std::size_t e = 0; e < edgeCount; ++e)
  {
    const std::array<int, 2> ends = edges[e]; // addStripsAt appends to edges
    for (const int v : ends)
    {
      const auto found = EndColumns.find(v);
      if (found == EndColumns.end() || found->second.rim || found->second.throughCrease ||
          Paired[v][CreaseSlot] < 0 || !creaseOnTheCut(collision, v))
        continue;
      EndColumn& column = found->second;
      const auto rows = static_cast<std::size_t>(Settings.cutSurfaceRows);
      std::vector<Vector3> offsets; // the jagged offsets, kept
      for (std::size_t i = 0; i < column.vertices.size(); ++i)
        offsets.push_back(column.vertices[i] < 0 ? Vector3::Zero().eval()
                                                 : Mesh.positions[column.vertices[i]] -
                                                     columnPlace(v, static_cast<int>(i)));
      column.throughCrease = true;
      column.vertices.resize(2 * rows + 1, -1);
      column.vertices[rows] = Paired[v][CreaseSlot];
      for (std::size_t i = 0; i < rows; ++i)
        if (column.vertices[i] >= 0)
        {
          Mesh.positions[column.vertices[i]] = columnPlace(v, static_cast<int>(i)) + offsets[i];
          context.rebound.push_back(column.vertices[i]);
        }
      addStripsAt(collision, v, edges);
    }
  }
}

void CuttableVisualMesh::addStripsAt(const CuttableCollisionMesh& collision,
  int v,
  std::vector<std::array<int, 2>>& edges) const
{
  for (int T : collision.trianglesOfVertex(v))
  {
    const Triangle& corners = collision.triangles()[T];
    for (int k = 0; k < 3; ++k)
    {
      const int x = std::min(corners[k], corners[(k + 1) % 3]);
      const int y = std::max(corners[k], corners[(k + 1) % 3]);
      if ((x == v || y == v) && Strips.count(edgeKey(x, y)))
        edges.push_back({ { x, y } });
    }
  }
}

int CuttableVisualMesh::stripRowCount(const CuttableCollisionMesh& collision,
  int a,
  int b,
  const CutStrip& strip)
{
  const auto spanA = columnSpan(collision, a, strip.cleft);
  const auto spanB = columnSpan(collision, b, strip.cleft);
  return std::max(spanA[1] - spanA[0], spanB[1] - spanB[0]) - 1;
}

void CuttableVisualMesh::growStrip(const CuttableCollisionMesh& collision,
  int a,
  int b,
  CutStrip& strip,
  CutContext& context)
{
  const auto rowCount = static_cast<std::size_t>(stripRowCount(collision, a, b, strip));
  const std::size_t old = strip.rows.size();
  if (old >= rowCount)
    return;
  // The old rows keep their places among the new (at fractions (r + 1) /
  // (old + 1) of the way between the paths; the new count is 2 old + 1).
  std::vector<std::vector<int>> rows(rowCount);
  for (std::size_t r = 0; r < old; ++r)
  {
    const double at =
      static_cast<double>(r + 1) * static_cast<double>(rowCount + 1) / static_cast<double>(old + 1);
    const auto index = static_cast<std::size_t>(std::max(1L, std::lround(at))) - 1;
    rows[std::min(index, rowCount - 1)] = std::move(strip.rows[r]);
  }
  strip.rows = std::move(rows);
  makeStripRows(collision, a, b, static_cast<int>(rowCount), strip, context);
}

Vector3 CuttableVisualMesh::columnPlace(int v, int index) const
{
  const std::array<int, 3>& paired = Paired[v];
  const int rows = Settings.cutSurfaceRows;
  int from = paired[1], to = paired[0], r = index;
  if (EndColumns.at(v).throughCrease)
  {
    if (index == rows)
      return Mesh.positions[paired[CreaseSlot]];
    if (index < rows)
      to = paired[CreaseSlot];
    else
    {
      from = paired[CreaseSlot];
      r = index - rows - 1;
    }
  }
  const double s = static_cast<double>(r + 1) / (rows + 1);
  return (1.0 - s) * Mesh.positions[from] + s * Mesh.positions[to];
}

std::array<int, 2> CuttableVisualMesh::columnSpan(const EndColumn& column,
  int v,
  const std::array<bool, 2>& cleft) const
{
  // Positions in the column with its ends: 0 the + paired vertex, then the
  // inner entries, then the - paired vertex (the crease's, on a column
  // that passes it by, counts as the - one).
  const auto inner = static_cast<int>(column.vertices.size());
  auto position = [&](int slot)
  {
    if (slot == 1)
      return 0;
    return slot == CreaseSlot && column.throughCrease ? Settings.cutSurfaceRows + 1 : inner + 1;
  };
  return { { position(pairedSlot(v, 1, cleft[1])), position(pairedSlot(v, 0, cleft[0])) } };
}

std::array<int, 2> CuttableVisualMesh::columnSpan(const CuttableCollisionMesh& collision,
  int v,
  const std::array<bool, 2>& cleft)
{
  const EndColumn& column = endColumn(collision, v);
  if (!column.throughCrease &&
      (pairedSlot(v, 0, cleft[0]) == CreaseSlot || pairedSlot(v, 1, cleft[1]) == CreaseSlot))
  {
    throw Error("visual cut of '" + Mesh.name + "': a leaf's cut surface reaches junction vertex " +
                std::to_string(v) + " after a cut through its body alone");
  }
  return columnSpan(column, v, cleft);
}

std::vector<int> CuttableVisualMesh::stripColumn(const CuttableCollisionMesh& collision,
  int v,
  const std::array<bool, 2>& cleft,
  const Vector3& outward)
{
  const auto [first, last] = columnSpan(collision, v, cleft);
  const auto inner = static_cast<int>(EndColumns.at(v).vertices.size());
  std::vector<int> part;
  part.reserve(static_cast<std::size_t>(last - first + 1));
  for (int i = first; i <= last; ++i)
  {
    if (i == 0 || i == inner + 1)
      part.push_back(Paired[v][i == 0 ? 1 : 0]);
    else
      part.push_back(columnVertex(v, i - 1, outward));
  }
  return part;
}

std::array<const std::vector<int>*, 2> CuttableVisualMesh::stripPaths(int a,
  int b,
  const CutStrip& strip) const
{
  const EdgePaths& paths = Paths.at(edgeKey(a, b));
  return { { &paths.sides[pathSlot(paths, 0, strip.cleft[0])],
    &paths.sides[pathSlot(paths, 1, strip.cleft[1])] } };
}

/// The part of an opened edge's path the cut surface joins: where two cuts
/// from one collision vertex share their first visual vertices (bound to
/// that vertex), the opening starts at the last of them.
std::vector<int> CuttableVisualMesh::openPart(const std::vector<int>& path, int a, int b) const
{
  auto boundTo = [&](int w, int c)
  { return Bindings[w].kind == BindingKind::CollisionVertex && Bindings[w].element == c; };
  std::size_t first = 0, last = path.size() - 1;
  while (first + 1 < last && boundTo(path[first + 1], a))
    ++first;
  while (last > first + 1 && boundTo(path[last - 1], b))
    --last;
  return std::vector<int>(path.begin() + static_cast<std::ptrdiff_t>(first),
    path.begin() + static_cast<std::ptrdiff_t>(last) + 1);
}

void CuttableVisualMesh::buildStrip(const CuttableCollisionMesh& collision,
  int a,
  int b,
  CutStrip& strip)
{
  for (int t : strip.triangles)
    freeTriangle(t);
  strip.triangles.clear();
  StripLip lip;
  if (!stripSides(collision, a, b, lip))
    lip.triangle = collision.trianglesOfEdge(a, b)[0];
  const int region = lip.triangle;
  const Vector3 outward = outwardAcross(collision, a, b);
  const auto paths = stripPaths(a, b, strip);
  const std::vector<int> columnA = stripColumn(collision, a, strip.cleft, outward);
  const std::vector<int> columnB = stripColumn(collision, b, strip.cleft, outward);
  const std::size_t rowCount = strip.rows.size();
  if (std::max(columnA.size(), columnB.size()) > rowCount + 2)
  {
    throw Error("visual cut of '" + Mesh.name + "': the cut surface on collision edge (" +
                std::to_string(a) + ", " + std::to_string(b) + ") has fewer rows than its end " +
                "columns");
  }
  std::vector<std::vector<int>> rows;
  rows.push_back(openPart(*paths[1], a, b));
  for (std::size_t r = 0; r < rowCount; ++r)
  {
    std::vector<int> row{ columnEntry(columnA, r, rowCount) };
    row.insert(row.end(), strip.rows[r].begin(), strip.rows[r].end());
    for (int w : strip.rows[r])
      if (Mesh.hasNormals())
        Mesh.normals[w] = outward;
    row.push_back(columnEntry(columnB, r, rowCount));
    rows.push_back(std::move(row));
  }
  rows.push_back(openPart(*paths[0], a, b));
  std::vector<std::vector<double>> at(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    at[r] = pathParameters(rows[r], a, b);
  std::vector<Triangle> triangles;
  for (std::size_t r = 0; r + 1 < rows.size(); ++r)
    zipRows(rows[r], at[r], rows[r + 1], at[r + 1], triangles);

  // Opposite to the + side's triangles along the path (the zip runs along
  // every row edge from lower to higher parameter).
  std::unordered_map<std::uint64_t, int> alongPath;
  for (std::size_t i = 0; i + 1 < rows[0].size(); ++i)
    alongPath.emplace(edgeKey(rows[0][i], rows[0][i + 1]), rows[0][i]);
  int forward = 0, backward = 0;
  for (int t : Regions[region][lip.side])
  {
    const Triangle& face = Mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      const auto found = alongPath.find(edgeKey(face[k], face[(k + 1) % 3]));
      if (found != alongPath.end())
        (found->second == face[k] ? forward : backward) += 1;
    }
  }
  const bool flip = forward > backward;
  for (Triangle t : triangles)
  {
    if (flip)
      std::swap(t[1], t[2]);
    const int index = addTriangle(t, region, 0, VisualMaterial::CutSurface);
    if (Mesh.hasTextureCoordinates())
    {
      if (CutSurfaceTexture < 0)
      {
        CutSurfaceTexture = static_cast<int>(Mesh.textureCoordinates.size());
        Mesh.textureCoordinates.push_back(Vector2::Zero());
      }
      Mesh.textureCorners[index] = { { CutSurfaceTexture, CutSurfaceTexture, CutSurfaceTexture } };
    }
    strip.triangles.push_back(index);
  }
}

void CuttableVisualMesh::makeStripRows(const CuttableCollisionMesh& collision,
  int a,
  int b,
  int rowCount,
  CutStrip& strip,
  CutContext& context)
{
  // Up-sampling: the rows take the parameters of both sides.
  const auto paths = stripPaths(a, b, strip);
  std::array<std::vector<double>, 2> at;
  std::vector<double> all;
  for (int side = 0; side < 2; ++side)
  {
    at[side] = pathParameters(*paths[side], a, b);
    for (double t : at[side])
      if (t > ColumnMerge && t < 1.0 - ColumnMerge)
        all.push_back(t);
  }
  std::sort(all.begin(), all.end());
  // Both sides often share a parameter (up to round-off): one column.
  all.erase(
    std::unique(
      all.begin(), all.end(), [](double x, double y) { return std::abs(x - y) < ColumnMerge; }),
    all.end());
  strip.rows.resize(static_cast<std::size_t>(rowCount));
  const Vector3 outward = outwardAcross(collision, a, b);
  for (int r = 0; r < rowCount; ++r)
  {
    if (!strip.rows[r].empty())
      continue; // kept by growStripRows
    const double s = static_cast<double>(r + 1) / (rowCount + 1);
    for (double u : all)
    {
      const Vector3 smooth = betweenPaths(Mesh.positions, paths, at, u, s);
      const int w = addVertexCopy((*paths[1])[1]);
      Mesh.positions[w] = smooth + jaggedOffset(smooth, outward);
      bindToEdge(w, a, b, u, 0);
      strip.rows[r].push_back(w);
      context.newVertices.push_back(w);
    }
  }
}

void CuttableVisualMesh::updateCutSurface(const CuttableCollisionMesh& collision,
  CutContext& context)
{
  std::vector<std::array<int, 2>> edges;
  for (int T : context.cut->changedTriangles)
  {
    const Triangle& tri = collision.triangles()[T];
    for (int k = 0; k < 3; ++k)
    {
      // The edge, and the edge it was copied from: the other lip of an
      // opened cut may lie in a triangle the cut did not change.
      const int x = tri[k], y = tri[(k + 1) % 3];
      for (const auto& [a, b] : { std::array<int, 2>{ { std::min(x, y), std::max(x, y) } },
             std::array<int, 2>{ { std::min(context.root(x), context.root(y)),
               std::max(context.root(x), context.root(y)) } } })
      {
        StripLip lip;
        if (stripSides(collision, a, b, lip))
          edges.push_back({ { a, b } });
      }
    }
  }
  handOverColumns(collision, context);
  upgradeColumns(collision, edges, context);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& ends : edges)
    for (const int v : ends)
      if (Paired[v][CreaseSlot] >= 0)
        checkColumnWalls(collision, v);
  for (const auto& [a, b] : edges)
  {
    const std::size_t before = Mesh.vertexCount();
    auto [it, added] = Strips.emplace(edgeKey(a, b), CutStrip{});
    CutStrip& strip = it->second;
    // The sides its lip faces now (a fold's strip whose leaves parted is
    // one leaf's).
    StripLip lip;
    stripSides(collision, a, b, lip);
    strip.cleft = lip.cleft;
    if (added)
    {
      // As many rows as the longer end column has inner entries (a body's
      // strip at a junction vertex runs + -> crease -> -).
      makeStripRows(collision, a, b, stripRowCount(collision, a, b, strip), strip, context);
    }
    else
      growStrip(collision, a, b, strip, context); // an end column grew
    buildStrip(collision, a, b, strip);
    for (std::size_t w = before; w < Mesh.vertexCount(); ++w)
      context.newVertices.push_back(static_cast<int>(w));
    context.changedTriangles.insert(
      context.changedTriangles.end(), strip.triangles.begin(), strip.triangles.end());
  }
}

void CuttableVisualMesh::smoothPlaces(std::uint64_t key,
  const CutStrip& strip,
  std::vector<SmoothPlace>& places) const
{
  const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
  const auto paths = stripPaths(a, b, strip);
  const std::array<std::vector<double>, 2> at{ { pathParameters(*paths[0], a, b),
    pathParameters(*paths[1], a, b) } };
  const auto rows = static_cast<int>(strip.rows.size());
  for (int r = 0; r < rows; ++r)
  {
    const double s = static_cast<double>(r + 1) / (rows + 1);
    for (int w : strip.rows[r])
    {
      const double u = edgeParameter(w, a, b);
      places.push_back({ w, u, betweenPaths(Mesh.positions, paths, at, u, s) });
    }
  }
  // The columns at the edge's ends (shared with the strips meeting there).
  for (const int end : { a, b })
  {
    const auto column = EndColumns.find(end);
    if (column == EndColumns.end() || column->second.rim)
      continue;
    const std::vector<int>& vertices = column->second.vertices;
    for (std::size_t r = 0; r < vertices.size(); ++r)
    {
      // A junction vertex's crease vertex belongs to the surface; entries
      // no strip needed are not made.
      if (vertices[r] >= 0 && vertices[r] != Paired[end][CreaseSlot])
        places.push_back(
          { vertices[r], end == a ? 0.0 : 1.0, columnPlace(end, static_cast<int>(r)) });
    }
  }
}

} // namespace thintissue
