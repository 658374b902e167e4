/* test_presentation.c - how the terrain is coloured ([presentation]).
 *
 *   test_presentation parse
 *     the scene keys (defaults, ranges, cross-field check) and the band rule
 *     at its edges (src/gpu/shade.c, the CPU mirror of shaders/shade.glsl).
 *   test_presentation stairs BACKEND METHOD
 *     a staircase terrain (4 flat steps at known heights, metres CRS) seen
 *     from above at a known altitude, relative colouring with 4 opaque
 *     bands: every pixel whose 3 x 3 neighbourhood sees one flat step must
 *     have exactly (+-2 of 255, the rounding) the colour of its band, the
 *     band found from the reference ray caster's hit height; each band must
 *     cover at least 2000 such pixels. The same view in the night palette
 *     (and its sky), and with absolute colouring (the day ramp). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/scene.h"
#include "core/units.h"
#include "gpu/shade.h"
#include "test_util.h"
#if FT_PRESENTATION_GL
#include "app/app.h"
#include "measure/reference.h"
#include "test_app_util.h"
#include "test_terrain_util.h"
#endif


/* ---- the scene keys ---------------------------------------------------------------- */

static ft_status parse(const char *text, ft_scene *s, ft_error *err)
{
    ft_scene_defaults(s);
    return ft_scene_parse(s, text, "test", err);
}

static void expect_refused(const char *text, const char *needle)
{
    static ft_scene s;
    ft_error err;
    memset(&err, 0, sizeof err);
    const ft_status st = parse(text, &s, &err);
    CHECK(st != FT_OK);
    if (st != FT_OK && strstr(err.text, needle) == NULL) {
        fprintf(stderr, "refused without '%s': %s\n", needle, err.text);
        CHECK(0);
    }
}

static int run_parse(void)
{
    static ft_scene s;
    ft_error err;
    REQUIRE(parse("", &s, &err) == FT_OK);
    CHECK(s.present_relative == 0 && s.present_palette == FT_PALETTE_DAY);
    CHECK(s.present_bands.edges == 2u && s.present_bands.colours == 3u);
    CHECK(s.present_bands.edge_ft[0] == -1000.0f && s.present_bands.edge_ft[1] == -100.0f);

    REQUIRE(parse("[presentation]\ncolouring = relative\npalette = night\n"
                  "band_edges_ft = -3000, -2000,-1000\n"
                  "band_rgba = 0000ffff, 00FF00FF, ffff0080 ,FF000000\n",
                  &s, &err) == FT_OK);
    CHECK(s.present_relative == 1 && s.present_palette == FT_PALETTE_NIGHT);
    CHECK(s.present_bands.edges == 3u && s.present_bands.colours == 4u);
    CHECK(s.present_bands.edge_ft[1] == -2000.0f);
    CHECK(s.present_bands.rgba[0][2] == 1.0f && s.present_bands.rgba[0][0] == 0.0f);
    CHECK_NEAR(s.present_bands.rgba[2][3], 128.0 / 255.0, 1e-7);

    expect_refused("[presentation]\ncolouring = relief\n", "expected absolute or relative");
    expect_refused("[presentation]\nhaze_km = 0.5\n", "0 (off) or 1..1000 km");
    expect_refused("[presentation]\nhaze_km = -1\n", "0 (off) or 1..1000 km");
    expect_refused("[presentation]\nhorizon = 2\n", "expected 0 or 1");
    expect_refused("[presentation]\ngrid_m = 5\n", "0 (off) or 10..10000 m");
    expect_refused("[presentation]\ngrid_m = 20000\n", "0 (off) or 10..10000 m");
    expect_refused("[presentation]\npalette = dusk\n", "expected day or night");
    expect_refused("[presentation]\nband_edges_ft = -100, -1000\n", "strictly increasing");
    expect_refused("[presentation]\nband_edges_ft = -100, -100\n", "strictly increasing");
    expect_refused("[presentation]\nband_edges_ft = 1, 2, 3, 4, 5, 6\n", "1 to 5");
    expect_refused("[presentation]\nband_edges_ft = 70000\n", "60000");
    expect_refused("[presentation]\nband_edges_ft = -100,\n", "1 to 5");
    expect_refused("[presentation]\nband_edges_ft = nan\n", "1 to 5");
    expect_refused("[presentation]\nband_rgba = FF0000, 00FF00FF\n", "RRGGBBAA");
    expect_refused("[presentation]\nband_rgba = GG0000FF, 00FF00FF\n", "RRGGBBAA");
    expect_refused("[presentation]\nband_rgba = FF0000FF\n", "2 to 6");
    /* edges and colours must agree, whatever order the keys come in */
    expect_refused("[presentation]\nband_edges_ft = -500\n", "band colours");
    expect_refused("[presentation]\nband_rgba = FF0000FF, 00FF00FF, 0000FFFF, 000000FF\n",
                   "band colours");

    /* the band rule at its edges: a height exactly on an edge is in the band above */
    ft_shade_state st;
    REQUIRE(parse("", &s, &err) == FT_OK);
    ft_shade_state_from_scene(&st, &s);
    st.aircraft_alt_m = 1000.0f;
    const float e0 = (float)(-1000.0 * FT_M_PER_FT), e1 = (float)(-100.0 * FT_M_PER_FT);
    CHECK(ft_shade_band_of(&st, 1000.0f + e0 - 0.01f) == 0u);
    CHECK(ft_shade_band_of(&st, 1000.0f + e0) == 1u);
    CHECK(ft_shade_band_of(&st, 1000.0f + e1 - 0.01f) == 1u);
    CHECK(ft_shade_band_of(&st, 1000.0f + e1) == 2u);
    CHECK(ft_shade_band_of(&st, 9000.0f) == 2u);
    CHECK(ft_shade_band_of(&st, -500.0f) == 0u);
    /* alpha 0 (band 0 by default) leaves the terrain colour as it is */
    const float up[3] = {0.0f, 0.0f, 1.0f};
    uint8_t a[4], b[4];
    st.relative = 1;
    ft_shade_rgba8_state(&st, 200.0f, up, 1000.0f, NULL, NULL, a);
    ft_shade_rgba8(200.0f, up, b);
    CHECK(memcmp(a, b, 4) == 0);
    return ft_test_result("presentation parse");
}

/* ---- the staircase ------------------------------------------------------------------ */

#if FT_PRESENTATION_GL

#define ST_SIDE 257u
#define ST_CELL_M 20.0
#define ST_STEP_COLS 64u /* steps: columns [0,64) [64,128) [128,192) [192,256] */
#define ST_X0 500000.0
#define ST_Y0 4900000.0
#define ST_ALT_M 5000.0
#define ST_W 320u
#define ST_H 240u
#define ST_MIN_PX_PER_BAND 2000u

/* heights relative to the aircraft: -4500, -3300, -2700, -2000 m; band edges
 * -12000, -10000, -8000 ft = -3657.6, -3048, -2438.4 m: one step per band */
static const double k_step_m[4] = {500.0, 1700.0, 2300.0, 3000.0};

static double stairs_height(double x, double y, uint32_t ix, uint32_t iy)
{
    (void)x;
    (void)y;
    (void)iy;
    const uint32_t k = ix / ST_STEP_COLS;
    return k_step_m[k < 4u ? k : 3u];
}

static ft_app g_app;
static char g_text[4096];
static int8_t g_cls[ST_W * ST_H]; /* per pixel: step 0..3, -1 sky, -2 by a riser */
static float g_hit_z[ST_W * ST_H], g_hit_d[ST_W * ST_H];

static const char k_stairs_scene[] =
    "[scene]\nname = stairs\nmethod = %s\nbackend = %s\n"
    "[view]\nwidth_px = 320\nheight_px = 240\nfovy_deg = 60\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\ntexture_bytes = 32M\n[metric]\nenabled = 0\n"
    "[presentation]\ncolouring = %s\npalette = %s\nhaze_km = %g\n"
    "band_edges_ft = -12000, -10000, -8000\n"
    "band_rgba = 0000FFFF, 00FF00FF, FFFF00FF, FF0000FF\n"
    "[budget]\nheights_bytes = 2M\npyramids_bytes = 8M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 512K\ngpu_staging_bytes = 2M\nmethod_bytes = 8M\npng_bytes = 512K\n";

/* Classifies every pixel by the reference ray caster: which flat step it
 * sees, the sky, or a riser (the cell between two steps and the cells
 * beside it, whose vertex normals are not the flat step's). */
/* The reference ray through pixel i = (px, py): on a hit, the hit minus the
 * eye (world axes), its height and distance (g_hit_z, g_hit_d), 1; on a
 * miss g_cls[i] = -1 (sky), 0. */
static int cast_pixel(const ft_terrain *t, const ft_camera *cam, uint32_t px, uint32_t py,
                      double rel[3])
{
    const size_t i = (size_t)py * ST_W + px;
    double dir[3], th = 0.0;
    ft_camera_pixel_ray(cam, px + 0.5, py + 0.5, dir);
    if (!ft_reference_ray(t, cam->eye_m, dir, &th)) {
        g_cls[i] = -1;
        return 0;
    }
    for (int k = 0; k < 3; ++k) rel[k] = dir[k] * th;
    g_hit_z[i] = (float)(cam->eye_m[2] + rel[2]);
    g_hit_d[i] = (float)th; /* dir is a unit vector */
    return 1;
}

static void classify(const ft_terrain *t, const ft_camera *cam)
{
    for (uint32_t py = 0; py < ST_H; ++py) {
        for (uint32_t px = 0; px < ST_W; ++px) {
            const size_t i = (size_t)py * ST_W + px;
            double rel[3];
            if (!cast_pixel(t, cam, px, py, rel)) {
                continue;
            }
            const double u = (cam->eye_m[0] + rel[0] - t->origin_world_x_m) / t->cell_x_m;
            const double cell = floor(u);
            const uint32_t c = cell < 0.0 ? 0u : (uint32_t)cell;
            /* the riser cell, and the cells beside it: a mesh's vertex
             * normals there lean towards the riser (central differences) */
            const uint32_t m = c % ST_STEP_COLS;
            const int riser = c < 3u * ST_STEP_COLS + 1u && c >= ST_STEP_COLS - 2u &&
                              (m >= ST_STEP_COLS - 2u || m == 0u);
            const uint32_t k = c / ST_STEP_COLS;
            g_cls[i] = riser ? (int8_t)-2 : (int8_t)(k < 4u ? k : 3u);
        }
    }
}

/* 1 when the pixel and its 8 neighbours see the same flat step. */
static int interior(uint32_t px, uint32_t py)
{
    if (px == 0u || py == 0u || px + 1u >= ST_W || py + 1u >= ST_H) {
        return 0;
    }
    const int8_t c = g_cls[(size_t)py * ST_W + px];
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            if (g_cls[(size_t)(py + (uint32_t)(int)dy) * ST_W + (px + (uint32_t)(int)dx)] != c) {
                return 0;
            }
        }
    }
    return c >= 0;
}

/* Renders the staircase with one colouring and palette; checks every
 * interior pixel against the CPU mirror and every sky pixel against the
 * palette's sky. */
static void stairs_case(const char *backend, const char *method, const char *dem,
                        const char *colouring, const char *palette, double haze_km)
{
    (void)snprintf(g_text, sizeof g_text, k_stairs_scene, method, backend, dem, colouring,
                   palette, haze_km);
    ft_test_app_init(&g_app, g_text, colouring);
    const ft_terrain *t = &g_app.terrain;
    const double m_per_deg = FT_EARTH_RADIUS_M * FT_PI / 180.0;
    const double ex = ST_X0 + 128.0 * ST_CELL_M, ey = ST_Y0 + 128.0 * ST_CELL_M;
    ft_pose p = {t->anchor_lat_deg + (ey - ST_Y0) / m_per_deg,
                 t->anchor_lon_deg + (ex - ST_X0) / (m_per_deg * cos(t->anchor_lat_deg * FT_PI / 180.0)),
                 ST_ALT_M, 0.0, -89.5, 0.0};
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_frame(&g_app, &p, &cam, &fs);
    CHECK(fabs(cam.eye_m[0] - ex) < 0.01 && fabs(cam.eye_m[1] - ey) < 0.01);
    classify(t, &cam);

    ft_shade_state st;
    ft_shade_state_from_scene(&st, &g_app.scene);
    st.aircraft_alt_m = (float)ST_ALT_M;
    float sky[3];
    ft_shade_palette_sky(st.palette, sky);
    const float up[3] = {0.0f, 0.0f, 1.0f};
    uint32_t checked[4] = {0u, 0u, 0u, 0u}, band_px[FT_BANDS_MAX] = {0u};
    uint32_t bad = 0u, sky_checked = 0u, sky_bad = 0u;
    const uint8_t *rgba = g_app.renderer.rgba;
    for (uint32_t py = 0; py < ST_H; ++py) {
        for (uint32_t px = 0; px < ST_W; ++px) {
            const size_t i = (size_t)py * ST_W + px;
            const uint8_t *got = rgba + 4u * i;
            if (g_cls[i] == -1) {
                /* sky away from the terrain's edge: it and its 4 neighbours */
                if (px > 0u && py > 0u && px + 1u < ST_W && py + 1u < ST_H &&
                    g_cls[i - 1u] == -1 && g_cls[i + 1u] == -1 && g_cls[i - ST_W] == -1 &&
                    g_cls[i + ST_W] == -1) {
                    ++sky_checked;
                    int off = 0;
                    for (int c = 0; c < 3; ++c) {
                        off |= abs((int)got[c] - (int)(sky[c] * 255.0f + 0.5f)) > 2;
                    }
                    sky_bad += (uint32_t)off;
                }
                continue;
            }
            if (!interior(px, py)) {
                continue;
            }
            uint8_t want[4];
            ft_shade_rgba8_state(&st, g_hit_z[i], up, g_hit_d[i], NULL, NULL, want);
            ++checked[g_cls[i]];
            ++band_px[ft_shade_band_of(&st, g_hit_z[i])];
            int off = 0;
            for (int c = 0; c < 3; ++c) {
                off |= abs((int)got[c] - (int)want[c]) > 2;
            }
            if (off) {
                if (bad < 5u) {
                    fprintf(stderr,
                            "  pixel (%u, %u), step %d, height %.1f m: got %u %u %u, want %u %u %u\n",
                            px, py, g_cls[i], (double)g_hit_z[i], got[0], got[1], got[2], want[0],
                            want[1], want[2]);
                }
                ++bad;
            }
        }
    }
    printf("%s %s %s %s haze %g km: interior pixels per step %u %u %u %u, per band %u %u %u %u, %u off; "
           "sky %u checked, %u off\n",
           backend, method, colouring, palette, haze_km, checked[0], checked[1], checked[2], checked[3],
           band_px[0], band_px[1], band_px[2], band_px[3], bad, sky_checked, sky_bad);
    CHECK(bad == 0u);
    CHECK(sky_bad == 0u);
    for (int k = 0; k < 4; ++k) {
        CHECK(checked[k] >= ST_MIN_PX_PER_BAND);
        /* relative: one step per band, so each band is seen (and checked) */
        if (st.relative) CHECK(band_px[k] == checked[k]);
    }
    ft_app_shutdown(&g_app);
}

static int run_stairs(const char *backend, const char *method)
{
    char dem[512];
    (void)snprintf(dem, sizeof dem, "%s/stairs_%s_%s.ftt", FT_TEST_OUT_DIR, backend, method);
    ft_terrain t;
    terrain_make(&t, ST_SIDE, ST_SIDE, ST_CELL_M, ST_CELL_M, ST_X0, ST_Y0, stairs_height);
    terrain_write_ftt(&t, dem);
    terrain_free(&t);
    stairs_case(backend, method, dem, "relative", "day", 0.0);
    stairs_case(backend, method, dem, "relative", "night", 0.0);
    stairs_case(backend, method, dem, "absolute", "day", 0.0);
    /* haze over 2000-4500 m at a 4 km visibility: 0.29-0.50 of the sky */
    stairs_case(backend, method, dem, "relative", "day", 4.0);
    return ft_test_result("presentation stairs");
}
#endif

/* ---- the conformal horizon ------------------------------------------------------- */

#if FT_PRESENTATION_GL
/* A flat sea at 0 m on a spherical earth (terrain.curvature = sphere), 512 x
 * 520 km, the eye 10 km north of its south edge looking north: the sea's
 * visible edge lies at the dip sqrt(2 h / R) below the horizontal (357 km
 * away at h = 10 km, inside the sea). */
#define SEA_SIDE_X 513u
#define SEA_SIDE_Y 521u
#define SEA_CELL_M 1000.0
#define SEA_EYE_ROW 10.0

static double sea_height(double x, double y, uint32_t ix, uint32_t iy)
{
    (void)x;
    (void)y;
    (void)ix;
    (void)iy;
    return 0.0;
}

static const char k_sea_scene[] =
    "[scene]\nname = sea\nmethod = brute\nbackend = %s\n"
    "[view]\nwidth_px = 320\nheight_px = 240\nfovy_deg = 45\n"
    "[terrain]\ndem = %s\ncurvature = sphere\n"
    "[gpu]\ntexture_bytes = 32M\n[metric]\nenabled = 0\n"
    "[presentation]\nhorizon = %d\n"
    "[budget]\nheights_bytes = 2M\npyramids_bytes = 8M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 512K\ngpu_staging_bytes = 2M\nmethod_bytes = 1M\npng_bytes = 512K\n";

static uint8_t g_sea_rgba[ST_W * ST_H * 4u];

static void sea_frame(const char *backend, const char *dem, int horizon, double alt_m,
                      double pitch_deg, ft_camera *cam)
{
    (void)snprintf(g_text, sizeof g_text, k_sea_scene, backend, dem, horizon);
    ft_test_app_init(&g_app, g_text, "sea");
    const ft_terrain *t = &g_app.terrain;
    const double m_per_deg = FT_EARTH_RADIUS_M * FT_PI / 180.0;
    const double ex = 256.0 * SEA_CELL_M, ey = SEA_EYE_ROW * SEA_CELL_M;
    ft_pose p = {t->anchor_lat_deg + ey / m_per_deg,
                 t->anchor_lon_deg + ex / (m_per_deg * cos(t->anchor_lat_deg * FT_PI / 180.0)),
                 alt_m, 0.0, pitch_deg, 0.0};
    ft_frame_stats fs;
    ft_test_frame(&g_app, &p, cam, &fs);
    memcpy(g_sea_rgba, g_app.renderer.rgba, sizeof g_sea_rgba);
    ft_app_shutdown(&g_app);
}

static int is_sky(const uint8_t *px)
{
    const int r = (int)(FT_SKY_R * 255.0f + 0.5f), g = (int)(FT_SKY_G * 255.0f + 0.5f),
              b = (int)(FT_SKY_B * 255.0f + 0.5f);
    return abs(px[0] - r) <= 2 && abs(px[1] - g) <= 2 && abs(px[2] - b) <= 2;
}

static int is_line(const uint8_t *px)
{
    return px[0] >= 250 && px[1] >= 250 && px[2] >= 250;
}

/* One altitude: the sea edge (no line) per column against the dip curve,
 * and the drawn line's centre per column against the zero-pitch line. */
static void sea_case(const char *backend, const char *dem, double alt_m, double pitch_deg)
{
    ft_camera cam;
    sea_frame(backend, dem, 0, alt_m, pitch_deg, &cam);
    const double k = (double)ST_H * 0.5 / tan(cam.fovy_rad * 0.5); /* px per unit tangent */
    const double dip = sqrt(2.0 * alt_m / FT_EARTH_RADIUS_M);
    const double p = pitch_deg * FT_PI / 180.0;
    double edge_err_max = 0.0, line_err_max = 0.0, dip_px_mid = 0.0, line_mid = 0.0;
    uint32_t edge_cols = 0u, line_cols = 0u, missing = 0u;
    for (uint32_t x = 0; x < ST_W; ++x) {
        /* the direction of depression delta at azimuth a, through this column,
         * with the camera pitched up by p: y_cam / z_cam in the camera frame */
        const double sx = ((x + 0.5) / ST_W * 2.0 - 1.0) * (double)ST_W / (double)ST_H *
                          tan(cam.fovy_rad * 0.5);
        /* a horizontal ray at elevation e and azimuth a: camera coords
         * z = cos e cos a cos p + sin e sin p, y = sin e cos p - cos e cos a sin p,
         * x = cos e sin a; solve for the column's a at e = -dip */
        const double e = -dip;
        double a = atan(sx * cos(p)); /* start; refine by Newton on x/z = sx */
        for (int it = 0; it < 20; ++it) {
            const double z = cos(e) * cos(a) * cos(p) + sin(e) * sin(p);
            const double xx = cos(e) * sin(a);
            const double f = xx / z - sx;
            const double dz = -cos(e) * sin(a) * cos(p);
            const double dx = cos(e) * cos(a);
            const double df = (dx * z - xx * dz) / (z * z);
            a -= f / df;
        }
        const double z = cos(e) * cos(a) * cos(p) + sin(e) * sin(p);
        const double y = sin(e) * cos(p) - cos(e) * cos(a) * sin(p);
        const double edge_y = ST_H * 0.5 - k * (y / z);
        uint32_t first = ST_H;
        for (uint32_t r = 0; r < ST_H; ++r) {
            if (!is_sky(g_sea_rgba + 4u * ((size_t)r * ST_W + x))) {
                first = r;
                break;
            }
        }
        if (first == ST_H) {
            ++missing;
            continue;
        }
        /* the first sea row is the first whose centre lies below the edge */
        const double err_px = fabs((double)first + 0.5 - edge_y) - 0.5;
        if (err_px > edge_err_max) edge_err_max = err_px;
        ++edge_cols;
        if (x == ST_W / 2u) dip_px_mid = edge_y - (ST_H * 0.5 + k * tan(p));
    }
    sea_frame(backend, dem, 1, alt_m, pitch_deg, &cam);
    const double line_y = ST_H * 0.5 + k * tan(p); /* zero pitch, roll 0: one row */
    for (uint32_t x = 1; x + 1u < ST_W; ++x) {
        double sum = 0.0;
        uint32_t n = 0u;
        for (uint32_t r = 0; r < ST_H; ++r) {
            if (is_line(g_sea_rgba + 4u * ((size_t)r * ST_W + x))) {
                sum += r + 0.5;
                ++n;
            }
        }
        if (n == 0u) {
            ++missing;
            continue;
        }
        const double err_px = fabs(sum / n - line_y);
        if (err_px > line_err_max) line_err_max = err_px;
        if (x == ST_W / 2u) line_mid = sum / n;
        ++line_cols;
    }
    printf("%s sea at %g m, pitch %g deg: dip %.4f deg = %.2f px below the zero-pitch line "
           "(centre column); sea edge within %.2f px of it over %u columns; line centre "
           "%.2f (want %.2f), within %.2f px over %u columns; %u columns missing\n",
           backend, alt_m, pitch_deg, dip * 180.0 / FT_PI, dip_px_mid, edge_err_max, edge_cols,
           line_mid, line_y, line_err_max, line_cols, missing);
    CHECK(missing == 0u && edge_cols == ST_W && line_cols == ST_W - 2u);
    CHECK(edge_err_max <= 1.0);
    CHECK(line_err_max <= 1.0);
}

static int run_horizon(const char *backend)
{
    char dem[512];
    (void)snprintf(dem, sizeof dem, "%s/sea_%s.ftt", FT_TEST_OUT_DIR, backend);
    ft_terrain t;
    terrain_make(&t, SEA_SIDE_X, SEA_SIDE_Y, SEA_CELL_M, SEA_CELL_M, 0.0, 0.0, sea_height);
    terrain_write_ftt(&t, dem);
    terrain_free(&t);
    sea_case(backend, dem, 1.0, 0.0);
    sea_case(backend, dem, 1000.0, 0.0);
    sea_case(backend, dem, 10000.0, 0.0);
    sea_case(backend, dem, 10000.0, -4.0);
    return ft_test_result("presentation horizon");
}
#endif

/* ---- unmeasured terrain ----------------------------------------------------------- */

#if FT_PRESENTATION_GL
/* A flat tile at 500 m (metres CRS), every sample of the east half
 * (columns >= VOID_COL0) void-filled: over 50% of the tile. */
#define VOID_SIDE 129u
#define VOID_COL0 64u
#define VOID_CELL_M 30.0

static double flat_height(double x, double y, uint32_t ix, uint32_t iy)
{
    (void)x;
    (void)y;
    (void)ix;
    (void)iy;
    return 500.0;
}

static const char k_void_scene[] =
    "[scene]\nname = voids\nmethod = %s\nbackend = %s\n"
    "[view]\nwidth_px = 320\nheight_px = 240\nfovy_deg = 60\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\ntexture_bytes = 32M\n[metric]\nenabled = 0\n"
    "[budget]\nheights_bytes = 8M\npyramids_bytes = 24M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 512K\ngpu_staging_bytes = 8M\nmethod_bytes = 12M\npng_bytes = 512K\n";

static uint8_t g_plain_rgba[ST_W * ST_H * 4u];

/* Marked (grey or hatch) by colour alone: no ramp colour is grey. */
static int looks_marked(const uint8_t *p)
{
    const int grey = abs(p[0] - p[1]) <= 1 && abs(p[1] - p[2]) <= 1;
    const int hatch = p[0] == (uint8_t)(FT_HATCH_R * 255.0f + 0.5f) && p[1] == 0u &&
                      p[2] == (uint8_t)(FT_HATCH_B * 255.0f + 0.5f);
    return grey || hatch;
}

/* Renders the pose; classifies every pixel by the reference ray caster: -1
 * sky, 0 a cell of measured samples only, 1 a cell with a filled corner.
 * Checks: every pixel whose 3 x 3 neighbourhood is one class shows the
 * marking exactly where the class says (hatch on the hatch pixels; with
 * `exact`, the CPU mirror's colour within 2 levels); the readback's count
 * equals the pixels that look marked. plain: the same view of the same
 * terrain without voids, which the measured pixels must equal (NULL: skip). */
static void void_case(const char *backend, const char *method, const char *dem,
                      const ft_pose *p, int exact, const uint8_t *plain, uint32_t *marked_out)
{
    (void)snprintf(g_text, sizeof g_text, k_void_scene, method, backend, dem);
    ft_test_app_init(&g_app, g_text, dem);
    const ft_terrain *t = &g_app.terrain;
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_frame(&g_app, p, &cam, &fs);
    const uint8_t *rgba = g_app.renderer.rgba;
    for (uint32_t py = 0; py < ST_H; ++py) {
        for (uint32_t px = 0; px < ST_W; ++px) {
            const size_t i = (size_t)py * ST_W + px;
            double rel[3];
            if (!cast_pixel(t, &cam, px, py, rel)) {
                continue;
            }
            const double gx = (cam.eye_m[0] + rel[0] - t->origin_world_x_m) / t->cell_x_m;
            const double gy = (cam.eye_m[1] + rel[1] - t->origin_world_y_m) / t->cell_y_m;
            uint32_t cx = gx <= 0.0 ? 0u : (uint32_t)gx, cy = gy <= 0.0 ? 0u : (uint32_t)gy;
            cx = cx > t->width - 2u ? t->width - 2u : cx;
            cy = cy > t->height - 2u ? t->height - 2u : cy;
            const size_t s0 = (size_t)cy * t->width + cx, s1 = s0 + t->width;
            g_cls[i] = (int8_t)(ft_terrain_sample_filled(t, s0) || ft_terrain_sample_filled(t, s0 + 1u) ||
                                ft_terrain_sample_filled(t, s1) || ft_terrain_sample_filled(t, s1 + 1u));
        }
    }
    ft_shade_state st;
    ft_shade_state_from_scene(&st, &g_app.scene);
    st.aircraft_alt_m = (float)cam.eye_m[2];
    const float up[3] = {0.0f, 0.0f, 1.0f};
    uint32_t checked[2] = {0u, 0u}, wrong[2] = {0u, 0u}, looks = 0u, changed = 0u;
    for (uint32_t py = 0; py < ST_H; ++py) {
        for (uint32_t px = 0; px < ST_W; ++px) {
            const size_t i = (size_t)py * ST_W + px;
            const uint8_t *got = rgba + 4u * i;
            looks += (uint32_t)(g_cls[i] >= 0 && looks_marked(got));
            if (!interior(px, py)) {
                continue;
            }
            const int marked = g_cls[i] == 1;
            ++checked[marked];
            int bad = looks_marked(got) != marked;
            /* window coordinates of the pixel centre, origin bottom-left */
            const float frag[2] = {(float)px + 0.5f, (float)(ST_H - 1u - py) + 0.5f};
            if (exact) {
                uint8_t want[4];
                ft_shade_rgba8_state(&st, g_hit_z[i], up, g_hit_d[i], NULL, marked ? frag : NULL,
                                     want);
                for (int c = 0; c < 3; ++c) bad |= abs((int)got[c] - (int)want[c]) > 2;
            }
            if (!marked && plain != NULL) {
                changed += (uint32_t)(memcmp(got, plain + 4u * i, 3u) != 0);
            }
            if (bad && wrong[marked] < 3u) {
                fprintf(stderr, "  pixel (%u, %u) %s: got %u %u %u\n", px, py,
                        marked ? "over a filled cell" : "over measured cells", got[0], got[1],
                        got[2]);
            }
            wrong[marked] += (uint32_t)bad;
        }
    }
    printf("%s %s %s: interior pixels over filled cells %u (%u wrong), over measured cells %u "
           "(%u wrong, %u differ from the tile without voids); unmeasured_px %llu, pixels that "
           "look marked %u\n",
           backend, method, dem, checked[1], wrong[1], checked[0], wrong[0], changed,
           (unsigned long long)fs.unmeasured_px, looks);
    CHECK(checked[0] >= 200u && (t->void_count == 0u || checked[1] >= 200u));
    CHECK(wrong[0] == 0u && wrong[1] == 0u && changed == 0u);
    CHECK(fs.unmeasured_px == looks);
    if (marked_out != NULL) {
        *marked_out = (uint32_t)fs.unmeasured_px;
    }
    if (plain == NULL) {
        memcpy(g_plain_rgba, rgba, sizeof g_plain_rgba);
    }
    ft_app_shutdown(&g_app);
}

static int run_voids(const char *backend, const char *method)
{
    /* the synthetic half-void tile, and the same tile measured everywhere */
    char dem[512], dem_plain[512];
    (void)snprintf(dem, sizeof dem, "%s/halfvoid_%s_%s.ftt", FT_TEST_OUT_DIR, backend, method);
    (void)snprintf(dem_plain, sizeof dem_plain, "%s/nohole_%s_%s.ftt", FT_TEST_OUT_DIR, backend,
                   method);
    ft_terrain t;
    terrain_make(&t, VOID_SIDE, VOID_SIDE, VOID_CELL_M, VOID_CELL_M, ST_X0, ST_Y0, flat_height);
    terrain_write_ftt(&t, dem_plain);
    static uint8_t mask[VOID_SIDE * VOID_SIDE];
    for (uint32_t k = 0; k < VOID_SIDE * VOID_SIDE; ++k) mask[k] = (uint8_t)(k % VOID_SIDE >= VOID_COL0);
    static uint8_t bits[(VOID_SIDE * VOID_SIDE + 7u) / 8u];
    t.void_count = ft_terrain_pack_void_bits(mask, VOID_SIDE, VOID_SIDE, bits);
    t.void_bits = bits;
    terrain_write_ftt(&t, dem);
    printf("half-void tile: %u of %u samples void-filled (%.1f%%)\n", t.void_count,
           VOID_SIDE * VOID_SIDE, 100.0 * t.void_count / (VOID_SIDE * VOID_SIDE));
    terrain_free(&t);
    const double m_per_deg = FT_EARTH_RADIUS_M * FT_PI / 180.0;
    const double ex = 60.0 * VOID_CELL_M, ey = 64.0 * VOID_CELL_M; /* just west of the edge */
    const ft_pose p = {45.0 + ey / m_per_deg, 9.0 + ex / (m_per_deg * cos(45.0 * FT_PI / 180.0)),
                       2500.0, 0.0, -89.5, 0.0};
    void_case(backend, method, dem_plain, &p, 1, NULL, NULL); /* fills g_plain_rgba */
    CHECK(g_app.renderer.void_tex == 0u); /* no voids: no texture, no variant */
    uint32_t marked = 0u;
    void_case(backend, method, dem, &p, 1, g_plain_rgba, &marked);
    CHECK(marked > 0u);

    /* N52E008 (SRTM3): its 3 filled samples seen from 600 m above the first */
    const char *hgt = FT_SHARED_DATA_DIR "/N52E008.hgt";
    if (!ft_test_have_data(hgt)) {
        return ft_test_result("presentation voids");
    }
    (void)snprintf(g_text, sizeof g_text, k_void_scene, method, backend, hgt);
    ft_test_app_init(&g_app, g_text, hgt);
    const ft_terrain *n52 = &g_app.terrain;
    CHECK(n52->void_count == 3u);
    size_t first = 0u;
    for (size_t k = (size_t)n52->width * n52->height; k-- > 0u;) {
        if (ft_terrain_sample_filled(n52, k)) first = k;
    }
    const uint32_t fx = (uint32_t)(first % n52->width), fy = (uint32_t)(first / n52->width);
    const ft_pose q = {n52->origin_y + fy * n52->spacing_y, n52->origin_x + fx * n52->spacing_x,
                       (double)n52->heights_m[first] + 600.0, 0.0, -89.5, 0.0};
    printf("N52E008: first filled sample at grid (%u, %u), %.1f m\n", fx, fy,
           (double)n52->heights_m[first]);
    ft_app_shutdown(&g_app);
    void_case(backend, method, hgt, &q, 0, NULL, NULL);
    return ft_test_result("presentation voids");
}
#endif

/* ---- ground grid -------------------------------------------------------------------- */

#if FT_PRESENTATION_GL
/* The flat tile of the void test, measured everywhere (500 m), seen
 * straight down from 800 m with a 1000 m grid: lines 20 m wide (s / 50),
 * about 14 px there (a pixel is 1.4 m). Every pixel whose 3 x 3
 * neighbourhood is all on or all off a line (by the CPU mirror at the
 * reference ray's hit) has the mirror's colour. */
static int run_grid(const char *backend, const char *method)
{
    char dem[512];
    (void)snprintf(dem, sizeof dem, "%s/grid_%s_%s.ftt", FT_TEST_OUT_DIR, backend, method);
    ft_terrain tt;
    terrain_make(&tt, VOID_SIDE, VOID_SIDE, VOID_CELL_M, VOID_CELL_M, ST_X0, ST_Y0, flat_height);
    terrain_write_ftt(&tt, dem);
    terrain_free(&tt);
    (void)snprintf(g_text, sizeof g_text, k_void_scene, method, backend, dem);
    const size_t used = strlen(g_text);
    (void)snprintf(g_text + used, sizeof g_text - used, "[presentation]\ngrid_m = 1000\n");
    ft_test_app_init(&g_app, g_text, dem);
    const ft_terrain *t = &g_app.terrain;
    const double m_per_deg = FT_EARTH_RADIUS_M * FT_PI / 180.0;
    /* above the crossing of the lines x = 2000 m and y = 2000 m, off centre */
    const double ex = 2031.0, ey = 1987.0;
    const ft_pose p = {45.0 + ey / m_per_deg, 9.0 + ex / (m_per_deg * cos(45.0 * FT_PI / 180.0)),
                       800.0, 0.0, -89.5, 0.0};
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_frame(&g_app, &p, &cam, &fs);
    ft_shade_state st;
    ft_shade_state_from_scene(&st, &g_app.scene);
    st.aircraft_alt_m = (float)cam.eye_m[2];
    st.px_per_rad = (float)cam.px_per_rad_k;
    st.void_map[0] = (float)(t->origin_world_x_m - cam.eye_m[0]);
    st.void_map[1] = (float)(t->origin_world_y_m - cam.eye_m[1]);
    static float rel[ST_W * ST_H][2];
    for (uint32_t py = 0; py < ST_H; ++py) {
        for (uint32_t px = 0; px < ST_W; ++px) {
            const size_t i = (size_t)py * ST_W + px;
            double hit[3];
            if (!cast_pixel(t, &cam, px, py, hit)) {
                continue;
            }
            rel[i][0] = (float)hit[0];
            rel[i][1] = (float)hit[1];
            g_cls[i] = (int8_t)(ft_shade_grid_weight(&st, rel[i], g_hit_d[i]) > 0.0f);
        }
    }
    const float up[3] = {0.0f, 0.0f, 1.0f};
    uint32_t checked[2] = {0u, 0u}, wrong = 0u;
    for (uint32_t py = 0; py < ST_H; ++py) {
        for (uint32_t px = 0; px < ST_W; ++px) {
            const size_t i = (size_t)py * ST_W + px;
            if (!interior(px, py)) {
                continue;
            }
            uint8_t want[4];
            ft_shade_rgba8_state(&st, g_hit_z[i], up, g_hit_d[i], rel[i], NULL, want);
            const uint8_t *got = g_app.renderer.rgba + 4u * i;
            int bad = 0;
            for (int c = 0; c < 3; ++c) bad |= abs((int)got[c] - (int)want[c]) > 2;
            if (bad && wrong < 3u) {
                fprintf(stderr, "  pixel (%u, %u) %s a line: got %u %u %u, want %u %u %u\n", px,
                        py, g_cls[i] ? "on" : "off", got[0], got[1], got[2], want[0], want[1],
                        want[2]);
            }
            wrong += (uint32_t)bad;
            ++checked[g_cls[i]];
        }
    }
    printf("%s %s grid 1000 m from 300 m above: interior pixels on lines %u, off lines %u, %u wrong\n",
           backend, method, checked[1], checked[0], wrong);
    CHECK(wrong == 0u && checked[1] >= 100u && checked[0] >= 10000u);
    ft_app_shutdown(&g_app);
    return ft_test_result("presentation grid");
}
#endif

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "parse") == 0) {
        return run_parse();
    }
#if FT_PRESENTATION_GL
    if (argc >= 4 && strcmp(argv[1], "stairs") == 0) {
        return run_stairs(argv[2], argv[3]);
    }
    if (argc >= 3 && strcmp(argv[1], "horizon") == 0) {
        return run_horizon(argv[2]);
    }
    if (argc >= 4 && strcmp(argv[1], "voids") == 0) {
        return run_voids(argv[2], argv[3]);
    }
    if (argc >= 4 && strcmp(argv[1], "grid") == 0) {
        return run_grid(argv[2], argv[3]);
    }
#endif
    fprintf(stderr, "usage: test_presentation parse | stairs BACKEND METHOD | horizon BACKEND | "
                    "voids BACKEND METHOD | grid BACKEND METHOD\n");
    return 2;
}
