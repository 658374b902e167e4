/* test_metric_gpu.c - the whole measuring chain on a real context:
 * terrain file -> arena -> GPU mesh -> RGBA32F position pass -> reference ray
 * caster -> metric.
 *
 * 1. A tilted plane at 1e7 m easting (a .ftt written here). The brute mesh
 *    represents a plane exactly, so the measured error must be ~0 (stated
 *    tolerance: max 0.05 px, the metric's own accuracy requirement) and the
 *    coverage must match the reference except at a few silhouette pixels.
 *    This also proves relative-to-eye rendering: in float world coordinates
 *    1e7 m has a 1 m ulp and the error would be hundreds of pixels.
 * 2. A wrong-by-design case: the same plane rendered, but measured against a
 *    terrain 5 m higher: the metric must see it (fails if it reports ~0).
 * 3. Real data (../shared/data/N42E001.hgt, skipped if absent): brute against
 *    the bilinear reference; the numbers are printed, and the bounds below
 *    are the stated tolerances (the brute mesh splits each bilinear cell
 *    along one diagonal, so it is not exact). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "core/units.h"
#include "terrain/pyramid.h"
#include "terrain/terrain_file.h"
#include "test_util.h"

static ft_app g_app;

static const char k_scene_common[] =
    "[scene]\nmethod = brute\nbackend = %s\n"
    "[view]\nwidth_px = 320\nheight_px = 240\nfovy_deg = 60\n"
    "[pose]\nlat_deg = %.9f\nlon_deg = %.9f\nalt_m = %.3f\n"
    "heading_deg = %.3f\npitch_deg = %.3f\nroll_deg = 0\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\ntexture_bytes = 32M\n[metric]\nenabled = 1\n"
    "[brute]\npatch_cells = 64\nmax_vertices = 2000000\n"
    "[budget]\nheights_bytes = 6M\npyramids_bytes = 18M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 512K\nframe_pos_bytes = 2M\nreference_bytes = 2M\nmetric_bytes = 2M\n"
    "gpu_staging_bytes = 32K\nmethod_bytes = 128K\npng_bytes = 512K\n";

static char g_text[4096];

static ft_status run(const char *backend, const char *dem, double lat, double lon, double alt,
                     double heading, double pitch, ft_error_stats *es, ft_error *err)
{
    ft_scene s;
    ft_camera cam;
    ft_frame_stats fs;
    (void)snprintf(g_text, sizeof g_text, k_scene_common, backend, lat, lon, alt, heading, pitch,
                   dem);
    ft_scene_defaults(&s);
    ft_status st = ft_scene_parse(&s, g_text, "test scene", err);
    if (st == FT_OK) st = ft_app_init(&g_app, &s, err);
    if (st != FT_OK) return st;
    st = ft_app_render(&g_app, &s.pose, &cam, &fs, err);
    if (st == FT_OK) st = ft_app_measure(&g_app, &cam, es, err);
    return st;
}

static ft_status stdio_write(void *ctx, const void *src, size_t bytes)
{
    return fwrite(src, 1, bytes, (FILE *)ctx) == bytes ? FT_OK : FT_ERR_IO;
}

static void write_plane(const char *path)
{
    const uint32_t n = 129;
    ft_terrain t;
    ft_error err;
    memset(&t, 0, sizeof t);
    t.width = t.height = n;
    t.unit = FT_UNIT_METRE;
    t.spacing_x = t.spacing_y = 10.0;
    t.origin_x = 1.0e7;
    t.origin_y = 5.0e6;
    t.anchor_lat_deg = 45.0;
    t.anchor_lon_deg = 9.0;
    (void)snprintf(t.crs, sizeof t.crs, "local-test");
    REQUIRE(ft_terrain_derive_frame(&t, NULL) == FT_OK);
    t.heights_m = malloc((size_t)n * n * sizeof(float));
    size_t pb = ft_pyramid_bytes(n, n);
    void *pyr = aligned_alloc(64, (pb + 63u) & ~(size_t)63u);
    REQUIRE(t.heights_m != NULL && pyr != NULL);
    REQUIRE(ft_pyramid_layout(&t, pyr, pb, NULL) == FT_OK);
    for (uint32_t y = 0; y < n; ++y) {
        for (uint32_t x = 0; x < n; ++x) {
            t.heights_m[y * n + x] = (float)(100.0 + 0.5 * x + 0.25 * y);
        }
    }
    ft_pyramid_build(&t);
    FILE *f = fopen(path, "wb");
    REQUIRE(f != NULL);
    ft_writer w = {f, stdio_write, path};
    ft_status st = ft_tfile_write(&t, -32768.0f, &w, &err);
    if (st != FT_OK) {
        fprintf(stderr, "write: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
    REQUIRE(fclose(f) == 0);
    free(t.heights_m);
    free(pyr);
}

int main(int argc, char **argv)
{
    ft_error err;
    ft_error_stats es;
    const char *backend = argc > 1 ? argv[1] : "egl-gles3";
    /* one file per backend: ctest runs the backends' tests side by side */
    char plane[512];
    (void)snprintf(plane, sizeof plane, FT_TEST_OUT_DIR "/plane_1e7_%s.ftt", backend);
    write_plane(plane);

    /* 1. exact plane at 1e7 m */
    double lon = 9.0 + 640.0 / (111195.0797 * cos(45.0 * FT_RAD_PER_DEG));
    double lat = 45.0 - 300.0 / 111195.0797;
    ft_status st = run(backend, plane, lat, lon, 600.0, 0.0, -25.0, &es, &err);
    if (st != FT_OK) {
        fprintf(stderr, "plane: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
    uint32_t px = 320u * 240u;
    printf("plane @1e7 m, %s: max %.5f px, p99.9 %.5f, mean %.6f; terrain %u px, "
           "mismatch %u + %u, nonfinite %u\n",
           backend, es.max_px, es.p999_px, es.mean_px, es.terrain_px, es.only_method_px,
           es.only_ref_px, es.nonfinite_px);
    CHECK(es.terrain_px > px / 4u && es.terrain_px < px);
    CHECK(es.nonfinite_px == 0);
    CHECK(es.max_px < 0.05);
    CHECK(es.only_method_px + es.only_ref_px <= px / 1000u); /* <= 0.1%: silhouette rounding */

    /* 2. the metric must see a 5 m error: same frame, truth raised by 5 m */
    {
        ft_terrain t2 = g_app.terrain;
        size_t n = (size_t)t2.width * t2.height;
        float *h = malloc(n * sizeof(float));
        REQUIRE(h != NULL);
        for (size_t i = 0; i < n; ++i) {
            h[i] = g_app.terrain.heights_m[i] + 5.0f;
        }
        t2.heights_m = h;
        ft_camera cam;
        ft_error_stats bad;
        REQUIRE(ft_renderer_camera(&g_app.renderer, &g_app.scene.pose, &cam, &err) == FT_OK);
        REQUIRE(ft_metric_compute(&t2, &cam, g_app.renderer.pos, NULL, g_app.metric_scratch,
                                  ft_metric_scratch_bytes(cam.width_px, cam.height_px), &bad,
                                  &err) == FT_OK);
        /* the nearest terrain is about 570 m away: 5 m there is about 1.8 px at K = 208 */
        double k = 240.0 / (2.0 * tan(30.0 * FT_RAD_PER_DEG));
        printf("plane measured against truth + 5 m: max %.3f px, mean %.3f px (K = %.1f)\n",
               bad.max_px, bad.mean_px, k);
        CHECK(bad.max_px > 1.0);
        CHECK(bad.mean_px > 0.3);
        free(h);
    }
    ft_app_shutdown(&g_app);

    /* 3. real DEM */
    const char *hgt = FT_SHARED_DATA_DIR "/N42E001.hgt";
    FILE *probe = fopen(hgt, "rb");
    if (probe == NULL) {
        printf("%s missing: real-data case skipped\n", hgt);
        return g_ft_test_failures ? 1 : FT_TEST_SKIP;
    }
    fclose(probe);
    st = run(backend, hgt, 42.30, 1.50, 3800.0, 0.0, -14.0, &es, &err);
    if (st != FT_OK) {
        fprintf(stderr, "N42E001: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
    printf("N42E001 brute vs bilinear reference, %s: max %.4f px, p99.9 %.4f, mean %.5f; "
           "terrain %u px, mismatch %u + %u\n",
           backend, es.max_px, es.p999_px, es.mean_px, es.terrain_px, es.only_method_px,
           es.only_ref_px);
    CHECK(es.nonfinite_px == 0);
    CHECK(es.terrain_px > px / 3u);
    CHECK(es.mean_px < 0.05);
    CHECK(es.p999_px < 1.0);
    CHECK(es.only_method_px + es.only_ref_px <= px / 200u); /* <= 0.5% */
    ft_app_shutdown(&g_app);
    return ft_test_result("test_metric_gpu");
}
