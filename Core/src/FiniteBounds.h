// The one pass that bounds a point set's finite points (and lists them where asked), on a team of
// threads: what the kernel, the Voronoi cells and fd3::finiteBounds() all use.
#ifndef fd3_FiniteBounds_h
#define fd3_FiniteBounds_h

#include "fd3/Bounds.h"
#include "fd3/Delaunay.h"
#include "system/Threads.h"

#include <cstddef>

namespace fd3
{

/// The box of the finite ones of `count` points (x,y,z triples), empty when none is, and, where
/// `finiteIds` is given, their ids in ascending order: each thread bounds a stretch of the points
/// (and writes its finite ids after those of the stretches before it). Recorded as `phase`.
Bounds finiteBounds(ThreadTeam& team, const char* phase, const double* xyz, std::size_t count,
  IdArray* finiteIds = nullptr);

} // namespace fd3

#endif
