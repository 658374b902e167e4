/* overlay.h - the failure annunciation drawn when the pose input is stale or
 * invalid: a red cross over the whole view (two thick diagonal bars, corner
 * to corner) and a short reason ("NO HEADING 250 MS") in red on a black box,
 * centred near the top.
 *
 * All memory is inside ft_overlay (the CPU vertex array) and one GPU vertex
 * buffer of fixed capacity, both made in ft_overlay_init; drawing takes no
 * memory. Every loop is bounded by FT_OVERLAY_TEXT_MAX and the glyph size.
 *
 * Geometry (pixels, origin top-left, y down; W x H the view):
 *   cross: bar thickness T = max(2, round(0.03 * min(W, H))), pure red.
 *   text:  glyph pixel S = max(1, H / 240) px, lowered (not below 1) until
 *          the box fits the width; the box pads the text by 2 S on every side
 *          and starts at y = max(2 S, H / 16), centred in x. Text longer than
 *          FT_OVERLAY_TEXT_MAX characters, or wider than the view at S = 1,
 *          is cut and ends in "...". An empty (or NULL) reason draws the cross
 *          only. Lower case shows as upper case; characters outside the font
 *          (src/gpu/font5x7.h) show as filled boxes.
 * Draw order: cross, black box, text, so the text stays readable where the
 * bars pass behind the box. Every vertex is on the whole-pixel grid, so each
 * glyph pixel covers exactly S x S framebuffer pixels. */
#ifndef FT_OVERLAY_H
#define FT_OVERLAY_H

#include <stdint.h>

#include "core/ft_status.h"
#include "gpu/font5x7.h"
#include "gpu/gl_api.h"

#define FT_OVERLAY_TEXT_MAX 96u /* characters shown at most, "..." included */

/* A 5-bit glyph row has at most 3 runs of set pixels; each run is one quad. */
#define FT_OVERLAY_QUADS_PER_GLYPH_MAX (FT_FONT5X7_ROWS * 3u)
#define FT_OVERLAY_VERTICES_PER_QUAD 6u /* two triangles, no index buffer */
#define FT_OVERLAY_CROSS_QUADS 2u
#define FT_OVERLAY_BOX_QUADS 1u
#define FT_OVERLAY_VERTICES_MAX                                                      \
    (FT_OVERLAY_VERTICES_PER_QUAD *                                                  \
     (FT_OVERLAY_CROSS_QUADS + FT_OVERLAY_BOX_QUADS +                                \
      FT_OVERLAY_TEXT_MAX * FT_OVERLAY_QUADS_PER_GLYPH_MAX))
/* Vertices are int16 pixel coordinates: views up to this size per side. */
#define FT_OVERLAY_VIEW_MAX_PX 8192u
/* One line across the view (the conformal horizon): a quad after them; none
 * in a build without the horizon. */
#if FT_WITH_HORIZON
#define FT_OVERLAY_LINE_VERTICES FT_OVERLAY_VERTICES_PER_QUAD
#else
#define FT_OVERLAY_LINE_VERTICES 0u
#endif
/* Bytes of the GPU vertex buffer (for the scene's GPU budget). */
#define FT_OVERLAY_GPU_BYTES                                                         \
    ((uint64_t)(FT_OVERLAY_VERTICES_MAX + FT_OVERLAY_LINE_VERTICES) * 2u * sizeof(int16_t))

/* Where the annunciation goes for one view and reason (pure CPU). */
typedef struct ft_overlay_layout {
    uint32_t thickness_px;  /* cross bar thickness T */
    uint32_t scale_px;      /* glyph pixel size S (0 when no text) */
    uint32_t chars;         /* characters shown (0: no text, no box) */
    int truncated;          /* the reason was cut and ends in "..." */
    int32_t box_x, box_y;   /* black box, top-left corner in pixels */
    uint32_t box_w, box_h;  /* 0 x 0 when no text */
    int32_t text_x, text_y; /* top-left corner of the first glyph */
    char text[FT_OVERLAY_TEXT_MAX + 1u]; /* what is shown, NUL-terminated */
} ft_overlay_layout;

typedef struct ft_overlay {
    GLuint program, vbo; /* program 0 until init succeeded */
    GLuint vao;          /* own VAO when the context has them (GLES 3, core) */
    GLint u_px_to_ndc, u_color;
    /* The vertices in the buffer were built for this view and layout; the
     * next draw with the same view and text skips the rebuild and upload. */
    int cache_valid;
    uint32_t cache_w, cache_h;
    ft_overlay_layout layout;
    uint32_t cross_vertices, box_vertices, text_vertices;
    int16_t verts[FT_OVERLAY_VERTICES_MAX][2];
#if FT_WITH_HORIZON
    int16_t line_verts[FT_OVERLAY_LINE_VERTICES][2];
#endif
} ft_overlay;

/* Computes the layout for a width_px x height_px view (both 1 ..
 * FT_OVERLAY_VIEW_MAX_PX) and reason (NULL = ""); reads at most
 * FT_OVERLAY_TEXT_MAX + 1 characters of reason. */
ft_status ft_overlay_layout_for(uint32_t width_px, uint32_t height_px, const char *reason,
                                ft_overlay_layout *out, ft_error *err);

/* Compiles the program and creates the vertex buffer (and a VAO on GLES 3 /
 * core). The context must be current. Leaves the VAO and ARRAY_BUFFER
 * bindings as it found them. */
ft_status ft_overlay_init(ft_overlay *ov, const ft_gl *gl, ft_error *err);

/* Draws the cross and the reason into the currently bound framebuffer (the
 * caller binds it), over the viewport (0, 0, width_px, height_px), which
 * must be the framebuffer's size. Depth, stencil, scissor, blend and face
 * culling are disabled and left disabled; the viewport, the program and the
 * ARRAY_BUFFER binding are changed (the renderer sets all of them every
 * frame). The bound VAO is restored; on GLES 2 (no VAO) attribute 0 is left
 * enabled, pointing into the overlay's buffer. */
ft_status ft_overlay_draw_annunciation(ft_overlay *ov, const ft_gl *gl, uint32_t width_px,
                                       uint32_t height_px, const char *reason, ft_error *err);

#if FT_WITH_HORIZON
/* Draws a line of thickness_px through p0 and p1 (pixels, origin top-left,
 * y down; two points on the view's border, ft_camera_horizon_px) in colour
 * rgba, with the same state rules as ft_overlay_draw_annunciation. Its
 * corners are rounded to whole pixels like every overlay vertex: the line's
 * centre is within half a pixel of the exact one. */
ft_status ft_overlay_draw_line(ft_overlay *ov, const ft_gl *gl, uint32_t width_px,
                               uint32_t height_px, const double p0[2], const double p1[2],
                               double thickness_px, const float rgba[4], ft_error *err);
#endif

/* Deletes the GL objects (context current); safe on a zeroed or failed ov. */
void ft_overlay_shutdown(ft_overlay *ov, const ft_gl *gl);

#endif
