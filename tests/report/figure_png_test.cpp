// The plots come out as PNG files of the asked size with something drawn in them. The files
// are left in the build tree to be looked at.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "wavebench/report/twin_plots.hpp"

namespace wavebench::report {
namespace {

namespace fs = std::filesystem;
const fs::path kOut = fs::path(WAVEBENCH_BINARY_DIR) / "test-output" / "report";

// Share of pixels that are not white; (width, height) through the out-parameters.
double ink_share(const fs::path& png, int& width, int& height) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  width = cairo_image_surface_get_width(s);
  height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  long ink = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const unsigned char* p = data + y * stride + 4 * x;
      if (p[0] < 200 || p[1] < 200 || p[2] < 200) ++ink;
    }
  }
  cairo_surface_destroy(s);
  return static_cast<double>(ink) / (static_cast<double>(width) * height);
}

model::SampledResponse synthetic_response() {
  model::SampledResponse r;
  const double fs_hz = 20000;
  for (int i = 0; i < 40000; ++i) {
    const double t = i / fs_hz;
    r.t.push_back(t);
    const double e = 1e-5 * std::sin(2 * std::numbers::pi * 90 * t) +
                     2e-6 * std::sin(2 * std::numbers::pi * 89.33 * t);
    r.te.push_back(e);
    r.alpha2.push_back(-e * std::pow(2 * std::numbers::pi * 90, 2));
  }
  return r;
}

TEST(FigurePng, WritesTheAskedSizeWithInk) {
  fs::create_directories(kOut);
  Figure fig(1, 1, "A line and a scatter");
  fig.axes(0, 0).line({0, 1, 2, 3}, {0, 1, 4, 9}, "y = x^2");
  fig.axes(0, 0).scatter({0.5, 1.5}, {3, 5}, "points");
  fig.axes(0, 0).annotate(2, 4, "x = 2");
  const fs::path p = kOut / "simple.png";
  fig.write_png(p, 640, 480);
  int w = 0, h = 0;
  const double ink = ink_share(p, w, h);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  EXPECT_GT(ink, 0.01);
  EXPECT_LT(ink, 0.5);
}

TEST(FigurePng, UnwritablePathThrows) {
  Figure fig(1, 1);
  EXPECT_THROW(fig.write_png("/nonexistent-dir/x.png", 100, 100), std::runtime_error);
}

TEST(FigurePng, TwinPlotsRender) {
  fs::create_directories(kOut);
  const auto r = synthetic_response();
  int w = 0, h = 0;

  time_response_figure(r, "Synthetic time response", 0.05).write_png(kOut / "time.png");
  EXPECT_GT(ink_share(kOut / "time.png", w, h), 0.02);

  std::vector<double> f, a;
  for (int i = 1; i < 30000; ++i) {
    f.push_back(i * 0.5);
    const double lines = 1.0 / (1 + std::pow((i * 0.5 - 90) / 0.2, 2)) +
                         0.2 / (1 + std::pow((i * 0.5 - 89.5) / 0.2, 2)) +
                         0.05 / (1 + std::pow((i * 0.5 - 12060) / 0.5, 2));
    a.push_back(1e-5 + lines);
  }
  spectrum_figure(f, a,
                  {{90, 1, "dF_i1, dF_i3, T1k_1"},
                   {89.5, 0.2, "dS_fix, dF_i2"},
                   {12060, 0.05, "df_i (tooth mesh)"}},
                  "alpha2 [rad/s^2]", "Synthetic spectrum")
      .write_png(kOut / "spectrum.png");
  EXPECT_GT(ink_share(kOut / "spectrum.png", w, h), 0.02);

  phase_portrait_figure({{"twist", "x", "v", r.te, r.alpha2}, {"output", "x", "v", r.alpha2, r.te}},
                        "Synthetic phase portrait")
      .write_png(kOut / "phase.png", 800, 700);
  EXPECT_GT(ink_share(kOut / "phase.png", w, h), 0.005);

  poincare_figure({1, 2, 3}, {1, 4, 9}, "x", "v", "period-3", "Synthetic Poincare")
      .write_png(kOut / "poincare.png", 800, 700);
  EXPECT_GT(ink_share(kOut / "poincare.png", w, h), 0.005);

  SweepBranch up{"up", {100, 500, 900}, {{1}, {1.5, 2}, {3, 3.5, 4}}, {1, 2, 4}};
  SweepBranch down{"down", {900, 500, 100}, {{3.8}, {1.2}, {0.9}}, {3.8, 1.2, 0.9}};
  bifurcation_figure({up, down}, "TE at section [arcsec]", "TE amplitude [arcsec]", {500},
                     "Synthetic sweep")
      .write_png(kOut / "bifurcation.png");
  EXPECT_GT(ink_share(kOut / "bifurcation.png", w, h), 0.005);
}

}  // namespace
}  // namespace wavebench::report
