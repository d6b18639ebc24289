// Drawing a Figure with cairo.
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "wavebench/report/axis_ticks.hpp"
#include "wavebench/report/figure.hpp"

namespace wavebench::report {
namespace {

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// One axis: data range and the map to pixels.
struct Scale {
  double lo = 0, hi = 1;
  double p0 = 0, p1 = 1;  // pixel of lo and of hi
  bool log = false;
  double operator()(double v) const {
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                         : (v - lo) / (hi - lo);
    return p0 + t * (p1 - p0);
  }
  bool usable(double v) const { return std::isfinite(v) && (!log || v > 0); }
};

void data_extent(const Axes& ax, bool along_x, bool log, double& lo, double& hi) {
  lo = kInf;
  hi = -kInf;
  for (const auto& s : ax.series) {
    const auto& v = along_x ? s.x : s.y;
    for (const double d : v) {
      if (!std::isfinite(d) || (log && d <= 0)) continue;
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
}

Scale make_scale(const Axes& ax, bool along_x, double p0, double p1) {
  Scale s;
  s.log = along_x ? ax.log_x : ax.log_y;
  s.p0 = p0;
  s.p1 = p1;
  double lo = 0, hi = 0;
  data_extent(ax, along_x, s.log, lo, hi);
  const auto& fixed_lo = along_x ? ax.x_min : ax.y_min;
  const auto& fixed_hi = along_x ? ax.x_max : ax.y_max;
  if (!std::isfinite(lo)) {
    lo = s.log ? 1 : 0;
    hi = s.log ? 10 : 1;
  }
  if (s.log && along_x) {
    s.lo = lo;  // a log frequency axis also spans the data exactly
    s.hi = hi > lo ? hi : lo * 10;
  } else if (s.log) {
    // Eight decades below the top are enough for any spectrum worth reading.
    lo = std::max(lo, hi * 1e-8);
    s.lo = std::pow(10.0, std::floor(std::log10(lo)));
    s.hi = std::pow(10.0, std::ceil(std::log10(hi)));
    if (s.hi <= s.lo) s.hi = s.lo * 10;
  } else if (along_x && std::all_of(ax.series.begin(), ax.series.end(), [](const Series& d) {
               return d.style == SeriesStyle::kLine;
             })) {
    s.lo = lo;  // time and frequency axes span the data exactly; scatter gets a margin
    s.hi = hi > lo ? hi : lo + 1;
  } else if (along_x) {
    const double pad = hi > lo ? 0.03 * (hi - lo) : 1.0;
    s.lo = lo - pad;
    s.hi = hi + pad;
  } else {
    const double pad = 0.05 * (hi - lo);
    const AxisRange r = nice_range(lo - pad, hi + pad);
    s.lo = r.lo;
    s.hi = r.hi;
  }
  if (fixed_lo) s.lo = *fixed_lo;
  if (fixed_hi) s.hi = *fixed_hi;
  if (s.log && s.lo <= 0) s.lo = s.hi * 1e-8;
  if (!(s.hi > s.lo)) s.hi = s.lo + 1;
  return s;
}

void set_color(cairo_t* cr, const Color& c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

double text_width(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  return ext.x_advance;
}

void draw_text(cairo_t* cr, double x, double y, const std::string& text, double align_x,
               double align_y) {
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  const double h = fe.ascent;
  cairo_move_to(cr, x - align_x * ext.x_advance, y + (1.0 - align_y) * h - 0.5 * h * 0.0);
  cairo_show_text(cr, text.c_str());
}

void draw_line_series(cairo_t* cr, const Series& s, const Scale& sx, const Scale& sy) {
  const std::size_t n = std::min(s.x.size(), s.y.size());
  if (n == 0) return;
  set_color(cr, s.color);
  cairo_set_line_width(cr, s.width);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  const double px_span = std::abs(sx.p1 - sx.p0);
  const bool ascending = std::is_sorted(s.x.begin(), s.x.begin() + static_cast<long>(n));
  if (ascending && static_cast<double>(n) > 4 * px_span) {
    // Too many points for the pixels: draw each pixel column's min-max, so peaks survive.
    long column = std::numeric_limits<long>::min();
    double ymin = kInf, ymax = -kInf;
    bool started = false;
    auto flush = [&](long col) {
      if (col == std::numeric_limits<long>::min() || !std::isfinite(ymin)) return;
      const double x = static_cast<double>(col) + 0.5;
      if (!started) {
        cairo_move_to(cr, x, sy(ymin));
        started = true;
      } else {
        cairo_line_to(cr, x, sy(ymin));
      }
      cairo_line_to(cr, x, sy(ymax));
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (!sx.usable(s.x[i]) || !sy.usable(s.y[i])) continue;
      const long col = std::lround(std::floor(sx(s.x[i])));
      if (col != column) {
        flush(column);
        column = col;
        ymin = kInf;
        ymax = -kInf;
      }
      ymin = std::min(ymin, s.y[i]);
      ymax = std::max(ymax, s.y[i]);
    }
    flush(column);
    cairo_stroke(cr);
    return;
  }
  // Stroked in short pieces: cairo's cost for one long self-crossing path (a phase portrait)
  // grows much faster than its length.
  bool pen_down = false;
  int segments = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!sx.usable(s.x[i]) || !sy.usable(s.y[i])) {
      pen_down = false;
      continue;
    }
    const double x = sx(s.x[i]);
    const double y = sy(s.y[i]);
    if (pen_down) {
      cairo_line_to(cr, x, y);
      if (++segments >= 256) {
        cairo_stroke(cr);
        cairo_move_to(cr, x, y);
        segments = 0;
      }
    } else {
      cairo_move_to(cr, x, y);
      pen_down = true;
    }
  }
  cairo_stroke(cr);
}

void draw_scatter_series(cairo_t* cr, const Series& s, const Scale& sx, const Scale& sy) {
  const std::size_t n = std::min(s.x.size(), s.y.size());
  set_color(cr, s.color, n > 2000 ? 0.5 : 0.9);
  for (std::size_t i = 0; i < n; ++i) {
    if (!sx.usable(s.x[i]) || !sy.usable(s.y[i])) continue;
    cairo_new_sub_path(cr);
    cairo_arc(cr, sx(s.x[i]), sy(s.y[i]), s.width, 0, 2 * std::numbers::pi);
  }
  cairo_fill(cr);
}

void draw_annotations(cairo_t* cr, const Axes& ax, const Scale& sx, const Scale& sy,
                      const Box& area) {
  cairo_set_font_size(cr, 11);
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  const double line_h = fe.ascent + fe.descent + 2;
  // Highest points first so the tallest peaks get the places closest to them.
  std::vector<const Annotation*> order;
  for (const auto& a : ax.annotations) {
    if (sx.usable(a.x) && sy.usable(a.y)) order.push_back(&a);
  }
  std::sort(order.begin(), order.end(),
            [&](const Annotation* a, const Annotation* b) { return sy(a->y) < sy(b->y); });
  std::vector<Box> placed;
  for (const Annotation* a : order) {
    const double px = sx(a->x);
    const double py = sy(a->y);
    if (px < area.x0 - 1 || px > area.x1 + 1) continue;
    const double w = text_width(cr, a->text) + 4;
    double left = std::clamp(px - w / 2, area.x0 + 2, area.x1 - w - 2);
    double top = std::max(area.y0 + 2, py - 8 - line_h);
    Box box{left, top, left + w, top + line_h};
    // Move down the plot (or further up) until the label is clear of the others.
    for (int tries = 0; tries < 40; ++tries) {
      bool clash = false;
      for (const auto& p : placed) clash = clash || box.overlaps(p);
      if (!clash) break;
      box.y0 += line_h;
      box.y1 += line_h;
      if (box.y1 > area.y1) {
        box.y0 = area.y0 + 2 + (tries % 6) * line_h;
        box.y1 = box.y0 + line_h;
        box.x0 = std::min(area.x1 - w - 2, box.x0 + w * 0.6);
        box.x1 = box.x0 + w;
      }
    }
    placed.push_back(box);
    if (a->marker) {
      cairo_set_source_rgb(cr, 0.8, 0.1, 0.1);
      cairo_arc(cr, px, py, 2.5, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    }
    const double cx = std::clamp(px, box.x0, box.x1);
    const double cy = py < box.y0 ? box.y0 : box.y1;
    if (std::abs(cy - py) > 10 || std::abs(cx - px) > 2) {
      cairo_set_source_rgba(cr, 0.5, 0.5, 0.5, 0.8);
      cairo_set_line_width(cr, 0.6);
      cairo_move_to(cr, px, py);
      cairo_line_to(cr, cx, cy);
      cairo_stroke(cr);
    }
    cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
    cairo_rectangle(cr, box.x0, box.y0, box.x1 - box.x0, box.y1 - box.y0);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_move_to(cr, box.x0 + 2, box.y0 + fe.ascent + 1);
    cairo_show_text(cr, a->text.c_str());
  }
}

void draw_legend(cairo_t* cr, const Axes& ax, const Box& area) {
  std::vector<const Series*> named;
  for (const auto& s : ax.series) {
    if (!s.label.empty()) named.push_back(&s);
  }
  if (named.empty()) return;
  cairo_set_font_size(cr, 11);
  double w = 0;
  for (const auto* s : named) w = std::max(w, text_width(cr, s->label));
  const double row = 15;
  const double bw = w + 36;
  const double bh = row * static_cast<double>(named.size()) + 6;
  const double x0 = area.x1 - bw - 6;
  const double y0 = area.y0 + 6;
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
  cairo_rectangle(cr, x0, y0, bw, bh);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);
  for (std::size_t i = 0; i < named.size(); ++i) {
    const double y = y0 + 3 + row * (static_cast<double>(i) + 0.5);
    set_color(cr, named[i]->color);
    if (named[i]->style == SeriesStyle::kLine) {
      cairo_set_line_width(cr, 2);
      cairo_move_to(cr, x0 + 6, y);
      cairo_line_to(cr, x0 + 26, y);
      cairo_stroke(cr);
    } else {
      cairo_arc(cr, x0 + 16, y, 3, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_text(cr, x0 + 30, y, named[i]->label, 0, 0.5);
  }
}

void draw_axes(cairo_t* cr, const Axes& ax, const Box& cell) {
  const Box area{cell.x0 + 78, cell.y0 + 30, cell.x1 - 16, cell.y1 - 48};
  if (area.x1 - area.x0 < 20 || area.y1 - area.y0 < 20) return;
  const Scale sx = make_scale(ax, true, area.x0, area.x1);
  const Scale sy = make_scale(ax, false, area.y1, area.y0);

  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, 13);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  draw_text(cr, (area.x0 + area.x1) / 2, cell.y0 + 8, ax.title, 0.5, 0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);

  // Grid and tick labels.
  cairo_set_font_size(cr, 11);
  const auto xt = sx.log ? log_ticks(sx.lo, sx.hi) : nice_ticks(sx.lo, sx.hi);
  const auto yt = sy.log ? log_ticks(sy.lo, sy.hi) : nice_ticks(sy.lo, sy.hi, 7);
  auto spacing = [](const std::vector<double>& t) { return t.size() > 1 ? t[1] - t[0] : 1.0; };
  for (const double t : xt) {
    const double x = sx(t);
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_set_line_width(cr, 0.8);
    cairo_move_to(cr, x, area.y0);
    cairo_line_to(cr, x, area.y1);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    draw_text(cr, x, area.y1 + 5, tick_label(t, sx.log ? t : spacing(xt)), 0.5, 0);
  }
  for (const double t : yt) {
    const double y = sy(t);
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_set_line_width(cr, 0.8);
    cairo_move_to(cr, area.x0, y);
    cairo_line_to(cr, area.x1, y);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    draw_text(cr, area.x0 - 5, y, tick_label(t, sy.log ? t : spacing(yt)), 1, 0.5);
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_font_size(cr, 12);
  draw_text(cr, (area.x0 + area.x1) / 2, area.y1 + 24, ax.x_label, 0.5, 0);
  cairo_save(cr);
  cairo_translate(cr, cell.x0 + 14, (area.y0 + area.y1) / 2);
  cairo_rotate(cr, -std::numbers::pi / 2);
  draw_text(cr, 0, 0, ax.y_label, 0.5, 0.5);
  cairo_restore(cr);

  cairo_save(cr);
  cairo_rectangle(cr, area.x0, area.y0, area.x1 - area.x0, area.y1 - area.y0);
  cairo_clip(cr);
  for (const auto& s : ax.series) {
    if (s.style == SeriesStyle::kLine) {
      draw_line_series(cr, s, sx, sy);
    } else {
      draw_scatter_series(cr, s, sx, sy);
    }
  }
  draw_annotations(cr, ax, sx, sy, area);
  cairo_restore(cr);

  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, area.x0, area.y0, area.x1 - area.x0, area.y1 - area.y0);
  cairo_stroke(cr);
  draw_legend(cr, ax, area);
}

}  // namespace

void Figure::write_png(const std::filesystem::path& path, int width, int height) const {
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height),
                     &cairo_surface_destroy);
  ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  double top = 0;
  if (!title_.empty()) {
    cairo_select_font_face(cr.get(), "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr.get(), 16);
    cairo_set_source_rgb(cr.get(), 0.05, 0.05, 0.05);
    draw_text(cr.get(), width / 2.0, 8, title_, 0.5, 0);
    top = 30;
  }
  const double cw = static_cast<double>(width) / cols_;
  const double ch = (static_cast<double>(height) - top) / rows_;
  for (int r = 0; r < rows_; ++r) {
    for (int c = 0; c < cols_; ++c) {
      const Box cell{c * cw, top + r * ch, (c + 1) * cw, top + (r + 1) * ch};
      draw_axes(cr.get(), axes(r, c), cell);
    }
  }
  cairo_surface_flush(surface.get());
  if (cairo_surface_write_to_png(surface.get(), path.c_str()) != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error("cannot write " + path.string());
  }
}

}  // namespace wavebench::report
