/* test_render_compare.c - the same scene through different backends and
 * height formats must give the same picture.
 *
 * usage: test_render_compare W H REFERENCE.rgba OTHER.rgba [...]
 * Tolerance (stated): at most 0.5% of pixels may differ by more than 8/255 in
 * any channel, and the mean absolute difference must stay below 0.5/255.
 * On this Mesa build EGL-GLES3 and OSMesa are bit-identical; the GLSL ES 1.00
 * variant and packed heights may round differently at a few pixels. */
#include <stdio.h>
#include <stdlib.h>

#include "test_util.h"

static unsigned char *load(const char *path, size_t bytes)
{
    unsigned char *buf = malloc(bytes);
    FILE *f = fopen(path, "rb");
    REQUIRE(buf != NULL);
    if (f == NULL) {
        fprintf(stderr, "cannot open %s (did its render test run?)\n", path);
        exit(1);
    }
    REQUIRE(fread(buf, 1, bytes, f) == bytes);
    fclose(f);
    return buf;
}

int main(int argc, char **argv)
{
    REQUIRE(argc >= 5);
    size_t w = strtoul(argv[1], NULL, 10), h = strtoul(argv[2], NULL, 10);
    size_t bytes = w * h * 4u;
    unsigned char *ref = load(argv[3], bytes);
    for (int k = 4; k < argc; ++k) {
        unsigned char *img = load(argv[k], bytes);
        size_t over = 0, identical = 0;
        double sum = 0.0;
        for (size_t i = 0; i < w * h; ++i) {
            int maxd = 0;
            for (int c = 0; c < 4; ++c) {
                int d = abs((int)img[i * 4 + c] - (int)ref[i * 4 + c]);
                sum += d;
                if (d > maxd) maxd = d;
            }
            over += (maxd > 8);
            identical += (maxd == 0);
        }
        double mean = sum / (double)bytes;
        double share = (double)over / (double)(w * h);
        printf("%s vs %s: %.3f%% pixels differ by > 8/255, %.2f%% identical, mean |d| %.4f/255\n",
               argv[k], argv[3], 100.0 * share, 100.0 * identical / (double)(w * h), mean);
        CHECK(share <= 0.005);
        CHECK(mean < 0.5);
        free(img);
    }
    free(ref);
    return ft_test_result("test_render_compare");
}
