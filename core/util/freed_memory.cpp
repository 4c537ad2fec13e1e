#include "core/util/freed_memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace irad {

void release_freed_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

} // namespace irad
