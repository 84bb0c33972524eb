// Deterministic point sets for tests, the demo and benchmarks.
#ifndef fd3_PointSets_h
#define fd3_PointSets_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fd3test
{

using Points = std::vector<double>; // x,y,z triples

Points uniformCube(std::size_t n, std::uint64_t seed);
/// n radii uniform in [lo, hi].
std::vector<double> uniformRadii(std::size_t n, double lo, double hi, std::uint64_t seed);
/// The weights r^2 of uniformRadii() (balls' weights).
std::vector<double> randomWeights(std::size_t n, double lo, double hi, std::uint64_t seed);
Points uniformBall(std::size_t n, std::uint64_t seed);
/// n points exactly on a sphere (integer coordinates, all cospherical: every insphere test among
/// them is a tie), about 1M at most. Built from integer quaternions of one norm N: q -> q i q* has
/// length N.
Points exactSphere(std::size_t n, std::uint64_t seed);
/// The k^3 integer lattice.
Points lattice(int k);
/// Tight clusters (spread `spread`) inside a sparse uniform background of the unit cube.
Points clusters(std::size_t n, int clusterCount, double spread, std::uint64_t seed);
/// A slab of the unit square with thickness `thickness`.
Points thinSlab(std::size_t n, double thickness, std::uint64_t seed);
/// Points on a curved surface (a torus), like the surface samples of the paper's examples.
Points torusSurface(std::size_t n, std::uint64_t seed);

/// Points on a cylinder x^2 + y^2 = 0.25, z in [0, 1), rounded to doubles (a pipe, a tunnel).
Points cylinderSurface(std::size_t n, std::uint64_t seed);
/// Points on the unit sphere with uniform radial noise of +-1e-3 (a noisy scan of a shell).
Points noisySphereShell(std::size_t n, std::uint64_t seed);
/// One smooth closed surface (a bumpy sphere) scanned 5 times, n/5 points each, every scan moved
/// by its own rigid motion of about 1e-4 (rotation and translation): overlapping registered scans.
Points overlappingScans(std::size_t n, std::uint64_t seed);
/// Airborne-LiDAR-like terrain: a smooth height field sampled at about 4 points per square metre,
/// x and y near 5e5 and z near 100 (metres), every coordinate snapped to a 1 cm grid, and 1% of
/// the points repeated exactly (multiple returns).
Points lidarTerrain(std::size_t n, std::uint64_t seed);

/// Every coordinate x of `p` as x * factor + offset.
Points scaled(Points p, double factor, double offset = 0);
/// The points of `a`, then those of `b`.
Points joined(Points a, const Points& b);
/// A thin spherical shell (4 spacings thick) of points at molecule-like spacing: a jittered cubic
/// lattice (spacing 1, jitter +-0.15), so no two points are closer than 0.7.
Points molecularShell(std::size_t n, std::uint64_t seed);

/// A globular molecule's atoms (angstroms) with their van der Waals radii: a chain of bonds 1.5
/// long at random angles, no atom closer than 2.5 to one two or more bonds back, folded into a
/// ball that holds about 0.01 atoms per cubic angstrom; the radii are those of C, N, O, S and H
/// (Bondi, 1964) in a protein's proportions.
Points molecule(std::size_t atoms, std::uint64_t seed, std::vector<double>& radii);

/// Structured and degenerate surface samples, as CAD and CFD meshes give them: exactly cospherical
/// and coplanar subsets everywhere (their coordinates come from linspace-like divisions, cos and
/// sin, so they are not on a small integer grid). The boundary nodes of a structured grid on a
/// 1 x 0.8 x 0.6 box, about n of them.
Points boxBoundary(std::size_t n);
/// A vase: rings at equally spaced heights, each of equally spaced angles.
Points surfaceOfRevolution(std::size_t n);
/// A cam profile of equally spaced angles, copied at equally spaced heights.
Points extrusion(std::size_t n);
/// Uniform points on three parallel planes.
Points parallelPlanes(std::size_t n, std::uint64_t seed);
/// A latitude-longitude grid on the unit sphere, with each pole once.
Points latitudeLongitude(std::size_t n);
/// A smooth convex surface: random points on the ellipsoid of semi-axes 1, 0.7, 0.4 (rounded to
/// doubles, so a few lie just inside the hull).
Points ellipsoidSurface(std::size_t n, std::uint64_t seed);
/// Random points on the ellipsoid of semi-axes `axes`: uniform by area, or, `latLong`, uniform in
/// latitude and longitude about the z axis, which crowds them at the two poles as a parametrised
/// surface's mesh does (density 1 / sin of the colatitude).
Points ellipsoid(
  std::size_t n, const std::array<double, 3>& axes, bool latLong, std::uint64_t seed);

/// For every point, the id of the first point at its position: exact duplicates map to one id, so
/// that simplices compare equal whichever copy they use.
std::vector<std::uint32_t> firstCopies(const Points& p);

/// Every generator's name, as generate() takes it.
const std::vector<std::string>& pointSetNames();
/// Generator by name (see pointSetNames()).
Points generate(const std::string& kind, std::size_t n, std::uint64_t seed);

} // namespace fd3test

#endif
