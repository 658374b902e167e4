/* picture_compare.c - compares two PNG pictures of the same size: the
 * share of pixels where any channel differs by more than TOL levels must
 * not exceed MAX_SHARE. Frames are bit-identical on one Mesa/LLVM build
 * (../shared/PLATFORM-NOTES.md); the tolerance is for another Mesa.
 * usage: picture_compare A.png B.png TOL MAX_SHARE
 * Exit 0 within tolerance, 1 outside it, 2 on a read or usage error. */
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static unsigned char *read_rgba(const char *path, png_image *img)
{
    memset(img, 0, sizeof *img);
    img->version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(img, path)) {
        fprintf(stderr, "picture_compare: %s: %s\n", path, img->message);
        return NULL;
    }
    img->format = PNG_FORMAT_RGBA;
    unsigned char *buf = malloc(PNG_IMAGE_SIZE(*img));
    if (buf == NULL || !png_image_finish_read(img, NULL, buf, 0, NULL)) {
        fprintf(stderr, "picture_compare: %s: %s\n", path, buf ? img->message : "no memory");
        free(buf);
        return NULL;
    }
    return buf;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: picture_compare A.png B.png TOL MAX_SHARE\n");
        return 2;
    }
    const int tol = atoi(argv[3]);
    const double max_share = atof(argv[4]);
    png_image ia, ib;
    unsigned char *a = read_rgba(argv[1], &ia);
    unsigned char *b = read_rgba(argv[2], &ib);
    int rc = 2;
    if (a != NULL && b != NULL) {
        if (ia.width != ib.width || ia.height != ib.height) {
            fprintf(stderr, "picture_compare: %ux%u against %ux%u\n", ia.width, ia.height,
                    ib.width, ib.height);
            rc = 1;
        } else {
            const size_t n = (size_t)ia.width * ia.height;
            size_t off = 0, exact = 0;
            int worst = 0;
            for (size_t i = 0; i < n; ++i) {
                int m = 0;
                for (int c = 0; c < 3; ++c) {
                    const int d = abs((int)a[4 * i + c] - (int)b[4 * i + c]);
                    m = d > m ? d : m;
                }
                off += (size_t)(m > tol);
                exact += (size_t)(m == 0);
                worst = m > worst ? m : worst;
            }
            const double share = (double)off / (double)n;
            printf("%s: %zu of %zu pixels identical, %zu (%.4f%%) differ by more than %d "
                   "levels (largest difference %d); allowed %.4f%%\n",
                   argv[2], exact, n, off, 100.0 * share, tol, worst, 100.0 * max_share);
            rc = share <= max_share ? 0 : 1;
        }
    }
    free(a);
    free(b);
    return rc;
}
