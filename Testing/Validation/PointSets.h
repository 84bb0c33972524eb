// Deterministic point sets for tests, the demo and benchmarks.
#ifndef fd3_PointSets_h
#define fd3_PointSets_h

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fd3test
{

using Points = std::vector<double>; // x,y,z triples

Points uniformCube(std::size_t n, std::uint64_t seed);
Points uniformBall(std::size_t n, std::uint64_t seed);
/// n points exactly on a sphere (integer coordinates, all cospherical: every insphere test among
/// them is a tie). Built from integer quaternions of one norm N: q -> q i q* has length N.
Points exactSphere(std::size_t n, std::uint64_t seed);
/// The k^3 integer lattice.
Points lattice(int k);
/// Tight clusters (spread `spread`) inside a sparse uniform background of the unit cube.
Points clusters(std::size_t n, int clusterCount, double spread, std::uint64_t seed);
/// A slab of the unit square with thickness `thickness`.
Points thinSlab(std::size_t n, double thickness, std::uint64_t seed);
/// Points on a curved surface (a torus), like the surface samples of the paper's examples.
Points torusSurface(std::size_t n, std::uint64_t seed);

/// Generator by name ("cube", "ball", "sphere", "lattice", "clusters", "slab", "torus").
Points generate(const std::string& kind, std::size_t n, std::uint64_t seed);

} // namespace fd3test

#endif
