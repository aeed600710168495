#pragma once
// The map cache (render --map-cache DIR, or SHADETLM_MAP_CACHE): the parallax maps a
// scene's materials read, built once and kept in DIR under a name made of everything
// they depend on — the height field's checksum, the map's kind and parameters
// (core::map_key) and the program that builds them (its version, its file's size and
// modification time) — so that later runs, and the shards of a
// sweep on a cluster sharing DIR, read them instead of building them again
// (docs/parallax.md, docs/benchmarks.md).
#include <string>

#include "shadetlm/core/scene.hpp"

namespace shadetlm::app {

// Points every parallax material that reads a map (distance or cone) and names no
// map_file at its map in `dir`, building and writing the ones `dir` lacks first. Each is
// written whole or not at all (core/output.hpp), so runs building the same map at once
// leave one whole copy. An entry that does not read as its map (truncated, damaged:
// its checksum) is built again, with a warning naming it. Returns the number of maps built.
int use_map_cache(core::Scene& scene, const std::string& dir);

}  // namespace shadetlm::app
