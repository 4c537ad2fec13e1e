// The fuzz build compiles tinygltf and stb_image from their (Debian) headers instead of linking
// libtinygltf.so and libstb.so, so that they are instrumented (coverage, ASan, UBSan) too.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#include <tiny_gltf.h>
