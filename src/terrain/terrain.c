#include "terrain/terrain.h"

#include <math.h>
#include <string.h>

#include "core/units.h"

static double m_per_deg_lat(void)
{
    return FT_EARTH_RADIUS_M * FT_RAD_PER_DEG;
}

/* Latitude of the grid's middle row: the equirectangular plane keeps
 * east-west scale exact there (error over one 1-degree tile < 1%). */
static double lat_ref_deg(const ft_terrain *t)
{
    if (t->unit == FT_UNIT_DEGREE) {
        return t->origin_y + 0.5 * t->spacing_y * (double)(t->height - 1u);
    }
    return t->anchor_lat_deg;
}

/* Range check of one derived or header quantity with a message naming it. */
static ft_status check_range(const char *field, double v, double lo, double hi, const char *unit,
                             ft_error *err)
{
    if (!isfinite(v) || v < lo || v > hi) {
        return ft_fail(err, FT_ERR_FORMAT, "terrain %s %g %s is outside %g..%g %s", field, v,
                       unit, lo, hi, unit);
    }
    return FT_OK;
}

ft_status ft_terrain_derive_frame(ft_terrain *t, ft_error *err)
{
    if (!(t->spacing_x > 0.0) || !(t->spacing_y > 0.0) || !isfinite(t->spacing_x) ||
        !isfinite(t->spacing_y)) {
        return ft_fail(err, FT_ERR_FORMAT, "terrain spacing %g x %g is not positive and finite",
                       t->spacing_x, t->spacing_y);
    }
    if (t->width < FT_GRID_SIDE_MIN || t->height < FT_GRID_SIDE_MIN ||
        t->width > FT_GRID_SIDE_MAX || t->height > FT_GRID_SIDE_MAX) {
        return ft_fail(err, FT_ERR_FORMAT, "terrain grid %ux%u is outside %u..%u samples per side",
                       t->width, t->height, FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX);
    }
    if (!isfinite(t->origin_x) || !isfinite(t->origin_y)) {
        return ft_fail(err, FT_ERR_FORMAT, "terrain origin (%g, %g) is not finite", t->origin_x,
                       t->origin_y);
    }
    ft_status st = check_range("anchor_lat_deg", t->anchor_lat_deg, -89.0, 89.0, "deg", err);
    if (st == FT_OK) {
        st = check_range("anchor_lon_deg", t->anchor_lon_deg, -360.0, 360.0, "deg", err);
    }
    if (st != FT_OK) {
        return st;
    }
    const double cols = (double)(t->width - 1u), rows = (double)(t->height - 1u);
    if (t->unit == FT_UNIT_DEGREE) {
        /* The origin becomes the anchor: check it before it overwrites the
         * (already checked) anchor fields. */
        st = check_range("origin_x (longitude)", t->origin_x, -360.0, 360.0, "deg", err);
        if (st == FT_OK) {
            st = check_range("origin_y (latitude)", t->origin_y, -90.0, 90.0, "deg", err);
        }
        if (st == FT_OK) {
            st = check_range("longitude extent (width-1)*spacing_x", cols * t->spacing_x, 0.0,
                             360.0, "deg", err);
        }
        if (st == FT_OK) {
            st = check_range("northern edge origin_y+(height-1)*spacing_y",
                             t->origin_y + rows * t->spacing_y, -90.0, 90.0, "deg", err);
        }
        if (st != FT_OK) {
            return st;
        }
        double lat = lat_ref_deg(t);
        if (fabs(lat) > 89.0) {
            return ft_fail(err, FT_ERR_FORMAT, "terrain latitude %.3f too close to a pole", lat);
        }
        t->cell_y_m = t->spacing_y * m_per_deg_lat();
        t->cell_x_m = t->spacing_x * m_per_deg_lat() * cos(lat * FT_RAD_PER_DEG);
        t->origin_world_x_m = 0.0;
        t->origin_world_y_m = 0.0;
        t->anchor_lat_deg = t->origin_y;
        t->anchor_lon_deg = t->origin_x;
    } else if (t->unit == FT_UNIT_METRE) {
        t->cell_x_m = t->spacing_x;
        t->cell_y_m = t->spacing_y;
        t->origin_world_x_m = t->origin_x;
        t->origin_world_y_m = t->origin_y;
    } else {
        return ft_fail(err, FT_ERR_FORMAT, "terrain spacing unit %d unknown", (int)t->unit);
    }
    st = check_range("cell_x_m", t->cell_x_m, FT_CELL_MIN_M, FT_CELL_MAX_M, "m", err);
    if (st == FT_OK) {
        st = check_range("cell_y_m", t->cell_y_m, FT_CELL_MIN_M, FT_CELL_MAX_M, "m", err);
    }
    if (st == FT_OK) {
        st = check_range("extent_x_m", cols * t->cell_x_m, 0.0, FT_EXTENT_MAX_M, "m", err);
    }
    if (st == FT_OK) {
        st = check_range("extent_y_m", rows * t->cell_y_m, 0.0, FT_EXTENT_MAX_M, "m", err);
    }
    if (st == FT_OK) {
        st = check_range("origin_world_x_m", t->origin_world_x_m, -FT_COORD_MAX_M,
                         FT_COORD_MAX_M, "m", err);
    }
    if (st == FT_OK) {
        st = check_range("origin_world_y_m", t->origin_world_y_m, -FT_COORD_MAX_M,
                         FT_COORD_MAX_M, "m", err);
    }
    if (st == FT_OK) {
        st = check_range("east edge x_m", t->origin_world_x_m + cols * t->cell_x_m,
                         -FT_COORD_MAX_M, FT_COORD_MAX_M, "m", err);
    }
    if (st == FT_OK) {
        st = check_range("north edge y_m", t->origin_world_y_m + rows * t->cell_y_m,
                         -FT_COORD_MAX_M, FT_COORD_MAX_M, "m", err);
    }
    return st;
}

int ft_terrain_height_ok(double v_m)
{
    return isfinite(v_m) && v_m >= FT_HEIGHT_MIN_M && v_m <= FT_HEIGHT_MAX_M;
}

ft_status ft_terrain_check_heights(const float *heights_m, uint32_t width, uint32_t height,
                                   const char *name, ft_error *err)
{
    if (name == NULL) {
        name = "terrain";
    }
    if (heights_m == NULL) {
        return ft_fail(err, FT_ERR_ARG, "%s: heights are not bound", name);
    }
    size_t n = (size_t)width * height;
    for (size_t k = 0u; k < n; ++k) {
        if (!ft_terrain_height_ok((double)heights_m[k])) {
            return ft_fail(err, FT_ERR_NUMERIC,
                           "%s: height %g m at row %zu col %zu (row 0 = south) is outside "
                           "%g..%g m",
                           name, (double)heights_m[k], k / width, k % width, FT_HEIGHT_MIN_M,
                           FT_HEIGHT_MAX_M);
        }
    }
    return FT_OK;
}

ft_status ft_terrain_check_crs(const char *crs, size_t cap, const char *name, ft_error *err)
{
    if (name == NULL) {
        name = "terrain";
    }
    if (crs == NULL) {
        return ft_fail(err, FT_ERR_ARG, "%s: crs text is NULL", name);
    }
    size_t limit = cap < FT_CRS_TEXT_MAX ? cap : FT_CRS_TEXT_MAX;
    size_t len = 0u;
    while (len < limit && crs[len] != '\0') {
        unsigned char c = (unsigned char)crs[len];
        if (c < 0x20u || c > 0x7eu) {
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s: crs has a non-printable byte 0x%02x at offset %zu (printable "
                           "ASCII 0x20..0x7e only)",
                           name, c, len);
        }
        ++len;
    }
    if (len >= limit) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: crs text is not NUL-terminated within %u bytes",
                       name, FT_CRS_TEXT_MAX);
    }
    return FT_OK;
}

uint32_t ft_terrain_sanitize_crs(const char *in, char out[FT_CRS_TEXT_MAX])
{
    size_t o = 0u;
    uint32_t runs = 0u;
    int in_run = 0;
    for (size_t i = 0u; in != NULL && in[i] != '\0' && o + 1u < FT_CRS_TEXT_MAX; ++i) {
        unsigned char c = (unsigned char)in[i];
        if (c >= 0x20u && c <= 0x7eu) {
            out[o++] = (char)c;
            in_run = 0;
        } else if (!in_run) {
            out[o++] = '?';
            ++runs;
            in_run = 1;
        }
    }
    for (size_t k = o; k < FT_CRS_TEXT_MAX; ++k) {
        out[k] = '\0';
    }
    return runs;
}

/* The turn of lon_deg nearest the grid's middle (a grid in degrees) or its
 * anchor: a grid that crosses the antimeridian runs on past 180 deg, where
 * a position reads -180 and up. */
static double lon_near_grid(const ft_terrain *t, double lon_deg)
{
    const double mid_deg = t->unit == FT_UNIT_DEGREE
                               ? t->origin_x + 0.5 * t->spacing_x * (double)(t->width - 1u)
                               : t->anchor_lon_deg;
    if (!isfinite(lon_deg) || !isfinite(mid_deg)) {
        return lon_deg;
    }
    return lon_deg + 360.0 * round((mid_deg - lon_deg) / 360.0);
}

void ft_terrain_geo_to_world(const ft_terrain *t, double lat_deg, double lon_deg, double *x_m,
                             double *y_m)
{
    lon_deg = lon_near_grid(t, lon_deg);
    double lat_ref = lat_ref_deg(t);
    double mx = m_per_deg_lat() * cos(lat_ref * FT_RAD_PER_DEG);
    *x_m = t->origin_world_x_m + (lon_deg - t->anchor_lon_deg) * mx;
    *y_m = t->origin_world_y_m + (lat_deg - t->anchor_lat_deg) * m_per_deg_lat();
}

/* The cell holding world (x, y) (clamped into the grid), its 4 heights and
 * the local coordinates in it. */
static void locate_cell(const ft_terrain *t, double x_m, double y_m, double h[4], double *fx,
                        double *fy)
{
    double gx = (x_m - t->origin_world_x_m) / t->cell_x_m;
    double gy = (y_m - t->origin_world_y_m) / t->cell_y_m;
    double maxx = (double)(t->width - 1u);
    double maxy = (double)(t->height - 1u);
    if (!(gx > 0.0)) gx = 0.0; /* also catches NaN */
    if (!(gy > 0.0)) gy = 0.0;
    if (gx > maxx) gx = maxx;
    if (gy > maxy) gy = maxy;
    uint32_t ix = (uint32_t)gx;
    uint32_t iy = (uint32_t)gy;
    if (ix > t->width - 2u) ix = t->width - 2u;
    if (iy > t->height - 2u) iy = t->height - 2u;
    *fx = gx - (double)ix;
    *fy = gy - (double)iy;
    const float *row0 = t->heights_m + (size_t)iy * t->width;
    const float *row1 = row0 + t->width;
    h[0] = row0[ix];
    h[1] = row0[ix + 1u];
    h[2] = row1[ix];
    h[3] = row1[ix + 1u];
}

double ft_terrain_height_at(const ft_terrain *t, double x_m, double y_m)
{
    double h[4], fx, fy;
    locate_cell(t, x_m, y_m, h, &fx, &fy);
    return (h[0] * (1.0 - fx) + h[1] * fx) * (1.0 - fy) + (h[2] * (1.0 - fx) + h[3] * fx) * fy;
}

void ft_terrain_gradient_at(const ft_terrain *t, double x_m, double y_m, double *dhdx,
                            double *dhdy)
{
    double h[4], fx, fy;
    locate_cell(t, x_m, y_m, h, &fx, &fy);
    *dhdx = ((h[1] - h[0]) * (1.0 - fy) + (h[3] - h[2]) * fy) / t->cell_x_m;
    *dhdy = ((h[2] - h[0]) * (1.0 - fx) + (h[3] - h[1]) * fx) / t->cell_y_m;
}

int ft_terrain_contains(const ft_terrain *t, double x_m, double y_m)
{
    double gx = (x_m - t->origin_world_x_m) / t->cell_x_m;
    double gy = (y_m - t->origin_world_y_m) / t->cell_y_m;
    return gx >= 0.0 && gy >= 0.0 && gx <= (double)(t->width - 1u) &&
           gy <= (double)(t->height - 1u);
}

double ft_terrain_curvature_drop(ft_curvature mode, ft_spacing_unit unit)
{
    int sphere = (mode == FT_CURVATURE_SPHERE) || (mode == FT_CURVATURE_AUTO && unit == FT_UNIT_DEGREE);
    return sphere ? 1.0 / (2.0 * FT_EARTH_RADIUS_M) : 0.0;
}

size_t ft_terrain_void_bits_bytes(uint32_t w, uint32_t h)
{
    return ((size_t)w * h + 7u) / 8u;
}

int ft_terrain_sample_filled(const ft_terrain *t, size_t i)
{
    return t->void_bits != NULL && ((t->void_bits[i >> 3] >> (i & 7u)) & 1u) != 0u;
}

uint32_t ft_terrain_pack_void_bits(const uint8_t *mask, uint32_t w, uint32_t h, uint8_t *bits)
{
    const size_t n = (size_t)w * h;
    memset(bits, 0, ft_terrain_void_bits_bytes(w, h));
    uint32_t set = 0u;
    for (size_t i = 0; i < n; ++i) {
        if (mask[i] != 0u) {
            bits[i >> 3] = (uint8_t)(bits[i >> 3] | (1u << (i & 7u)));
            ++set;
        }
    }
    return set;
}

ft_status ft_terrain_check_void_bits(const uint8_t *bits, uint32_t w, uint32_t h,
                                     uint32_t void_count, const char *what, ft_error *err)
{
    const size_t n = (size_t)w * h, bytes = ft_terrain_void_bits_bytes(w, h);
    uint64_t set = 0u;
    for (size_t b = 0; b < bytes; ++b) {
        unsigned v = bits[b];
        if (b == bytes - 1u && (n & 7u) != 0u && (v >> (n & 7u)) != 0u) {
            return ft_fail(err, FT_ERR_FORMAT, "%s: void bits set past the last sample", what);
        }
        for (; v != 0u; v &= v - 1u) {
            ++set;
        }
    }
    if (set != void_count) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: %llu samples marked void-filled, the header says %u",
                       what, (unsigned long long)set, void_count);
    }
    return FT_OK;
}
