#include "wavebench/report/figure.hpp"

#include <stdexcept>
#include <utility>

namespace wavebench::report {

Color palette(int index) {
  static constexpr Color kColors[] = {
      {0.12, 0.38, 0.70}, {0.85, 0.33, 0.10}, {0.20, 0.60, 0.25}, {0.58, 0.30, 0.65},
      {0.55, 0.35, 0.20}, {0.85, 0.20, 0.45}, {0.40, 0.40, 0.40}, {0.70, 0.65, 0.10},
  };
  const int n = static_cast<int>(sizeof kColors / sizeof kColors[0]);
  return kColors[((index % n) + n) % n];
}

Axes& Axes::line(std::vector<double> x, std::vector<double> y, std::string label,
                 std::optional<Color> color) {
  Series s;
  s.label = std::move(label);
  s.x = std::move(x);
  s.y = std::move(y);
  s.style = SeriesStyle::kLine;
  s.color = color.value_or(palette(static_cast<int>(series.size())));
  series.push_back(std::move(s));
  return *this;
}

Axes& Axes::scatter(std::vector<double> x, std::vector<double> y, std::string label,
                    std::optional<Color> color, double radius) {
  Series s;
  s.label = std::move(label);
  s.x = std::move(x);
  s.y = std::move(y);
  s.style = SeriesStyle::kScatter;
  s.color = color.value_or(palette(static_cast<int>(series.size())));
  s.width = radius;
  series.push_back(std::move(s));
  return *this;
}

Axes& Axes::annotate(double x, double y, std::string text, bool marker) {
  annotations.push_back({x, y, std::move(text), marker});
  return *this;
}

Figure::Figure(int rows, int cols, std::string title)
    : rows_(rows), cols_(cols), title_(std::move(title)) {
  if (rows < 1 || cols < 1) throw std::invalid_argument("a figure needs at least one axes");
  axes_.resize(static_cast<std::size_t>(rows * cols));
}

Axes& Figure::axes(int row, int col) {
  return axes_.at(static_cast<std::size_t>(row * cols_ + col));
}

const Axes& Figure::axes(int row, int col) const {
  return axes_.at(static_cast<std::size_t>(row * cols_ + col));
}

}  // namespace wavebench::report
