#include "BindingCache.h"

#include "AtomicFileWriter.h"
#include "ThinTissueError.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <type_traits>

namespace thintissue
{

namespace
{

constexpr char Magic[8] = { 'T', 'T', 'B', 'I', 'N', 'D', '\r', '\n' };

/// 64-bit FNV-1a over bytes.
class Checksum
{
public:
  void add(const void* data, std::size_t size)
  {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
    {
      Hash = (Hash ^ bytes[i]) * 1099511628211ull;
    }
  }
  std::uint64_t value() const { return Hash; }

private:
  std::uint64_t Hash = 14695981039346656037ull;
};

/// Little binary writer into a byte buffer (the platforms we build on are
/// little-endian; the magic's "\r\n" catches text-mode mangling).
class Writer
{
public:
  template <typename T>
  void pod(const T& value)
  {
    static_assert(std::is_standard_layout<T>::value, "plain data only");
    const auto* bytes = reinterpret_cast<const char*>(&value);
    Bytes.insert(Bytes.end(), bytes, bytes + sizeof(T));
  }
  template <typename T>
  void vector(const std::vector<T>& values)
  {
    // Fixed-size Eigen vectors and std::arrays of numbers: no padding.
    static_assert(std::is_standard_layout<T>::value, "plain data only");
    pod(static_cast<std::uint64_t>(values.size()));
    const auto* bytes = reinterpret_cast<const char*>(values.data());
    Bytes.insert(Bytes.end(), bytes, bytes + values.size() * sizeof(T));
  }
  void string(const std::string& s)
  {
    pod(static_cast<std::uint64_t>(s.size()));
    Bytes.insert(Bytes.end(), s.begin(), s.end());
  }
  void attributes(const VertexAttributes& attributes)
  {
    const auto names = attributes.names();
    pod(static_cast<std::uint64_t>(names.size()));
    for (const auto& name : names)
    {
      string(name);
      pod(static_cast<std::int32_t>(attributes.get(name).components));
      vector(attributes.get(name).values);
    }
  }
  void mesh(const TriangleMesh& m)
  {
    string(m.name);
    vector(m.positions);
    vector(m.triangles);
    vector(m.normals);
    vector(m.textureCoordinates);
    vector(m.textureCorners);
    attributes(m.pointAttributes);
  }
  std::vector<char> Bytes;
};

/// The matching reader: every read is bounds-checked; a short or
/// inconsistent buffer throws (caught by readBindingCache: "damaged").
class Reader
{
public:
  explicit Reader(const std::vector<char>& bytes)
    : Bytes(bytes)
  {
  }
  template <typename T>
  T pod()
  {
    T value;
    take(&value, sizeof(T));
    return value;
  }
  template <typename T>
  std::vector<T> vector()
  {
    const auto size = pod<std::uint64_t>();
    if (size > (Bytes.size() - Position) / sizeof(T))
    {
      throw Error("array longer than the file");
    }
    std::vector<T> values(static_cast<std::size_t>(size));
    take(values.data(), values.size() * sizeof(T));
    return values;
  }
  std::string string()
  {
    const auto chars = vector<char>();
    return std::string(chars.begin(), chars.end());
  }
  VertexAttributes attributes()
  {
    VertexAttributes attributes;
    const auto count = pod<std::uint64_t>();
    for (std::uint64_t k = 0; k < count; ++k)
    {
      const std::string name = string();
      const auto components = pod<std::int32_t>();
      attributes.set(name, components, vector<double>());
    }
    return attributes;
  }
  TriangleMesh mesh()
  {
    TriangleMesh m;
    m.name = string();
    m.positions = vector<Vector3>();
    m.triangles = vector<Triangle>();
    m.normals = vector<Vector3>();
    m.textureCoordinates = vector<Vector2>();
    m.textureCorners = vector<Triangle>();
    m.pointAttributes = attributes();
    m.checkConsistency();
    return m;
  }
  bool atEnd() const { return Position == Bytes.size(); }

private:
  void take(void* out, std::size_t size)
  {
    if (size == 0)
    {
      return; // an empty vector or string: `out` may be null
    }
    if (size > Bytes.size() - Position)
    {
      throw Error("the file ends early");
    }
    std::memcpy(out, Bytes.data() + Position, size);
    Position += size;
  }
  const std::vector<char>& Bytes;
  std::size_t Position = 0;
};

void addMesh(Checksum& sum, const TriangleMesh& m)
{
  Writer w;
  // The name is not content: a renamed file is the same mesh.
  w.vector(m.positions);
  w.vector(m.triangles);
  w.vector(m.normals);
  w.vector(m.textureCoordinates);
  w.vector(m.textureCorners);
  w.attributes(m.pointAttributes);
  sum.add(w.Bytes.data(), w.Bytes.size());
}

struct FileHeader
{
  char magic[8];
  std::uint32_t version;
  std::uint32_t hasSimulation;
  std::uint64_t inputChecksum;
  std::uint64_t payloadSize;
  std::uint64_t payloadChecksum;
};

/// Sizes and indices that the binding's users rely on.
void checkBinding(const VisualCollisionBinding& b)
{
  const std::size_t visualVertices = b.visual.vertexCount();
  const std::size_t visualTriangles = b.visual.triangleCount();
  const auto collisionVertices = static_cast<int>(b.collisionPositions.size());
  const auto collisionTriangles = static_cast<int>(b.collisionTriangles.size());
  const auto edges = static_cast<int>(b.collisionEdges.size());
  auto require = [](bool ok, const char* what)
  {
    if (!ok)
    {
      throw Error(what);
    }
  };
  require(b.vertices.size() == visualVertices, "one binding per visual vertex");
  require(b.triangleRegion.size() == visualTriangles && b.triangleSide.size() == visualTriangles,
    "one region per visual triangle");
  require(
    b.pairedVisualVertices.size() == b.collisionPositions.size(), "one pair per collision vertex");
  require(b.creaseVisualVertices.size() == b.collisionPositions.size(),
    "one crease entry per collision vertex");
  for (int v : b.creaseVisualVertices)
  {
    require(v >= -1 && v < static_cast<int>(visualVertices), "crease vertex in range");
  }
  require(
    b.collisionRadii.size() == b.collisionPositions.size(), "one radius per collision vertex");
  for (const Triangle& t : b.collisionTriangles)
  {
    for (int v : t)
    {
      require(v >= 0 && v < collisionVertices, "collision triangle index in range");
    }
  }
  for (const auto& e : b.collisionEdges)
  {
    require(e[0] >= 0 && e[0] < e[1] && e[1] < collisionVertices, "collision edge in range");
  }
  for (const auto& pair : b.pairedVisualVertices)
  {
    for (int v : pair)
    {
      require(v >= 0 && static_cast<std::size_t>(v) < visualVertices, "paired vertex in range");
    }
  }
  for (const VisualVertexBinding& v : b.vertices)
  {
    const int limit = v.kind == BindingKind::CollisionVertex ? collisionVertices
                      : v.kind == BindingKind::CollisionEdge ? edges
                                                             : collisionTriangles;
    require(static_cast<int>(v.kind) <= 2 && v.element >= 0 && v.element < limit && v.side >= -1 &&
              v.side <= 1 && v.parameters.allFinite(),
      "vertex binding in range");
  }
  for (std::size_t t = 0; t < visualTriangles; ++t)
  {
    require(b.triangleRegion[t] >= 0 && b.triangleRegion[t] < collisionTriangles,
      "triangle region in range");
  }
  for (const BindingPath& p : b.paths)
  {
    require(p.collisionEdge >= 0 && p.collisionEdge < edges && p.side >= -1 && p.side <= 1,
      "path edge in range");
    require(p.detours >= 0 && static_cast<std::size_t>(p.detours) <= p.visualVertices.size(),
      "path detours in range");
    for (int v : p.visualVertices)
    {
      require(v >= 0 && static_cast<std::size_t>(v) < visualVertices, "path vertex in range");
    }
  }
}

} // namespace

std::uint64_t bindingInputChecksum(const TriangleMesh& visual,
  const TriangleMesh& collision,
  const VisualCollisionBindingSettings& settings)
{
  Checksum sum;
  sum.add(&BindingCacheVersion, sizeof(BindingCacheVersion));
  addMesh(sum, visual);
  addMesh(sum, collision);
  Writer w;
  w.string(settings.radiusArrayName);
  w.pod(settings.insideTolerance);
  w.pod(settings.thinnessFactor);
  // The default method adds nothing: the caches written before it keep
  // their checksums.
  if (settings.rimPaths != RimPathMethod::Automatic)
  {
    w.pod(static_cast<std::int32_t>(settings.rimPaths));
  }
  sum.add(w.Bytes.data(), w.Bytes.size());
  return sum.value();
}

std::string bindingCacheBytes(const VisualCollisionBinding& binding,
  std::uint64_t inputChecksum,
  const HexahedralMesh* simulation,
  const std::string& metadata)
{
  Writer payload;
  payload.mesh(binding.visual);
  payload.vector(binding.collisionPositions);
  payload.vector(binding.collisionTriangles);
  payload.vector(binding.collisionEdges);
  payload.vector(binding.pairedVisualVertices);
  payload.vector(binding.creaseVisualVertices);
  // Field by field: the struct has padding, whose bytes are not content.
  payload.pod(static_cast<std::uint64_t>(binding.vertices.size()));
  for (const VisualVertexBinding& v : binding.vertices)
  {
    payload.pod(static_cast<std::uint8_t>(v.kind));
    payload.pod(static_cast<std::int32_t>(v.element));
    payload.pod(static_cast<std::int8_t>(v.side));
    payload.pod(v.parameters);
  }
  payload.vector(binding.triangleRegion);
  payload.vector(binding.triangleSide);
  payload.pod(static_cast<std::uint64_t>(binding.paths.size()));
  for (const BindingPath& p : binding.paths)
  {
    payload.pod(static_cast<std::int32_t>(p.collisionEdge));
    payload.pod(static_cast<std::int32_t>(p.side));
    payload.pod(p.length);
    payload.pod(p.detours);
    payload.vector(p.visualVertices);
  }
  payload.vector(binding.collisionRadii);
  if (simulation != nullptr)
  {
    payload.string(simulation->name);
    payload.vector(simulation->nodes);
    payload.vector(simulation->hexahedra);
    payload.vector(simulation->fixedNodes);
    payload.attributes(simulation->nodeAttributes);
  }
  payload.string(metadata);
  Checksum content;
  content.add(payload.Bytes.data(), payload.Bytes.size());
  FileHeader header{};
  std::memcpy(header.magic, Magic, sizeof(Magic));
  header.version = BindingCacheVersion;
  header.hasSimulation = simulation != nullptr ? 1 : 0;
  header.inputChecksum = inputChecksum;
  header.payloadSize = payload.Bytes.size();
  header.payloadChecksum = content.value();

  std::string bytes(reinterpret_cast<const char*>(&header), sizeof(header));
  bytes.append(payload.Bytes.data(), payload.Bytes.size());
  return bytes;
}

void writeBindingCache(const std::string& path,
  const VisualCollisionBinding& binding,
  std::uint64_t inputChecksum,
  const HexahedralMesh* simulation,
  const std::string& metadata)
{
  const std::string bytes = bindingCacheBytes(binding, inputChecksum, simulation, metadata);
  writeFileAtomically(path,
    [&](std::ostream& out)
    { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

namespace
{
/// The content of a binding file (`path` names it in messages) read from
/// `in`, a stream of `fileSize` bytes positioned at its start.
std::optional<BindingCacheContents> readContents(const std::string& path,
  std::istream& in,
  std::uintmax_t fileSize,
  const std::uint64_t* expectedInputChecksum,
  std::string* whyNot,
  std::uint64_t* inputChecksum)
{
  auto refuse = [&](const std::string& reason) -> std::optional<BindingCacheContents>
  {
    if (whyNot != nullptr)
    {
      *whyNot = "binding file '" + path + "': " + reason;
    }
    return std::nullopt;
  };
  FileHeader header{};
  if (!in.read(reinterpret_cast<char*>(&header), sizeof(header)) ||
      std::memcmp(header.magic, Magic, sizeof(Magic)) != 0)
  {
    return refuse("not a ThinTissue binding file");
  }
  if (header.version != BindingCacheVersion)
  {
    return refuse("format version " + std::to_string(header.version) + ", expected " +
                  std::to_string(BindingCacheVersion));
  }
  if (inputChecksum != nullptr)
  {
    *inputChecksum = header.inputChecksum;
  }
  if (expectedInputChecksum != nullptr && header.inputChecksum != *expectedInputChecksum)
  {
    return refuse("stale: made from other meshes or settings");
  }
  if (header.payloadSize != fileSize - sizeof(header))
  {
    return refuse("damaged: " + std::to_string(fileSize) + " bytes where the header announces " +
                  std::to_string(header.payloadSize + sizeof(header)));
  }
  std::vector<char> bytes(static_cast<std::size_t>(header.payloadSize));
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
  {
    return refuse("damaged: cannot read the content");
  }
  Checksum content;
  content.add(bytes.data(), bytes.size());
  if (content.value() != header.payloadChecksum)
  {
    return refuse("damaged: content checksum mismatch");
  }
  try
  {
    Reader r(bytes);
    BindingCacheContents contents;
    VisualCollisionBinding& b = contents.binding;
    b.visual = r.mesh();
    b.collisionPositions = r.vector<Vector3>();
    b.collisionTriangles = r.vector<Triangle>();
    b.collisionEdges = r.vector<std::array<int, 2>>();
    b.pairedVisualVertices = r.vector<std::array<int, 2>>();
    b.creaseVisualVertices = r.vector<int>();
    const auto vertexCount = r.pod<std::uint64_t>();
    if (vertexCount > bytes.size())
    {
      throw Error("vertex count larger than the file");
    }
    b.vertices.resize(static_cast<std::size_t>(vertexCount));
    for (VisualVertexBinding& v : b.vertices)
    {
      const auto kind = r.pod<std::uint8_t>();
      if (kind > 2)
      {
        throw Error("unknown binding kind");
      }
      v.kind = static_cast<BindingKind>(kind);
      v.element = r.pod<std::int32_t>();
      v.side = r.pod<std::int8_t>();
      v.parameters = r.pod<Vector3>();
    }
    b.triangleRegion = r.vector<int>();
    b.triangleSide = r.vector<std::int8_t>();
    const auto pathCount = r.pod<std::uint64_t>();
    if (pathCount > bytes.size())
    {
      throw Error("path count larger than the file");
    }
    b.paths.resize(static_cast<std::size_t>(pathCount));
    for (BindingPath& p : b.paths)
    {
      p.collisionEdge = r.pod<std::int32_t>();
      p.side = r.pod<std::int32_t>();
      p.length = r.pod<double>();
      p.detours = r.pod<int>();
      p.visualVertices = r.vector<int>();
    }
    b.collisionRadii = r.vector<double>();
    if (header.hasSimulation != 0)
    {
      HexahedralMesh simulation;
      simulation.name = r.string();
      simulation.nodes = r.vector<Vector3>();
      simulation.hexahedra = r.vector<Hexahedron>();
      simulation.fixedNodes = r.vector<std::uint8_t>();
      simulation.nodeAttributes = r.attributes();
      simulation.checkConsistency();
      contents.simulation = std::move(simulation);
    }
    contents.metadata = r.string();
    if (!r.atEnd())
    {
      throw Error("trailing bytes");
    }
    checkBinding(b);
    TriangleMesh collision;
    collision.positions = b.collisionPositions;
    collision.triangles = b.collisionTriangles;
    b.collisionSides = analyseCollisionSides(collision);
    return contents;
  }
  catch (const std::exception& e)
  {
    return refuse(std::string("damaged: ") + e.what());
  }
}

/// readContents on the file `path`.
std::optional<BindingCacheContents> readContentsOfFile(const std::string& path,
  const std::uint64_t* expectedInputChecksum,
  std::string* whyNot,
  std::uint64_t* inputChecksum)
{
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path))
  {
    if (whyNot != nullptr)
    {
      *whyNot = "binding file '" + path + "': missing";
    }
    return std::nullopt;
  }
  return readContents(
    path, in, std::filesystem::file_size(path), expectedInputChecksum, whyNot, inputChecksum);
}

} // namespace

std::optional<BindingCacheContents> readBindingCache(const std::string& path,
  std::uint64_t expectedInputChecksum,
  std::string* whyNot)
{
  return readContentsOfFile(path, &expectedInputChecksum, whyNot, nullptr);
}

std::optional<BindingCacheContents> readBindingFile(const std::string& path,
  std::string* whyNot,
  std::uint64_t* inputChecksum)
{
  return readContentsOfFile(path, nullptr, whyNot, inputChecksum);
}

std::optional<BindingCacheContents> readBindingBytes(const std::string& bytes,
  const std::string& name,
  std::string* whyNot,
  std::uint64_t* inputChecksum)
{
  std::istringstream in(bytes);
  return readContents(name, in, bytes.size(), nullptr, whyNot, inputChecksum);
}

VisualCollisionBinding loadOrBuildBinding(const std::string& cachePath,
  const TriangleMesh& visual,
  const TriangleMesh& collision,
  const VisualCollisionBindingSettings& settings,
  const BindingProgress& progress,
  bool* rebuilt,
  std::string* whyRebuilt)
{
  const std::uint64_t checksum = bindingInputChecksum(visual, collision, settings);
  std::string reason;
  if (auto cached = readBindingCache(cachePath, checksum, &reason))
  {
    if (rebuilt != nullptr)
    {
      *rebuilt = false;
    }
    return std::move(cached->binding);
  }
  if (rebuilt != nullptr)
  {
    *rebuilt = true;
  }
  if (whyRebuilt != nullptr)
  {
    *whyRebuilt = reason;
  }
  VisualCollisionBinding binding = bindVisualToCollision(visual, collision, settings, progress);
  writeBindingCache(cachePath, binding, checksum);
  return binding;
}

} // namespace thintissue
