// The depth-16 tree (OctoMap's layout) is compiled once here; other depths instantiate on use.
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {
template class OccupancyOctree<16>;
}  // namespace sonarmap
