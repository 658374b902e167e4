/* test_app_util.h - the few steps every real-context test takes with an
 * ft_app (tests/test_*_gl.c): a pose, init from scene text, a frame, its
 * error, and the skip when ../shared/data is not there. Each REQUIRE's
 * message names the step and GL/init error text. */
#ifndef FT_TEST_APP_UTIL_H
#define FT_TEST_APP_UTIL_H

#include <stdio.h>

#include "app.h"
#include "test_util.h"

static inline ft_pose ft_test_pose(double lat, double lon, double alt, double heading,
                                   double pitch, double roll)
{
    ft_pose p = {lat, lon, alt, heading, pitch, roll};
    return p;
}

/* Parses scene_text over the defaults and inits app; what names the set-up
 * in the failure message. */
static inline void ft_test_app_init(ft_app *app, const char *scene_text, const char *what)
{
    static ft_scene s; /* large: not on the stack */
    ft_error err;
    ft_scene_defaults(&s);
    ft_status st = ft_scene_parse(&s, scene_text, "test scene", &err);
    if (st == FT_OK) st = ft_app_init(app, &s, &err);
    if (st != FT_OK) fprintf(stderr, "init (%s): %s\n", what, err.text);
    REQUIRE(st == FT_OK);
}

static inline void ft_test_frame(ft_app *app, const ft_pose *p, ft_camera *cam,
                                 ft_frame_stats *fs)
{
    ft_error err;
    ft_status st = ft_app_render(app, p, cam, fs, &err);
    if (st != FT_OK) fprintf(stderr, "frame: %s\n", err.text);
    REQUIRE(st == FT_OK);
}

static inline void ft_test_measure(ft_app *app, const ft_camera *cam, ft_error_stats *es)
{
    ft_error err;
    ft_status st = ft_app_measure(app, cam, es, &err);
    if (st != FT_OK) fprintf(stderr, "measure: %s\n", err.text);
    REQUIRE(st == FT_OK);
}

/* 1 when path can be opened; else says the test is skipped (return
 * FT_TEST_SKIP then). */
static inline int ft_test_have_data(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        printf("%s missing: skipped (needs ../shared/data)\n", path);
        return 0;
    }
    fclose(f);
    return 1;
}

#endif
