#pragma once
// Where the suite finds the source tree and the irad binary. The two paths are compiled into
// tests/test_paths.cpp alone: every other test file compiles to the same object in any clone, so
// that ccache serves it to every clone (CMakeLists.txt, CCACHE_BASEDIR).
namespace irad::test_paths {

const char* source_dir();  // the repository's root, without a trailing slash
const char* irad_binary(); // build/bin/irad of this build

} // namespace irad::test_paths

#define IRAD_SOURCE_DIR (::irad::test_paths::source_dir())
#define IRAD_BINARY (::irad::test_paths::irad_binary())
