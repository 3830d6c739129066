// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/ParetoPlot.h>

#include "PlotFont.h"

#include <strata/IntegerMath.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace strata::scene {

namespace {

using Color = std::array<std::uint8_t, 3>;

struct Canvas
{
    render::Image& image;

    void blend(int x, int y, const Color& c, double alpha)
    {
        if (x < 0 || y < 0 || x >= image.width || y >= image.height || alpha <= 0.0) return;
        std::uint8_t* p = image.at(x, y);
        for (int i = 0; i < 3; ++i) p[i] = std::uint8_t(roundToInt<int>(p[i] * (1.0 - alpha) + c[std::size_t(i)] * alpha));
    }

    void line(int x0, int y0, int x1, int y1, const Color& c, int thickness = 1)
    {
        const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
        const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
        int err = dx + dy;
        for (;;) {
            for (int t = 0; t < thickness; ++t) {
                if (dx >= -dy) blend(x0, y0 + t - thickness / 2, c, 1.0);
                else blend(x0 + t - thickness / 2, y0, c, 1.0);
            }
            if (x0 == x1 && y0 == y1) break;
            const int e2 = 2 * err;
            if (e2 >= dy) { err += dy; x0 += sx; }
            if (e2 <= dx) { err += dx; y0 += sy; }
        }
    }

    void disc(int cx, int cy, int r, const Color& c)
    {
        for (int y = -r; y <= r; ++y)
            for (int x = -r; x <= r; ++x)
                if (x * x + y * y <= r * r) blend(cx + x, cy + y, c, 1.0);
    }

    /// Text with its top-left cell corner at (x, y); vertical: rotated 90°
    /// counter-clockwise, reading bottom to top, (x, y) the bottom-left.
    void text(int x, int y, const std::string& s, const Color& c, bool vertical = false)
    {
        for (std::size_t i = 0; i < s.size(); ++i) {
            for (int gy = 0; gy < GLYPH_HEIGHT; ++gy) {
                for (int gx = 0; gx < GLYPH_WIDTH; ++gx) {
                    const int coverage = glyphCoverage(s[i], gx, gy);
                    if (coverage == 0) continue;
                    const int advance = int(i) * GLYPH_WIDTH + gx;
                    if (vertical) blend(x + gy, y - advance, c, coverage / 15.0);
                    else blend(x + advance, y + gy, c, coverage / 15.0);
                }
            }
        }
    }
};

int textWidth(const std::string& s) { return int(s.size()) * GLYPH_WIDTH; }

std::string tickText(double v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", v);
    return buffer;
}

struct Axis
{
    double lo = 0.0, hi = 1.0; // in axis space (log10 when log)
    bool log = false;
    std::vector<double> ticks; // data values

    double toAxis(double v) const { return log ? std::log10(v) : v; }
    double fraction(double v) const { return (toAxis(v) - lo) / (hi - lo); }
};

bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }

Axis makeAxis(std::vector<double> values, bool log)
{
    Axis a;
    a.log = log;
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (double v : values) {
        if (!usable(v, log)) continue;
        lo = std::min(lo, a.toAxis(v));
        hi = std::max(hi, a.toAxis(v));
    }
    if (!(lo <= hi)) lo = 0.0, hi = 1.0;
    if (hi - lo < 1e-9) lo -= log ? 0.5 : std::max(1e-3, std::abs(lo) * 0.1), hi += log ? 0.5 : std::max(1e-3, std::abs(hi) * 0.1);
    const double pad = 0.08 * (hi - lo);
    lo -= pad;
    hi += pad;
    a.lo = lo;
    a.hi = hi;
    if (log) {
        for (int e = floorToInt<int>(lo); e <= ceilToInt<int>(hi); ++e) {
            for (double m : {1.0, 2.0, 5.0}) {
                const double v = m * std::pow(10.0, e);
                if (std::log10(v) >= lo && std::log10(v) <= hi) a.ticks.push_back(v);
            }
        }
    } else {
        const double raw = (hi - lo) / 6.0;
        const double decade = std::pow(10.0, std::floor(std::log10(raw)));
        double step = decade;
        for (double m : {1.0, 2.0, 5.0, 10.0}) {
            if (m * decade >= raw) {
                step = m * decade;
                break;
            }
        }
        for (double v = std::ceil(lo / step) * step; v <= hi + 1e-12 * step; v += step) {
            a.ticks.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
        }
    }
    return a;
}

} // namespace

std::vector<std::size_t> paretoFront(const PlotPanel& panel)
{
    std::vector<std::size_t> front;
    const auto& p = panel.points;
    auto better = [&](double a, double b) { return panel.higherIsBetter ? a > b : a < b; };
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (!usable(p[i].x, panel.logX) || !usable(p[i].y, panel.logY)) continue;
        bool dominated = false;
        for (std::size_t j = 0; j < p.size() && !dominated; ++j) {
            if (j == i || !usable(p[j].x, panel.logX) || !usable(p[j].y, panel.logY)) continue;
            const bool noWorse = p[j].x <= p[i].x && !better(p[i].y, p[j].y);
            const bool strictly = p[j].x < p[i].x || better(p[j].y, p[i].y);
            dominated = noWorse && strictly;
        }
        if (!dominated) front.push_back(i);
    }
    std::sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
        return p[a].x < p[b].x || (p[a].x == p[b].x && a < b);
    });
    return front;
}

render::Image drawPlot(const std::vector<PlotPanel>& panels, int panelWidth, int height)
{
    render::Image image;
    image.width = panelWidth * int(panels.size());
    image.height = height;
    image.pixels.assign(std::size_t(image.width) * std::size_t(height) * 4, 255);
    Canvas canvas{image};
    const Color black{0, 0, 0}, grey{225, 225, 225}, frontColor{230, 120, 20};
    const int left = 78, right = 24, top = 34, bottom = 56;

    for (std::size_t n = 0; n < panels.size(); ++n) {
        const PlotPanel& panel = panels[n];
        const int x0 = int(n) * panelWidth + left, x1 = int(n + 1) * panelWidth - right;
        const int y0 = top, y1 = height - bottom; // y0 top, y1 bottom of the plot area
        std::vector<double> xs, ys;
        for (const PlotPoint& p : panel.points) {
            if (!usable(p.x, panel.logX) || !usable(p.y, panel.logY)) continue;
            xs.push_back(p.x);
            ys.push_back(p.y);
        }
        const Axis ax = makeAxis(xs, panel.logX), ay = makeAxis(ys, panel.logY);
        auto px = [&](double v) { return x0 + roundToInt<int>(ax.fraction(v) * (x1 - x0)); };
        auto py = [&](double v) { return y1 - roundToInt<int>(ay.fraction(v) * (y1 - y0)); };

        // Grid and ticks.
        for (double t : ax.ticks) {
            const int x = px(t);
            canvas.line(x, y0, x, y1, grey);
            canvas.line(x, y1, x, y1 + 5, black);
            const std::string s = tickText(t);
            canvas.text(x - textWidth(s) / 2, y1 + 8, s, black);
        }
        for (double t : ay.ticks) {
            const int y = py(t);
            canvas.line(x0, y, x1, y, grey);
            canvas.line(x0 - 5, y, x0, y, black);
            const std::string s = tickText(t);
            canvas.text(x0 - 8 - textWidth(s), y - GLYPH_HEIGHT / 2, s, black);
        }
        // Frame.
        canvas.line(x0, y0, x1, y0, black);
        canvas.line(x0, y1, x1, y1, black);
        canvas.line(x0, y0, x0, y1, black);
        canvas.line(x1, y0, x1, y1, black);
        // Labels.
        canvas.text((x0 + x1) / 2 - textWidth(panel.title) / 2, 10, panel.title, black);
        canvas.text((x0 + x1) / 2 - textWidth(panel.xLabel) / 2, height - 22, panel.xLabel, black);
        canvas.text(int(n) * panelWidth + 6, (y0 + y1) / 2 + textWidth(panel.yLabel) / 2, panel.yLabel, black, true);

        // The Pareto front, then the points over it.
        const std::vector<std::size_t> front = paretoFront(panel);
        for (std::size_t i = 1; i < front.size(); ++i) {
            const PlotPoint& a = panel.points[front[i - 1]];
            const PlotPoint& b = panel.points[front[i]];
            canvas.line(px(a.x), py(a.y), px(b.x), py(b.y), frontColor, 2);
        }
        for (const PlotPoint& p : panel.points) {
            if (!usable(p.x, panel.logX) || !usable(p.y, panel.logY)) continue;
            const int x = px(p.x), y = py(p.y);
            canvas.disc(x, y, p.large ? 6 : 4, black);
            canvas.disc(x, y, p.large ? 5 : 3, p.color);
        }
        // Labels last (never under a marker), large markers' first; a label
        // goes right, left, above or below its marker, wherever it overlaps
        // no marker and no label drawn before and stays inside the plot, else
        // it is left out (report.md has every row).
        struct Box
        {
            int x0, y0, x1, y1;
            bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
        };
        std::vector<Box> taken;
        for (const PlotPoint& p : panel.points) { // labels avoid every marker too
            if (!usable(p.x, panel.logX) || !usable(p.y, panel.logY)) continue;
            const int r = p.large ? 6 : 4;
            taken.push_back({px(p.x) - r, py(p.y) - r, px(p.x) + r + 1, py(p.y) + r + 1});
        }
        for (int pass = 0; pass < 2; ++pass) {
            for (const PlotPoint& p : panel.points) {
                if (p.large != (pass == 0)) continue;
                if (p.label.empty() || !usable(p.x, panel.logX) || !usable(p.y, panel.logY)) continue;
                const int w = textWidth(p.label), h = GLYPH_HEIGHT, mx = px(p.x), my = py(p.y);
                const Box candidates[] = {{mx + 8, my - h / 2, mx + 8 + w, my + h / 2},
                                          {mx - 8 - w, my - h / 2, mx - 8, my + h / 2},
                                          {mx - w / 2, my - 8 - h, mx + w / 2 + 1, my - 8},
                                          {mx - w / 2, my + 8, mx + w / 2 + 1, my + 8 + h}};
                for (const Box& box : candidates) {
                    if (box.x0 < x0 + 2 || box.x1 > x1 - 2 || box.y0 < y0 + 2 || box.y1 > y1 - 2) continue;
                    if (std::any_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(box); })) continue;
                    taken.push_back(box);
                    canvas.text(box.x0, box.y0, p.label, p.large ? black : Color{60, 60, 60});
                    break;
                }
            }
        }
    }
    return image;
}

} // namespace strata::scene
