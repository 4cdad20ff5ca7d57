#include "MeshRepair.h"

#include "MeshPieces.h"

#include "ThinTissueError.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

namespace thintissue
{

namespace
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Surface = CGAL::Surface_mesh<Point>;
using VertexIndex = Surface::Vertex_index;
using FaceIndex = Surface::Face_index;
using HalfedgeIndex = Surface::Halfedge_index;
namespace PMP = CGAL::Polygon_mesh_processing;

/// Input vertex indices of a triangle's corners, in the triangle's order.
using Corners = std::array<int, 3>;
/// The same indices sorted: a triangle's identity whatever its orientation.
using TriangleKey = std::array<int, 3>;

TriangleKey keyOf(Corners corners)
{
  std::sort(corners.begin(), corners.end());
  return corners;
}

/// +1 when `corners` run the same way round as `reference`, -1 when the
/// other way, 0 when they are not the same three vertices.
int orientationAgainst(const Corners& corners, const Corners& reference)
{
  for (int shift = 0; shift < 3; ++shift)
  {
    if (corners[0] == reference[shift] && corners[1] == reference[(shift + 1) % 3] &&
        corners[2] == reference[(shift + 2) % 3])
    {
      return 1;
    }
    if (corners[0] == reference[shift] && corners[1] == reference[(shift + 2) % 3] &&
        corners[2] == reference[(shift + 1) % 3])
    {
      return -1;
    }
  }
  return 0;
}

Vector3 vectorOf(const Point& p)
{
  return Vector3(p.x(), p.y(), p.z());
}

std::string positionText(const Vector3& x)
{
  std::ostringstream out;
  out << std::setprecision(6) << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return out.str();
}

std::string listText(const std::vector<int>& values, std::size_t shown)
{
  std::string text;
  for (std::size_t i = 0; i < std::min(values.size(), shown); ++i)
  {
    text += (i > 0 ? ", " : "") + std::to_string(values[i]);
  }
  return values.size() > shown ? text + ", ..." : text;
}

double diagonalOf(const TriangleMesh& mesh)
{
  const BoundingBox box = mesh.boundingBox();
  return box.isEmpty() ? 0.0 : box.diagonal().norm();
}

/// "1 hole", "2 holes", "3 vertices".
std::string counted(int count, const std::string& noun)
{
  const bool es = noun.size() > 1 && noun.compare(noun.size() - 2, 2, "ex") == 0;
  const std::string plural = es ? noun.substr(0, noun.size() - 2) + "ices" : noun + "s";
  return std::to_string(count) + " " + (count == 1 ? noun : plural);
}

/// The input as the repair sees it. Repair never moves a point, so a
/// position names the input vertex it came from (the first one there, when
/// several coincide), and a vertex triple names the input triangle.
class InputIndex
{
public:
  explicit InputIndex(const TriangleMesh& mesh)
    : Mesh(mesh)
  {
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    {
      const Vector3& x = mesh.positions[v];
      VertexByPosition.emplace(std::array<double, 3>{ x.x(), x.y(), x.z() }, static_cast<int>(v));
    }
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      TriangleByKey.emplace(keyOf(corners(static_cast<int>(t))), static_cast<int>(t));
    }
  }

  const TriangleMesh& mesh() const { return Mesh; }

  /// The input vertex at `p`, -1 for a point repair added.
  int vertexAt(const Point& p) const
  {
    const auto found = VertexByPosition.find({ p.x(), p.y(), p.z() });
    return found == VertexByPosition.end() ? -1 : found->second;
  }

  int vertexAt(int v) const
  {
    const Vector3& x = Mesh.positions[v];
    return vertexAt(Point(x.x(), x.y(), x.z()));
  }

  /// Corners of input triangle t, coincident vertices merged.
  Corners corners(int t) const
  {
    const Triangle& tri = Mesh.triangles[t];
    return { vertexAt(tri[0]), vertexAt(tri[1]), vertexAt(tri[2]) };
  }

  /// The first input triangle with these vertices, -1 for a new triangle.
  int triangleOf(const Corners& corners) const
  {
    const auto found = TriangleByKey.find(keyOf(corners));
    return found == TriangleByKey.end() ? -1 : found->second;
  }

  std::string vertexPlace(int v) const
  {
    return "vertex " + std::to_string(v) + " at " + positionText(Mesh.positions[v]);
  }

private:
  const TriangleMesh& Mesh;
  std::map<std::array<double, 3>, int> VertexByPosition;
  std::map<TriangleKey, int> TriangleByKey;
};

/// Kinds of change; each is listed up to a limit and counted beyond it.
enum class Change
{
  Merge,
  Unreferenced,
  Degenerate,
  Duplicate,
  NonManifold,
  Hole,
  OpenBorder,
  Flip,
  Normal,
  Kinds
};

const char* const ChangeNames[] = { "merged vertices",
  "removed unreferenced vertices",
  "removed degenerate triangles",
  "removed duplicate triangles",
  "non-manifold splits",
  "filled holes",
  "open borders",
  "flipped triangles",
  "reversed normals" };

/// Collects the lines of MeshRepairReport::changes.
class RepairLog
{
public:
  RepairLog(MeshRepairReport& report, int listedPerKind)
    : Report(report)
    , Limit(std::max(0, listedPerKind))
  {
  }

  void note(Change kind, const std::string& text)
  {
    int& noted = Noted[static_cast<int>(kind)];
    if (noted++ < Limit)
    {
      Report.changes.push_back(text);
    }
  }

  /// Says how many of each kind were not listed.
  void finish()
  {
    for (int kind = 0; kind < static_cast<int>(Change::Kinds); ++kind)
    {
      if (Noted[kind] > Limit)
      {
        Report.changes.push_back(
          "... and " + std::to_string(Noted[kind] - Limit) + " more " + ChangeNames[kind]);
      }
    }
  }

private:
  MeshRepairReport& Report;
  int Limit;
  std::array<int, static_cast<int>(Change::Kinds)> Noted{};
};

struct Soup
{
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
};

Soup soupOf(const TriangleMesh& mesh)
{
  Soup soup;
  soup.points.reserve(mesh.vertexCount());
  for (const Vector3& x : mesh.positions)
  {
    soup.points.emplace_back(x.x(), x.y(), x.z());
  }
  soup.polygons.reserve(mesh.triangleCount());
  for (const Triangle& tri : mesh.triangles)
  {
    soup.polygons.push_back({ static_cast<std::size_t>(tri[0]),
      static_cast<std::size_t>(tri[1]),
      static_cast<std::size_t>(tri[2]) });
  }
  return soup;
}

Corners soupCorners(const Soup& soup, std::size_t p, const InputIndex& input)
{
  const auto& polygon = soup.polygons[p];
  return { input.vertexAt(soup.points[polygon[0]]),
    input.vertexAt(soup.points[polygon[1]]),
    input.vertexAt(soup.points[polygon[2]]) };
}

/// Names the input triangles the soup repair dropped: the soup keeps one of
/// each set of triangles on the same vertices (the first in input order is
/// named as kept) and none with a repeated vertex.
void noteRemovedTriangles(const Soup& soup,
  const InputIndex& input,
  RepairLog& log,
  MeshRepairReport& report)
{
  std::map<TriangleKey, int> remaining;
  for (std::size_t p = 0; p < soup.polygons.size(); ++p)
  {
    ++remaining[keyOf(soupCorners(soup, p, input))];
  }
  for (std::size_t t = 0; t < input.mesh().triangleCount(); ++t)
  {
    const Corners corners = input.corners(static_cast<int>(t));
    const TriangleKey key = keyOf(corners);
    if (remaining[key] > 0)
    {
      --remaining[key];
      continue;
    }
    const std::string vertices = listText({ corners[0], corners[1], corners[2] }, 3);
    if (key[0] == key[1] || key[1] == key[2])
    {
      ++report.removedDegenerateTriangles;
      log.note(Change::Degenerate,
        "removed triangle " + std::to_string(t) + " (vertices " + vertices +
          ", a repeated vertex) at " + input.vertexPlace(corners[0]));
      continue;
    }
    ++report.removedDuplicateTriangles;
    log.note(Change::Duplicate,
      "removed triangle " + std::to_string(t) + ", a duplicate of triangle " +
        std::to_string(input.triangleOf(corners)) + " (vertices " + vertices + ") at " +
        input.vertexPlace(corners[0]));
  }
}

/// Merges coincident points and drops triangles with a repeated vertex,
/// duplicate triangles and unreferenced points (CGAL repair_polygon_soup).
void cleanSoup(Soup& soup, const InputIndex& input, RepairLog& log, MeshRepairReport& report)
{
  const TriangleMesh& mesh = input.mesh();
  report.mergedCoincidentVertices =
    static_cast<int>(PMP::merge_duplicate_points_in_polygon_soup(soup.points, soup.polygons));
  std::vector<char> used(mesh.vertexCount(), 0);
  for (const Triangle& tri : mesh.triangles)
  {
    used[tri[0]] = used[tri[1]] = used[tri[2]] = 1;
  }
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    const int same = input.vertexAt(static_cast<int>(v));
    if (same != static_cast<int>(v) && used[v])
    {
      log.note(Change::Merge,
        "merged vertex " + std::to_string(v) + " into " + input.vertexPlace(same) +
          " (same position)");
    }
    else if (!used[v])
    {
      ++report.removedUnreferencedVertices;
      log.note(Change::Unreferenced, "removed unreferenced " + input.vertexPlace(int(v)));
    }
  }
  PMP::repair_polygon_soup(soup.points, soup.polygons);
  noteRemovedTriangles(soup, input, log, report);
}

/// Receives CGAL's findings while it orients the soup (CGAL copies the
/// visitor, so it writes through a pointer).
struct OrientationFindings
{
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> nonManifoldEdges;
  std::map<std::size_t, std::size_t> nonManifoldVertices;
};

struct OrientationVisitor : PMP::Default_orientation_visitor
{
  explicit OrientationVisitor(OrientationFindings* findings)
    : Findings(findings)
  {
  }
  void non_manifold_edge(std::size_t a, std::size_t b, std::size_t triangles)
  {
    Findings->nonManifoldEdges[std::minmax(a, b)] = triangles;
  }
  void non_manifold_vertex(std::size_t v, std::size_t fans)
  {
    Findings->nonManifoldVertices[v] = fans;
  }
  OrientationFindings* Findings;
};

/// Orients the soup's triangles consistently and splits the points where
/// the surface is not a disk around them (CGAL orient_polygon_soup), so
/// that it becomes a polygon mesh.
void orientSoup(Soup& soup, const InputIndex& input, RepairLog& log, MeshRepairReport& report)
{
  OrientationFindings findings;
  const std::size_t pointCount = soup.points.size();
  PMP::orient_polygon_soup(
    soup.points, soup.polygons, CGAL::parameters::visitor(OrientationVisitor(&findings)));
  report.splitNonManifoldVertices += static_cast<int>(soup.points.size() - pointCount);
  report.nonManifoldEdges += static_cast<int>(findings.nonManifoldEdges.size());
  report.nonManifoldVertices += static_cast<int>(findings.nonManifoldVertices.size());
  for (const auto& [edge, triangles] : findings.nonManifoldEdges)
  {
    const int a = input.vertexAt(soup.points[edge.first]);
    log.note(Change::NonManifold,
      "separated the " + std::to_string(triangles) + " triangles at non-manifold edge " +
        std::to_string(a) + "-" + std::to_string(input.vertexAt(soup.points[edge.second])) +
        " at " + input.vertexPlace(a));
  }
  for (const auto& [v, fans] : findings.nonManifoldVertices)
  {
    log.note(Change::NonManifold,
      "split non-manifold " + input.vertexPlace(input.vertexAt(soup.points[v])) + " into " +
        std::to_string(fans) + " vertices, one per fan of triangles");
  }
}

Surface surfaceOf(const Soup& soup, const std::string& name)
{
  if (!PMP::is_polygon_soup_a_polygon_mesh(soup.polygons))
  {
    throw InvalidInputError("mesh '" + name + "': repair could not make a manifold surface of it");
  }
  Surface surface;
  PMP::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, surface);
  return surface;
}

Corners surfaceCorners(const Surface& surface, FaceIndex f, const InputIndex& input)
{
  Corners corners{ -1, -1, -1 };
  int k = 0;
  for (VertexIndex v : CGAL::vertices_around_face(surface.halfedge(f), surface))
  {
    corners[k++] = input.vertexAt(surface.point(v));
  }
  return corners;
}

/// A polygon mesh can still hold a vertex pinched between two fans that
/// share no edge; CGAL splits those here.
void splitPinchedVertices(Surface& surface,
  const InputIndex& input,
  RepairLog& log,
  MeshRepairReport& report)
{
  std::vector<std::vector<VertexIndex>> groups;
  const std::size_t added = PMP::duplicate_non_manifold_vertices(
    surface, CGAL::parameters::output_iterator(std::back_inserter(groups)));
  report.splitNonManifoldVertices += static_cast<int>(added);
  report.nonManifoldVertices += static_cast<int>(groups.size());
  for (const auto& group : groups)
  {
    log.note(Change::NonManifold,
      "split non-manifold " + input.vertexPlace(input.vertexAt(surface.point(group.front()))) +
        " into " + std::to_string(group.size()) + " vertices, one per fan of triangles");
  }
}

/// validateTriangleMesh (by default) calls a triangle degenerate when its
/// area is below this fraction of the squared bounding-box diagonal; repair
/// must remove what validation refuses.
constexpr double DegenerateAreaTolerance = 1e-14;
/// Such a triangle is a cap (an angle above about 177 degrees) or a needle
/// (an edge a thousand times shorter than another), which CGAL removes by
/// flipping or collapsing an edge.
constexpr double CapCosine = -0.999;
constexpr double NeedleRatio = 1000.0;

void noteDegenerate(const Surface& surface,
  const std::vector<FaceIndex>& faces,
  const char* what,
  const InputIndex& input,
  RepairLog& log)
{
  for (FaceIndex f : faces)
  {
    const Corners corners = surfaceCorners(surface, f, input);
    log.note(Change::Degenerate,
      std::string("removed ") + what + " triangle " + std::to_string(input.triangleOf(corners)) +
        " (vertices " + listText({ corners[0], corners[1], corners[2] }, 3) + ") at " +
        input.vertexPlace(corners[0]) + "; an edge there flipped or collapsed");
  }
}

constexpr double Infinity = std::numeric_limits<double>::infinity();

/// Triangles of area at most `area` that are neither caps nor needles but
/// tiny all round (flying edges makes them where the iso-surface passes
/// next to a sample: three crossings near one point): their shortest edge
/// collapsed (where the link condition allows). False when some stay.
bool collapseTinyTriangles(Surface& surface, double area)
{
  for (int pass = 0; pass < 8; ++pass)
  {
    bool changed = false;
    bool left = false;
    for (FaceIndex f : surface.faces())
    {
      if (surface.is_removed(f) || PMP::face_area(f, surface) > area)
      {
        continue;
      }
      HalfedgeIndex shortest = surface.halfedge(f);
      double length = Infinity;
      for (HalfedgeIndex h : CGAL::halfedges_around_face(surface.halfedge(f), surface))
      {
        const double l = CGAL::squared_distance(
          surface.point(surface.source(h)), surface.point(surface.target(h)));
        if (l < length)
        {
          length = l;
          shortest = h;
        }
      }
      if (CGAL::Euler::does_satisfy_link_condition(surface.edge(shortest), surface))
      {
        CGAL::Euler::collapse_edge(surface.edge(shortest), surface);
        changed = true;
      }
      else
      {
        left = true;
      }
    }
    surface.collect_garbage();
    if (!changed)
    {
      return !left;
    }
  }
  return false;
}

/// Zero-area triangles with three distinct corners: exactly collinear ones
/// (CGAL remove_degenerate_faces), then those whose area is round-off only
/// (CGAL's experimental remove_almost_degenerate_faces on just those).
void removeDegenerateTriangles(Surface& surface,
  double diagonal,
  const InputIndex& input,
  RepairLog& log,
  MeshRepairReport& report)
{
  std::vector<FaceIndex> degenerate;
  PMP::degenerate_faces(surface, std::back_inserter(degenerate));
  noteDegenerate(surface, degenerate, "zero-area", input, log);
  report.removedDegenerateTriangles += static_cast<int>(degenerate.size());
  if (!degenerate.empty() && !PMP::remove_degenerate_faces(surface))
  {
    log.note(Change::Degenerate, "some zero-area triangles could not be removed");
  }
  surface.collect_garbage();
  std::vector<FaceIndex> flat;
  for (FaceIndex f : surface.faces())
  {
    if (PMP::face_area(f, surface) <= DegenerateAreaTolerance * diagonal * diagonal)
    {
      flat.push_back(f);
    }
  }
  noteDegenerate(surface, flat, "nearly flat", input, log);
  report.removedDegenerateTriangles += static_cast<int>(flat.size());
  if (!flat.empty() && !PMP::experimental::remove_almost_degenerate_faces(
                         flat, surface, CapCosine, NeedleRatio, 0.0))
  {
    log.note(Change::Degenerate, "some nearly flat triangles could not be removed");
  }
  surface.collect_garbage();
  if (!collapseTinyTriangles(surface, DegenerateAreaTolerance * diagonal * diagonal))
  {
    log.note(Change::Degenerate, "some tiny triangles could not be removed");
  }
}

/// Per vertex of the surface: the input vertex whose attributes it takes,
/// and whether repair added it.
struct VertexSources
{
  Surface::Property_map<VertexIndex, int> source;
  Surface::Property_map<VertexIndex, bool> added;
};

VertexSources addVertexSources(Surface& surface, const InputIndex& input)
{
  VertexSources sources{ surface.add_property_map<VertexIndex, int>("v:source", -1).first,
    surface.add_property_map<VertexIndex, bool>("v:added", false).first };
  for (VertexIndex v : surface.vertices())
  {
    sources.source[v] = input.vertexAt(surface.point(v));
  }
  return sources;
}

struct HoleBorder
{
  HalfedgeIndex halfedge;
  std::vector<VertexIndex> vertices;
  double length = 0.0;
};

HoleBorder borderOf(const Surface& surface, HalfedgeIndex h)
{
  HoleBorder border{ h, {}, 0.0 };
  for (HalfedgeIndex g : CGAL::halfedges_around_face(h, surface))
  {
    border.vertices.push_back(surface.target(g));
    border.length += std::sqrt(CGAL::to_double(
      CGAL::squared_distance(surface.point(surface.source(g)), surface.point(surface.target(g)))));
  }
  return border;
}

std::string borderText(const HoleBorder& border,
  const VertexSources& sources,
  const InputIndex& input)
{
  std::vector<int> vertices;
  for (VertexIndex v : border.vertices)
  {
    vertices.push_back(sources.source[v]);
  }
  std::ostringstream out;
  out << border.vertices.size() << " border edges, length " << std::setprecision(4) << border.length
      << ", vertices " << listText(vertices, 6) << ", at "
      << input.vertexPlace(sources.source[border.vertices.front()]);
  return out.str();
}

/// Fills one hole (CGAL triangulate_hole, refined when asked); the vertices
/// it adds take the attributes of the nearest border vertex.
void fillHole(Surface& surface,
  const HoleBorder& border,
  bool refine,
  VertexSources& sources,
  MeshRepairReport& report)
{
  std::vector<FaceIndex> faces;
  std::vector<VertexIndex> vertices;
  if (refine)
  {
    PMP::triangulate_and_refine_hole(
      surface, border.halfedge, std::back_inserter(faces), std::back_inserter(vertices));
  }
  else
  {
    PMP::triangulate_hole(surface, border.halfedge, std::back_inserter(faces));
  }
  for (VertexIndex v : vertices)
  {
    const auto nearer = [&](VertexIndex a, VertexIndex b)
    {
      return CGAL::squared_distance(surface.point(v), surface.point(a)) <
             CGAL::squared_distance(surface.point(v), surface.point(b));
    };
    sources.source[v] =
      sources.source[*std::min_element(border.vertices.begin(), border.vertices.end(), nearer)];
    sources.added[v] = true;
  }
  report.addedTriangles += static_cast<int>(faces.size());
  report.addedVertices += static_cast<int>(vertices.size());
  if (faces.empty())
  {
    ++report.unfilledHoles;
  }
}

/// Fills holes whose border is short next to the mesh; leaves longer
/// borders open (they are openings of the shape) and reports both.
void fillSmallHoles(Surface& surface,
  const MeshRepairSettings& settings,
  double diagonal,
  VertexSources& sources,
  const InputIndex& input,
  RepairLog& log,
  MeshRepairReport& report)
{
  std::vector<HalfedgeIndex> cycles;
  PMP::extract_boundary_cycles(surface, std::back_inserter(cycles));
  std::vector<HoleBorder> borders;
  for (HalfedgeIndex h : cycles)
  {
    borders.push_back(borderOf(surface, h));
  }
  for (const HoleBorder& border : borders)
  {
    const int edges = static_cast<int>(border.vertices.size());
    const std::string where = borderText(border, sources, input);
    if (border.length > settings.maximumHoleFraction * diagonal ||
        edges > settings.maximumHoleEdges)
    {
      ++report.openBorders;
      report.openBorderEdges += edges;
      log.note(Change::OpenBorder, "left open (longer than a hole): a border of " + where);
      continue;
    }
    const int addedTriangles = report.addedTriangles;
    const int addedVertices = report.addedVertices;
    fillHole(surface, border, settings.refineFilledHoles, sources, report);
    if (report.addedTriangles == addedTriangles)
    {
      log.note(Change::Hole, "could not fill the hole with " + where);
      continue;
    }
    ++report.filledHoles;
    report.filledHoleBorderEdges += edges;
    log.note(Change::Hole,
      "filled the hole with " + where + ": " +
        counted(report.addedTriangles - addedTriangles, "triangle") + ", " +
        counted(report.addedVertices - addedVertices, "new vertex"));
  }
}

/// +1 / -1 when face f runs as / against its input triangle, 0 when new.
int faceAgainstInput(const Surface& surface,
  FaceIndex f,
  const VertexSources& sources,
  const InputIndex& input)
{
  Corners corners{ -1, -1, -1 };
  int k = 0;
  for (VertexIndex v : CGAL::vertices_around_face(surface.halfedge(f), surface))
  {
    if (sources.added[v])
    {
      return 0;
    }
    corners[k++] = sources.source[v];
  }
  const int t = input.triangleOf(corners);
  return t < 0 ? 0 : orientationAgainst(corners, input.corners(t));
}

/// A closed surface is turned to bound its volume (CGAL
/// orient_to_bound_a_volume); otherwise each piece takes the orientation
/// most of its input triangles had, since there is no inside to face away
/// from.
void orientPieces(Surface& surface,
  bool outward,
  const VertexSources& sources,
  const InputIndex& input)
{
  if (outward && CGAL::is_closed(surface))
  {
    PMP::orient_to_bound_a_volume(surface);
    return;
  }
  auto piece = surface.add_property_map<FaceIndex, std::size_t>("f:piece", 0).first;
  const std::size_t pieces = PMP::connected_components(surface, piece);
  std::vector<long> votes(pieces, 0);
  for (FaceIndex f : surface.faces())
  {
    votes[piece[f]] += faceAgainstInput(surface, f, sources, input);
  }
  std::vector<FaceIndex> reversed;
  for (FaceIndex f : surface.faces())
  {
    if (votes[piece[f]] < 0)
    {
      reversed.push_back(f);
    }
  }
  PMP::reverse_face_orientations(reversed, surface);
  surface.remove_property_map(piece);
}

/// The repaired surface as a TriangleMesh without attributes, and per
/// vertex and triangle where it came from in the input (-1: added).
struct RepairedMesh
{
  TriangleMesh mesh;
  std::vector<int> vertexSource;
  std::vector<char> vertexAdded;
  std::vector<int> triangleSource;
  std::vector<char> triangleFlipped;
};

/// Rotates `corners` (output indices) so that a kept triangle starts at the
/// same corner as its input triangle: untouched triangles stay identical,
/// and a flipped one is its input with the last two corners swapped.
Triangle alignedTriangle(const Triangle& corners, const Corners& sources, const Corners& input)
{
  for (int shift = 0; shift < 3; ++shift)
  {
    if (sources[shift] == input[0])
    {
      return { corners[shift], corners[(shift + 1) % 3], corners[(shift + 2) % 3] };
    }
  }
  return corners;
}

RepairedMesh meshOf(const Surface& surface,
  const VertexSources& sources,
  const InputIndex& input,
  RepairLog& log,
  MeshRepairReport& report)
{
  RepairedMesh repaired;
  repaired.mesh.name = input.mesh().name;
  // Surface indices count removed elements too (none remain after the
  // garbage collection of removeDegenerateTriangles; hole filling only adds).
  std::vector<int> number(surface.num_vertices(), -1);
  for (VertexIndex v : surface.vertices())
  {
    number[v.idx()] = static_cast<int>(repaired.mesh.positions.size());
    repaired.mesh.positions.push_back(vectorOf(surface.point(v)));
    repaired.vertexSource.push_back(sources.source[v]);
    repaired.vertexAdded.push_back(sources.added[v] ? 1 : 0);
  }
  for (FaceIndex f : surface.faces())
  {
    Triangle tri{};
    Corners corners{};
    int k = 0;
    for (VertexIndex v : CGAL::vertices_around_face(surface.halfedge(f), surface))
    {
      tri[k] = number[v.idx()];
      // An added vertex matches no input vertex (distinct negative values).
      corners[k] = sources.added[v] ? -1 - k : sources.source[v];
      ++k;
    }
    const int t = input.triangleOf(corners);
    const int orientation = t < 0 ? 0 : orientationAgainst(corners, input.corners(t));
    if (orientation < 0)
    {
      ++report.flippedTriangles;
      const Corners was = input.corners(t);
      log.note(Change::Flip,
        "flipped triangle " + std::to_string(t) + " (vertices " +
          listText({ was[0], was[1], was[2] }, 3) + ") at " + input.vertexPlace(was[0]));
    }
    repaired.mesh.triangles.push_back(
      orientation != 0 ? alignedTriangle(tri, corners, input.corners(t)) : tri);
    repaired.triangleSource.push_back(orientation == 0 ? -1 : t);
    repaired.triangleFlipped.push_back(orientation < 0 ? 1 : 0);
  }
  return repaired;
}

/// Input vertices that a degenerate triangle's edge collapse took away.
void noteCollapsedVertices(const RepairedMesh& repaired,
  const InputIndex& input,
  RepairLog& log,
  MeshRepairReport& report)
{
  const TriangleMesh& mesh = input.mesh();
  std::vector<char> kept(mesh.vertexCount(), 0);
  for (std::size_t v = 0; v < repaired.vertexSource.size(); ++v)
  {
    kept[repaired.vertexSource[v]] |= repaired.vertexAdded[v] ? 0 : 1;
  }
  std::vector<char> used(mesh.vertexCount(), 0);
  for (const Triangle& tri : mesh.triangles)
  {
    used[tri[0]] = used[tri[1]] = used[tri[2]] = 1;
  }
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    const int vi = static_cast<int>(v);
    if (used[v] && input.vertexAt(vi) == vi && !kept[v])
    {
      ++report.collapsedVertices;
      log.note(Change::Degenerate,
        "removed " + input.vertexPlace(vi) + ": an edge of a degenerate triangle collapsed");
    }
  }
}

/// Kept vertices keep their normals, except where a flipped triangle left a
/// normal pointing against the surface; added vertices get area-weighted
/// normals.
void carryNormals(const TriangleMesh& input,
  RepairedMesh& repaired,
  RepairLog& log,
  MeshRepairReport& report)
{
  TriangleMesh& mesh = repaired.mesh;
  std::vector<char> nearFlip(mesh.vertexCount(), 0);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    if (repaired.triangleFlipped[t])
    {
      nearFlip[mesh.triangles[t][0]] = nearFlip[mesh.triangles[t][1]] =
        nearFlip[mesh.triangles[t][2]] = 1;
    }
  }
  mesh.computeVertexNormals();
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
  {
    if (repaired.vertexAdded[v])
    {
      continue;
    }
    const Vector3 kept = input.normals[repaired.vertexSource[v]];
    if (nearFlip[v] && kept.dot(mesh.normals[v]) < 0.0)
    {
      ++report.reversedNormals;
      log.note(Change::Normal,
        "reversed the normal of vertex " + std::to_string(repaired.vertexSource[v]) +
          " (it pointed against the re-oriented triangles)");
      mesh.normals[v] = -kept;
      continue;
    }
    mesh.normals[v] = kept;
  }
}

/// Per-vertex arrays follow their vertex; added vertices copy their source.
void carryPointAttributes(const TriangleMesh& input, RepairedMesh& repaired)
{
  for (const std::string& name : input.pointAttributes.names())
  {
    const AttributeArray& from = input.pointAttributes.get(name);
    std::vector<double> values;
    values.reserve(repaired.vertexSource.size() * from.components);
    for (const int source : repaired.vertexSource)
    {
      values.insert(values.end(), from.element(source), from.element(source) + from.components);
    }
    repaired.mesh.pointAttributes.set(name, from.components, std::move(values));
  }
}

/// Kept triangles keep their texture corners; new triangles (hole filling,
/// edge flips) take, at each corner, the first texture coordinate the
/// source vertex had in the input.
void carryTextureCoordinates(const TriangleMesh& input, RepairedMesh& repaired)
{
  std::vector<int> firstCorner(input.vertexCount(), 0);
  for (std::size_t t = input.triangleCount(); t-- > 0;)
  {
    for (int k = 0; k < 3; ++k)
    {
      firstCorner[input.triangles[t][k]] = input.textureCorners[t][k];
    }
  }
  TriangleMesh& mesh = repaired.mesh;
  mesh.textureCoordinates = input.textureCoordinates;
  mesh.textureCorners.resize(mesh.triangleCount());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const int source = repaired.triangleSource[t];
    for (int k = 0; k < 3; ++k)
    {
      const int vertex = repaired.vertexSource[mesh.triangles[t][k]];
      int corner = firstCorner[vertex];
      for (int j = 0; source >= 0 && j < 3; ++j)
      {
        corner = input.triangles[source][j] == vertex ? input.textureCorners[source][j] : corner;
      }
      mesh.textureCorners[t][k] = corner;
    }
  }
}

} // namespace

bool MeshRepairReport::changed() const
{
  return mergedCoincidentVertices + removedUnreferencedVertices + removedDegenerateTriangles +
           collapsedVertices + removedDuplicateTriangles + nonManifoldVertices +
           splitNonManifoldVertices + nonManifoldEdges + filledHoles + addedTriangles +
           addedVertices + flippedTriangles + reversedNormals >
         0;
}

std::string MeshRepairReport::summary() const
{
  // Only what happened, so that a short repair reads short.
  std::vector<std::string> parts;
  const auto add = [&parts](int count, const std::string& text)
  {
    if (count > 0)
    {
      parts.push_back(text);
    }
  };
  add(mergedCoincidentVertices, "merged " + counted(mergedCoincidentVertices, "coincident vertex"));
  add(removedUnreferencedVertices,
    "removed " + counted(removedUnreferencedVertices, "unreferenced vertex"));
  add(removedDegenerateTriangles,
    "removed " + counted(removedDegenerateTriangles, "degenerate triangle"));
  add(collapsedVertices,
    "removed " + counted(collapsedVertices, "vertex") + " with degenerate triangles");
  add(removedDuplicateTriangles,
    "removed " + counted(removedDuplicateTriangles, "duplicate triangle"));
  add(nonManifoldVertices,
    "split " + counted(nonManifoldVertices, "non-manifold vertex") + " (" +
      counted(splitNonManifoldVertices, "vertex") + " added)");
  add(nonManifoldEdges,
    "separated the triangles at " + counted(nonManifoldEdges, "non-manifold edge"));
  add(filledHoles,
    "filled " + counted(filledHoles, "hole") + " (" +
      counted(filledHoleBorderEdges, "border edge") + "; " + counted(addedTriangles, "triangle") +
      " and " + counted(addedVertices, "vertex") + " added)");
  add(flippedTriangles, "flipped " + counted(flippedTriangles, "triangle"));
  add(reversedNormals, "reversed " + counted(reversedNormals, "normal"));
  add(openBorders,
    "left open " + counted(openBorders, "border") + " longer than a hole (" +
      counted(openBorderEdges, "edge") + ")");
  add(unfilledHoles, "could not fill " + counted(unfilledHoles, "hole"));
  std::string text = "repair of mesh '" + meshName + "': ";
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    text += (i > 0 ? "; " : "") + parts[i];
  }
  text += parts.empty() ? "nothing to repair\n" : "\n";
  for (const std::string& change : changes)
  {
    text += "  " + change + "\n";
  }
  return text;
}

std::string MeshRepairReport::toJson() const
{
  nlohmann::json json;
  json["mergedCoincidentVertices"] = mergedCoincidentVertices;
  json["removedUnreferencedVertices"] = removedUnreferencedVertices;
  json["removedDegenerateTriangles"] = removedDegenerateTriangles;
  json["collapsedVertices"] = collapsedVertices;
  json["removedDuplicateTriangles"] = removedDuplicateTriangles;
  json["nonManifoldVertices"] = nonManifoldVertices;
  json["splitNonManifoldVertices"] = splitNonManifoldVertices;
  json["nonManifoldEdges"] = nonManifoldEdges;
  json["filledHoles"] = filledHoles;
  json["filledHoleBorderEdges"] = filledHoleBorderEdges;
  json["addedTriangles"] = addedTriangles;
  json["addedVertices"] = addedVertices;
  json["openBorders"] = openBorders;
  json["openBorderEdges"] = openBorderEdges;
  json["unfilledHoles"] = unfilledHoles;
  json["flippedTriangles"] = flippedTriangles;
  json["reversedNormals"] = reversedNormals;
  json["changes"] = changes;
  return json.dump();
}

TriangleMesh repairTriangleMesh(const TriangleMesh& mesh,
  const MeshRepairSettings& settings,
  MeshRepairReport* report)
{
  mesh.checkConsistency();
  MeshRepairReport local;
  MeshRepairReport& out = report ? *report : local;
  out = MeshRepairReport{};
  out.meshName = mesh.name;
  RepairLog log(out, settings.maximumListedPerKind);
  const InputIndex input(mesh);
  Soup soup = soupOf(mesh);
  cleanSoup(soup, input, log, out);
  orientSoup(soup, input, log, out);
  Surface surface = surfaceOf(soup, mesh.name);
  splitPinchedVertices(surface, input, log, out);
  removeDegenerateTriangles(surface, diagonalOf(mesh), input, log, out);
  VertexSources sources = addVertexSources(surface, input);
  fillSmallHoles(surface, settings, diagonalOf(mesh), sources, input, log, out);
  orientPieces(surface, settings.orientOutward, sources, input);
  RepairedMesh repaired = meshOf(surface, sources, input, log, out);
  noteCollapsedVertices(repaired, input, log, out);
  if (mesh.hasNormals())
  {
    carryNormals(mesh, repaired, log, out);
  }
  carryPointAttributes(mesh, repaired);
  if (mesh.hasTextureCoordinates())
  {
    carryTextureCoordinates(mesh, repaired);
  }
  log.finish();
  // Nothing changed: hand back the input itself, not an equal copy made
  // through CGAL (vertex order and first corners are then certainly kept).
  return out.changed() ? repaired.mesh : mesh;
}

TriangleMesh closeOpeningsKeepLargest(const TriangleMesh& mesh)
{
  MeshRepairSettings settings;
  settings.maximumListedPerKind = 0;
  settings.maximumHoleFraction = 2.0;
  settings.maximumHoleEdges = 2000;
  TriangleMesh closed = repairTriangleMesh(mesh, settings);
  if (countPieces(closed) > 1)
    closed = std::move(splitIntoPieces(closed).front().mesh);
  closed.name = mesh.name;
  return closed;
}

} // namespace thintissue
