#pragma once
// A rotation- and reflection-invariant distance between two drape outlines r(θ) (weft fit's
// drape_photos target, docs/photos.md): the amplitudes of r(θ)'s Fourier harmonics compared
// harmonic by harmonic.
//
// Write an outline sampled in N equal bins as r(θ) = a₀ + Σₖ aₖ cos(kθ + φₖ): a₀ is its mean
// radius, aₖ ≥ 0 the amplitude of harmonic k (a drape with n even nodes has its largest aₖ at
// k = n) and φₖ its phase. Rotating the outline by α changes each φₖ by kα; reflecting it
// (θ → −θ) negates each φₖ; neither changes an aₖ. Where the nodes of a Cusick drape lie is
// arbitrary from specimen to specimen, and a photo may be mirrored, so only the amplitudes are
// compared:
//
//   D(r, s)² = (a₀ʳ − a₀ˢ)² + ½ Σ_{k = 2…K} (aₖʳ − aₖˢ)²
//
// By Parseval's theorem, ½ Σ |aₖʳ e^{iφₖʳ} − aₖˢ e^{iφₖˢ}|² over k ≥ 1 plus the k = 0 term is the
// mean square of r − s over θ; since |aʳ − aˢ| ≤ |aʳe^{iφ} − aˢe^{iψ}|, D is at most the rms
// difference of r and s under every rotation and reflection (of the harmonics 0, 2…K): D = 0 for
// a rotated or mirrored copy, D ≤ the best-aligned rms distance otherwise. It is smooth in r
// wherever no aₖ is 0, needs no search over alignments (whose best shift jumps from one node to
// the next as the shape changes, a kink in the objective), and has the unit of r.
//
// Harmonic 1 is left out: it is the offset of the outline's centre from the point r(θ) is
// measured about — the support's axis in a simulation, the silhouette's centroid (or a given
// centre) in a photo — which says where the specimen lay, not how the fabric drapes.
// Harmonics above K are left out: K = 30 (a 12° period) keeps the nodes of Cusick drapes
// (4–12) and two overtones of their shape, and drops the raster's bin-to-bin noise.

#include <vector>

namespace weft::app {

inline constexpr int default_outline_harmonics = 30;

// a₀…a_K of an outline of N ≥ 2K + 1 bins (bin j at θ = 2π(j + ½)/N), in the outline's unit.
// Throws std::invalid_argument for K < 2 or too few bins.
std::vector<double> outline_amplitudes(const std::vector<double>& radii, int harmonics);

// D(r, s) above from two amplitude lists of the same length (outline_amplitudes); throws
// std::invalid_argument when the lengths differ or are < 3.
double outline_spectrum_distance(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace weft::app
