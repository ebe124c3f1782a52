#pragma once
// Calibration figures as PNG files drawn by gnuplot (pngcairo). Data files live in a private
// temporary folder that is removed afterwards; the PNG is written under a temporary name next to
// its final name and renamed, so a failed plot never leaves a partial image. Without gnuplot the
// functions throw RunError: plots are optional, callers decide whether to warn.
#include <string>
#include <vector>

namespace terracal::bayes {

// One measured curve with its fitted model curve, e.g. pressure against sinkage for one plate.
struct FitSeries {
  std::string label;                     // legend text, e.g. "plate 0.10 m"
  std::vector<double> x, observed, fit;  // same length; rows are sorted by x before drawing
  std::vector<double> lo, hi;            // 95 % posterior-predictive band; both empty -> no band
};

// Observed values as points, the fit as a line and the band as a transparent area, one colour
// per series. Labels should carry units, e.g. "sinkage z [m]". Throws RunError on inconsistent
// lengths, an empty series list, a missing target folder or a gnuplot failure.
void plot_fit(const std::string& png_path, const std::string& title, const std::string& xlabel,
              const std::string& ylabel, const std::vector<FitSeries>& series);

// Pairwise marginals ("corner plot"): histograms on the diagonal, scatter of draws below it
// (thinned evenly to at most 2000 points; histograms use every draw). `names` label the axes and
// should carry units, e.g. "phi [deg]". draws[k] is one posterior draw: draws[k][p] is the value of
// names[p]. Non-finite values are left out. Throws RunError like plot_fit.
void plot_pairs(const std::string& png_path, const std::vector<std::string>& names,
                const std::vector<std::vector<double>>& draws);

}  // namespace terracal::bayes
