#include "sectors_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "heatmap_plot.hpp"

namespace gridloc::cli {
namespace {

using plot::View;

constexpr int kLeft = 72;         // room for the y tick labels
constexpr int kTop = 84;          // title, caption, the y axis label
constexpr int kRight = 28;        // the frame's right edge clear of the canvas
constexpr int kAxisBelow = 56;    // x tick labels and axis label
constexpr int kMaxPlotPx = 1480;  // plot area's longer side: the image stays <= ~1600 px
constexpr double kMarginM = 0.3;  // map beyond its boundary's bounding box (m)
constexpr int kHatch = 12;        // period of the ambiguous sectors' hatching (px)

const cv::Vec3b kOutside(205, 205, 205);   // outside the boundary, obstacles
const cv::Scalar kWall(45, 45, 45);        // polygon edges and vertices
const cv::Scalar kAmbiguous(40, 40, 215);  // red: hatching and outline
const cv::Vec3b kBorder(110, 110, 110);    // between two sectors

cv::Vec3b to_vec(const cv::Scalar& s) {
  return {static_cast<std::uint8_t>(s[0]), static_cast<std::uint8_t>(s[1]),
          static_cast<std::uint8_t>(s[2])};
}

cv::Vec3b blend(const cv::Vec3b& top, const cv::Vec3b& under, double alpha) {
  cv::Vec3b out;
  for (int k = 0; k < 3; ++k) {
    out[k] = static_cast<std::uint8_t>(std::lround(alpha * top[k] + (1.0 - alpha) * under[k]));
  }
  return out;
}

/// Sector k's fill: hues a golden angle apart, so that sectors found one after the other (often
/// neighbours) differ most; pastel, so that dark numbers and red hatching stay readable.
cv::Vec3b sector_colour(int k) {
  const double hue = std::fmod(k * 0.618033988749895, 1.0) * 180.0;  // OpenCV: 0..180
  const double sat = k % 3 == 0 ? 95.0 : (k % 3 == 1 ? 140.0 : 115.0);
  const double val = k % 2 == 0 ? 250.0 : 228.0;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, sat, val)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  return bgr.at<cv::Vec3b>(0, 0);
}

bool in_free_space(const PolygonMap& map, const Eigen::Vector2d& p) {
  if (!inside(map.boundary, p)) return false;
  return std::none_of(map.obstacles.begin(), map.obstacles.end(),
                      [&](const Polygon& o) { return inside(o, p); });
}

/// The sector of a world point; a point of the free space whose cell centre lies outside it
/// (along the walls) takes the nearest neighbouring cell's, so that the fill reaches the walls.
int sector_near(const SectorMap& s, const Eigen::Vector2d& p) {
  const int k = s.sector_at(p);
  if (k >= 0 || !in_free_space(s.map, p)) return k;
  const GridGeometry& g = s.grid;
  const Cell c = g.cell_of(p.x() - g.origin.x(), p.y() - g.origin.y());
  int best = -1;
  double best_d = 1e300;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (!g.contains(c.ix + dx, c.iy + dy)) continue;
      const int n = s.sector_of[g.index(c.ix + dx, c.iy + dy)];
      const double d = (g.origin + g.cell_center(c.ix + dx, c.iy + dy) - p).squaredNorm();
      if (n >= 0 && d < best_d) best = n, best_d = d;
    }
  }
  return best;
}

/// A legend swatch: a 24 x 14 px box filled by `fill`.
plot::LegendItem swatch(std::function<void(cv::Mat&, const cv::Rect&)> fill, std::string label) {
  return {[fill](cv::Mat& m, const cv::Point2d& p) {
            const cv::Rect r(static_cast<int>(p.x) + 2, static_cast<int>(p.y) - 7, 24, 14);
            fill(m, r);
            cv::rectangle(m, r, cv::Scalar(150, 150, 150), 1);
          },
          std::move(label)};
}

/// A sector's mark on the picture: its text and the baseline origin of that text.
struct Mark {
  std::string text;
  cv::Point origin;
};

/// What names sector k on the picture: "k+1 label" (the table's row and the label) where it
/// fits, else the row number alone, centred on the representative point, in plot-area pixels.
/// Largest sectors first; a mark is left out unless nearly all of its box lies on its own
/// sector and clear of those placed before, so that it can name no other sector.
std::vector<std::optional<Mark>> place_marks(const SectorMap& s, const cv::Mat& id,
                                             const View& view) {
  std::vector<std::size_t> order(s.sectors.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return s.sectors[a].cells > s.sectors[b].cells;
  });
  std::vector<std::optional<Mark>> at(s.sectors.size());
  std::vector<cv::Rect> placed;
  const cv::Rect plot_area(0, 0, id.cols, id.rows);
  const auto fits = [&](std::size_t k, const std::string& text) -> std::optional<Mark> {
    const cv::Size ts = plot::text_size(text, plot::kLabelScale);
    const Eigen::Vector2d& p = s.sectors[k].representative;
    const cv::Point2d q = view.px(p.x(), p.y()) - cv::Point2d(view.origin);
    const cv::Point org(static_cast<int>(std::lround(q.x - ts.width / 2.0)),
                        static_cast<int>(std::lround(q.y + ts.height / 2.0)));
    const cv::Rect box(org.x - 2, org.y - ts.height - 3, ts.width + 4, ts.height + 6);
    if ((box & plot_area) != box) return std::nullopt;
    if (std::any_of(placed.begin(), placed.end(),
                    [&](const cv::Rect& r) { return (r & box).area() > 0; })) {
      return std::nullopt;
    }
    int own = 0;
    for (int r = box.y; r < box.y + box.height; ++r) {
      for (int c = box.x; c < box.x + box.width; ++c)
        own += id.at<int>(r, c) == static_cast<int>(k);
    }
    if (own < 0.85 * box.area()) return std::nullopt;
    placed.push_back(box);
    return Mark{text, org};
  };
  for (const std::size_t k : order) {
    const std::string number = std::to_string(k + 1);
    at[k] = s.sectors[k].label.empty() ? std::nullopt : fits(k, number + " " + s.sectors[k].label);
    if (!at[k]) at[k] = fits(k, number);
  }
  return at;
}

}  // namespace

cv::Mat render_sectors(const SectorMap& s, const std::string& name) {
  // The boundary's bounding box and a margin, in world metres (the view's frame).
  Eigen::Vector2d lo = s.map.boundary.front(), hi = lo;
  for (const auto& p : s.map.boundary) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  View view;
  view.x0 = lo.x() - kMarginM;
  view.y0 = lo.y() - kMarginM;
  view.x1 = hi.x() + kMarginM;
  view.y1 = hi.y() + kMarginM;
  const double w = view.x1 - view.x0, h = view.y1 - view.y0;
  view.scale =
      std::min(plot::fit_scale(w, h, s.grid.resolution, 900.0), kMaxPlotPx / std::max(w, h));
  view.origin = {kLeft, kTop};

  // Each plot pixel's sector.
  const int pw = view.width(), ph = view.height();
  cv::Mat id(ph, pw, CV_32S);
  for (int r = 0; r < ph; ++r) {
    for (int c = 0; c < pw; ++c) {
      const cv::Point2d p = view.at(c, r);
      id.at<int>(r, c) = sector_near(s, {p.x, p.y});
    }
  }
  const std::vector<std::optional<Mark>> marks = place_marks(s, id, view);
  const auto numbered =
      std::count_if(marks.begin(), marks.end(), [](const auto& n) { return n.has_value(); });
  const auto labelled = std::count_if(marks.begin(), marks.end(), [](const auto& n) {
    return n.has_value() && n->text.find(' ') != std::string::npos;
  });

  int ambiguous = 0;
  for (const Sector& sector : s.sectors) ambiguous += sector.ambiguous ? 1 : 0;
  const std::string title =
      "Visibility sectors of " + name + ": " + std::to_string(s.sectors.size()) +
      (s.sectors.size() == 1 ? " sector, " : " sectors, ") + std::to_string(ambiguous) +
      " ambiguous, N'_min " + std::to_string(s.n_min_two()) + " readings per turn";
  // Many small sectors cannot all carry a number, nor many numbers their label: say how many
  // do.
  const std::string which =
      (numbered == static_cast<long>(s.sectors.size())
           ? std::string("every sector is numbered")
           : std::to_string(numbered) + " sectors large enough are numbered") +
      " (the rows of the table of `gridloc sectors`), " + std::to_string(labelled) +
      " with their label";
  const std::string caption = "sampled on " + plot::number(s.grid.resolution) + " m cells; " +
                              which + ", read counter-clockwise from east";
  const int width = std::max({kLeft + view.width() + kRight,
                              plot::text_size(title, plot::kTitleScale, 2).width + 24,
                              plot::text_size(caption, plot::kTickScale).width + 24});
  cv::Mat img(kTop + view.height() + kAxisBelow + 140, width, CV_8UC3, cv::Scalar(255, 255, 255));

  // The fill: sector colours, grey elsewhere, ambiguous sectors hatched with a red rim, a thin
  // grey line where two sectors meet.
  std::vector<cv::Vec3b> colour;
  for (std::size_t k = 0; k < s.sectors.size(); ++k) {
    colour.push_back(sector_colour(static_cast<int>(k)));
  }
  const cv::Vec3b red = to_vec(kAmbiguous);
  const auto at = [&](int r, int c) {
    return r < 0 || c < 0 || r >= ph || c >= pw ? -1 : id.at<int>(r, c);
  };
  for (int r = 0; r < ph; ++r) {
    auto* row = img.ptr<cv::Vec3b>(kTop + r) + kLeft;
    for (int c = 0; c < pw; ++c) {
      const int k = id.at<int>(r, c);
      if (k < 0) {
        row[c] = kOutside;
        continue;
      }
      row[c] = colour[k];
      if (s.sectors[k].ambiguous) {
        bool rim = false;
        for (int d = 1; d <= 2 && !rim; ++d) {
          rim = at(r, c + d) != k || at(r, c - d) != k || at(r + d, c) != k || at(r - d, c) != k;
        }
        if (rim) {
          row[c] = red;
        } else if ((c + r) % kHatch < 2) {
          row[c] = blend(red, row[c], 0.75);
        }
        continue;
      }
      const int right = at(r, c + 1), below = at(r + 1, c);
      if ((right >= 0 && right != k) || (below >= 0 && below != k)) row[c] = kBorder;
    }
  }

  // Walls over the fill, the vertices as dots, then the numbers.
  for (const auto& [a, b] : polygon_edges(s.map)) {
    plot::line(img, view.px(a.x(), a.y()), view.px(b.x(), b.y()), kWall, 2);
  }
  for (const Eigen::Vector2d& v : s.vertices) {
    plot::circle(img, view.px(v.x(), v.y()), 4.0, kWall, cv::FILLED);
  }
  for (std::size_t k = 0; k < s.sectors.size(); ++k) {
    if (!marks[k]) continue;
    plot::halo_text(img, marks[k]->text, marks[k]->origin + view.origin, plot::kLabelScale,
                    s.sectors[k].ambiguous ? kAmbiguous : plot::kInk);
  }
  plot::axes_m(img, view, 0.0, 0.0, "x (m)", "y (m)");
  plot::text(img, title, {12, 24}, plot::kTitleScale, plot::kInk, 2);
  plot::text(img, caption, {12, 48}, plot::kTickScale);

  std::vector<plot::LegendItem> items;
  items.push_back(swatch(
      [&](cv::Mat& m, const cv::Rect& r) {
        for (int k = 0; k < 3; ++k) {
          const cv::Vec3b c = sector_colour(k);
          m(cv::Rect(r.x + k * 8, r.y, 8, r.height)) = cv::Scalar(c[0], c[1], c[2]);
        }
      },
      "sectors, numbered as in the table"));
  items.push_back(swatch(
      [&](cv::Mat& m, const cv::Rect& r) {
        m(r) = cv::Scalar(250, 250, 250);
        for (int y = 0; y < r.height; ++y) {
          for (int x = 0; x < r.width; ++x) {
            if ((x + y) % kHatch < 2) m.at<cv::Vec3b>(r.y + y, r.x + x) = red;
          }
        }
        cv::rectangle(m, r, kAmbiguous, 2);
      },
      "ambiguous: another sector's label turned (seed 000 4.1)"));
  items.push_back(
      swatch([](cv::Mat& m,
                const cv::Rect& r) { m(r) = cv::Scalar(kOutside[0], kOutside[1], kOutside[2]); },
             "outside, obstacles"));
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     plot::line(m, p + cv::Point2d(0, 0), p + cv::Point2d(26, 0), kWall, 2);
                     plot::circle(m, p + cv::Point2d(0, 0), 4.0, kWall, cv::FILLED);
                     plot::circle(m, p + cv::Point2d(26, 0), 4.0, kWall, cv::FILLED);
                   },
                   "walls and vertices"});
  const cv::Rect pr = view.rect();
  const int last = plot::legend(img, items, 12, pr.y + pr.height + kAxisBelow + 20, img.cols - 8);
  return img.rowRange(0, std::min(img.rows, last + 16)).clone();
}

}  // namespace gridloc::cli
