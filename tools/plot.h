/* plot.h - a small scatter-plot rasteriser for `fixterrain bench`: error
 * against run time, one colour per method, the Pareto front of each method
 * drawn as a line. Everything is drawn into a caller's RGBA8 buffer (row 0
 * at the top) and written as PNG with zlib. Tools code: plot_write_png
 * allocates its output buffer on the heap; nothing else allocates.
 *
 * Rasteriser rules (tested in tests/test_plot.c):
 *   - pixels outside the image are clipped, never written;
 *   - plot_line is Bresenham: both end points and exactly
 *     max(|dx|, |dy|) + 1 pixels, one per step along the major axis;
 *   - plot_marker of radius r covers the pixels of the shape centred on
 *     (cx, cy): a square |dx|, |dy| <= r; a disc dx^2 + dy^2 <= r^2 + r;
 *     a diamond |dx| + |dy| <= r; a triangle (apex up) rows dy in [-r, r]
 *     with |dx| <= (dy + r) / 2; PLOT_MARKER_RING is the disc minus the
 *     disc of radius r - 2 (a hollow circle);
 *   - plot_text draws src/gpu/font5x7.h glyphs, each pixel a scale x scale
 *     block, glyph advance 6 * scale; returns the width drawn;
 *     plot_text_up draws it rotated 90 deg counter-clockwise (reading
 *     bottom to top), the first glyph's bottom-left at (x, y).
 *
 * Pareto front (plot_pareto_front): among points with finite x and y, the
 * ones no other point dominates (x' <= x and y' <= y with one of them
 * strictly less); equal points are kept once (the lowest index). Returned
 * sorted by x ascending, so y is strictly decreasing along the front. */
#ifndef FT_TOOLS_PLOT_H
#define FT_TOOLS_PLOT_H

#include <stddef.h>
#include <stdint.h>

typedef struct plot_image {
    uint8_t *rgba; /* w * h * 4 bytes, row 0 = top */
    uint32_t w, h;
} plot_image;

typedef struct plot_rgba {
    uint8_t r, g, b, a;
} plot_rgba;

typedef enum plot_marker_kind {
    PLOT_MARKER_SQUARE,
    PLOT_MARKER_DISC,
    PLOT_MARKER_DIAMOND,
    PLOT_MARKER_TRIANGLE,
    PLOT_MARKER_RING,
    PLOT_MARKER_COUNT
} plot_marker_kind;

/* Indices of the front, sorted by x ascending; returns their count (<= n).
 * idx_out holds n entries; work needs n entries of scratch. */
size_t plot_pareto_front(const double *x, const double *y, size_t n, size_t *idx_out,
                         size_t *work);

/* ---- rasteriser ------------------------------------------------------------ */
void plot_clear(plot_image *im, plot_rgba c);
void plot_pixel(plot_image *im, int x, int y, plot_rgba c);
/* c with alpha < 255 blends over the pixel (plot_pixel writes it as is). */
void plot_pixel_blend(plot_image *im, int x, int y, plot_rgba c);
void plot_line(plot_image *im, int x0, int y0, int x1, int y1, plot_rgba c);
/* A line `width` pixels wide (the Bresenham line offset across its minor axis). */
void plot_line_wide(plot_image *im, int x0, int y0, int x1, int y1, int width, plot_rgba c);
/* Dashed: on_px pixels drawn, off_px skipped, along the major axis. */
void plot_line_dashed(plot_image *im, int x0, int y0, int x1, int y1, int on_px, int off_px,
                      plot_rgba c);
void plot_fill_rect(plot_image *im, int x0, int y0, int x1, int y1, plot_rgba c); /* inclusive */
void plot_marker(plot_image *im, int cx, int cy, int r, plot_marker_kind kind, plot_rgba c);
int plot_text(plot_image *im, int x, int y, const char *s, int scale, plot_rgba c);
int plot_text_up(plot_image *im, int x, int y, const char *s, int scale, plot_rgba c);
int plot_text_width(const char *s, int scale);

/* ---- axes ------------------------------------------------------------------ */
typedef struct plot_axis {
    double lo, hi; /* data range (log axes: lo > 0) */
    int log;       /* 1: log10 scale */
    int p0, p1;    /* pixel positions of lo and hi (p1 < p0 for a y axis) */
} plot_axis;

/* Pixel coordinate of v (not clamped). */
double plot_axis_map(const plot_axis *a, double v);

/* Chooses a range covering [vmin, vmax]: linear axes round outward to a
 * 1/2/5 x 10^k step (and start at 0 when vmin >= 0 and vmin < vmax / 2),
 * log axes to whole decades. */
void plot_axis_fit(plot_axis *a, double vmin, double vmax, int log);

/* Tick values: linear axes every 1/2/5 x 10^k step (4..10 ticks), log axes
 * at each decade (and 2, 5 times it when there are at most 3 decades).
 * Returns the count (<= cap). */
int plot_axis_ticks(const plot_axis *a, double *ticks, int cap);

/* "0.5", "10", "1e-03": at most 15 characters. */
void plot_format_tick(double v, char *buf, size_t cap);

/* ---- chart ------------------------------------------------------------------ */
#define PLOT_SERIES_MAX 8
#define PLOT_HLINES_MAX 4

typedef struct plot_series {
    const char *name;
    plot_rgba colour;
    plot_marker_kind marker;
    const double *x, *y;
    const char *const *labels; /* per point, may be NULL; drawn next to front points */
    size_t n;
} plot_series;

typedef struct plot_chart {
    const char *title, *x_label, *y_label;
    int x_log, y_log;
    double y_floor;   /* log y: values below are drawn at the floor (0: none) */
    plot_series series[PLOT_SERIES_MAX];
    int series_count;
    double hline[PLOT_HLINES_MAX]; /* dashed reference lines (e.g. 1 px, 2 px) */
    int hline_count;
} plot_chart;

/* Draws the whole chart (background, frame, ticks, grid, reference lines,
 * series, fronts, legend). Axes are fitted to the data (the x range from 0
 * on a linear axis). Returns 0 when no series has a finite point. The axes
 * used are stored in *xa and *ya when not NULL. */
int plot_chart_draw(plot_image *im, const plot_chart *ch, plot_axis *xa, plot_axis *ya);

/* RGBA8 PNG (colour type 6, no interlace, filter 0). Returns 0 on success,
 * else -1 with a reason in err. */
int plot_write_png(const char *path, const plot_image *im, char *err, size_t err_cap);

/* ---- CSV (RFC 4180) -------------------------------------------------------- */
/* The bench writes its table as CSV; a text field that holds a comma, a
 * double quote, CR or LF is written quoted ("a ""b"", c"), any other as is. */

/* src as one CSV field into dst (NUL-terminated); 0 when it does not fit. */
int plot_csv_field(char *dst, size_t cap, const char *src);

/* Reads one record from *text (advanced past it and its line end): fields
 * unquoted into buf (cap bytes), field i at fields[i]. Returns the field
 * count (0 at the end of the text), -1 on a malformed record (an unclosed
 * quote, text after a closing quote) or one that does not fit buf or max. */
int plot_csv_record(const char **text, char *buf, size_t cap, char *fields[], int max);

#endif
