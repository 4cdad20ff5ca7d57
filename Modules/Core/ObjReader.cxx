// Wavefront OBJ parser. OBJ indexes positions, texture coordinates and
// normals separately, so positions stay welded across texture seams and the
// texture coordinates are kept per triangle corner, exactly as in the file.
#include "MeshImport.h"
#include "ThinTissueError.h"

#include <charconv>
#include <cmath>
#include <string_view>

namespace thintissue
{
namespace
{

class ObjParser
{
public:
  ObjParser(const std::string& text, const std::string& name)
    : Text(text)
    , Name(name)
  {
  }

  TriangleMesh parse()
  {
    TriangleMesh mesh;
    mesh.name = Name;
    std::vector<Vector3> fileNormals;
    std::vector<std::array<int, 3>> cornerNormals; // per triangle corner, -1 if none
    bool anyTexture = false;
    bool anyCornerWithoutTexture = false;
    std::vector<Corner> polygon;

    std::size_t position = 0;
    while (position < Text.size())
    {
      ++LineNumber;
      std::size_t end = Text.find('\n', position);
      if (end == std::string::npos)
      {
        end = Text.size();
      }
      Line = std::string_view(Text).substr(position, end - position);
      position = end + 1;
      if (!Line.empty() && Line.back() == '\r')
      {
        Line.remove_suffix(1);
      }
      skipSpaces();
      const std::string_view keyword = nextToken();
      if (keyword == "v")
      {
        // Separate statements: argument evaluation order is unspecified.
        const double x = readNumber();
        const double y = readNumber();
        const double z = readNumber();
        mesh.positions.emplace_back(x, y, z);
      }
      else if (keyword == "vt")
      {
        const double u = readNumber();
        skipSpaces();
        const double v = Line.empty() ? 0.0 : readNumber();
        mesh.textureCoordinates.emplace_back(u, v);
      }
      else if (keyword == "vn")
      {
        const double x = readNumber();
        const double y = readNumber();
        const double z = readNumber();
        fileNormals.emplace_back(x, y, z);
      }
      else if (keyword == "f")
      {
        polygon.clear();
        skipSpaces();
        while (!Line.empty())
        {
          polygon.push_back(
            readCorner(mesh.positions.size(), mesh.textureCoordinates.size(), fileNormals.size()));
          skipSpaces();
        }
        if (polygon.size() < 3)
        {
          fail("face with " + std::to_string(polygon.size()) + " vertices (at least 3 needed)");
        }
        // Fan triangulation: quads and convex polygons of modelling tools.
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
        {
          const Corner& a = polygon[0];
          const Corner& b = polygon[k];
          const Corner& c = polygon[k + 1];
          mesh.triangles.push_back({ a.position, b.position, c.position });
          mesh.textureCorners.push_back({ a.texture, b.texture, c.texture });
          cornerNormals.push_back({ a.normal, b.normal, c.normal });
          for (const Corner* corner : { &a, &b, &c })
          {
            anyTexture |= corner->texture >= 0;
            anyCornerWithoutTexture |= corner->texture < 0;
          }
        }
      }
      // Other statements (o, g, s, usemtl, mtllib, l, p, comments) carry no
      // surface geometry.
    }

    if (!anyTexture)
    {
      mesh.textureCorners.clear();
    }
    else if (anyCornerWithoutTexture)
    {
      // Mixed faces: give untextured corners an explicit (0, 0) coordinate.
      const int fallback = static_cast<int>(mesh.textureCoordinates.size());
      mesh.textureCoordinates.emplace_back(0.0, 0.0);
      for (auto& corners : mesh.textureCorners)
      {
        for (int& c : corners)
        {
          c = c < 0 ? fallback : c;
        }
      }
    }
    assignVertexNormals(mesh, fileNormals, cornerNormals);
    return mesh;
  }

private:
  struct Corner
  {
    int position = -1;
    int texture = -1;
    int normal = -1;
  };

  [[noreturn]] void fail(const std::string& problem) const
  {
    throw FileError(Name, "line " + std::to_string(LineNumber) + ": " + problem);
  }

  void skipSpaces()
  {
    std::size_t i = 0;
    while (i < Line.size() && (Line[i] == ' ' || Line[i] == '\t'))
    {
      ++i;
    }
    Line.remove_prefix(i);
  }

  std::string_view nextToken()
  {
    std::size_t i = 0;
    while (i < Line.size() && Line[i] != ' ' && Line[i] != '\t')
    {
      ++i;
    }
    const std::string_view token = Line.substr(0, i);
    Line.remove_prefix(i);
    return token;
  }

  double readNumber()
  {
    skipSpaces();
    double value = 0.0;
    if (!Line.empty() && Line[0] == '+')
    {
      Line.remove_prefix(1); // from_chars does not accept an explicit plus
    }
    const char* begin = Line.data();
    const char* end = begin + Line.size();
    const auto result = std::from_chars(begin, end, value);
    if (result.ec != std::errc() ||
        (result.ptr != end && *result.ptr != ' ' && *result.ptr != '\t'))
    {
      // from_chars rejects "nan"/"inf" spelt differently; name the token.
      const std::string_view token = nextToken();
      const std::string text(token);
      if (text == "nan" || text == "NaN" || text == "inf" || text == "-inf")
      {
        fail("non-finite coordinate '" + text + "'");
      }
      fail("expected a number, found '" + text + "'");
    }
    if (!std::isfinite(value))
    {
      fail("non-finite coordinate");
    }
    Line.remove_prefix(static_cast<std::size_t>(result.ptr - begin));
    return value;
  }

  /// Resolves a 1-based (or negative, relative) OBJ index into 0-based.
  int resolveIndex(long long index, std::size_t count, const char* what, const char* plural) const
  {
    const long long resolved = index > 0 ? index - 1 : static_cast<long long>(count) + index;
    if (index == 0 || resolved < 0 || resolved >= static_cast<long long>(count))
    {
      fail(std::string("face ") + what + " index " + std::to_string(index) + " out of range (" +
           std::to_string(count) + " " + (count == 1 ? what : plural) + " defined so far)");
    }
    return static_cast<int>(resolved);
  }

  long long readInteger(std::string_view token, const char* what) const
  {
    long long value = 0;
    const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
    if (result.ec != std::errc() || result.ptr != token.data() + token.size())
    {
      fail(std::string("malformed face ") + what + " index '" + std::string(token) + "'");
    }
    return value;
  }

  Corner readCorner(std::size_t positions, std::size_t textures, std::size_t normals)
  {
    const std::string_view token = nextToken();
    Corner corner;
    const std::size_t slash1 = token.find('/');
    corner.position =
      resolveIndex(readInteger(token.substr(0, slash1), "vertex"), positions, "vertex", "vertices");
    if (slash1 != std::string_view::npos)
    {
      const std::string_view rest = token.substr(slash1 + 1);
      const std::size_t slash2 = rest.find('/');
      const std::string_view texture = rest.substr(0, slash2);
      if (!texture.empty())
      {
        corner.texture = resolveIndex(readInteger(texture, "texture coordinate"),
          textures,
          "texture coordinate",
          "texture coordinates");
      }
      if (slash2 != std::string_view::npos && slash2 + 1 < rest.size())
      {
        corner.normal = resolveIndex(
          readInteger(rest.substr(slash2 + 1), "normal"), normals, "normal", "normals");
      }
    }
    return corner;
  }

  /// Vertex normals from the file's per-corner normals (averaged where a
  /// vertex has several, e.g. at hard edges); none if any corner lacks one.
  static void assignVertexNormals(TriangleMesh& mesh,
    const std::vector<Vector3>& fileNormals,
    const std::vector<std::array<int, 3>>& cornerNormals)
  {
    if (fileNormals.empty())
    {
      return;
    }
    std::vector<Vector3> sums(mesh.positions.size(), Vector3::Zero());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (cornerNormals[t][k] < 0)
        {
          return;
        }
        sums[mesh.triangles[t][k]] += fileNormals[cornerNormals[t][k]];
      }
    }
    for (Vector3& n : sums)
    {
      const double length = n.norm();
      n = length > 0.0 ? Vector3(n / length) : Vector3::UnitZ();
    }
    mesh.normals = std::move(sums);
  }

  const std::string& Text;
  const std::string& Name;
  std::string_view Line;
  std::size_t LineNumber = 0;
};

} // namespace

TriangleMesh parseObj(const std::string& text, const std::string& name)
{
  return ObjParser(text, name).parse();
}

} // namespace thintissue
