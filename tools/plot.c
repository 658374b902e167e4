/* plot.c - see plot.h. */
#include "plot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "gpu/font5x7.h"

/* ---- Pareto front --------------------------------------------------------- */

/* a before b: x ascending, then y ascending, then index ascending */
static int pareto_before(const double *x, const double *y, size_t a, size_t b)
{
    if (x[a] != x[b]) return x[a] < x[b];
    if (y[a] != y[b]) return y[a] < y[b];
    return a < b;
}

size_t plot_pareto_front(const double *x, const double *y, size_t n, size_t *idx_out,
                         size_t *work)
{
    size_t m = 0;
    for (size_t i = 0; i < n; ++i) {
        if (isfinite(x[i]) && isfinite(y[i])) {
            /* insertion sort: n is a few dozen settings */
            size_t j = m++;
            while (j > 0 && pareto_before(x, y, i, work[j - 1])) {
                work[j] = work[j - 1];
                --j;
            }
            work[j] = i;
        }
    }
    size_t k = 0;
    double best = INFINITY;
    for (size_t j = 0; j < m; ++j) {
        size_t i = work[j];
        if (y[i] < best) {
            idx_out[k++] = i;
            best = y[i];
        }
    }
    return k;
}

/* ---- rasteriser --------------------------------------------------------------- */

void plot_clear(plot_image *im, plot_rgba c)
{
    size_t n = (size_t)im->w * im->h;
    for (size_t i = 0; i < n; ++i) {
        uint8_t *p = im->rgba + i * 4u;
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
        p[3] = c.a;
    }
}

void plot_pixel(plot_image *im, int x, int y, plot_rgba c)
{
    if (x < 0 || y < 0 || (uint32_t)x >= im->w || (uint32_t)y >= im->h) return;
    uint8_t *p = im->rgba + ((size_t)y * im->w + (size_t)x) * 4u;
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
    p[3] = c.a;
}

void plot_pixel_blend(plot_image *im, int x, int y, plot_rgba c)
{
    if (x < 0 || y < 0 || (uint32_t)x >= im->w || (uint32_t)y >= im->h) return;
    uint8_t *p = im->rgba + ((size_t)y * im->w + (size_t)x) * 4u;
    unsigned a = c.a, b = 255u - a;
    p[0] = (uint8_t)((c.r * a + p[0] * b + 127u) / 255u);
    p[1] = (uint8_t)((c.g * a + p[1] * b + 127u) / 255u);
    p[2] = (uint8_t)((c.b * a + p[2] * b + 127u) / 255u);
    p[3] = 255u;
}

/* Bresenham; calls back for every pixel with its step number. */
typedef void (*line_fn)(plot_image *im, int x, int y, int step, const void *ctx);

static void walk_line(plot_image *im, int x0, int y0, int x1, int y1, line_fn fn, const void *ctx)
{
    int dx = abs(x1 - x0), dy = -abs(y1 - y0);
    int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int e = dx + dy, step = 0;
    for (;;) {
        fn(im, x0, y0, step++, ctx);
        if (x0 == x1 && y0 == y1) break;
        int e2 = 2 * e;
        if (e2 >= dy) {
            e += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            e += dx;
            y0 += sy;
        }
    }
}

typedef struct line_ctx {
    plot_rgba c;
    int on, period;        /* dashes */
    int width, minor_is_y; /* wide lines */
} line_ctx;

static void put_plain(plot_image *im, int x, int y, int step, const void *ctx)
{
    (void)step;
    plot_pixel(im, x, y, ((const line_ctx *)ctx)->c);
}

static void put_dashed(plot_image *im, int x, int y, int step, const void *ctx)
{
    const line_ctx *l = ctx;
    if (step % l->period < l->on) plot_pixel(im, x, y, l->c);
}

static void put_wide(plot_image *im, int x, int y, int step, const void *ctx)
{
    const line_ctx *l = ctx;
    (void)step;
    for (int o = -(l->width - 1) / 2; o <= l->width / 2; ++o) {
        if (l->minor_is_y) plot_pixel(im, x, y + o, l->c);
        else plot_pixel(im, x + o, y, l->c);
    }
}

void plot_line(plot_image *im, int x0, int y0, int x1, int y1, plot_rgba c)
{
    line_ctx l = {c, 1, 1, 1, 0};
    walk_line(im, x0, y0, x1, y1, put_plain, &l);
}

void plot_line_wide(plot_image *im, int x0, int y0, int x1, int y1, int width, plot_rgba c)
{
    line_ctx l = {c, 1, 1, width < 1 ? 1 : width, abs(x1 - x0) >= abs(y1 - y0)};
    walk_line(im, x0, y0, x1, y1, put_wide, &l);
}

void plot_line_dashed(plot_image *im, int x0, int y0, int x1, int y1, int on_px, int off_px,
                      plot_rgba c)
{
    line_ctx l = {c, on_px < 1 ? 1 : on_px, (on_px < 1 ? 1 : on_px) + (off_px < 0 ? 0 : off_px),
                  1, 0};
    walk_line(im, x0, y0, x1, y1, put_dashed, &l);
}

void plot_fill_rect(plot_image *im, int x0, int y0, int x1, int y1, plot_rgba c)
{
    if (x1 < x0) {
        int t = x0;
        x0 = x1;
        x1 = t;
    }
    if (y1 < y0) {
        int t = y0;
        y0 = y1;
        y1 = t;
    }
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) plot_pixel(im, x, y, c);
    }
}

static int in_marker(int dx, int dy, int r, plot_marker_kind kind)
{
    switch (kind) {
    case PLOT_MARKER_SQUARE: return abs(dx) <= r && abs(dy) <= r;
    case PLOT_MARKER_DISC: return dx * dx + dy * dy <= r * r + r;
    case PLOT_MARKER_DIAMOND: return abs(dx) + abs(dy) <= r;
    case PLOT_MARKER_TRIANGLE: return dy >= -r && dy <= r && 2 * abs(dx) <= dy + r;
    case PLOT_MARKER_RING: {
        int q = r - 2;
        return dx * dx + dy * dy <= r * r + r && (q < 0 || dx * dx + dy * dy > q * q + q);
    }
    default: return 0;
    }
}

void plot_marker(plot_image *im, int cx, int cy, int r, plot_marker_kind kind, plot_rgba c)
{
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            if (in_marker(dx, dy, r, kind)) plot_pixel(im, cx + dx, cy + dy, c);
        }
    }
}

int plot_text_width(const char *s, int scale)
{
    return (int)strlen(s) * (int)FT_FONT5X7_ADVANCE * scale;
}

/* up = 0: left to right; up = 1: rotated 90 deg counter-clockwise */
static int draw_text(plot_image *im, int x, int y, const char *s, int scale, plot_rgba c, int up)
{
    int tx = 0;
    for (const char *p = s; *p != '\0'; ++p) {
        const uint8_t *g = ft_font5x7_glyph(*p);
        if (*p != ' ') {
            for (int row = 0; row < (int)FT_FONT5X7_ROWS; ++row) {
                for (int col = 0; col < (int)FT_FONT5X7_COLS; ++col) {
                    if (!(g[row] & (0x10u >> col))) continue;
                    for (int a = 0; a < scale; ++a) {
                        for (int b = 0; b < scale; ++b) {
                            int u = tx + col * scale + a, v = row * scale + b;
                            if (up) plot_pixel(im, x + v, y - u, c);
                            else plot_pixel(im, x + u, y + v, c);
                        }
                    }
                }
            }
        }
        tx += (int)FT_FONT5X7_ADVANCE * scale;
    }
    return tx;
}

int plot_text(plot_image *im, int x, int y, const char *s, int scale, plot_rgba c)
{
    return draw_text(im, x, y, s, scale, c, 0);
}

int plot_text_up(plot_image *im, int x, int y, const char *s, int scale, plot_rgba c)
{
    return draw_text(im, x, y, s, scale, c, 1);
}

/* ---- axes ------------------------------------------------------------------- */

double plot_axis_map(const plot_axis *a, double v)
{
    double lo = a->lo, hi = a->hi;
    if (a->log) {
        lo = log10(lo);
        hi = log10(hi);
        v = log10(v);
    }
    return a->p0 + (v - lo) / (hi - lo) * (a->p1 - a->p0);
}

/* The 1/2/5 x 10^k step that gives closest to 6 intervals over [lo, hi]. */
static double linear_step(double lo, double hi)
{
    double range = hi - lo;
    if (!(range > 0.0)) return 1.0;
    int e0 = (int)floor(log10(range));
    double best = pow(10.0, e0), best_score = 1e300;
    static const double f[3] = {1.0, 2.0, 5.0};
    for (int e = e0 - 2; e <= e0 + 1; ++e) {
        for (int i = 0; i < 3; ++i) {
            double step = f[i] * pow(10.0, e);
            double n = ceil(hi / step - 1e-9) - floor(lo / step + 1e-9);
            double score = fabs(n - 6.0);
            if (n >= 3.0 && n <= 10.0 && score < best_score) {
                best = step;
                best_score = score;
            }
        }
    }
    return best;
}

void plot_axis_fit(plot_axis *a, double vmin, double vmax, int log)
{
    a->log = log;
    if (log) {
        if (!(vmin > 0.0)) vmin = 1e-3;
        if (!(vmax >= vmin)) vmax = vmin;
        a->lo = pow(10.0, floor(log10(vmin) + 1e-9));
        a->hi = pow(10.0, ceil(log10(vmax) - 1e-9));
        if (!(a->hi > a->lo)) a->hi = a->lo * 10.0;
        return;
    }
    if (!isfinite(vmin) || !isfinite(vmax)) {
        vmin = 0.0;
        vmax = 1.0;
    }
    if (vmin >= 0.0 && vmin < vmax / 2.0) vmin = 0.0;
    if (!(vmax > vmin)) vmax = vmin + (vmin != 0.0 ? fabs(vmin) * 0.1 : 1.0);
    double step = linear_step(vmin, vmax);
    a->lo = floor(vmin / step + 1e-9) * step;
    a->hi = ceil(vmax / step - 1e-9) * step;
    if (!(a->hi > a->lo)) a->hi = a->lo + step;
}

int plot_axis_ticks(const plot_axis *a, double *ticks, int cap)
{
    int n = 0;
    if (a->log) {
        int d0 = (int)floor(log10(a->lo) + 1e-9), d1 = (int)ceil(log10(a->hi) - 1e-9);
        int minor = d1 - d0 <= 3;
        for (int d = d0; d <= d1 && n < cap; ++d) {
            double base = pow(10.0, d);
            static const double m[3] = {1.0, 2.0, 5.0};
            for (int i = 0; i < (minor ? 3 : 1) && n < cap; ++i) {
                double v = base * m[i];
                if (v >= a->lo * (1.0 - 1e-9) && v <= a->hi * (1.0 + 1e-9)) ticks[n++] = v;
            }
        }
        return n;
    }
    double step = linear_step(a->lo, a->hi);
    double k0 = ceil(a->lo / step - 1e-9), k1 = floor(a->hi / step + 1e-9);
    for (double k = k0; k <= k1 && n < cap; k += 1.0) {
        double v = k * step;
        ticks[n++] = fabs(v) < step * 1e-9 ? 0.0 : v;
    }
    return n;
}

void plot_format_tick(double v, char *buf, size_t cap)
{
    double av = fabs(v);
    if (v == 0.0) (void)snprintf(buf, cap, "0");
    else if (av >= 1e-3 && av < 1e5) (void)snprintf(buf, cap, "%.4g", v);
    else (void)snprintf(buf, cap, "%.0e", v);
}

/* ---- chart -------------------------------------------------------------------- */

#define CHART_LEFT 78
#define CHART_RIGHT 24
#define CHART_TOP 44
#define CHART_BOTTOM 56
#define CHART_TICKS_MAX 40

static const plot_rgba k_white = {255, 255, 255, 255};
static const plot_rgba k_black = {0, 0, 0, 255};
static const plot_rgba k_grid = {226, 226, 226, 255};
static const plot_rgba k_ref = {150, 150, 150, 255};
static const plot_rgba k_text = {40, 40, 40, 255};

static double chart_y(const plot_chart *ch, double y)
{
    if (ch->y_log && ch->y_floor > 0.0 && y < ch->y_floor) return ch->y_floor;
    return y;
}

static int point_ok(const plot_chart *ch, double x, double y)
{
    if (!isfinite(x) || !isfinite(y)) return 0;
    if (ch->x_log && !(x > 0.0)) return 0;
    if (ch->y_log && !(chart_y(ch, y) > 0.0)) return 0;
    return 1;
}

int plot_chart_draw(plot_image *im, const plot_chart *ch, plot_axis *xa_out, plot_axis *ya_out)
{
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    size_t points = 0;
    for (int s = 0; s < ch->series_count; ++s) {
        const plot_series *se = &ch->series[s];
        for (size_t i = 0; i < se->n; ++i) {
            if (!point_ok(ch, se->x[i], se->y[i])) continue;
            double y = chart_y(ch, se->y[i]);
            xmin = fmin(xmin, se->x[i]);
            xmax = fmax(xmax, se->x[i]);
            ymin = fmin(ymin, y);
            ymax = fmax(ymax, y);
            ++points;
        }
    }
    plot_clear(im, k_white);
    if (points == 0) {
        (void)plot_text(im, 10, 10, "no data", 2, k_black);
        return 0;
    }
    for (int h = 0; h < ch->hline_count; ++h) {
        if (!ch->y_log || ch->hline[h] > 0.0) {
            ymin = fmin(ymin, ch->hline[h]);
            ymax = fmax(ymax, ch->hline[h]);
        }
    }
    const int L = CHART_LEFT, R = (int)im->w - CHART_RIGHT, T = CHART_TOP,
              B = (int)im->h - CHART_BOTTOM;
    plot_axis xa, ya;
    if (ch->x_log) plot_axis_fit(&xa, xmin / 1.2, xmax * 1.2, 1);
    else plot_axis_fit(&xa, xmin >= 0.0 ? 0.0 : xmin, xmax * 1.04, 0);
    if (ch->y_log) plot_axis_fit(&ya, ymin / 1.2, ymax * 1.2, 1);
    else plot_axis_fit(&ya, ymin, ymax * 1.04, 0);
    xa.p0 = L;
    xa.p1 = R;
    ya.p0 = B;
    ya.p1 = T;

    /* grid and tick labels */
    double ticks[CHART_TICKS_MAX];
    char buf[32];
    int nt = plot_axis_ticks(&xa, ticks, CHART_TICKS_MAX);
    for (int i = 0; i < nt; ++i) {
        int px = (int)lround(plot_axis_map(&xa, ticks[i]));
        plot_line(im, px, T, px, B, k_grid);
        plot_line(im, px, B, px, B + 4, k_black);
        plot_format_tick(ticks[i], buf, sizeof buf);
        (void)plot_text(im, px - plot_text_width(buf, 1) / 2, B + 8, buf, 1, k_text);
    }
    nt = plot_axis_ticks(&ya, ticks, CHART_TICKS_MAX);
    for (int i = 0; i < nt; ++i) {
        int py = (int)lround(plot_axis_map(&ya, ticks[i]));
        plot_line(im, L, py, R, py, k_grid);
        plot_line(im, L - 4, py, L, py, k_black);
        plot_format_tick(ticks[i], buf, sizeof buf);
        (void)plot_text(im, L - 8 - plot_text_width(buf, 1), py - 3, buf, 1, k_text);
    }
    /* reference lines */
    for (int h = 0; h < ch->hline_count; ++h) {
        double v = ch->hline[h];
        if ((ch->y_log && !(v > 0.0)) || v < ya.lo || v > ya.hi) continue;
        int py = (int)lround(plot_axis_map(&ya, v));
        plot_line_dashed(im, L, py, R, py, 6, 4, k_ref);
        plot_format_tick(v, buf, sizeof buf);
        size_t len = strlen(buf);
        (void)snprintf(buf + len, sizeof buf - len, " px");
        (void)plot_text(im, R - 4 - plot_text_width(buf, 1), py - 10, buf, 1, k_ref);
    }
    /* frame */
    plot_line(im, L, T, R, T, k_black);
    plot_line(im, L, B, R, B, k_black);
    plot_line(im, L, T, L, B, k_black);
    plot_line(im, R, T, R, B, k_black);

    /* series: fronts first (lines under the markers), then points, then labels */
    size_t idx[256], work[256];
    for (int s = 0; s < ch->series_count; ++s) {
        const plot_series *se = &ch->series[s];
        double fx[256], fy[256];
        size_t n = se->n < 256 ? se->n : 256;
        for (size_t i = 0; i < n; ++i) {
            fx[i] = point_ok(ch, se->x[i], se->y[i]) ? se->x[i] : NAN;
            fy[i] = chart_y(ch, se->y[i]);
        }
        size_t m = plot_pareto_front(fx, fy, n, idx, work);
        for (size_t k = 1; k < m; ++k) {
            plot_line_wide(im, (int)lround(plot_axis_map(&xa, fx[idx[k - 1]])),
                           (int)lround(plot_axis_map(&ya, fy[idx[k - 1]])),
                           (int)lround(plot_axis_map(&xa, fx[idx[k]])),
                           (int)lround(plot_axis_map(&ya, fy[idx[k]])), 2, se->colour);
        }
    }
    /* markers: series with more points first, so a lone baseline point stays visible */
    int order[PLOT_SERIES_MAX];
    for (int s = 0; s < ch->series_count; ++s) {
        int j = s;
        while (j > 0 && ch->series[order[j - 1]].n < ch->series[s].n) {
            order[j] = order[j - 1];
            --j;
        }
        order[j] = s;
    }
    for (int o = 0; o < ch->series_count; ++o) {
        const plot_series *se = &ch->series[order[o]];
        for (size_t i = 0; i < se->n; ++i) {
            if (!point_ok(ch, se->x[i], se->y[i])) continue;
            int px = (int)lround(plot_axis_map(&xa, se->x[i]));
            int py = (int)lround(plot_axis_map(&ya, chart_y(ch, se->y[i])));
            plot_marker(im, px, py, 5, se->marker, k_black);
            plot_marker(im, px, py, 4, se->marker, se->colour);
        }
    }
    for (int s = 0; s < ch->series_count; ++s) {
        const plot_series *se = &ch->series[s];
        if (se->labels == NULL) continue;
        double fx[256], fy[256];
        size_t n = se->n < 256 ? se->n : 256;
        for (size_t i = 0; i < n; ++i) {
            fx[i] = point_ok(ch, se->x[i], se->y[i]) ? se->x[i] : NAN;
            fy[i] = chart_y(ch, se->y[i]);
        }
        size_t m = plot_pareto_front(fx, fy, n, idx, work);
        for (size_t k = 0; k < m; ++k) {
            const char *lab = se->labels[idx[k]];
            if (lab == NULL || lab[0] == '\0') continue;
            int px = (int)lround(plot_axis_map(&xa, fx[idx[k]]));
            int py = (int)lround(plot_axis_map(&ya, fy[idx[k]]));
            int w = plot_text_width(lab, 1);
            int tx = px + 8;
            if (tx + w > R - 2) tx = px - 8 - w;
            (void)plot_text(im, tx, py - 11, lab, 1, se->colour);
        }
    }

    /* titles */
    if (ch->title != NULL) {
        int w = plot_text_width(ch->title, 2);
        int x = ((int)im->w - w) / 2;
        (void)plot_text(im, x < 4 ? 4 : x, 14, ch->title, 2, k_black);
    }
    if (ch->x_label != NULL) {
        (void)plot_text(im, (L + R - plot_text_width(ch->x_label, 1)) / 2, B + 26, ch->x_label, 1,
                        k_black);
    }
    if (ch->y_label != NULL) {
        (void)plot_text_up(im, 12, (T + B + plot_text_width(ch->y_label, 1)) / 2, ch->y_label, 1,
                           k_black);
    }

    /* legend inside the plot area */
    int lw = 0;
    for (int s = 0; s < ch->series_count; ++s) {
        int w = plot_text_width(ch->series[s].name != NULL ? ch->series[s].name : "", 1);
        lw = w > lw ? w : lw;
    }
    const char *front_text = "line: Pareto front";
    lw = plot_text_width(front_text, 1) > lw + 34 ? plot_text_width(front_text, 1) : lw + 34;
    const int box_w = lw + 16, box_h = 12 + 16 * ch->series_count + 12;
    /* the corner of the plot area that hides the fewest points */
    int best_corner = 0, best_count = -1;
    for (int corner = 0; corner < 4; ++corner) {
        int bx0 = (corner & 1) ? L + 8 : R - 8 - box_w, by0 = (corner & 2) ? B - 8 - box_h : T + 8;
        int count = 0;
        for (int s = 0; s < ch->series_count; ++s) {
            const plot_series *se = &ch->series[s];
            for (size_t i = 0; i < se->n; ++i) {
                if (!point_ok(ch, se->x[i], se->y[i])) continue;
                double px = plot_axis_map(&xa, se->x[i]), py = plot_axis_map(&ya, chart_y(ch, se->y[i]));
                count += px >= bx0 - 16 && px <= bx0 + box_w + 16 && py >= by0 - 16 &&
                         py <= by0 + box_h + 16;
            }
        }
        if (best_count < 0 || count < best_count) {
            best_count = count;
            best_corner = corner;
        }
    }
    int lx0 = (best_corner & 1) ? L + 8 : R - 8 - box_w, lx1 = lx0 + box_w;
    int ly0 = (best_corner & 2) ? B - 8 - box_h : T + 8, ly1 = ly0 + box_h;
    plot_fill_rect(im, lx0, ly0, lx1, ly1, k_white);
    plot_line(im, lx0, ly0, lx1, ly0, k_black);
    plot_line(im, lx0, ly1, lx1, ly1, k_black);
    plot_line(im, lx0, ly0, lx0, ly1, k_black);
    plot_line(im, lx1, ly0, lx1, ly1, k_black);
    for (int s = 0; s < ch->series_count; ++s) {
        const plot_series *se = &ch->series[s];
        int cy = ly0 + 12 + 16 * s;
        plot_line_wide(im, lx0 + 6, cy, lx0 + 26, cy, 2, se->colour);
        plot_marker(im, lx0 + 16, cy, 5, se->marker, k_black);
        plot_marker(im, lx0 + 16, cy, 4, se->marker, se->colour);
        (void)plot_text(im, lx0 + 34, cy - 3, se->name != NULL ? se->name : "", 1, k_text);
    }
    (void)plot_text(im, lx0 + 8, ly1 - 12, front_text, 1, k_text);

    if (xa_out != NULL) *xa_out = xa;
    if (ya_out != NULL) *ya_out = ya;
    return 1;
}

/* ---- PNG ---------------------------------------------------------------------- */

static void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static int write_chunk(FILE *f, const char type[4], const uint8_t *data, size_t len)
{
    uint8_t head[8];
    put_be32(head, (uint32_t)len);
    memcpy(head + 4, type, 4);
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, (const Bytef *)type, 4);
    if (len > 0) crc = crc32(crc, data, (uInt)len);
    uint8_t tail[4];
    put_be32(tail, (uint32_t)crc);
    return fwrite(head, 1, 8, f) == 8 && (len == 0 || fwrite(data, 1, len, f) == len) &&
           fwrite(tail, 1, 4, f) == 4;
}

int plot_write_png(const char *path, const plot_image *im, char *err, size_t err_cap)
{
    size_t row = (size_t)im->w * 4u + 1u, raw_len = row * im->h;
    uint8_t *raw = malloc(raw_len);
    uLongf z_len = compressBound((uLong)raw_len);
    uint8_t *z = malloc(z_len);
    if (raw == NULL || z == NULL) {
        free(raw);
        free(z);
        (void)snprintf(err, err_cap, "%s: out of memory for the PNG", path);
        return -1;
    }
    for (uint32_t y = 0; y < im->h; ++y) {
        raw[y * row] = 0; /* filter: none */
        memcpy(raw + y * row + 1u, im->rgba + (size_t)y * im->w * 4u, (size_t)im->w * 4u);
    }
    int zrc = compress2(z, &z_len, raw, (uLong)raw_len, 6);
    free(raw);
    if (zrc != Z_OK) {
        free(z);
        (void)snprintf(err, err_cap, "%s: zlib compress failed (%d)", path, zrc);
        return -1;
    }
    FILE *f = fopen(path, "wb");
    if (f == NULL) {
        free(z);
        (void)snprintf(err, err_cap, "%s: cannot open for writing", path);
        return -1;
    }
    static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    uint8_t ihdr[13];
    put_be32(ihdr, im->w);
    put_be32(ihdr + 4, im->h);
    ihdr[8] = 8;  /* bit depth */
    ihdr[9] = 6;  /* RGBA */
    ihdr[10] = 0; /* deflate */
    ihdr[11] = 0; /* filter method 0 */
    ihdr[12] = 0; /* no interlace */
    int ok = fwrite(sig, 1, 8, f) == 8 && write_chunk(f, "IHDR", ihdr, sizeof ihdr) &&
             write_chunk(f, "IDAT", z, z_len) && write_chunk(f, "IEND", NULL, 0);
    free(z);
    if (fclose(f) != 0) ok = 0;
    if (!ok) {
        (void)snprintf(err, err_cap, "%s: write failed", path);
        return -1;
    }
    return 0;
}

/* ---- CSV ---------------------------------------------------------------------- */

int plot_csv_field(char *dst, size_t cap, const char *src)
{
    if (cap == 0u) return 0;
    const int quote = strpbrk(src, ",\"\r\n") != NULL;
    size_t n = 0;
    if (quote) {
        if (n + 1u >= cap) return 0;
        dst[n++] = '"';
    }
    for (const char *p = src; *p != '\0'; ++p) {
        const size_t need = (*p == '"') ? 2u : 1u;
        if (n + need >= cap) return 0;
        if (*p == '"') dst[n++] = '"';
        dst[n++] = *p;
    }
    if (quote) {
        if (n + 1u >= cap) return 0;
        dst[n++] = '"';
    }
    dst[n] = '\0';
    return 1;
}

int plot_csv_record(const char **text, char *buf, size_t cap, char *fields[], int max)
{
    const char *p = *text;
    if (*p == '\0') return 0;
    size_t n = 0;
    int count = 0;
    for (;;) { /* one field per pass; bounded by the text's length */
        if (count >= max || n >= cap) return -1;
        fields[count++] = buf + n;
        if (*p == '"') {
            ++p;
            for (;;) {
                if (*p == '\0') return -1; /* unclosed quote */
                if (*p == '"') {
                    if (p[1] != '"') break;
                    ++p; /* "" is one quote */
                }
                if (n + 1u >= cap) return -1;
                buf[n++] = *p++;
            }
            ++p; /* the closing quote */
            if (*p != ',' && *p != '\r' && *p != '\n' && *p != '\0') return -1;
        } else {
            while (*p != ',' && *p != '\r' && *p != '\n' && *p != '\0') {
                if (*p == '"' || n + 1u >= cap) return -1; /* a quote inside a bare field */
                buf[n++] = *p++;
            }
        }
        if (n >= cap) return -1;
        buf[n++] = '\0';
        if (*p == ',') {
            ++p;
            continue;
        }
        if (*p == '\r') ++p;
        if (*p == '\n') ++p;
        *text = p;
        return count;
    }
}
