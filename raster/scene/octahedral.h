#pragma once
// Unit normals in 4 bytes for the GPU's vertices: the octahedral map (Meyer et al. 2010, "On
// floating-point normal vectors"). n / (|n.x| + |n.y| + |n.z|) lies on the octahedron; its upper
// half projects onto the diamond |u| + |v| <= 1, its lower half is folded over the diamond's
// edges onto the corners of [-1, 1]^2; (u, v) is stored as two 16-bit integers u * 32767.
//
// Encoding rounds (u, v) to the nearest integers: 6.4e-5 radians off at most over a million random
// directions (tests/test_octahedral.cpp), so a cosine changes by at most that much (the closest
// of the four roundings gains little, 4.3e-5, for six times the encoding's time). The GPU decodes
// as octahedral_decode does (the camera passes' vertex shader, raster/glsl/shaders.h
// camera_vertex); normals along the axes come back exactly.
#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

namespace irad::gl {

inline constexpr float kOctahedralScale = 32767.0f;

// n: unit length (a zero vector encodes as +z).
glm::i16vec2 octahedral_encode(const glm::vec3& n);
// The unit normal of an encoding.
glm::vec3 octahedral_decode(glm::i16vec2 e);

} // namespace irad::gl
