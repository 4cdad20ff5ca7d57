// Stanford PLY reader of MeshImport (ASCII and binary, either byte order):
// assimp's PLY loader misreads some binary files that VTK writes (a
// segmented meniscus of 32,928 triangles came back with 7 empty faces and
// a point, and its triangulation step then aborted the process), so PLY is
// read here, with every problem a FileError naming the file.
#include "MeshImport.h"
#include "MeshImportPrivate.h"
#include "ThinTissueError.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>

namespace thintissue
{
namespace
{

enum class PlyFormat
{
  Ascii,
  BinaryLittleEndian,
  BinaryBigEndian
};

/// A scalar type of the header: its size in bytes and whether it is
/// integral, signed.
struct PlyScalar
{
  int size = 0;
  bool integral = false;
  bool isSigned = false;
};

struct PlyProperty
{
  std::string name;
  PlyScalar type;
  bool list = false;
  PlyScalar countType; ///< of a list's length
};

struct PlyElement
{
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader
{
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t dataStart = 0; ///< byte offset after "end_header\n"
};

bool scalarNamed(const std::string& name, PlyScalar& type)
{
  static const std::map<std::string, PlyScalar> types{ { "char", { 1, true, true } },
    { "int8", { 1, true, true } },
    { "uchar", { 1, true, false } },
    { "uint8", { 1, true, false } },
    { "short", { 2, true, true } },
    { "int16", { 2, true, true } },
    { "ushort", { 2, true, false } },
    { "uint16", { 2, true, false } },
    { "int", { 4, true, true } },
    { "int32", { 4, true, true } },
    { "uint", { 4, true, false } },
    { "uint32", { 4, true, false } },
    { "float", { 4, false, true } },
    { "float32", { 4, false, true } },
    { "double", { 8, false, true } },
    { "float64", { 8, false, true } } };
  const auto found = types.find(name);
  if (found == types.end())
  {
    return false;
  }
  type = found->second;
  return true;
}

PlyProperty parseProperty(std::istringstream& words, const std::string& path, int line)
{
  PlyProperty property;
  std::string type;
  words >> type;
  if (type == "list")
  {
    std::string countType;
    words >> countType >> type;
    property.list = true;
    if (!scalarNamed(countType, property.countType) || !property.countType.integral)
    {
      throw FileError(path,
        "PLY header line " + std::to_string(line) + ": bad list length type '" + countType + "'");
    }
  }
  if (!scalarNamed(type, property.type))
  {
    throw FileError(
      path, "PLY header line " + std::to_string(line) + ": unknown property type '" + type + "'");
  }
  words >> property.name;
  return property;
}

PlyHeader parseHeader(const std::string& bytes, const std::string& path)
{
  if (bytes.compare(0, 4, "ply\n") != 0 && bytes.compare(0, 5, "ply\r\n") != 0)
  {
    throw FileError(path, "cannot be parsed: not a PLY file (no 'ply' line first)");
  }
  PlyHeader header;
  bool formatSeen = false;
  std::size_t position = 0;
  for (int line = 1;; ++line)
  {
    const std::size_t end = bytes.find('\n', position);
    if (end == std::string::npos)
    {
      throw FileError(path, "cannot be parsed: the PLY header has no 'end_header' line");
    }
    std::string text = bytes.substr(position, end - position);
    position = end + 1;
    if (!text.empty() && text.back() == '\r')
    {
      text.pop_back();
    }
    std::istringstream words(text);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header")
    {
      break;
    }
    if (keyword == "format")
    {
      std::string format;
      words >> format;
      formatSeen = true;
      if (format == "ascii")
        header.format = PlyFormat::Ascii;
      else if (format == "binary_little_endian")
        header.format = PlyFormat::BinaryLittleEndian;
      else if (format == "binary_big_endian")
        header.format = PlyFormat::BinaryBigEndian;
      else
        throw FileError(
          path, "PLY header line " + std::to_string(line) + ": unknown format '" + format + "'");
    }
    else if (keyword == "element")
    {
      PlyElement element;
      long long count = -1;
      words >> element.name >> count;
      if (element.name.empty() || count < 0)
      {
        throw FileError(path, "PLY header line " + std::to_string(line) + ": bad element");
      }
      element.count = static_cast<std::size_t>(count);
      header.elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (header.elements.empty())
      {
        throw FileError(
          path, "PLY header line " + std::to_string(line) + ": a property before any element");
      }
      header.elements.back().properties.push_back(parseProperty(words, path, line));
    }
    else if (!keyword.empty() && keyword != "comment" && keyword != "obj_info" && line > 1)
    {
      throw FileError(
        path, "PLY header line " + std::to_string(line) + ": unknown keyword '" + keyword + "'");
    }
  }
  if (!formatSeen)
  {
    throw FileError(path, "cannot be parsed: the PLY header has no 'format' line");
  }
  header.dataStart = position;
  return header;
}

/// Reads the values of the body, one at a time, in the file's format.
class PlyBody
{
public:
  PlyBody(const std::string& bytes, const PlyHeader& header, const std::string& path)
    : Bytes(bytes)
    , Format(header.format)
    , Path(path)
    , Position(header.dataStart)
  {
  }

  double next(const PlyScalar& type)
  {
    return Format == PlyFormat::Ascii ? nextWord() : nextBinary(type);
  }

  /// The length of a list: a count of the list's length type.
  std::size_t nextLength(const PlyScalar& type)
  {
    const double length = next(type);
    if (!(length >= 0.0 && length <= 1e9) || length != std::floor(length))
    {
      std::ostringstream text;
      text << "PLY data: bad list length " << length;
      throw FileError(Path, text.str());
    }
    return static_cast<std::size_t>(length);
  }

private:
  double nextWord()
  {
    while (Position < Bytes.size() && std::isspace(static_cast<unsigned char>(Bytes[Position])))
    {
      ++Position;
    }
    const char* begin = Bytes.c_str() + Position;
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin)
    {
      throw FileError(Path,
        "PLY data: expected a number at byte " + std::to_string(Position) +
          (Position >= Bytes.size() ? " (the file ends early)" : ""));
    }
    Position += static_cast<std::size_t>(end - begin);
    return value;
  }

  double nextBinary(const PlyScalar& type)
  {
    if (Position + static_cast<std::size_t>(type.size) > Bytes.size())
    {
      throw FileError(Path,
        "PLY data: the file ends early (byte " + std::to_string(Position) + " of " +
          std::to_string(Bytes.size()) + ")");
    }
    unsigned char raw[8];
    std::memcpy(raw, Bytes.data() + Position, static_cast<std::size_t>(type.size));
    Position += static_cast<std::size_t>(type.size);
    const bool bigEndian = Format == PlyFormat::BinaryBigEndian;
    std::uint64_t bits = 0;
    for (int k = 0; k < type.size; ++k)
    {
      const int index = bigEndian ? k : type.size - 1 - k;
      bits = (bits << 8) | raw[index];
    }
    if (!type.integral)
    {
      if (type.size == 4)
      {
        const auto narrow = static_cast<std::uint32_t>(bits);
        float value = 0.0f;
        std::memcpy(&value, &narrow, sizeof(value));
        return value;
      }
      double value = 0.0;
      std::memcpy(&value, &bits, sizeof(value));
      return value;
    }
    if (type.isSigned && type.size < 8 && (bits >> (8 * type.size - 1)) != 0)
    {
      return static_cast<double>(
        static_cast<std::int64_t>(bits) - (static_cast<std::int64_t>(1) << (8 * type.size)));
    }
    return static_cast<double>(bits);
  }

  const std::string& Bytes;
  PlyFormat Format;
  const std::string& Path;
  std::size_t Position;
};

/// Index of the first of `names` among the element's scalar properties, or
/// -1.
int propertyIndex(const PlyElement& element, std::initializer_list<const char*> names)
{
  for (const char* name : names)
  {
    for (std::size_t k = 0; k < element.properties.size(); ++k)
    {
      if (!element.properties[k].list && element.properties[k].name == name)
      {
        return static_cast<int>(k);
      }
    }
  }
  return -1;
}

/// Per-vertex positions, normals and texture coordinates.
struct PlyVertices
{
  std::vector<Vector3> positions;
  std::vector<Vector3> normals;
  std::vector<Vector2> textureCoordinates;
};

PlyVertices readVertices(PlyBody& body, const PlyElement& element, const std::string& path)
{
  const int x = propertyIndex(element, { "x" });
  const int y = propertyIndex(element, { "y" });
  const int z = propertyIndex(element, { "z" });
  if (x < 0 || y < 0 || z < 0)
  {
    throw FileError(path, "PLY vertex element without x, y and z properties");
  }
  const std::array<int, 3> normal{ { propertyIndex(element, { "nx" }),
    propertyIndex(element, { "ny" }),
    propertyIndex(element, { "nz" }) } };
  const std::array<int, 2> uv{ { propertyIndex(element, { "u", "s", "texture_u", "texture_s" }),
    propertyIndex(element, { "v", "t", "texture_v", "texture_t" }) } };
  const bool hasNormals = normal[0] >= 0 && normal[1] >= 0 && normal[2] >= 0;
  const bool hasUv = uv[0] >= 0 && uv[1] >= 0;
  PlyVertices vertices;
  std::vector<double> values(element.properties.size());
  for (std::size_t v = 0; v < element.count; ++v)
  {
    for (std::size_t k = 0; k < element.properties.size(); ++k)
    {
      const PlyProperty& property = element.properties[k];
      if (property.list)
      {
        const std::size_t length = body.nextLength(property.countType);
        for (std::size_t i = 0; i < length; ++i)
        {
          body.next(property.type);
        }
        continue;
      }
      values[k] = body.next(property.type);
    }
    vertices.positions.emplace_back(values[x], values[y], values[z]);
    if (hasNormals)
    {
      vertices.normals.emplace_back(values[normal[0]], values[normal[1]], values[normal[2]]);
    }
    if (hasUv)
    {
      vertices.textureCoordinates.emplace_back(values[uv[0]], values[uv[1]]);
    }
  }
  return vertices;
}

/// The faces' corner lists, fan-triangulated; points and lines dropped.
std::vector<Triangle> readFaces(PlyBody& body, const PlyElement& element, const std::string& path)
{
  int indices = -1;
  for (std::size_t k = 0; k < element.properties.size(); ++k)
  {
    const PlyProperty& property = element.properties[k];
    if (property.list && (property.name == "vertex_indices" || property.name == "vertex_index"))
    {
      indices = static_cast<int>(k);
    }
  }
  if (indices < 0)
  {
    throw FileError(path, "PLY face element without a vertex_indices list");
  }
  std::vector<Triangle> triangles;
  std::vector<int> corners;
  for (std::size_t f = 0; f < element.count; ++f)
  {
    for (std::size_t k = 0; k < element.properties.size(); ++k)
    {
      const PlyProperty& property = element.properties[k];
      if (!property.list)
      {
        body.next(property.type);
        continue;
      }
      const std::size_t length = body.nextLength(property.countType);
      corners.clear();
      for (std::size_t i = 0; i < length; ++i)
      {
        const double index = body.next(property.type);
        if (static_cast<int>(k) == indices)
        {
          if (!(index >= 0.0 && index < 2147483647.0))
          {
            throw FileError(path,
              "PLY face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                " out of range");
          }
          corners.push_back(static_cast<int>(index));
        }
      }
      for (std::size_t c = 2; static_cast<int>(k) == indices && c < corners.size(); ++c)
      {
        triangles.push_back({ { corners[0], corners[c - 1], corners[c] } });
      }
    }
  }
  return triangles;
}

/// Vertices at bitwise identical positions merged (the same welding as the
/// other readers): triangles re-indexed, attributes of the first kept.
void weldIdenticalPositions(TriangleMesh& mesh)
{
  std::map<std::array<double, 3>, int> first;
  std::vector<int> map(mesh.positions.size());
  std::vector<Vector3> positions;
  std::vector<Vector3> normals;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
  {
    const Vector3& p = mesh.positions[v];
    // +0 and -0 are one position.
    const std::array<double, 3> key{ { p.x() + 0.0, p.y() + 0.0, p.z() + 0.0 } };
    const auto [it, inserted] = first.emplace(key, static_cast<int>(positions.size()));
    map[v] = it->second;
    if (inserted)
    {
      positions.push_back(p);
      if (!mesh.normals.empty())
      {
        normals.push_back(mesh.normals[v]);
      }
    }
  }
  if (positions.size() == mesh.positions.size())
  {
    return;
  }
  for (Triangle& t : mesh.triangles)
  {
    for (int& corner : t)
    {
      corner = map[static_cast<std::size_t>(corner)];
    }
  }
  // Texture coordinates stay per original vertex (a seam keeps both).
  mesh.positions = std::move(positions);
  mesh.normals = std::move(normals);
}

} // namespace

namespace detail
{

TriangleMesh parsePly(const std::string& bytes, const std::string& path, bool weld)
{
  const PlyHeader header = parseHeader(bytes, path);
  PlyBody body(bytes, header, path);
  PlyVertices vertices;
  std::vector<Triangle> triangles;
  for (const PlyElement& element : header.elements)
  {
    if (element.name == "vertex")
    {
      vertices = readVertices(body, element, path);
    }
    else if (element.name == "face")
    {
      triangles = readFaces(body, element, path);
    }
    else
    {
      for (std::size_t i = 0; i < element.count; ++i)
      {
        for (const PlyProperty& property : element.properties)
        {
          const std::size_t length = property.list ? body.nextLength(property.countType) : 1;
          for (std::size_t k = 0; k < length; ++k)
          {
            body.next(property.type);
          }
        }
      }
    }
  }
  TriangleMesh mesh;
  mesh.name = path;
  mesh.positions = std::move(vertices.positions);
  mesh.triangles = std::move(triangles);
  mesh.normals = std::move(vertices.normals);
  if (!vertices.textureCoordinates.empty())
  {
    mesh.textureCorners = mesh.triangles;
    mesh.textureCoordinates = std::move(vertices.textureCoordinates);
  }
  if (weld)
  {
    weldIdenticalPositions(mesh);
  }
  return mesh;
}

} // namespace detail
} // namespace thintissue
