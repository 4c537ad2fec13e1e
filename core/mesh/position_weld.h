#pragma once
// Vertices at one position welded: welded[v] is the first vertex (lowest index) whose position
// has the same bits as v's (as meshopt_generateVertexRemap compares them: 0.0 and -0.0 differ,
// a NaN equals only its own bits). The shadow hierarchy's build welds before it simplifies
// (core/mesh/hierarchy/mesh_clusters.h), over every vertex of the scene.
//
// On all cores: each thread takes the positions whose hash falls in its part, in ascending
// order, into an open-addressing table of its own, so the first vertex of a position is the
// first its thread meets. The result is the same on any number of threads.
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace irad {

// threads: 0 all cores.
std::vector<std::uint32_t> weld_positions(const std::vector<glm::vec3>& positions,
                                          unsigned threads = 0);

} // namespace irad
