#include "plot.hpp"

#include "heatmap_layout.hpp"

#include "gridloc/grids/error.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <utility>

namespace gridloc::cli::plot {

// Written with libpng's simplified API rather than OpenCV's imgcodecs: imgcodecs pulls in
// GDAL and a hundred more libraries, 40 MB of every gridloc run's resident memory (issue 35).
void write_png(const std::string& path, const cv::Mat& img) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(img.cols);
  image.height = static_cast<png_uint_32>(img.rows);
  const int channels = img.channels();
  image.format = channels == 1 ? PNG_FORMAT_GRAY : channels == 3 ? PNG_FORMAT_BGR : PNG_FORMAT_BGRA;
  if (img.depth() != CV_8U || (channels != 1 && channels != 3 && channels != 4) || img.empty()) {
    throw Error(path + ": cannot write the image (not an 8-bit grey, BGR or BGRA picture)");
  }
  const bool ok = png_image_write_to_file(&image, path.c_str(), 0, img.data,
                                          static_cast<png_int_32>(img.step[0]), nullptr) != 0;
  if (!ok) throw Error(path + ": cannot write the image (" + image.message + ")");
}

namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kSub = 1 << kShift;

}  // namespace

void text(cv::Mat& img, const std::string& s, cv::Point org, double scale, const cv::Scalar& colour,
          int thickness) {
  cv::putText(img, s, org, kFont, scale, colour, thickness, cv::LINE_AA);
}

void halo_text(cv::Mat& img, const std::string& s, cv::Point org, double scale,
               const cv::Scalar& colour, int thickness) {
  cv::putText(img, s, org, kFont, scale, kWhite, thickness + 3, cv::LINE_AA);
  cv::putText(img, s, org, kFont, scale, colour, thickness, cv::LINE_AA);
}

cv::Size text_size(const std::string& s, double scale, int thickness) {
  int baseline = 0;
  return cv::getTextSize(s, kFont, scale, thickness, &baseline);
}

std::vector<std::string> wrap(const std::string& s, double scale, int thickness, int width) {
  std::vector<std::string> lines;
  std::string line, word;
  const auto flush_word = [&] {
    if (word.empty()) return;
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_size(longer, scale, thickness).width > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
    word.clear();
  };
  for (const char c : s) {
    if (c == ' ')
      flush_word();
    else
      word += c;
  }
  flush_word();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

void title_block(cv::Mat& img, const std::vector<std::string>& title,
                 const std::vector<std::string>& caption) {
  int y = 24;
  for (const std::string& line : title) {
    text(img, line, {12, y}, kTitleScale, kInk, 2);
    y += 28;
  }
  for (const std::string& line : caption) {
    text(img, line, {12, y - 4}, kTickScale);
    y += 20;
  }
}

int title_block_bottom(std::size_t title_lines, std::size_t caption_lines) {
  return 24 + 28 * static_cast<int>(title_lines) + 20 * static_cast<int>(caption_lines);
}

std::string fixed(double v, int digits) {
  std::ostringstream ss;
  ss << std::fixed << std::setprecision(digits) << (std::abs(v) < 0.5e-9 ? 0.0 : v);
  return ss.str();
}

std::string number(double v) {
  std::ostringstream ss;
  ss << std::setprecision(4) << (std::abs(v) < 1e-9 ? 0.0 : v);
  return ss.str();
}

double nice_step(double at_least) {
  const double p = std::pow(10.0, std::floor(std::log10(at_least)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= at_least * (1.0 - 1e-9)) return m * p;
  }
  return 10.0 * p;
}

int View::width() const {
  return static_cast<int>(std::lround((x1 - x0) * scale));
}
int View::height() const {
  return static_cast<int>(std::lround((y1 - y0) * scale));
}

Box padded(Box box, double margin_fraction) {
  if (box.empty()) box.add(Eigen::Vector2d::Zero());
  const double side = (box.hi - box.lo).maxCoeff();
  if (side < 0.01) {
    const Eigen::Vector2d centre = 0.5 * (box.lo + box.hi);
    return {centre - Eigen::Vector2d::Constant(0.5), centre + Eigen::Vector2d::Constant(0.5)};
  }
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(margin_fraction * side);
  return {box.lo - margin, box.hi + margin};
}

double fit_scale(double w, double h, double cell, double target_px) {
  const double side = std::max(w, h);
  double s = target_px / side;
  if (s * cell < 4.0) s = std::max(s, std::min(4.0 / cell, 1600.0 / side));
  return s;
}

cv::Point sub(const cv::Point2d& p) {
  return {static_cast<int>(std::lround(p.x * kSub)), static_cast<int>(std::lround(p.y * kSub))};
}

void line(cv::Mat& img, const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& colour,
          int thickness) {
  cv::line(img, sub(a), sub(b), colour, thickness, cv::LINE_AA, kShift);
}

void dashed_line(cv::Mat& img, const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& colour,
                 int thickness, double dash) {
  const cv::Point2d d = b - a;
  const double length = std::hypot(d.x, d.y);
  if (length <= 0.0) return;
  for (double s = 0.0; s < length; s += 2.0 * dash) {
    const double e = std::min(s + dash, length);
    line(img, a + d * (s / length), a + d * (e / length), colour, thickness);
  }
}

void circle(cv::Mat& img, const cv::Point2d& c, double radius, const cv::Scalar& colour,
            int thickness) {
  cv::circle(img, sub(c), static_cast<int>(std::lround(radius * kSub)), colour, thickness,
             cv::LINE_AA, kShift);
}

namespace {
/// The rings that can be drawn (an empty ring is left out).
Contours drawable(Contours rings) {
  std::erase_if(rings, [](const std::vector<cv::Point>& ring) { return ring.empty(); });
  return rings;
}
}  // namespace

void fill_rings(cv::Mat& img, const Contours& rings, const cv::Scalar& colour) {
  const Contours kept = drawable(rings);
  if (!kept.empty()) cv::fillPoly(img, kept, colour, cv::LINE_AA, kShift);
}

void outline_rings(cv::Mat& img, const Contours& rings, const cv::Scalar& colour, int thickness) {
  const Contours kept = drawable(rings);
  if (!kept.empty()) cv::polylines(img, kept, true, colour, thickness, cv::LINE_AA, kShift);
}

cv::Point2d direction(double heading) {
  return {std::cos(heading), -std::sin(heading)};  // image rows grow downwards
}

void axes_m(cv::Mat& img, const View& v, double ox, double oy, const std::string& x_label,
            const std::string& y_label) {
  const cv::Rect r = v.rect();
  cv::rectangle(img, r, kInk, 1);
  // Ticks at least ~70 px apart, labelled in metres.
  const double step = nice_step(70.0 / v.scale);
  const int digits = step >= 1.0 ? 0 : (step >= 0.1 ? 1 : 2);
  for (double t = std::ceil((v.x0 + ox) / step) * step; t <= v.x1 + ox + 1e-9; t += step) {
    const double x = v.px(t - ox, 0.0).x;
    line(img, {x, static_cast<double>(r.y + r.height)}, {x, r.y + r.height + 5.0}, kInk, 1);
    const std::string s = fixed(t, digits);
    const cv::Size ts = text_size(s, kTickScale);
    text(img, s, {static_cast<int>(std::lround(x)) - ts.width / 2, r.y + r.height + 8 + ts.height},
         kTickScale);
  }
  for (double t = std::ceil((v.y0 + oy) / step) * step; t <= v.y1 + oy + 1e-9; t += step) {
    const double y = v.px(0.0, t - oy).y;
    line(img, {r.x - 5.0, y}, {static_cast<double>(r.x), y}, kInk, 1);
    const std::string s = fixed(t, digits);
    const cv::Size ts = text_size(s, kTickScale);
    text(img, s, {r.x - 8 - ts.width, static_cast<int>(std::lround(y)) + ts.height / 2},
         kTickScale);
  }
  const cv::Size xs = text_size(x_label, kLabelScale);
  text(img, x_label, {r.x + r.width / 2 - xs.width / 2, r.y + r.height + 26 + xs.height},
       kLabelScale);
  text(img, y_label, {std::max(2, r.x - 8 - text_size(y_label, kLabelScale).width), r.y - 8},
       kLabelScale);
}

void colour_bar(cv::Mat& img, const cv::Mat& lut, int x, int top, int bottom, double lo, double hi,
                const std::string& title) {
  constexpr int kWidth = 22;
  const int h = bottom - top;
  for (int r = 0; r < h; ++r) {
    const int k = h > 1 ? static_cast<int>(std::lround(255.0 * (h - 1 - r) / (h - 1))) : 255;
    const cv::Vec3b c = lut.at<cv::Vec3b>(k);
    cv::line(img, {x, top + r}, {x + kWidth - 1, top + r}, cv::Scalar(c[0], c[1], c[2]), 1);
  }
  cv::rectangle(img, {x - 1, top - 1, kWidth + 2, h + 2}, kInk, 1);
  auto tick = [&](double value) {
    const double f = hi > lo ? (value - lo) / (hi - lo) : 1.0;
    const int y = top + static_cast<int>(std::lround((1.0 - f) * (h - 1)));
    cv::line(img, {x + kWidth, y}, {x + kWidth + 5, y}, kInk, 1);
    const std::string s = number(value);
    text(img, s, {x + kWidth + 8, y + text_size(s, kTickScale).height / 2}, kTickScale);
    return y;
  };
  const int y_hi = tick(hi), y_lo = tick(lo);
  if (hi > lo) {  // round values in between, clear of the ends
    const double step = nice_step((hi - lo) / 5.0);
    for (double t = std::ceil(lo / step) * step; t < hi; t += step) {
      const int y = top + static_cast<int>(std::lround((1.0 - (t - lo) / (hi - lo)) * (h - 1)));
      if (y - y_hi > 16 && y_lo - y > 16) tick(t);
    }
  }
  text(img, title, {x, top - 10}, kLabelScale);
}

void scale_bar(cv::Mat& img, const View& v) {
  const double length = nice_step(std::min(v.x1 - v.x0, v.y1 - v.y0) / 6.0);
  const double px = length * v.scale;
  const std::string s = length >= 1.0 ? fixed(length, 0) + " m" : fixed(length * 100.0, 0) + " cm";
  const cv::Size ts = text_size(s, kTickScale);
  const cv::Rect r = v.rect();
  const int x = r.x + 10, y = r.y + r.height - 12;
  const int box_w = static_cast<int>(std::lround(px)) + ts.width + 24;
  cv::rectangle(img, {x - 6, y - ts.height - 10, box_w, ts.height + 18}, kWhite, cv::FILLED);
  cv::rectangle(img, {x - 6, y - ts.height - 10, box_w, ts.height + 18}, kInk, 1);
  const double ym = y - ts.height / 2.0 - 1.0;
  line(img, {static_cast<double>(x), ym}, {x + px, ym}, kInk, 3);
  line(img, {static_cast<double>(x), ym - 5}, {static_cast<double>(x), ym + 5}, kInk, 1);
  line(img, {x + px, ym - 5}, {x + px, ym + 5}, kInk, 1);
  text(img, s, {x + static_cast<int>(std::lround(px)) + 8, y}, kTickScale);
}

void estimate_marker(cv::Mat& img, const cv::Point2d& p, double heading) {
  const cv::Point2d tip = p + direction(heading) * 26.0;
  line(img, p, tip, kWhite, 6);
  circle(img, p, 8.0, kWhite, cv::FILLED);
  line(img, p, tip, kEstimate, 3);
  circle(img, p, 6.0, kEstimate, cv::FILLED);
}

void hypothesis_marker(cv::Mat& img, const cv::Point2d& p, double heading, int n) {
  if (std::isfinite(heading)) {
    const cv::Point2d d = direction(heading);
    line(img, p, p + d * 16.0, kWhite, 5);
    line(img, p, p + d * 16.0, kInk, 2);
  }
  circle(img, p, 5.5, kWhite, cv::FILLED);
  circle(img, p, 5.5, kInk, 2);
  // The number beside the disc, opposite its heading tick, so that it stays readable when
  // another marker lies on the disc.
  const std::string s = std::to_string(n);
  const cv::Size ts = text_size(s, kLabelScale, 2);
  const cv::Point2d at =
      std::isfinite(heading) ? p - direction(heading) * 15.0 : p + cv::Point2d(-11.0, -11.0);
  halo_text(img, s,
            {static_cast<int>(std::lround(at.x - ts.width / 2.0)),
             static_cast<int>(std::lround(at.y + ts.height / 2.0))},
            kLabelScale, kInk, 2);
}

void truth_marker(cv::Mat& img, const cv::Point2d& p, double heading) {
  const cv::Point2d tip = p + direction(heading) * 26.0;
  const cv::Point2d a(8.0, 8.0), b(8.0, -8.0);
  for (const auto& [colour, thickness] : {std::pair{kWhite, 6}, std::pair{kTruth, 3}}) {
    dashed_line(img, p, tip, colour, thickness - 1, 4.0);
    line(img, p - a, p + a, colour, thickness);
    line(img, p - b, p + b, colour, thickness);
  }
}

int legend(cv::Mat& img, const std::vector<LegendItem>& items, int x, int y, int max_x) {
  const int x_start = x;
  for (const LegendItem& item : items) {
    const int w = 48 + text_size(item.label, kTickScale).width + 24;
    if (x + w > max_x && x > x_start) {
      x = x_start;
      y += 28;
    }
    item.symbol(img, {x + 12.0, y - 5.0});
    text(img, item.label, {x + 48, y}, kTickScale);
    x += w;
  }
  return y;
}

LegendItem swatch(std::function<void(cv::Mat&, const cv::Rect&)> fill, std::string label) {
  return {[fill](cv::Mat& m, const cv::Point2d& p) {
            const cv::Rect r(static_cast<int>(p.x) + 2, static_cast<int>(p.y) - 7, 24, 14);
            fill(m, r);
            cv::rectangle(m, r, kSwatchEdge, 1);
          },
          std::move(label)};
}

LegendItem filled(const cv::Scalar& colour, std::string label) {
  return swatch([colour](cv::Mat& m, const cv::Rect& r) { m(r) = colour; }, std::move(label));
}

LegendItem stroke(const cv::Scalar& colour, int thickness, std::string label) {
  return {[colour, thickness](cv::Mat& m, const cv::Point2d& p) {
            line(m, p, p + cv::Point2d(26, 0), colour, thickness);
          },
          std::move(label)};
}

cv::Mat viridis() {
  cv::Mat ramp(256, 1, CV_8UC1);
  for (int k = 0; k < 256; ++k) ramp.at<std::uint8_t>(k) = static_cast<std::uint8_t>(k);
  cv::Mat lut;
  cv::applyColorMap(ramp, lut, cv::COLORMAP_VIRIDIS);
  return lut;
}

void paint_grid(cv::Mat& img, const OccupancyMap& map, const View& view) {
  if (map.cells.empty()) return;
  const GridGeometry& g = map.geometry;
  const double c = std::cos(g.yaw), s = std::sin(g.yaw);
  for (int row = 0; row < img.rows; ++row) {
    auto* pixel = img.ptr<cv::Vec3b>(row);
    for (int col = 0; col < img.cols; ++col) {
      const cv::Point2d w = view.at(col, row);
      const double dx = w.x - g.origin.x(), dy = w.y - g.origin.y();
      const Cell cell = g.cell_of(c * dx + s * dy, -s * dx + c * dy);
      const CellState state =
          g.contains(cell.ix, cell.iy) ? map.at(cell.ix, cell.iy) : CellState::Unknown;
      const double level = state == CellState::Free       ? 255.0
                           : state == CellState::Occupied ? layout::kOccupiedGrey
                                                          : layout::kUnknownGrey;
      pixel[col] = cv::Vec3b::all(static_cast<unsigned char>(level));
    }
  }
}

}  // namespace gridloc::cli::plot
