/* compare-image.c - compares two RGB images (binary PPM as QMP `screendump`
 * writes it, or PNG as fixterrain writes it; alpha is ignored) pixel by
 * pixel and says whether they match within a tolerance.
 *   compare-image A B [--level N] [--max-fraction F] [--max-mean M] [--expect-differ]
 * A pixel "differs" when any channel differs by more than N levels (default
 * 2). The images match when they have the same size, at most fraction F of
 * the pixels differ (default 0.001) and the mean absolute channel difference
 * is at most M (default 0.5 levels). --expect-differ inverts the verdict (a
 * deliberately wrong frame must not match). Prints one line of numbers.
 * Exit: 0 verdict as wanted, 1 not, 2 usage or read error. */
#define _POSIX_C_SOURCE 200809L
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct image {
    uint32_t w, h;
    uint8_t *rgb; /* w * h * 3 */
} image;

static int ppm_token(FILE *f, unsigned long *out)
{
    int c = fgetc(f);
    for (;;) { /* whitespace and # comments */
        while (c == ' ' || c == '\t' || c == '\n' || c == '\r') c = fgetc(f);
        if (c != '#') break;
        while (c != '\n' && c != EOF) c = fgetc(f);
    }
    if (c < '0' || c > '9') return 0;
    unsigned long v = 0;
    while (c >= '0' && c <= '9' && v < 100000000ul) {
        v = v * 10u + (unsigned long)(c - '0');
        c = fgetc(f);
    }
    *out = v; /* c (one whitespace byte) is consumed, as P6 wants */
    return 1;
}

static int read_ppm(const char *path, image *im)
{
    FILE *f = fopen(path, "rb");
    unsigned long w = 0, h = 0, maxv = 0;
    if (f == NULL) {
        perror(path);
        return 0;
    }
    if (fgetc(f) != 'P' || fgetc(f) != '6' || !ppm_token(f, &w) || !ppm_token(f, &h) ||
        !ppm_token(f, &maxv) || maxv != 255u || w == 0u || h == 0u || w > 16384u ||
        h > 16384u) {
        fprintf(stderr, "%s: not an 8-bit binary PPM (P6)\n", path);
        fclose(f);
        return 0;
    }
    im->w = (uint32_t)w;
    im->h = (uint32_t)h;
    im->rgb = malloc((size_t)w * h * 3u);
    if (im->rgb == NULL || fread(im->rgb, 3u, (size_t)w * h, f) != (size_t)w * h) {
        fprintf(stderr, "%s: truncated PPM\n", path);
        fclose(f);
        return 0;
    }
    fclose(f);
    return 1;
}

static int read_png(const char *path, image *im)
{
    png_image p;
    memset(&p, 0, sizeof p);
    p.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&p, path)) {
        fprintf(stderr, "%s: %s\n", path, p.message);
        return 0;
    }
    p.format = PNG_FORMAT_RGB;
    im->w = p.width;
    im->h = p.height;
    im->rgb = malloc(PNG_IMAGE_SIZE(p));
    if (im->rgb == NULL || !png_image_finish_read(&p, NULL, im->rgb, 0, NULL)) {
        fprintf(stderr, "%s: %s\n", path, p.message);
        png_image_free(&p);
        return 0;
    }
    return 1;
}

static int read_image(const char *path, image *im)
{
    FILE *f = fopen(path, "rb");
    unsigned char magic[2] = {0, 0};
    if (f == NULL) {
        perror(path);
        return 0;
    }
    size_t n = fread(magic, 1, 2, f);
    fclose(f);
    if (n == 2 && magic[0] == 'P' && magic[1] == '6') {
        return read_ppm(path, im);
    }
    return read_png(path, im);
}

int main(int argc, char **argv)
{
    unsigned level = 2;
    double max_fraction = 0.001, max_mean = 0.5;
    int expect_differ = 0;
    if (argc < 3) {
        fprintf(stderr, "usage: compare-image A B [--level N] [--max-fraction F] "
                        "[--max-mean M] [--expect-differ]\n");
        return 2;
    }
    for (int i = 3; i < argc; ++i) {
        if (strcmp(argv[i], "--expect-differ") == 0) {
            expect_differ = 1;
        } else if (i + 1 < argc && strcmp(argv[i], "--level") == 0) {
            level = (unsigned)strtoul(argv[++i], NULL, 10);
        } else if (i + 1 < argc && strcmp(argv[i], "--max-fraction") == 0) {
            max_fraction = strtod(argv[++i], NULL);
        } else if (i + 1 < argc && strcmp(argv[i], "--max-mean") == 0) {
            max_mean = strtod(argv[++i], NULL);
        } else {
            fprintf(stderr, "compare-image: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    image a = {0, 0, NULL}, b = {0, 0, NULL};
    if (!read_image(argv[1], &a) || !read_image(argv[2], &b)) {
        return 2;
    }
    int match;
    if (a.w != b.w || a.h != b.h) {
        printf("compare-image: %s is %ux%u, %s is %ux%u: sizes differ\n", argv[1], a.w, a.h,
               argv[2], b.w, b.h);
        match = 0;
    } else {
        const size_t px = (size_t)a.w * a.h;
        size_t differ = 0, exact = 0;
        unsigned max_d = 0;
        double sum = 0.0;
        for (size_t i = 0; i < px; ++i) {
            unsigned pmax = 0;
            for (int c = 0; c < 3; ++c) {
                int d = (int)a.rgb[i * 3u + (size_t)c] - (int)b.rgb[i * 3u + (size_t)c];
                unsigned ad = (unsigned)(d < 0 ? -d : d);
                sum += ad;
                if (ad > pmax) pmax = ad;
            }
            if (pmax > max_d) max_d = pmax;
            differ += (pmax > level);
            exact += (pmax == 0u);
        }
        const double fraction = (double)differ / (double)px;
        const double mean = sum / (double)(px * 3u);
        match = fraction <= max_fraction && mean <= max_mean;
        printf("compare-image: %s vs %s: %ux%u, identical pixels %.4f%%, max channel diff %u, "
               "mean abs diff %.4f levels, pixels over %u levels %zu (%.4f%%; allowed %.4f%%, "
               "mean <= %.2f): %s\n",
               argv[1], argv[2], a.w, a.h, 100.0 * (double)exact / (double)px, max_d, mean,
               level, differ, 100.0 * fraction, 100.0 * max_fraction, max_mean,
               match ? "MATCH" : "DIFFERENT");
    }
    free(a.rgb);
    free(b.rgb);
    return (match != expect_differ) ? 0 : 1;
}
