#include <algorithm>
#include "shadetlm/core/input_file.hpp"
#include "shadetlm/core/mesh_io.hpp"

#include <cmath>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

Mesh load_mesh_file(const std::string& path) {
  check_input_file(path, "", kMaxMeshBytes);
  Assimp::Importer importer;
  // Points and lines are not shaded: drop them.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                aiProcess_CalcTangentSpace | aiProcess_PreTransformVertices |
                aiProcess_SortByPType | aiProcess_FindDegenerates | aiProcess_ValidateDataStructure);
  // (not aiProcess_FindInvalidData: it drops NaN normals and texture coordinates
  // silently, which are refused here instead)
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw InputError(path, "", std::string("cannot load the mesh: ") + importer.GetErrorString());

  Mesh out;
  out.uvs_given = false;
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* m = scene->mMeshes[mi];
    if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const uint32_t base = static_cast<uint32_t>(out.vertex_count());
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      glm::dvec3 p(m->mVertices[v].x, m->mVertices[v].y, m->mVertices[v].z);
      glm::dvec3 n = m->HasNormals()
                         ? glm::dvec3(m->mNormals[v].x, m->mNormals[v].y, m->mNormals[v].z)
                         : glm::dvec3(0, 0, 1);
      if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z))
        throw InputError(path, "", "a vertex normal is NaN or infinite");
      if (!(glm::length(n) > 0)) n = glm::dvec3(0, 0, 1);  // a lone vertex has no normal
      n = glm::normalize(n);
      glm::dvec2 uv(0, 0);
      if (m->HasTextureCoords(0)) uv = {m->mTextureCoords[0][v].x, m->mTextureCoords[0][v].y}, out.uvs_given = true;
      glm::dvec4 t(any_tangent(n), 1.0);
      if (m->HasTangentsAndBitangents()) {
        glm::dvec3 tu(m->mTangents[v].x, m->mTangents[v].y, m->mTangents[v].z);
        glm::dvec3 bv(m->mBitangents[v].x, m->mBitangents[v].y, m->mBitangents[v].z);
        tu -= n * glm::dot(n, tu);  // Gram-Schmidt against the normal
        if (glm::length(tu) > 1e-12 && std::isfinite(glm::length(tu))) {
          tu = glm::normalize(tu);
          t = glm::dvec4(tu, glm::dot(glm::cross(n, tu), bv) < 0 ? -1.0 : 1.0);
        }
      }
      out.add(p, n, t, uv);
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int k = 0; k < 3; ++k)
        if (face.mIndices[k] >= m->mNumVertices)
          throw InputError(path, "", "a face indexes a vertex that does not exist");
      out.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  auto finite = [](auto v) {
    for (int k = 0; k < v.length(); ++k)
      if (!std::isfinite(v[k])) return false;
    return true;
  };
  for (size_t i = 0; i < out.vertex_count(); ++i) {
    if (!finite(out.positions[i])) throw InputError(path, "", "a vertex position is NaN or infinite");
    if (!finite(out.normals[i])) throw InputError(path, "", "a vertex normal is NaN or infinite");
    if (!finite(out.uvs[i])) throw InputError(path, "", "a texture coordinate is NaN or infinite");
    for (int k = 0; k < 3; ++k)
      if (std::abs(out.positions[i][k]) > 1e6)
        throw InputError(path, "", "vertex coordinates must lie within ±1e6");
  }
  if (out.triangles.empty()) throw InputError(path, "", "the file holds no triangles");
  const bool some_area = std::any_of(out.triangles.begin(), out.triangles.end(), [&](const glm::u32vec3& t) {
    const glm::dvec3& a = out.positions[t.x];
    return glm::length(glm::cross(out.positions[t.y] - a, out.positions[t.z] - a)) > 0;
  });
  if (!some_area) throw InputError(path, "", "no triangle has an area (every one is a line or a point)");
  return out;
}

}  // namespace shadetlm::core
