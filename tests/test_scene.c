/* test_scene.c - the scene file: the embedded default resolves to exactly the
 * documented defaults, every error names the line and key, and ranges hold. */
#include <math.h>
#include <string.h>

#include "core/scene.h"
/* The scene is configuration, not GL: it must build where no GL header is
 * included (the profile tool compiles it for the build host). */
#if defined(GL_ES_VERSION_2_0) || defined(GL_ES_VERSION_3_0)
#error "core/scene.h pulls in a GL header"
#endif
#include "test_util.h"

static ft_status parse(const char *text, ft_scene *s, ft_error *err)
{
    ft_scene_defaults(s);
    memset(err, 0, sizeof *err);
    return ft_scene_parse(s, text, "test.ini", err);
}

static void expect_error(const char *text, const char *needle)
{
    ft_scene s;
    ft_error err;
    ft_status st = parse(text, &s, &err);
    CHECK(st == FT_ERR_CONFIG);
    if (strstr(err.text, needle) == NULL) {
        fprintf(stderr, "error text '%s' lacks '%s'\n", err.text, needle);
        CHECK(0);
    }
}

int main(void)
{
    ft_scene a, b;
    ft_error err;

    /* The embedded default scene sets every key to the built-in defaults:
     * parse it over a zeroed struct and compare with ft_scene_defaults. */
    memset(&a, 0, sizeof a);
    a.backend = FT_BACKEND_EGL_GLES3;
    CHECK(ft_scene_parse(&a, ft_default_scene_text, "embedded", &err) == FT_OK);
    ft_scene_defaults(&b);
    CHECK(strcmp(a.name, b.name) == 0);
    CHECK(a.method == b.method && a.backend == b.backend && a.display == b.display);
    CHECK(a.width_px == b.width_px && a.height_px == b.height_px);
    CHECK_NEAR(a.fovy_deg, b.fovy_deg, 0.0);
    CHECK_NEAR(a.pose.lat_deg, b.pose.lat_deg, 0.0);
    CHECK_NEAR(a.pose.lon_deg, b.pose.lon_deg, 0.0);
    CHECK_NEAR(a.pose.alt_m, b.pose.alt_m, 0.0);
    CHECK(a.synth.side == b.synth.side && a.synth.seed == b.synth.seed);
    CHECK(a.gpu_texture_bytes == b.gpu_texture_bytes);
    CHECK(a.brute_patch_cells == b.brute_patch_cells);
    CHECK(a.brute_max_vertices == b.brute_max_vertices);
    CHECK(a.metric_enabled == b.metric_enabled);
    CHECK(a.bintree_template_k == b.bintree_template_k && a.bintree_tiles_max == b.bintree_tiles_max);
    CHECK_NEAR(a.bintree_tau_px, b.bintree_tau_px, 0.0);
    CHECK(a.bintree_morph == b.bintree_morph);
    CHECK(a.bintree_tiles_per_draw == b.bintree_tiles_per_draw);
    CHECK(a.bintree_heights_clipmap == b.bintree_heights_clipmap && a.bintree_heights_clipmap == 0);
    CHECK(a.pgm_grid_cols == b.pgm_grid_cols && a.pgm_grid_rows == b.pgm_grid_rows);
    CHECK(a.pgrid_grid_cols == b.pgrid_grid_cols && a.pgrid_grid_rows == b.pgrid_grid_rows);
    CHECK(a.pgrid_view_distribution == b.pgrid_view_distribution);
    CHECK(a.pgrid_ray_casting == b.pgrid_ray_casting);
    CHECK_NEAR(a.pgrid_gamma_px, b.pgrid_gamma_px, 0.0);
    CHECK(a.pgrid_raycast_max_px == b.pgrid_raycast_max_px);
    CHECK(a.pgrid_raycast_tile_px == b.pgrid_raycast_tile_px);
    CHECK_NEAR(a.frame_period_ms, b.frame_period_ms, 0.0);
    CHECK_NEAR(a.frame_budget_ms, b.frame_budget_ms, 0.0);
    CHECK(a.frame_degrade == b.frame_degrade);
    CHECK_NEAR(a.frame_degrade_max_scale, b.frame_degrade_max_scale, 0.0);
    CHECK(a.pose_horizon_ms == b.pose_horizon_ms && a.can_failover_ms == b.can_failover_ms);
    CHECK(strcmp(a.can_iface, b.can_iface) == 0 && strcmp(a.can_backup_iface, "") == 0);
    CHECK(a.can_map.count == b.can_map.count && a.can_map.count == 13u);
    CHECK(a.pose_velocity_required == b.pose_velocity_required && a.pose_velocity_required == 0);
    CHECK(a.pose_converge_ms == b.pose_converge_ms && a.pose_converge_ms == 300u);
    CHECK_NEAR(a.pose_snap_m, b.pose_snap_m, 0.0);
    CHECK_NEAR(a.pose_snap_m, 100.0, 0.0);
    CHECK(memcmp(&a.can_map, &b.can_map, sizeof a.can_map) == 0);
    CHECK(strcmp(a.gpio_chip, b.gpio_chip) == 0 && a.gpio_heartbeat_line == -1);
    CHECK(memcmp(a.gpio_input_line, b.gpio_input_line, sizeof a.gpio_input_line) == 0);
    CHECK(a.gpio_debounce_ms == b.gpio_debounce_ms && a.gpio_active_low == b.gpio_active_low);
    CHECK(a.build_inputs == b.build_inputs && a.build_png == b.build_png);
    CHECK(a.present_relative == b.present_relative && a.present_palette == b.present_palette);
    CHECK(memcmp(&a.present_bands, &b.present_bands, sizeof a.present_bands) == 0);
    CHECK(a.present_horizon == b.present_horizon && a.present_haze_km == b.present_haze_km);
    CHECK(a.present_grid_m == b.present_grid_m);
    CHECK(a.pyramid_textures == b.pyramid_textures);
    CHECK(a.height_format == b.height_format);
    for (int i = 0; i < FT_POOL_COUNT; ++i) {
        if (a.budget_bytes[i] != b.budget_bytes[i]) {
            fprintf(stderr, "budget.%s: ini %llu vs defaults %llu\n", ft_pool_key((ft_pool_id)i),
                    (unsigned long long)a.budget_bytes[i], (unsigned long long)b.budget_bytes[i]);
            CHECK(0);
        }
    }
    CHECK(a.dem_path[0] == '\0');
    /* ... and the whole struct: config/default.ini states every key */
    b.pose_given = 1; /* the file has a [pose] section; the defaults do not */
    CHECK(memcmp(&a, &b, sizeof a) == 0);

    /* The schema: no key twice, every default accepted by its own row, a
     * row for every memory pool and every discrete input, and what each
     * kind of row accepts in words. */
    if (ft_scene_schema_check(&a, &err) != FT_OK) {
        fprintf(stderr, "%s\n", err.text);
        CHECK(0);
    }
    size_t nkeys = 0u;
    const ft_scene_key *keys = ft_scene_keys(&nkeys);
    CHECK(nkeys > 80u);
    for (int i = 0; i < FT_POOL_COUNT + FT_GPIO_INPUT_COUNT; ++i) {
        char want[64];
        const char *section = i < FT_POOL_COUNT ? "budget" : "gpio";
        if (i < FT_POOL_COUNT) {
            (void)snprintf(want, sizeof want, "%s", ft_pool_key((ft_pool_id)i));
        } else {
            (void)snprintf(want, sizeof want, "%s_line",
                           ft_gpio_input_name((ft_gpio_input)(i - FT_POOL_COUNT)));
        }
        int rows = 0;
        for (size_t k = 0; k < nkeys; ++k) {
            rows += strcmp(keys[k].section, section) == 0 && strcmp(keys[k].key, want) == 0;
        }
        if (rows != 1) {
            fprintf(stderr, "%s.%s: %d schema rows\n", section, want, rows);
            CHECK(0);
        }
    }
    {
        char text[256];
        int seen = 0;
        for (size_t k = 0; k < nkeys; ++k) {
            const char *t = ft_scene_key_accepts(&keys[k], text, sizeof text);
            if (strcmp(keys[k].key, "width_px") == 0) {
                CHECK(strcmp(t, "16..8192 px") == 0);
                ++seen;
            } else if (strcmp(keys[k].key, "curvature") == 0) {
                CHECK(strcmp(t, "auto, sphere or flat") == 0);
                ++seen;
            } else if (strcmp(keys[k].key, "inputs") == 0) {
                CHECK(strcmp(t, "a comma list of replay, can, gpio") == 0);
                ++seen;
            } else if (strcmp(keys[k].key, "haze_km") == 0) {
                CHECK(strcmp(t, "0 (off) or 1..1000 km") == 0);
                ++seen;
            }
        }
        CHECK(seen == 4);
    }
    /* validate holds every row's range, whatever set the field */
    ft_scene_defaults(&a);
    a.present_haze_km = 0.5;
    CHECK(ft_scene_validate(&a, &err) == FT_ERR_CONFIG &&
          strstr(err.text, "presentation.haze_km = 0.5") != NULL);
    ft_scene_defaults(&a);
    a.build_inputs = 0u;
    CHECK(ft_scene_validate(&a, &err) == FT_ERR_CONFIG && strstr(err.text, "build.inputs") != NULL);
    ft_scene_defaults(&a);
    a.method = FT_METHOD_COUNT;
    CHECK(ft_scene_validate(&a, &err) == FT_ERR_CONFIG && strstr(err.text, "scene.method") != NULL);
    ft_scene_defaults(&a);
    a.gpio_input_line[FT_GPIO_NIGHT] = 512;
    CHECK(ft_scene_validate(&a, &err) == FT_ERR_CONFIG && strstr(err.text, "gpio.night_line") != NULL);
    ft_scene_defaults(&a);
    CHECK(ft_scene_validate(&a, &err) == FT_OK);
    CHECK(a.pose_horizon_ms == FT_POSE_HORIZON_DEFAULT_MS &&
          a.pose_converge_ms == FT_POSE_CONVERGE_DEFAULT_MS &&
          a.pose_snap_m == FT_POSE_SNAP_DEFAULT_M);
    CHECK(a.bintree_morph_width == FT_BT_MORPH_WIDTH);

    /* Suffixes and overrides. */
    CHECK(parse("[budget]\nheights_bytes = 3M\npng_bytes=512K\n[view]\nwidth_px=640\n", &a, &err) ==
          FT_OK);
    CHECK(a.budget_bytes[FT_POOL_HEIGHTS] == 3u * 1024u * 1024u);
    CHECK(a.budget_bytes[FT_POOL_PNG] == 512u * 1024u);
    CHECK(a.width_px == 640);
    CHECK(parse("[scene]\nbackend = osmesa\n[gpu]\nheight_format = packed\n", &a, &err) == FT_OK);
    CHECK(a.backend == FT_BACKEND_OSMESA && a.height_format == FT_HEIGHT_FORMAT_PACKED);

    /* CAN map: replace by id, add a quantity, start empty. */
    CHECK(parse("[can_map]\npitch = 311,0.5,-90,90,50\n", &a, &err) == FT_OK);
    CHECK(a.can_map.count == 13u);
    for (uint32_t i = 0; i < a.can_map.count; ++i) {
        if (a.can_map.e[i].can_id == 311u) {
            CHECK_NEAR(a.can_map.e[i].scale, 0.5, 0.0);
            CHECK(a.can_map.e[i].timeout_ms == 50u && a.can_map.e[i].qty == FT_QTY_PITCH);
        }
    }
    CHECK(parse("[can_map]\ndefaults = 0\nheading = 400,1,0,360,80\n", &a, &err) == FT_OK);
    CHECK(a.can_map.count == 1u && a.can_map.e[0].can_id == 400u &&
          a.can_map.e[0].qty == FT_QTY_HEADING);
    CHECK(parse("[can_map]\nalt = 320,1,-1000,25000,500,0\nalt = 1038,1,-1000,25000,500,1\n",
                &a, &err) == FT_OK);
    CHECK(a.can_map.count == 13u);
    /* velocity: replace the default ground speed (knots on id 1500), add a
     * backup altitude rate */
    CHECK(parse("[can_map]\nground_speed = 1500,0.514444,0,1000,200\n"
                "alt_rate = 1501,1,-300,300,200,1\ntrack = 1040,1,0,360,250\n",
                &a, &err) == FT_OK);
    CHECK(a.can_map.count == 14u);
    int seen = 0;
    for (uint32_t i = 0; i < a.can_map.count; ++i) {
        const ft_can_map_entry *e = &a.can_map.e[i];
        CHECK(e->can_id != 1039u);
        if (e->can_id == 1500u) {
            seen |= 1;
            CHECK(e->qty == FT_QTY_GROUND_SPEED && e->timeout_ms == 200u);
            CHECK_NEAR(e->scale, 0.514444, 0.0);
        } else if (e->can_id == 1501u) {
            seen |= 2;
            CHECK(e->qty == FT_QTY_ALT_RATE && e->priority == 1u);
        } else if (e->can_id == 314u) {
            seen |= 4;
            CHECK(e->qty == FT_QTY_ALT_RATE && e->priority == 0u);
        } else if (e->can_id == 1040u) {
            seen |= 8;
            CHECK(e->qty == FT_QTY_TRACK && e->timeout_ms == 250u && e->min_value == 0.0);
        }
    }
    CHECK(seen == 15);
    CHECK(parse("[pose_input]\nvelocity_required = 1\nconverge_ms = 0\nsnap_m = 25\n", &a,
                &err) == FT_OK);
    CHECK(a.pose_velocity_required == 1 && a.pose_converge_ms == 0u);
    CHECK_NEAR(a.pose_snap_m, 25.0, 0.0);
    expect_error("[pose_input]\nvelocity_required = 2\n", "pose_input.velocity_required");
    expect_error("[pose_input]\nconverge_ms = 10001\n", "expected 0..10000");
    expect_error("[pose_input]\nsnap_m = 0.5\n", "expected 1..100000");
    expect_error("[can_map]\nground_speed = 1039,1,0,1000,0\n", "can_map.ground_speed");
    expect_error("[can_map]\nvertical_speed = 314,1,-1,1,100\n", "unknown section or key");
    expect_error("[can_map]\npitch = 3000,1,-90,90,100\n", "can_map.pitch");
    expect_error("[can_map]\npitch = 311,1,-90,90\n", "TIMEOUT_MS");
    expect_error("[can_map]\npitch = 311,1,90,-90,100\n", "can_map.pitch");
    expect_error("[can_map]\nroll = 311,1,-90,90,100\npitch = 311,1,-90,90,100\n", "mapped");
    expect_error("[can_map]\nspeed = 500,1,0,1,100\n", "unknown section or key");
    expect_error("[can]\ninterface = averyveryverylongname0\n", "longer than 15");
    expect_error("[frame]\nperiod_ms = 0\n", "frame.period_ms");
    expect_error("[frame]\ndegrade_max_scale = 0.5\n", "frame.degrade_max_scale");
    expect_error("[build]\ninputs = replay,usb\n", "build.inputs");
    CHECK(parse("[build]\ninputs = replay\npng = 0\n", &a, &err) == FT_OK);
    CHECK(a.build_inputs == FT_BUILD_INPUT_REPLAY && a.build_png == 0);
    expect_error("[gpio]\nfreeze_line = 1.5\n", "gpio.freeze_line");
    expect_error("[gpio]\nfreeze_line = 3\nheartbeat_line = 3\n", "line 3 is used twice");
    CHECK(parse("[gpio]\nchip = gpiochip1\nfreeze_line = 0\ntest_line = 2\nheartbeat_line = 7\n",
                &a, &err) == FT_OK);
    CHECK(a.gpio_input_line[FT_GPIO_FREEZE] == 0 && a.gpio_input_line[FT_GPIO_TEST] == 2 &&
          a.gpio_heartbeat_line == 7 && strcmp(a.gpio_chip, "gpiochip1") == 0);
    expect_error("[pose_input]\nhorizon_ms = 5000\n", "expected 0..1000");

    /* [can_map] defaults = 1 resets the CAN map only: a [gpio] or [build]
     * section before it keeps every key it set */
    CHECK(parse("[gpio]\nchip = gpiochip2\nfreeze_line = 4\nsource_line = 5\ntest_line = 6\n"
                "heartbeat_line = 9\nactive_low = 1\ndebounce_ms = 25\n"
                "[build]\ninputs = replay,gpio\npng = 0\n"
                "[can_map]\ndefaults = 0\npitch = 311,1,-90,90,100\ndefaults = 1\n",
                &a, &err) == FT_OK);
    CHECK(strcmp(a.gpio_chip, "gpiochip2") == 0);
    CHECK(a.gpio_input_line[FT_GPIO_FREEZE] == 4 && a.gpio_input_line[FT_GPIO_SOURCE] == 5 &&
          a.gpio_input_line[FT_GPIO_TEST] == 6 && a.gpio_heartbeat_line == 9);
    CHECK(a.gpio_active_low == 1 && a.gpio_debounce_ms == 25u);
    CHECK(a.build_inputs == (FT_BUILD_INPUT_REPLAY | FT_BUILD_INPUT_GPIO) && a.build_png == 0);
    ft_scene_defaults(&b);
    CHECK(memcmp(&a.can_map, &b.can_map, sizeof a.can_map) == 0); /* the default map again */
    CHECK(parse("[build]\ninputs = can\n[can_map]\ndefaults = 0\n", &a, &err) == FT_OK);
    CHECK(a.can_map.count == 0u && a.build_inputs == FT_BUILD_INPUT_CAN);

    /* Errors carry the line number, the key and the reason. */
    expect_error("[view]\nwidth_px = 8193\n", "test.ini:2: view.width_px");
    expect_error("[view]\nwidth_px = 12abc\n", "expected 16..8192");
    expect_error("[budget]\nheigths_bytes = 1M\n", "unknown section or key");
    expect_error("[budget]\nheights_bytes = -1\n", "byte count");
    expect_error("[budget]\nheights_bytes = 99999999999999999999\n", "byte count");
    expect_error("[scene]\nmethod = magic\n", "unknown method");
    expect_error("[scene]\nbackend = vulkan\n", "unknown backend");
    expect_error("[nosuch]\nkey = 1\n", "nosuch.key");
    expect_error("[pose]\npitch_deg = 91\n", "expected -90..90");
    expect_error("[pose]\nalt_m = nan\n", "pose.alt_m");
    expect_error("[view]\nfovy_deg = inf\n", "view.fovy_deg");
    expect_error("[metric]\nenabled = 2\n", "expected 0 or 1");
    expect_error("[bintree]\ntemplate_k = 7\n", "bintree.template_k");
    expect_error("[bintree]\ntiles_max = 1\n", "expected 2..1048576");
    expect_error("[bintree]\ntau_px = -0.5\n", "bintree.tau_px");
    expect_error("[bintree]\nmorph = yes\n", "expected 0 or 1");
    CHECK(parse("[scene]\nmethod = bintree\n[bintree]\ntemplate_k = 4\ntau_px = 0.5\n", &a, &err) ==
          FT_OK);
    CHECK(a.method == FT_METHOD_BINTREE && a.bintree_template_k == 4);
    CHECK_NEAR(a.bintree_tau_px, 0.5, 0.0);
    expect_error("[pgm]\ngrid_cols = 1\n", "pgm.grid_cols");
    expect_error("[pgm]\ngrid_rows = 8193\n", "expected 2..8192");
    expect_error("[pgm]\ngrid_size = 100\n", "unknown section or key");
    expect_error("[pgrid]\ndistribution = log\n", "expected uniform or view");
    expect_error("[pgrid]\ngamma_px = 0\n", "expected 0.1..100");
    expect_error("[pgrid]\nray_casting = 2\n", "expected 0 or 1");
    CHECK(parse("[scene]\nmethod = pgrid\n[pgrid]\ndistribution = uniform\ngrid_cols = 150\n"
                "raycast_max_px = 1000\n", &a, &err) == FT_OK);
    CHECK(a.method == FT_METHOD_PGRID && a.pgrid_view_distribution == 0 &&
          a.pgrid_grid_cols == 150u && a.pgrid_raycast_max_px == 1000u);
    CHECK(parse("[scene]\nmethod = pgm\n[pgm]\ngrid_cols = 200\ngrid_rows = 800\n", &a, &err) ==
          FT_OK);
    CHECK(a.method == FT_METHOD_PGM && a.pgm_grid_cols == 200u && a.pgm_grid_rows == 800u);
    a.pgm_grid_rows = 1u; /* validate catches what a command line could set */
    CHECK(ft_scene_validate(&a, &err) == FT_ERR_CONFIG && strstr(err.text, "pgm") != NULL);
    expect_error("[view]\n\nwidth_px = 640\nthis line is wrong\n", "test.ini:4");

    /* --pose parsing */
    ft_pose p;
    CHECK(ft_pose_parse("46.85,-121.76,4500,90,-10,5", &p, &err) == FT_OK);
    CHECK_NEAR(p.lon_deg, -121.76, 1e-12);
    CHECK_NEAR(p.roll_deg, 5.0, 1e-12);
    CHECK(ft_pose_parse("46.85,-121.76,4500,90,-10", &p, &err) == FT_ERR_ARG);
    CHECK(ft_pose_parse("46.85,-121.76,4500,90,-10,5,7", &p, &err) == FT_ERR_ARG);
    CHECK(ft_pose_parse("46.85,x,4500,90,-10,5", &p, &err) == FT_ERR_ARG);
    CHECK(ft_pose_parse("95,0,4500,90,-10,5", &p, &err) == FT_ERR_ARG);
    CHECK(ft_pose_parse("46,0,nan,90,-10,5", &p, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "alt_m") != NULL && strstr(err.text, "not finite") != NULL);

    /* One range table for every way a pose enters: --pose says what the
     * scene's [pose] says, naming the field and its range. */
    CHECK(ft_pose_parse("46.5,8.2,1e300,0,-30,0", &p, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "alt_m = 1e+300") != NULL &&
          strstr(err.text, "[-12000, 1e+06] m") != NULL);
    CHECK(ft_pose_parse("46.5,8.2,1e999,0,-30,0", &p, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "alt_m") != NULL);
    CHECK(ft_pose_parse("46.5,8.2,-12001,0,-30,0", &p, &err) == FT_ERR_ARG);
    CHECK(ft_pose_parse("46.5,400,3000,0,-30,0", &p, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "lon_deg") != NULL && strstr(err.text, "[-360, 360]") != NULL);
    CHECK(ft_pose_parse("46.5,8,3000,inf,-30,0", &p, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "heading_deg") != NULL);
    CHECK(ft_pose_parse("46.5,8,3000,0,-30,-2e9", &p, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "roll_deg") != NULL);
    CHECK(ft_pose_parse("46.5,8,1e6,0,-90,0", &p, &err) == FT_OK); /* the edges are in */
    CHECK(ft_pose_parse("-89,-360,-12000,1e9,90,-1e9", &p, &err) == FT_OK);
    for (int f = 0; f < FT_POSE_FIELD_COUNT; ++f) {
        /* the scene's [pose] uses the same table: just outside each end fails */
        const ft_pose_range *r = ft_pose_range_of((ft_pose_field)f);
        REQUIRE(r != NULL);
        char text[128];
        const double out_of[2] = {r->min - fabs(r->min) * 1e-3 - 1e-3,
                                  r->max + fabs(r->max) * 1e-3 + 1e-3};
        for (int e = 0; e < 2; ++e) {
            (void)snprintf(text, sizeof text, "[pose]\n%s = %.17g\n", r->key, out_of[e]);
            char needle[64];
            (void)snprintf(needle, sizeof needle, "pose.%s", r->key);
            expect_error(text, needle);
        }
        (void)snprintf(text, sizeof text, "[pose]\n%s = %.17g\n", r->key, r->max);
        CHECK(parse(text, &a, &err) == FT_OK);
        CHECK(ft_pose_get(&a.pose, (ft_pose_field)f) == r->max);
    }
    /* CAN is a way a pose enters too: a position or attitude entry's valid
     * range lies within the table (the default map's latitude is narrowed) */
    expect_error("[can_map]\nalt = 320,1,-1000,1e300,500\n", "within pose.alt_m [-12000, 1e+06] m");
    expect_error("[can_map]\nlat = 1036,1,-90,90,500\n", "within pose.lat_deg [-89, 89] deg");
    expect_error("[can_map]\npitch = 311,1,-91,90,100\n", "can_map.pitch");
    CHECK(parse("[can_map]\nlat = 1036,1,-89,89,500\nground_speed = 1039,1,0,1e6,500\n", &a,
                &err) == FT_OK);
    ft_scene_defaults(&a);
    for (uint32_t i = 0; i < a.can_map.count; ++i) {
        if (a.can_map.e[i].qty == FT_QTY_LAT) {
            CHECK(a.can_map.e[i].min_value == -89.0 && a.can_map.e[i].max_value == 89.0);
        }
    }
    ft_scene_defaults(&a);
    a.pose.alt_m = 1e300; /* what a command line could set: validate names it */
    CHECK(ft_scene_validate(&a, &err) == FT_ERR_CONFIG && strstr(err.text, "pose.alt_m") != NULL);
    return ft_test_result("test_scene");
}
