#pragma once
// The io component (shadetlm::io), all of this header.
#include <string>

#include "shadetlm/core/mesh.hpp"

namespace shadetlm::core {

// Loads every triangle of a mesh file through assimp (OBJ, PLY, glTF, 3DS, STL, …),
// with the node transforms applied, into one mesh. Normals are generated where the
// file has none (smooth), tangents from the uv parameterization where it has none.
// Throws InputError naming the file.
Mesh load_mesh_file(const std::string& path);

}  // namespace shadetlm::core
