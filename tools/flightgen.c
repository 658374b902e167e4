/* flightgen.c - fixterrain-flightgen: a flight path -> a CANaerospace
 * candump -l log at the rates an AHRS and a GPS send, for tests,
 * benchmarks and canplayer on a vcan bus.
 *
 *   fixterrain-flightgen (--path orbit|climb|dive|turn360|valley | --waypoints FILE)
 *       [--centre LAT,LON] [--alt M] [--radius M] [--speed M/S] [--duration S]
 *       [--start-time S] [--iface NAME] [--out FILE] [--quiet] [--no-velocity]
 *       [--drop-every N] [--nan-at S] [--stall FROM,TO] [--bad-dlc-at S]
 *       [--duplicate-at S] [--velocity-stop S] [--gps-jump S,M]
 *
 * The path model, the schedule and the faults are described in
 * flight_path.h. A summary goes to stderr (unless --quiet); the log goes to
 * --out or stdout. Exit status: 0 done, 1 failed, 2 bad command line. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flight_path.h"

#define FG_FILE_MAX_BYTES (16u * 1024u * 1024u) /* a waypoint file is text */
#define FG_OUT_BUFFER_BYTES (1u << 20)

static void usage(FILE *to)
{
    fprintf(to,
            "usage: fixterrain-flightgen (--path NAME | --waypoints FILE) [options]\n"
            "  --path NAME         orbit | climb | dive | turn360 | valley\n"
            "  --waypoints FILE    lines 't_s lat_deg lon_deg alt_m [heading_deg pitch_deg "
            "roll_deg]', '#' comments\n"
            "  --centre LAT,LON    orbit centre / start of a built-in path (default %g,%g)\n"
            "  --alt M             altitude (orbit 1000, dive 3000, turn360 300, valley 150; "
            "climb is 50..10000)\n"
            "  --radius M          orbit radius (default 2000)\n"
            "  --speed M/S         (orbit 60, climb 130, dive 120, turn360 70, valley 100)\n"
            "  --duration S        built-in: path length (orbit: one revolution, climb 900, "
            "dive 60,\n"
            "                      turn360 100, valley 120); waypoints: log only the first S s;\n"
            "                      at least one log period (0.0125 s)\n"
            "  --start-time S      log time of the path start (default 1700000000.000000)\n"
            "  --iface NAME        interface name in the log (default vcan0)\n"
            "  --out FILE          write the log here (default stdout)\n"
            "  --quiet             no summary on stderr\n"
            "  --no-velocity       leave out the velocity (1039 ground speed, 1040 track,\n"
            "                      314 altitude rate): position only, as older logs\n"
            "faults (times S are path times inside the logged path):\n"
            "  --drop-every N      leave out every Nth attitude frame (311/312/321)\n"
            "  --nan-at S          a NaN pitch at S\n"
            "  --stall FROM,TO     no frames at all in [FROM, TO)\n"
            "  --bad-dlc-at S      a frame with DLC 7 at S\n"
            "  --duplicate-at S    a frame sent twice at S\n"
            "  --velocity-stop S   no velocity frames from S on (the position goes on)\n"
            "  --gps-jump S,M      from S on every latitude is sent M metres north of the\n"
            "                      path (a GPS reset)\n",
            FLIGHT_DEFAULT_CENTRE_LAT_DEG, FLIGHT_DEFAULT_CENTRE_LON_DEG);
}

static int parse_double(const char *s, double *out)
{
    if (s == NULL || *s == '\0') {
        return 0;
    }
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) {
        return 0;
    }
    *out = v;
    return 1;
}

/* "A,B" -> two finite numbers */
static int parse_pair(const char *s, double *a, double *b)
{
    const char *comma = s != NULL ? strchr(s, ',') : NULL;
    if (comma == NULL || (size_t)(comma - s) >= 63u) {
        return 0;
    }
    char first[64];
    memcpy(first, s, (size_t)(comma - s));
    first[comma - s] = '\0';
    return parse_double(first, a) && parse_double(comma + 1, b);
}

static int parse_u32(const char *s, uint32_t *out)
{
    if (s == NULL || *s < '0' || *s > '9') {
        return 0;
    }
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (*end != '\0' || errno == ERANGE || v > 0xFFFFFFFFull) {
        return 0;
    }
    *out = (uint32_t)v;
    return 1;
}

/* "1700000000.0125" -> microseconds, exactly (a double has only ~16 digits,
 * and a 10-digit second count leaves none for the microseconds). */
static int parse_start_us(const char *s, uint64_t *out)
{
    uint64_t sec = 0u, usec = 0u;
    size_t i = 0u, digits = 0u;
    while (s[i] >= '0' && s[i] <= '9' && digits < 12u) {
        sec = sec * 10u + (uint64_t)(s[i] - '0');
        ++i;
        ++digits;
    }
    if (digits == 0u) {
        return 0;
    }
    if (s[i] == '.') {
        ++i;
        uint64_t scale = 100000u;
        size_t fd = 0u;
        while (s[i] >= '0' && s[i] <= '9' && fd < 6u) {
            usec += (uint64_t)(s[i] - '0') * scale;
            scale /= 10u;
            ++i;
            ++fd;
        }
        if (fd == 0u) {
            return 0;
        }
    }
    if (s[i] != '\0') {
        return 0; /* more than 6 decimals or junk */
    }
    uint64_t us = sec * 1000000u + usec;
    if (us > FLIGHTGEN_START_MAX_US) {
        return 0;
    }
    *out = us;
    return 1;
}

static char *read_file(const char *path, size_t *len_out, char *why, size_t why_cap)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        (void)snprintf(why, why_cap, "%s: %s", path, strerror(errno));
        return NULL;
    }
    char *buf = malloc(FG_FILE_MAX_BYTES + 1u);
    if (buf == NULL) {
        fclose(f);
        (void)snprintf(why, why_cap, "%s: out of memory", path);
        return NULL;
    }
    size_t n = fread(buf, 1u, FG_FILE_MAX_BYTES + 1u, f);
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        (void)snprintf(why, why_cap, "%s: read error", path);
        return NULL;
    }
    if (n > FG_FILE_MAX_BYTES) {
        free(buf);
        (void)snprintf(why, why_cap, "%s: larger than %u bytes", path, FG_FILE_MAX_BYTES);
        return NULL;
    }
    *len_out = n;
    return buf;
}

typedef struct file_sink {
    FILE *f;
} file_sink;

static ft_status write_line(void *ctx, const ft_candump_record *rec, const char *line, size_t len,
                            ft_error *err)
{
    (void)rec;
    file_sink *fs = ctx;
    if (fwrite(line, 1u, len, fs->f) != len || fputc('\n', fs->f) == EOF) {
        return ft_fail(err, FT_ERR_IO, "write failed: %s", strerror(errno));
    }
    return FT_OK;
}

typedef struct cli {
    const char *path_name, *waypoints, *out;
    flight_builtin_params bp;
    flightgen_options opt;
    double duration_s;
    int centre_set, quiet;
} cli;

/* Returns 0 on success, 2 (and a message) on a bad command line. */
static int parse_args(int argc, char **argv, cli *c)
{
    memset(c, 0, sizeof *c);
    flight_builtin_defaults(&c->bp, FLIGHT_ORBIT);
    flightgen_options_default(&c->opt);
    c->duration_s = NAN;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            exit(0);
        }
        if (strcmp(a, "--quiet") == 0) {
            c->quiet = 1;
            continue;
        }
        if (strcmp(a, "--no-velocity") == 0) {
            c->opt.velocity = 0;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "flightgen: %s needs a value (or is unknown; see --help)\n", a);
            return 2;
        }
        const char *v = argv[++i];
        int ok = 1;
        if (strcmp(a, "--path") == 0) {
            c->path_name = v;
        } else if (strcmp(a, "--waypoints") == 0) {
            c->waypoints = v;
        } else if (strcmp(a, "--out") == 0) {
            c->out = v;
        } else if (strcmp(a, "--centre") == 0 || strcmp(a, "--center") == 0) {
            ok = parse_pair(v, &c->bp.centre_lat_deg, &c->bp.centre_lon_deg);
            c->centre_set = 1;
        } else if (strcmp(a, "--alt") == 0) {
            ok = parse_double(v, &c->bp.alt_m);
        } else if (strcmp(a, "--radius") == 0) {
            ok = parse_double(v, &c->bp.radius_m);
        } else if (strcmp(a, "--speed") == 0) {
            ok = parse_double(v, &c->bp.speed_m_s);
        } else if (strcmp(a, "--duration") == 0) {
            ok = parse_double(v, &c->duration_s) && c->duration_s > 0.0;
        } else if (strcmp(a, "--start-time") == 0) {
            ok = parse_start_us(v, &c->opt.start_us);
        } else if (strcmp(a, "--iface") == 0) {
            size_t n = strlen(v);
            ok = n >= 1u && n <= FT_CANDUMP_IFACE_MAX && strpbrk(v, " \t") == NULL;
            if (ok) {
                memcpy(c->opt.iface, v, n + 1u);
            }
        } else if (strcmp(a, "--drop-every") == 0) {
            ok = parse_u32(v, &c->opt.drop_every) && c->opt.drop_every > 0u;
        } else if (strcmp(a, "--nan-at") == 0) {
            ok = parse_double(v, &c->opt.nan_at_s);
        } else if (strcmp(a, "--bad-dlc-at") == 0) {
            ok = parse_double(v, &c->opt.bad_dlc_at_s);
        } else if (strcmp(a, "--duplicate-at") == 0) {
            ok = parse_double(v, &c->opt.duplicate_at_s);
        } else if (strcmp(a, "--velocity-stop") == 0) {
            ok = parse_double(v, &c->opt.velocity_stop_s);
        } else if (strcmp(a, "--gps-jump") == 0) {
            ok = parse_pair(v, &c->opt.gps_jump_at_s, &c->opt.gps_jump_m) &&
                 fabs(c->opt.gps_jump_m) <= 1e6;
        } else if (strcmp(a, "--stall") == 0) {
            ok = parse_pair(v, &c->opt.stall_from_s, &c->opt.stall_to_s) &&
                 c->opt.stall_from_s < c->opt.stall_to_s;
        } else {
            fprintf(stderr, "flightgen: unknown option %s (see --help)\n", a);
            return 2;
        }
        if (!ok) {
            fprintf(stderr, "flightgen: bad value '%s' for %s (see --help)\n", v, a);
            return 2;
        }
    }
    if ((c->path_name == NULL) == (c->waypoints == NULL)) {
        fprintf(stderr, "flightgen: give exactly one of --path NAME and --waypoints FILE\n");
        return 2;
    }
    if (c->path_name != NULL) {
        int k = flight_builtin_from_name(c->path_name);
        if (k < 0) {
            fprintf(stderr, "flightgen: unknown path '%s' (orbit, climb, dive, turn360, valley)\n",
                    c->path_name);
            return 2;
        }
        c->bp.kind = (flight_builtin_kind)k;
        c->bp.duration_s = c->duration_s;
    } else {
        if (c->centre_set || !isnan(c->bp.alt_m) || !isnan(c->bp.radius_m) ||
            !isnan(c->bp.speed_m_s)) {
            fprintf(stderr, "flightgen: --centre, --alt, --radius and --speed apply to --path "
                            "only\n");
            return 2;
        }
        c->opt.duration_s = c->duration_s;
    }
    return 0;
}

int main(int argc, char **argv)
{
    cli c;
    int rc = parse_args(argc, argv, &c);
    if (rc != 0) {
        return rc;
    }
    flight_path *path = malloc(sizeof *path);
    if (path == NULL) {
        fprintf(stderr, "flightgen: out of memory\n");
        return 1;
    }
    ft_error err;
    memset(&err, 0, sizeof err);
    ft_status s;
    if (c.waypoints != NULL) {
        char why[512];
        size_t len = 0u;
        char *text = read_file(c.waypoints, &len, why, sizeof why);
        if (text == NULL) {
            fprintf(stderr, "flightgen: %s\n", why);
            free(path);
            return 1;
        }
        s = flight_path_parse_waypoints(path, text, len, c.waypoints, &err);
        free(text);
    } else {
        s = flight_path_builtin(path, &c.bp, &err);
    }
    if (s != FT_OK) {
        fprintf(stderr, "flightgen: %s\n", err.text);
        free(path);
        return 1;
    }
    file_sink fs = {stdout};
    if (c.out != NULL) {
        fs.f = fopen(c.out, "wb");
        if (fs.f == NULL) {
            fprintf(stderr, "flightgen: %s: %s\n", c.out, strerror(errno));
            free(path);
            return 1;
        }
    }
    (void)setvbuf(fs.f, NULL, _IOFBF, FG_OUT_BUFFER_BYTES);
    flightgen_stats st;
    s = flightgen_run(path, &c.opt, write_line, &fs, &st, &err);
    int close_bad = (c.out != NULL) ? fclose(fs.f) != 0 : fflush(fs.f) != 0;
    if (s == FT_OK && close_bad) {
        s = ft_fail(&err, FT_ERR_IO, "%s: write failed", c.out != NULL ? c.out : "stdout");
    }
    if (s != FT_OK) {
        fprintf(stderr, "flightgen: %s\n", err.text);
        if (c.out != NULL) {
            (void)remove(c.out); /* no half log that looks complete */
        }
        free(path);
        return 1;
    }
    if (!c.quiet) {
        double dur_s = isnan(c.opt.duration_s) ? flight_path_duration_s(path) : c.opt.duration_s;
        fprintf(stderr,
                "flightgen: %s: %.3f s of flight, %llu lines (%.1f per second), %u waypoints, "
                "velocity %s; faults: %llu dropped, %llu stalled, %u NaN, %u bad DLC, "
                "%u duplicate, %llu velocity frames stopped, %llu latitudes jumped\n",
                path->name, dur_s, (unsigned long long)st.lines, (double)st.lines / dur_s,
                (unsigned)path->count, c.opt.velocity ? "sent" : "left out",
                (unsigned long long)st.dropped, (unsigned long long)st.stalled,
                (unsigned)st.nan_injected, (unsigned)st.bad_dlc_injected,
                (unsigned)st.duplicates_injected, (unsigned long long)st.velocity_stopped,
                (unsigned long long)st.gps_jumped);
    }
    free(path);
    return 0;
}
