#include "sectors_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "plot.hpp"

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

const cv::Vec3b kAmbiguousFill = to_vec(kAmbiguous);  // red, as a pixel

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
int sector_near(const SectorMap& sectors, const Eigen::Vector2d& p) {
  const int k = sectors.sector_at(p);
  if (k >= 0 || !in_free_space(sectors.map, p)) return k;
  const GridGeometry& grid = sectors.grid;
  const Cell c = grid.cell_of(p.x() - grid.origin.x(), p.y() - grid.origin.y());
  int best = -1;
  double best_d = 1e300;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (!grid.contains(c.ix + dx, c.iy + dy)) continue;
      const int n = sectors.sector_of[grid.index(c.ix + dx, c.iy + dy)];
      const double d = (grid.origin + grid.cell_center(c.ix + dx, c.iy + dy) - p).squaredNorm();
      if (n >= 0 && d < best_d) best = n, best_d = d;
    }
  }
  return best;
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
std::vector<std::optional<Mark>> place_marks(const SectorMap& sectors, const cv::Mat& id,
                                             const View& view) {
  std::vector<std::size_t> order(sectors.sectors.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return sectors.sectors[a].cells > sectors.sectors[b].cells;
  });
  std::vector<std::optional<Mark>> at(sectors.sectors.size());
  std::vector<cv::Rect> placed;
  const cv::Rect plot_area(0, 0, id.cols, id.rows);
  const auto fits = [&](std::size_t k, const std::string& text) -> std::optional<Mark> {
    const cv::Size ts = plot::text_size(text, plot::kLabelScale);
    const Eigen::Vector2d& p = sectors.sectors[k].representative;
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
    at[k] = sectors.sectors[k].label.empty() ? std::nullopt
                                             : fits(k, number + " " + sectors.sectors[k].label);
    if (!at[k]) at[k] = fits(k, number);
  }
  return at;
}

/// The boundary's bounding box and a margin, in world metres (the view's frame).
View sectors_view(const SectorMap& sectors) {
  Eigen::Vector2d lo = sectors.map.boundary.front(), hi = lo;
  for (const auto& p : sectors.map.boundary) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  View view;
  view.x0 = lo.x() - kMarginM;
  view.y0 = lo.y() - kMarginM;
  view.x1 = hi.x() + kMarginM;
  view.y1 = hi.y() + kMarginM;
  const double w = view.x1 - view.x0, h = view.y1 - view.y0;
  view.scale =
      std::min(plot::fit_scale(w, h, sectors.grid.resolution, 900.0), kMaxPlotPx / std::max(w, h));
  view.origin = {kLeft, kTop};
  return view;
}

/// Each plot pixel's sector (sector_near; -1 outside the free space).
cv::Mat sector_ids(const SectorMap& sectors, const View& view) {
  const int pw = view.width(), ph = view.height();
  cv::Mat id(ph, pw, CV_32S);
  for (int r = 0; r < ph; ++r) {
    for (int c = 0; c < pw; ++c) {
      const cv::Point2d p = view.at(c, r);
      id.at<int>(r, c) = sector_near(sectors, {p.x, p.y});
    }
  }
  return id;
}

/// The title line and the caption line under it.
struct TitleLines {
  std::string title, caption;
};

/// The counts of sectors and ambiguous ones, N'_min; how many sectors carry their number and
/// how many their label (many small sectors cannot all carry a number, nor many numbers their
/// label: say how many do).
TitleLines title_lines(const SectorMap& sectors, const std::string& name,
                       const std::vector<std::optional<Mark>>& marks) {
  const auto numbered =
      std::count_if(marks.begin(), marks.end(), [](const auto& n) { return n.has_value(); });
  const auto labelled = std::count_if(marks.begin(), marks.end(), [](const auto& n) {
    return n.has_value() && n->text.find(' ') != std::string::npos;
  });
  int ambiguous = 0;
  for (const Sector& sector : sectors.sectors) ambiguous += sector.ambiguous ? 1 : 0;
  TitleLines h;
  h.title = "Visibility sectors of " + name + ": " + std::to_string(sectors.sectors.size()) +
            (sectors.sectors.size() == 1 ? " sector, " : " sectors, ") + std::to_string(ambiguous) +
            " ambiguous, N'_min " + std::to_string(sectors.n_min_two()) + " readings per turn";
  const std::string which =
      (numbered == static_cast<long>(sectors.sectors.size())
           ? std::string("every sector is numbered")
           : std::to_string(numbered) + " sectors large enough are numbered") +
      " (the rows of the table of `gridloc sectors`), " + std::to_string(labelled) +
      " with their label";
  h.caption = "sampled on " + plot::number(sectors.grid.resolution) + " m cells; " + which +
              ", read counter-clockwise from east";
  return h;
}

/// A white canvas for the plot area of `view`, wide enough for the heading's lines.
cv::Mat sectors_canvas(const View& view, const TitleLines& h) {
  const int width = std::max({kLeft + view.width() + kRight,
                              plot::text_size(h.title, plot::kTitleScale, 2).width + 24,
                              plot::text_size(h.caption, plot::kTickScale).width + 24});
  return cv::Mat(kTop + view.height() + kAxisBelow + 140, width, CV_8UC3,
                 cv::Scalar(255, 255, 255));
}

/// The sector of plot pixel (r, c); -1 beyond the plot area.
int id_at(const cv::Mat& id, int r, int c) {
  return r < 0 || c < 0 || r >= id.rows || c >= id.cols ? -1 : id.at<int>(r, c);
}

/// The fill of plot pixel (r, c): its sector's colour, grey outside, an ambiguous sector
/// hatched with a red rim, a thin grey line where two sectors meet.
cv::Vec3b fill_pixel(const SectorMap& sectors, const cv::Mat& id,
                     const std::vector<cv::Vec3b>& colour, int r, int c) {
  const int k = id.at<int>(r, c);
  if (k < 0) return kOutside;
  if (sectors.sectors[k].ambiguous) {
    bool rim = false;
    for (int d = 1; d <= 2 && !rim; ++d) {
      rim = id_at(id, r, c + d) != k || id_at(id, r, c - d) != k || id_at(id, r + d, c) != k ||
            id_at(id, r - d, c) != k;
    }
    if (rim) return kAmbiguousFill;
    if ((c + r) % kHatch < 2) return blend(kAmbiguousFill, colour[k], 0.75);
    return colour[k];
  }
  const int right = id_at(id, r, c + 1), below = id_at(id, r + 1, c);
  if ((right >= 0 && right != k) || (below >= 0 && below != k)) return kBorder;
  return colour[k];
}

/// The fill of the plot area (fill_pixel), its top-left corner at (kLeft, kTop).
void paint_sectors(cv::Mat& img, const SectorMap& sectors, const cv::Mat& id) {
  std::vector<cv::Vec3b> colour;
  for (std::size_t k = 0; k < sectors.sectors.size(); ++k) {
    colour.push_back(sector_colour(static_cast<int>(k)));
  }
  for (int r = 0; r < id.rows; ++r) {
    auto* row = img.ptr<cv::Vec3b>(kTop + r) + kLeft;
    for (int c = 0; c < id.cols; ++c) row[c] = fill_pixel(sectors, id, colour, r, c);
  }
}

/// Walls over the fill, the vertices as dots, then the numbers.
void draw_walls_and_marks(cv::Mat& img, const View& view, const SectorMap& sectors,
                          const std::vector<std::optional<Mark>>& marks) {
  for (const auto& [a, b] : polygon_edges(sectors.map)) {
    plot::line(img, view.px(a.x(), a.y()), view.px(b.x(), b.y()), kWall, 2);
  }
  for (const Eigen::Vector2d& v : sectors.vertices) {
    plot::circle(img, view.px(v.x(), v.y()), 4.0, kWall, cv::FILLED);
  }
  for (std::size_t k = 0; k < sectors.sectors.size(); ++k) {
    if (!marks[k]) continue;
    plot::halo_text(img, marks[k]->text, marks[k]->origin + view.origin, plot::kLabelScale,
                    sectors.sectors[k].ambiguous ? kAmbiguous : plot::kInk);
  }
}

/// The sectors, the ambiguous ones, the outside and the walls.
std::vector<plot::LegendItem> sectors_legend() {
  std::vector<plot::LegendItem> items;
  items.push_back(plot::swatch(
      [](cv::Mat& m, const cv::Rect& r) {
        for (int k = 0; k < 3; ++k) {
          const cv::Vec3b c = sector_colour(k);
          m(cv::Rect(r.x + k * 8, r.y, 8, r.height)) = cv::Scalar(c[0], c[1], c[2]);
        }
      },
      "sectors, numbered as in the table"));
  items.push_back(plot::swatch(
      [](cv::Mat& m, const cv::Rect& r) {
        m(r) = cv::Scalar(250, 250, 250);
        for (int y = 0; y < r.height; ++y) {
          for (int x = 0; x < r.width; ++x) {
            if ((x + y) % kHatch < 2) m.at<cv::Vec3b>(r.y + y, r.x + x) = kAmbiguousFill;
          }
        }
        cv::rectangle(m, r, kAmbiguous, 2);
      },
      "ambiguous: another sector's label turned (seed 000 4.1)"));
  items.push_back(plot::swatch(
      [](cv::Mat& m, const cv::Rect& r) {
        m(r) = cv::Scalar(kOutside[0], kOutside[1], kOutside[2]);
      },
      "outside, obstacles"));
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     plot::line(m, p + cv::Point2d(0, 0), p + cv::Point2d(26, 0), kWall, 2);
                     plot::circle(m, p + cv::Point2d(0, 0), 4.0, kWall, cv::FILLED);
                     plot::circle(m, p + cv::Point2d(26, 0), 4.0, kWall, cv::FILLED);
                   },
                   "walls and vertices"});
  return items;
}

}  // namespace

cv::Mat render_sectors(const SectorMap& sectors, const std::string& name) {
  const View view = sectors_view(sectors);
  const cv::Mat id = sector_ids(sectors, view);
  const std::vector<std::optional<Mark>> marks = place_marks(sectors, id, view);
  const TitleLines h = title_lines(sectors, name, marks);
  cv::Mat img = sectors_canvas(view, h);
  paint_sectors(img, sectors, id);
  draw_walls_and_marks(img, view, sectors, marks);
  plot::axes_m(img, view, 0.0, 0.0, "x (m)", "y (m)");
  plot::text(img, h.title, {12, 24}, plot::kTitleScale, plot::kInk, 2);
  plot::text(img, h.caption, {12, 48}, plot::kTickScale);
  const cv::Rect pr = view.rect();
  const int last =
      plot::legend(img, sectors_legend(), 12, pr.y + pr.height + kAxisBelow + 20, img.cols - 8);
  return img.rowRange(0, std::min(img.rows, last + 16)).clone();
}

}  // namespace gridloc::cli
