#pragma once
// How far a rig's curve moves between a run and its check (a bigger bin, a longer run): the measure
// the pipeline's checks and studies/pipeline/plate_bin_check.sh report against the 5 % bound
// (docs/decisions.md, "Bin-size and run-length checks").
#include <vector>

namespace terracal::rigs {

// A curve y(x) sampled at increasing x (sinkage for a plate, angle for an annulus).
struct Curve {
  std::vector<double> x, y;
};

// The check curve is read at the base curve's x by linear interpolation (two runs sample at
// different x when their time steps differ), over the x both cover; that common range is cut into
// five parts by sample, and the result is the largest difference of the parts' means over the
// largest part mean. Averaging over a fifth of the curve keeps CRM's step-to-step force noise
// (about 10 % on the annulus) out of a measure of where the curve lies. Returns 0 when fewer than
// five base samples lie in the common range.
double curve_change(const Curve& base, const Curve& check);

// The mean of several realisations of one curve (runs that differ only in where their bed's settling
// started): each is read at the first's x by linear interpolation, over the x all of them cover.
// A check of a curve that scatters from run to run compares such means (the pipeline's
// --check-realisations). Throws InputError for no curves or a curve curve_change would refuse.
Curve mean_curve(const std::vector<Curve>& realisations);

// The largest curve_change between any two realisations: how far single runs scatter.
double realisation_scatter(const std::vector<Curve>& realisations);

}  // namespace terracal::rigs
