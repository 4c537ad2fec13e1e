#include "tests/test_paths.h"

namespace irad::test_paths {

const char* source_dir() {
  return IRAD_TEST_SOURCE_DIR;
}
const char* irad_binary() {
  return IRAD_TEST_BINARY;
}

} // namespace irad::test_paths
