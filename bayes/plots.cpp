#include "bayes/plots.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/gnuplot.hpp"

namespace terracal::bayes {
namespace {

namespace fs = std::filesystem;

// Okabe-Ito colours: distinguishable with the common colour-vision deficiencies and in grey
// print. (Their yellow is left out: unreadable on white.)
constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"};
constexpr std::size_t kNumColours = sizeof(kColours) / sizeof(kColours[0]);
// Past the seventh series the colours repeat: each round of them gets its own dash and point type,
// so that series 1 and 8 still read apart.
constexpr std::array<int, 4> kPointTypes = {7, 5, 9, 11};
std::size_t colour_cycle(std::size_t series) { return series / kNumColours; }

constexpr std::size_t kMaxScatterPoints = 2000;  // more only hides structure and slows gnuplot
constexpr int kPairsSize = 1000;                 // pixels; square, so that every panel is square

// A private folder for gnuplot's data files and script, removed with everything in it on exit.
class TempFolder {
 public:
  TempFolder() {
    static std::atomic<unsigned> counter{0};
    const fs::path base = fs::temp_directory_path();
    for (int attempt = 0; attempt < 100; ++attempt) {
      path_ = base / ("terracal_plot_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
      std::error_code ec;
      if (fs::create_directory(path_, ec)) return;  // false when it exists already: try the next name
    }
    throw RunError("plotting: cannot create a temporary folder under '" + base.string() + "'");
  }
  ~TempFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// A gnuplot double-quoted string. The terminal is `noenhanced`, so names like "k_c" or "n^2"
// appear literally; only backslash, quote and newline need escaping here.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

// Shortest text that reads back to the same double; "?" (declared missing) for NaN and inf.
std::string num(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string("?"); }

void write_data_file(const fs::path& file, const std::string& content) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << content;
  out.close();
  if (!out) throw RunError("plotting: cannot write the data file '" + file.string() + "'");
}

// Checks the target folder first: gnuplot's own "cannot open file" message is less clear.
void check_target(const std::string& png_path) {
  const fs::path parent = fs::path(png_path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw RunError("plotting '" + png_path + "': the folder '" + parent.string() + "' does not exist");
}

// Runs `body` (which reads data files by relative name from `work`) with the PNG terminal set up,
// drawing into a temporary file next to `png_path` that is renamed only when gnuplot succeeded.
void render(const std::string& png_path, const TempFolder& work, int width, int height, int font_size,
            const std::string& body) {
  const std::string tmp = fs::absolute(temporary_path_for(png_path)).string();
  std::ostringstream script;
  script << "set terminal pngcairo noenhanced size " << width << "," << height << " font "
         << quoted(fmt::format("Sans,{}", font_size)) << " linewidth 1.2\n"
         << "set output " << quoted(tmp) << "\n"
         << "set datafile missing \"?\"\n"
         << body << "\nunset output\n";
  try {
    run_gnuplot(script.str(), work.path().string());
    std::error_code ec;
    if (!fs::is_regular_file(tmp, ec) || fs::file_size(tmp, ec) == 0)
      throw RunError("plotting '" + png_path + "': gnuplot finished but wrote no image");
    commit_file(tmp, png_path);
  } catch (const RunError& e) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    const std::string msg = e.what();
    if (msg.find(png_path) != std::string::npos) throw;
    throw RunError("plotting '" + png_path + "': " + msg);
  }
}

// ---------------------------------------------------------------------------------------------
// plot_fit

void check_series(const std::string& png_path, const FitSeries& s) {
  const auto bad = [&](const std::string& what) {
    throw RunError("plotting '" + png_path + "': series '" + s.label + "': " + what);
  };
  if (s.x.empty()) bad("no points");
  if (s.observed.size() != s.x.size() || s.fit.size() != s.x.size())
    bad(fmt::format("x, observed and fit have {}, {} and {} values (must be equal)", s.x.size(), s.observed.size(),
                    s.fit.size()));
  if (s.lo.size() != s.hi.size() || (!s.lo.empty() && s.lo.size() != s.x.size()))
    bad(fmt::format("band has {} lower and {} upper values for {} points (must both be {} or empty)", s.lo.size(),
                    s.hi.size(), s.x.size(), s.x.size()));
}

// Rows in increasing x (non-finite x last): the fit line and the band are drawn in row order, so
// unsorted input would zig-zag.
std::string fit_data(const FitSeries& s) {
  std::vector<std::size_t> order(s.x.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const bool fa = std::isfinite(s.x[a]), fb = std::isfinite(s.x[b]);
    if (fa != fb) return fa;
    return fa && s.x[a] < s.x[b];
  });
  std::string out = "# x observed fit lo hi\n";
  const bool band = !s.lo.empty();
  for (const std::size_t i : order)
    out += fmt::format("{} {} {} {} {}\n", num(s.x[i]), num(s.observed[i]), num(s.fit[i]), band ? num(s.lo[i]) : "?",
                       band ? num(s.hi[i]) : "?");
  return out;
}

// ---------------------------------------------------------------------------------------------
// plot_pairs

struct Range {
  double lo = 0, hi = 0;
};

// Finite extent of column p, padded so that points on the edge stay visible.
Range padded_range(const std::vector<std::vector<double>>& draws, std::size_t p, const std::string& png_path,
                   const std::string& name) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& d : draws)
    if (std::isfinite(d[p])) lo = std::min(lo, d[p]), hi = std::max(hi, d[p]);
  if (!(lo <= hi)) throw RunError("plotting '" + png_path + "': parameter '" + name + "' has no finite draws");
  const double pad = hi > lo ? 0.04 * (hi - lo) : (lo != 0 ? 0.05 * std::abs(lo) : 1.0);
  return {lo - pad, hi + pad};
}

// Ticks at round values (1, 2, 2.5 or 5 times a power of ten), as many as fit without the labels
// touching: in narrow panels gnuplot's own choice overlaps them. `panel_px` is the panel's length
// along the axis, `font_pt` the tick font. Labels of the x axis stand side by side, so their
// width counts; those of the y axis are stacked, so only their height does.
std::string tics(char axis, const Range& r, double panel_px, double font_pt) {
  const double span = r.hi - r.lo;
  const double char_px = 0.65 * font_pt;  // digit width of the Sans font at pngcairo's scale
  const int first = static_cast<int>(std::floor(std::log10(span / 10.0)));
  // (options repeated: `unset ytics` on the diagonal and a new tic series reset them)
  const auto command = [&](double start, double step) {
    return fmt::format("set {}tics nomirror out font \",{}\" {}, {}, {}\n", axis, font_pt, num(start), num(step),
                       num(r.hi));
  };
  for (int e = first; e <= first + 3; ++e) {
    for (const double m : {1.0, 2.0, 2.5, 5.0}) {
      const double step = m * std::pow(10.0, e);
      const double start = std::ceil(r.lo / step) * step;
      const int n = static_cast<int>(std::floor((r.hi - start) / step + 1e-9)) + 1;
      if (n > 5) continue;
      std::size_t chars = 0;
      for (int i = 0; i < n; ++i) chars = std::max(chars, fmt::format("{:g}", start + i * step).size());
      const double needed_px = axis == 'x' ? (double(chars) + 2.0) * char_px : 2.5 * font_pt;
      if (step / span * panel_px >= needed_px) return command(start, step);
    }
  }
  return command(r.lo, span);  // not reached for spans of ordinary numbers
}

// Histogram of column p over its range: rows "centre count width" for `with boxes`. About
// sqrt(draws) bins, between 10 and 40, and no more than bars of 6 pixels allow in narrow panels.
std::string histogram_data(const std::vector<std::vector<double>>& draws, std::size_t p, double panel_px) {
  std::vector<double> v;
  for (const auto& d : draws)
    if (std::isfinite(d[p])) v.push_back(d[p]);
  const auto [mn, mx] = std::minmax_element(v.begin(), v.end());
  const double lo = *mn, hi = *mx;
  const std::size_t most = std::clamp<std::size_t>(static_cast<std::size_t>(panel_px / 6.0), 10, 40);
  const std::size_t bins = hi > lo ? std::clamp<std::size_t>(std::lround(std::sqrt(double(v.size()))), 10, most) : 1;
  const double width = hi > lo ? (hi - lo) / double(bins) : (lo != 0 ? 0.02 * std::abs(lo) : 0.1);
  std::vector<std::size_t> count(bins, 0);
  for (const double x : v) {
    const auto b = hi > lo ? static_cast<std::size_t>((x - lo) / width) : 0;
    ++count[std::min(b, bins - 1)];  // the maximum falls on the upper edge of the last bin
  }
  std::string out = "# centre count width\n";
  for (std::size_t b = 0; b < bins; ++b)
    out += fmt::format("{} {} {}\n", num(hi > lo ? lo + (double(b) + 0.5) * width : lo), count[b], num(width));
  return out;
}

}  // namespace

void plot_fit(const std::string& png_path, const std::string& title, const std::string& xlabel,
              const std::string& ylabel, const std::vector<FitSeries>& series) {
  if (series.empty()) throw RunError("plotting '" + png_path + "': no series to plot");
  for (const FitSeries& s : series) check_series(png_path, s);
  check_target(png_path);
  if (!gnuplot_available()) throw RunError("plotting '" + png_path + "': gnuplot was not found on PATH");

  TempFolder work;
  bool any_band = false;
  for (std::size_t i = 0; i < series.size(); ++i) {
    write_data_file(work.path() / fmt::format("series{}.dat", i), fit_data(series[i]));
    any_band = any_band || !series[i].lo.empty();
  }

  const std::size_t legend_entries = series.size() + (any_band ? 3 : 2);
  std::ostringstream gp;
  gp << "set title " << quoted(title) << " font \",17\"\n"
     << "set xlabel " << quoted(xlabel) << "\n"
     << "set ylabel " << quoted(ylabel) << "\n"
     << "set grid lt 1 lc rgb \"#e3e3e3\" lw 1\n"
     << "set border lc rgb \"#444444\"\n"
     // The legend goes below the plot, in rows of three: the curves keep the full width, and no
     // place inside the axes is free for every data set. It is placed by hand with a bottom margin
     // sized for its rows, because gnuplot's own `key below` box overlaps the x label.
     << "set key at screen 0.5, screen 0.015 center bottom horizontal maxcols 3 samplen 3 box lc rgb \"#bbbbbb\"\n"
     << fmt::format("set bmargin {}\n", num(4.3 + 1.35 * double((legend_entries + 2) / 3)))
     // x range exactly the data plus 2 %, so no point sits on the frame
     << "set autoscale xfix\n"
     << "set offsets graph 0.02, graph 0.02, graph 0.05, graph 0.02\n";
  // Draw order: all bands, then all lines, then all points, so no band hides another series'
  // data. The legend names each series once (by its line); the grey entries explain the styles.
  std::vector<std::string> items;
  for (std::size_t i = 0; i < series.size(); ++i)
    if (!series[i].lo.empty())
      items.push_back(
          fmt::format("'series{}.dat' using 1:4:5 with filledcurves fc rgb \"{}\" fs transparent solid 0.18 "
                      "noborder notitle",
                      i, kColours[i % kNumColours]));
  for (std::size_t i = 0; i < series.size(); ++i)
    items.push_back(fmt::format("'series{}.dat' using 1:3 with lines lw 2.5 dt {} lc rgb \"{}\" title {}", i,
                                1 + colour_cycle(i), kColours[i % kNumColours], quoted(series[i].label)));
  for (std::size_t i = 0; i < series.size(); ++i)
    items.push_back(fmt::format("'series{}.dat' using 1:2 with points pt {} ps 1.1 lc rgb \"{}\" notitle", i,
                                kPointTypes[colour_cycle(i) % kPointTypes.size()], kColours[i % kNumColours]));
  items.push_back("keyentry with points pt 7 ps 1.1 lc rgb \"#666666\" title \"observed\"");
  items.push_back("keyentry with lines lw 2.5 lc rgb \"#666666\" title \"posterior fit\"");
  if (any_band)
    items.push_back(
        "keyentry with filledcurves fc rgb \"#666666\" fs transparent solid 0.18 noborder "
        "title \"95 % predictive band\"");
  gp << "plot ";
  for (std::size_t k = 0; k < items.size(); ++k) gp << (k ? ", \\\n     " : "") << items[k];
  gp << "\n";

  render(png_path, work, 1000, 700, 13, gp.str());
}

void plot_pairs(const std::string& png_path, const std::vector<std::string>& names,
                const std::vector<std::vector<double>>& draws) {
  const std::size_t P = names.size();
  if (P == 0) throw RunError("plotting '" + png_path + "': no parameters to plot");
  if (draws.empty()) throw RunError("plotting '" + png_path + "': no draws to plot");
  for (std::size_t k = 0; k < draws.size(); ++k)
    if (draws[k].size() != P)
      throw RunError(
          fmt::format("plotting '{}': draw {} has {} values for {} parameter names", png_path, k, draws[k].size(), P));
  std::vector<Range> range(P);
  for (std::size_t p = 0; p < P; ++p) range[p] = padded_range(draws, p, png_path, names[p]);
  check_target(png_path);
  if (!gnuplot_available()) throw RunError("plotting '" + png_path + "': gnuplot was not found on PATH");

  TempFolder work;
  // Even thinning (every stride-th draw) keeps the picture of the whole run, chains included.
  const std::size_t stride = (draws.size() + kMaxScatterPoints - 1) / kMaxScatterPoints;
  std::size_t shown = 0;
  {
    std::string scatter;
    for (std::size_t k = 0; k < draws.size(); k += stride, ++shown) {
      for (std::size_t p = 0; p < P; ++p) scatter += (p ? " " : "") + num(draws[k][p]);
      scatter += "\n";
    }
    write_data_file(work.path() / "draws.dat", scatter);
  }
  // Panels placed by explicit screen margins so that columns share x ranges and rows share y
  // ranges exactly; axis names and tick labels only on the outer edges (bottom row, left column).
  const double left = P > 1 ? 0.11 : 0.08, right = 0.97, bottom = 0.09, top = 0.92, gap = 0.006;
  const double w = (right - left) / double(P), h = (top - bottom) / double(P);
  for (std::size_t p = 0; p < P; ++p)
    write_data_file(work.path() / fmt::format("hist{}.dat", p), histogram_data(draws, p, w * kPairsSize));

  const int tick_font = P > 4 ? 10 : 12;
  std::ostringstream gp;
  gp << "set multiplot title " << quoted(fmt::format("Pairwise posterior marginals ({} draws)", draws.size()))
     << " font \",17\"\n"
     << "set tics font \"," << tick_font << "\" nomirror out\n"
     << "set border 3 lc rgb \"#444444\"\n"
     << "set grid lc rgb \"#e5e5e5\"\n"
     << "unset key\n";
  if (P > 1)  // the empty upper triangle holds the legend
    gp << "set label 1 "
       << quoted(fmt::format("diagonal: histogram of each parameter ({} draws)\n"
                             "below: pairs of draws ({} of {} shown)",
                             draws.size(), shown, draws.size()))
       << " at screen " << num(right) << ", screen " << num(top - 0.25 * h) << " right font \",13\"\n";
  for (std::size_t i = 0; i < P; ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      const double x0 = left + double(j) * w, y1 = top - double(i) * h;
      gp << fmt::format("set lmargin at screen {}\nset rmargin at screen {}\n", num(x0 + gap), num(x0 + w - gap))
         << fmt::format("set bmargin at screen {}\nset tmargin at screen {}\n", num(y1 - h + gap), num(y1 - gap))
         << fmt::format("set xrange [{}:{}]\n", num(range[j].lo), num(range[j].hi))
         << tics('x', range[j], w * kPairsSize, tick_font)
         << (i + 1 == P ? "set format x \"%g\"\nset xlabel " + quoted(names[j]) + "\n"
                        : std::string("set format x \"\"\nunset xlabel\n"));
      if (i == j) {
        gp << "set yrange [0:*]\nunset ytics\nunset ylabel\n"
           << fmt::format(
                  "plot 'hist{}.dat' using 1:2:3 with boxes fs solid 0.55 border lc rgb \"#ffffff\" "
                  "lc rgb \"{}\"\n",
                  j, kColours[0]);
      } else {
        gp << fmt::format("set yrange [{}:{}]\n", num(range[i].lo), num(range[i].hi))
           << tics('y', range[i], h * kPairsSize, tick_font)
           << (j == 0 ? "set format y \"%g\"\nset ylabel " + quoted(names[i]) + "\n"
                      : std::string("set format y \"\"\nunset ylabel\n"))
           << fmt::format("plot 'draws.dat' using {}:{} with points pt 7 ps 0.35 lc rgb \"#99{}\"\n", j + 1, i + 1,
                          std::string(kColours[0]).substr(1));
      }
      if (i == 0 && j == 0) gp << "unset label 1\n";  // drawn once, with the first panel
    }
  }
  gp << "unset multiplot\n";
  render(png_path, work, kPairsSize, kPairsSize, 12, gp.str());
}

}  // namespace terracal::bayes
