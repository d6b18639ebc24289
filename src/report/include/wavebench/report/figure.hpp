#pragma once
// A small plotting layer: a figure is a grid of axes; axes hold line and scatter series and
// text annotations in data coordinates. write_png() draws it with cairo.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wavebench::report {

struct Color {
  double r = 0, g = 0, b = 0;
};

// Columns of a min/max envelope of a long record (analysis::min_max_columns): about one per
// pixel column of a plot on a 1400 px wide figure, so the envelope draws what every sample would.
inline constexpr std::size_t kEnvelopeColumns = 1000;

// A palette that stays distinguishable in print.
Color palette(int index);

enum class SeriesStyle { kLine, kScatter };

struct Series {
  std::string label;  // shown in the legend when not empty
  std::vector<double> x, y;
  SeriesStyle style = SeriesStyle::kLine;
  Color color;
  double width = 1.2;  // line width, or marker radius for scatter [px]
};

struct Annotation {
  double x = 0, y = 0;  // data coordinates of the point the text refers to
  std::string text;
  bool marker = true;  // draw a small mark at (x, y)
};

struct Axes {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::optional<double> x_min, x_max, y_min, y_max;  // otherwise from the data

  Axes& line(std::vector<double> x, std::vector<double> y, std::string label = {},
             std::optional<Color> color = std::nullopt);
  Axes& scatter(std::vector<double> x, std::vector<double> y, std::string label = {},
                std::optional<Color> color = std::nullopt, double radius = 1.5);
  Axes& annotate(double x, double y, std::string text, bool marker = true);

  std::vector<Series> series;
  std::vector<Annotation> annotations;
};

class Figure {
 public:
  Figure(int rows, int cols, std::string title = {});

  Axes& axes(int row, int col);
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  const std::string& title() const { return title_; }
  const Axes& axes(int row, int col) const;

  // Throws std::runtime_error when the file cannot be written.
  void write_png(const std::filesystem::path& path, int width = 1400, int height = 900) const;

 private:
  int rows_, cols_;
  std::string title_;
  std::vector<Axes> axes_;
};

}  // namespace wavebench::report
