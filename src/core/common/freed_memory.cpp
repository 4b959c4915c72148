#include "semantic_edge_vo/common/freed_memory.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace semantic_edge_vo {

void releaseFreedMemory() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

}  // namespace semantic_edge_vo
