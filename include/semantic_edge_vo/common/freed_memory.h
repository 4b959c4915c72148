#pragma once

namespace semantic_edge_vo {

/// Gives the pages the allocator keeps for reuse back to the system (glibc's malloc_trim; nothing
/// elsewhere). Frames are large (pyramids, a field per class) and freed out of order: without it the
/// process grows by each burst (a new initialisation holds a dozen frames) and keeps it. A few ms.
void releaseFreedMemory();

}  // namespace semantic_edge_vo
