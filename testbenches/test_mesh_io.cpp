// Meshes through assimp: each format the scene format promises, written here with
// assimp's exporter from a primitive and read back through core::load_mesh_file.
#include <algorithm>
#include <fstream>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include "shadetlm/core/mesh.hpp"
#include "shadetlm/core/mesh_io.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {
// An aiScene holding one mesh: positions and normals of `m` (and its uvs when asked).
void export_mesh(const core::Mesh& m, const std::string& format, const std::string& path, bool with_uv) {
  aiScene scene;
  scene.mRootNode = new aiNode();
  scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene.mNumMaterials = 1;
  scene.mMeshes = new aiMesh*[1]{new aiMesh()};
  scene.mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};
  scene.mRootNode->mNumMeshes = 1;
  aiMesh* mesh = scene.mMeshes[0];
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = unsigned(m.vertex_count());
  mesh->mVertices = new aiVector3D[m.vertex_count()];
  mesh->mNormals = new aiVector3D[m.vertex_count()];
  if (with_uv) {
    mesh->mTextureCoords[0] = new aiVector3D[m.vertex_count()];
    mesh->mNumUVComponents[0] = 2;
  }
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    mesh->mVertices[i] = aiVector3D(float(m.positions[i].x), float(m.positions[i].y), float(m.positions[i].z));
    mesh->mNormals[i] = aiVector3D(float(m.normals[i].x), float(m.normals[i].y), float(m.normals[i].z));
    if (with_uv) mesh->mTextureCoords[0][i] = aiVector3D(float(m.uvs[i].x), float(m.uvs[i].y), 0);
  }
  mesh->mNumFaces = unsigned(m.triangles.size());
  mesh->mFaces = new aiFace[m.triangles.size()];
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    mesh->mFaces[f].mNumIndices = 3;
    mesh->mFaces[f].mIndices = new unsigned[3]{m.triangles[f].x, m.triangles[f].y, m.triangles[f].z};
  }
  Assimp::Exporter exporter;
  REQUIRE(exporter.Export(&scene, format, path) == AI_SUCCESS);
}
}  // namespace

TEST_CASE("meshes load from OBJ, PLY, glTF, 3DS and STL", "[mesh_io]") {
  const auto dir = test::temp_dir("mesh-io");
  const core::Mesh torus = core::make_torus(1, 0.4, 24, 12);
  glm::dvec3 lo(1e9), hi(-1e9);
  for (const auto& p : torus.positions) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  const std::pair<const char*, const char*> formats[] = {
      {"obj", "obj"}, {"ply", "ply"}, {"gltf2", "gltf"}, {"3ds", "3ds"}, {"stl", "stl"}};
  for (const auto& [format, ext] : formats) {
    INFO(format);
    const std::string path = (dir / (std::string("torus.") + ext)).string();
    const bool with_uv = std::string(format) != "stl";
    export_mesh(torus, format, path, with_uv);
    const core::Mesh m = core::load_mesh_file(path);
    CHECK(m.triangles.size() == torus.triangles.size());
    glm::dvec3 mlo(1e9), mhi(-1e9);
    for (const auto& p : m.positions) { mlo = glm::min(mlo, p); mhi = glm::max(mhi, p); }
    // Formats store floats, and 3DS (z up) comes back with y and z exchanged:
    // compare the box's sorted extents.
    glm::dvec3 e = hi - lo, me = mhi - mlo;
    std::sort(&e[0], &e[0] + 3);
    std::sort(&me[0], &me[0] + 3);
    for (int k = 0; k < 3; ++k) CHECK(me[k] == Approx(e[k]).margin(1e-4));
    CHECK(glm::length(mhi + mlo) < 1e-4);  // still centred
    for (size_t i = 0; i < m.vertex_count(); ++i) {
      CHECK(glm::length(m.normals[i]) == Approx(1).margin(1e-6));
      CHECK(std::abs(glm::dot(m.normals[i], glm::dvec3(m.tangents[i]))) < 1e-6);
    }
  }
}

TEST_CASE("the committed mesh asset loads with tangents from its uvs", "[mesh_io]") {
  const core::Mesh m = core::load_mesh_file(test::source_path("scenes/assets/knot.obj"));
  CHECK(m.triangles.size() > 1000);
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    CHECK(glm::length(m.normals[i]) == Approx(1).margin(1e-6));
    CHECK(glm::length(glm::dvec3(m.tangents[i])) == Approx(1).margin(1e-6));
    CHECK(std::abs(glm::dot(m.normals[i], glm::dvec3(m.tangents[i]))) < 1e-6);
  }
  // The file has no tangents: they must follow dP/du of the uv parameterization (and
  // B = w·N×T follow dP/dv), which an arbitrary orthogonal vector would not.
  for (const auto& t : m.triangles) {
    const glm::dvec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    const glm::dvec2 d1 = m.uvs[t.y] - m.uvs[t.x], d2 = m.uvs[t.z] - m.uvs[t.x];
    const double det = d1.x * d2.y - d2.x * d1.y;
    REQUIRE(std::abs(det) > 1e-12);
    const glm::dvec3 dpdu = glm::normalize(((b - a) * d2.y - (c - a) * d1.y) / det);
    const glm::dvec3 dpdv = glm::normalize(((c - a) * d1.x - (b - a) * d2.x) / det);
    const glm::dvec4 tan = m.tangents[t.x];
    CHECK(glm::dot(glm::dvec3(tan), dpdu) > 0.8);
    CHECK(glm::dot(tan.w * glm::cross(m.normals[t.x], glm::dvec3(tan)), dpdv) > 0.8);
  }
}

TEST_CASE("a broken mesh file names the file", "[mesh_io][bad]") {
  const auto dir = test::temp_dir("mesh-bad");
  const std::string path = (dir / "broken.ply").string();
  std::ofstream(path) << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n0 0\n";
  try {
    core::load_mesh_file(path);
    FAIL("no error");
  } catch (const core::InputError& e) {
    CHECK(e.file() == path);
  }
}
