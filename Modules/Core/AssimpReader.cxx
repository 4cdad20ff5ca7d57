// assimp back-end of MeshImport: STL, PLY, OFF, glTF, FBX, Collada, 3DS.
#include "MeshImportPrivate.h"
#include "ThinTissueError.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstring>
#include <unordered_map>

namespace thintissue
{
namespace detail
{
namespace
{

/// Exact bitwise key of a float triple: welding merges identical positions
/// only, never nearby ones, so distinct but touching surfaces stay apart.
struct FloatTripleKey
{
  std::uint32_t bits[3];
  bool operator==(const FloatTripleKey& other) const
  {
    return std::memcmp(bits, other.bits, sizeof(bits)) == 0;
  }
};

struct FloatTripleHash
{
  std::size_t operator()(const FloatTripleKey& key) const
  {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t b : key.bits)
    {
      h = (h ^ b) * 1099511628211ull;
    }
    return static_cast<std::size_t>(h);
  }
};

FloatTripleKey makeKey(float x, float y, float z)
{
  FloatTripleKey key;
  // +0 and -0 compare equal but differ in bits: normalise.
  const float values[3] = { x == 0.0f ? 0.0f : x, y == 0.0f ? 0.0f : y, z == 0.0f ? 0.0f : z };
  std::memcpy(key.bits, values, sizeof(values));
  return key;
}

} // namespace

TriangleMesh readWithAssimp(const std::string& path, const MeshImportOptions& options)
{
  Assimp::Importer importer;
  importer.SetPropertyInteger(
    AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Validation first: a loader that misreads its file (assimp's PLY loader
  // did, on a body starting with '\n') then gives an error instead of
  // faces with indices out of range, on which the triangulation's
  // assertion aborts the process.
  const aiScene* scene = importer.ReadFile(path,
    aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
      aiProcess_SortByPType | aiProcess_PreTransformVertices);
  if (scene == nullptr)
  {
    throw FileError(path, std::string("cannot be parsed: ") + importer.GetErrorString());
  }

  TriangleMesh mesh;
  mesh.name = path;
  bool allTextured = scene->mNumMeshes > 0;
  bool allNormals = scene->mNumMeshes > 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
  {
    allTextured &= scene->mMeshes[m]->HasTextureCoords(0);
    allNormals &= scene->mMeshes[m]->HasNormals();
  }

  std::unordered_map<FloatTripleKey, int, FloatTripleHash> weldedPositions;
  std::unordered_map<FloatTripleKey, int, FloatTripleHash> distinctTextureCoordinates;
  std::vector<Vector3> normalSums;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
  {
    const aiMesh* source = scene->mMeshes[m];
    std::vector<int> vertexMap(source->mNumVertices);
    std::vector<int> textureMap(allTextured ? source->mNumVertices : 0);
    for (unsigned v = 0; v < source->mNumVertices; ++v)
    {
      const aiVector3D& p = source->mVertices[v];
      int index = static_cast<int>(mesh.positions.size());
      if (options.weldCoincidentVertices)
      {
        index = weldedPositions.emplace(makeKey(p.x, p.y, p.z), index).first->second;
      }
      if (index == static_cast<int>(mesh.positions.size()))
      {
        mesh.positions.emplace_back(p.x, p.y, p.z);
        normalSums.emplace_back(Vector3::Zero());
      }
      vertexMap[v] = index;
      if (allNormals)
      {
        const aiVector3D& n = source->mNormals[v];
        normalSums[index] += Vector3(n.x, n.y, n.z);
      }
      if (allTextured)
      {
        const aiVector3D& uv = source->mTextureCoords[0][v];
        const int next = static_cast<int>(mesh.textureCoordinates.size());
        const int t =
          distinctTextureCoordinates.emplace(makeKey(uv.x, uv.y, 0.0f), next).first->second;
        if (t == next)
        {
          mesh.textureCoordinates.emplace_back(uv.x, uv.y);
        }
        textureMap[v] = t;
      }
    }
    for (unsigned f = 0; f < source->mNumFaces; ++f)
    {
      const aiFace& face = source->mFaces[f];
      if (face.mNumIndices != 3)
      {
        continue; // points and lines were sorted out; nothing else remains
      }
      Triangle tri;
      Triangle corners;
      for (int k = 0; k < 3; ++k)
      {
        const unsigned i = face.mIndices[k];
        if (i >= source->mNumVertices)
        {
          throw FileError(path,
            "face " + std::to_string(f) + " has vertex index " + std::to_string(i) +
              " out of range (" + std::to_string(source->mNumVertices) + " vertices)");
        }
        tri[k] = vertexMap[i];
        corners[k] = allTextured ? textureMap[i] : 0;
      }
      mesh.triangles.push_back(tri);
      if (allTextured)
      {
        mesh.textureCorners.push_back(corners);
      }
    }
  }
  if (allNormals)
  {
    for (Vector3& n : normalSums)
    {
      const double length = n.norm();
      n = length > 0.0 ? Vector3(n / length) : Vector3::UnitZ();
    }
    mesh.normals = std::move(normalSums);
  }
  return mesh;
}

} // namespace detail
} // namespace thintissue
