/* program.h - the GL programs terrain is drawn with: compiling and linking
 * embedded GLSL ES (a prelude per API, then compile-time defines, then the
 * body), and locating a program's uniforms once, at init.
 *
 * A terrain program has the uniforms every method's vertex shader shares
 * (heights, grid, camera, curvature), those of shaders/shade.glsl (colour),
 * and the method's own: each method lists its uniform names
 * (ft_method_ops.uniforms) and reads their locations from method_u in its
 * own order, so nothing here knows a method. The renderer builds its
 * programs through this module, and so do methods that draw passes of
 * their own (pgrid), without depending on the renderer. */
#ifndef FT_PROGRAM_H
#define FT_PROGRAM_H

#include <stdint.h>

#include "core/ft_status.h"
#include "core/scene.h"
#include "gpu/gl_api.h"
#include "gpu/shade.h"
#include "terrain/terrain.h"

/* Attribute slots of every program: 0 the template vertex (name per
 * program); 1 and 2 only for a program that names them (the bench's oracle). */
#define FT_ATTRIB_UV 0u
#define FT_ATTRIB_EXTRA1 1u
#define FT_ATTRIB_EXTRA2 2u

/* The unmeasured-cell texture's unit: above every unit a method uses (0-7),
 * so it stays bound from init on. */
#define FT_TEX_UNIT_VOID 8
/* pgrid's ray caster: its max atlas and its tile texture (units of their own,
 * bound at init and left there) */
#define FT_TEX_UNIT_RC_MAX 9
#define FT_TEX_UNIT_RC_TILES 10

/* The colour uniforms of shaders/shade.glsl (-1 where a program lacks them:
 * position passes; a part's outside its variant, and always in a build
 * without the part). */
typedef struct ft_shade_locs {
    GLint ramp_h, ramp_rgb, sun, light;
    GLint band_edge, band_rgba, aircraft_alt;
    GLint haze; /* FT_SHADE_HAZE variant */
    GLint void_cells, void_map, void_size; /* FT_SHADE_VOID variant */
    GLint grid;                            /* FT_SHADE_GRID variant */
} ft_shade_locs;

/* A method's uniforms: rows of names, each taking `count` consecutive
 * locations (count > 1: an array, located element by element as
 * "name[0]" .. "name[count-1]", which GLSL ES 1.00 needs). A method writes
 * the list with FT_UNIFORM_ROW and its index enum with FT_UNIFORM_ENUM from
 * one X-list X(id, "name", count), so the two cannot disagree. */
typedef struct ft_uniform_name {
    const char *name;
    uint32_t count;
} ft_uniform_name;
typedef struct ft_uniform_list {
    const ft_uniform_name *rows;
    uint32_t row_count;
} ft_uniform_list;
#define FT_UNIFORM_ROW(id, name, count) {name, count},
#define FT_UNIFORM_ENUM(id, name, count) id, id##_LAST_ = id + (count) - 1,
#define FT_METHOD_UNIFORMS_MAX 96u

typedef struct ft_terrain_program {
    GLuint program;
    GLint u_heights, u_grid_size, u_patch_origin, u_patch_stride, u_cell_m;
    GLint u_origin_rel_eye_m, u_view_proj, u_pack, u_clamp_box;
    GLint u_earth_drop_per_m2; /* curvature (shaders/curvature.glsl) */
    ft_shade_locs shade;       /* shade.ramp_h < 0: a position pass */
    /* The method's uniforms, in the order of its list (-1: not in this
     * program, which GL ignores when set). */
    const ft_uniform_list *method_uniforms;
    GLint method_u[FT_METHOD_UNIFORMS_MAX];
    /* The same pass compiled for tiles whose every vertex is on a sample
     * (ft_method_vertex_defines_coarse), or NULL: the bintree draws its
     * coarse tiles with it, so they run none of the sub-sample code. */
    const struct ft_terrain_program *coarse;
    /* The colour state in force (palette, bands, aircraft altitude), for
     * passes a method draws with programs of its own (pgrid's ray cast). */
    const ft_shade_state *shade_state;
} ft_terrain_program;

/* Heights and (gpu.pyramid_textures = 1) the pyramids as vertex textures,
 * one single-channel texture per array, all in the same format: R32F (ES3),
 * LUMINANCE/FLOAT (ES2 + OES_texture_float) or RGBA8 packed 24-bit fixed
 * point over [pack_min_m, pack_min_m + pack_range_m]. NEAREST sampling. */
typedef struct ft_gpu_terrain {
    ft_height_format format; /* resolved: FLOAT or PACKED */
    float pack_min_m, pack_range_m;
    GLuint heights_tex;
    uint32_t pyramid_levels_avg;    /* textures in avg_tex (level 0 = heights_tex) */
    uint32_t pyramid_levels_minmax; /* textures in min_tex / max_tex */
    GLuint avg_tex[FT_PYRAMID_LEVELS_MAX];
    GLuint min_tex[FT_PYRAMID_LEVELS_MAX];
    GLuint max_tex[FT_PYRAMID_LEVELS_MAX];
    uint64_t bytes;
} ft_gpu_terrain;

/* Compiles and links embedded shaders vert + frag (frag after the lines
 * frag_defines, NULL: none) with attribute 0 bound to attr0. */
ft_status ft_program_link(const ft_gl *gl, const char *vert_name, const char *frag_name,
                          const char *frag_defines, const char *attr0, GLuint *out,
                          ft_error *err);

/* What a terrain program is built from. */
typedef struct ft_terrain_program_desc {
    const char *vert_name, *vert_defines; /* embedded name; lines before its body or NULL */
    const char *frag_name, *frag_defines;
    const char *const *attribs; /* names for slots 0, 1, 2; NULL: a_uv only */
    const ft_uniform_list *method_uniforms; /* NULL: none */
} ft_terrain_program_desc;

/* Links the program, locates its uniforms and sets those that never change
 * for the terrain (grid, cell size, height packing, curvature). */
ft_status ft_terrain_program_build(const ft_gl *gl, const ft_terrain *t, const ft_gpu_terrain *gt,
                                   const ft_terrain_program_desc *d, ft_terrain_program *p,
                                   ft_error *err);

/* After a relink of p->program (which may move uniforms and resets their
 * values): locates them again and sets the unchanging ones. */
void ft_terrain_program_relocate(const ft_gl *gl, const ft_terrain *t, const ft_gpu_terrain *gt,
                                 ft_terrain_program *p);

/* The colour variant a scene needs, written into buf and returned: one
 * "#define FT_SHADE_<PART> 1\n" line per part it uses: RELATIVE (relative
 * colouring), HAZE, GRID (ground grid), VOID when the terrain has
 * void-filled samples (the marking is not optional there), else "" (the
 * code of a part the scene does not use is not compiled at all). */
#define FT_SHADE_DEFINES_MAX 160u
const char *ft_program_shade_defines(const ft_scene *s, const ft_terrain *t,
                                     char buf[FT_SHADE_DEFINES_MAX]);
/* The colour parts this build has (built = 1) or left out (built = 0), as
 * their define names ("FT_SHADE_RELATIVE FT_SHADE_GRID ..."; "none"),
 * written into buf and returned. Unmeasured-terrain marking (FT_SHADE_VOID)
 * is in every build. */
#define FT_SHADE_PARTS_MAX 96u
const char *ft_program_shade_parts(int built, char buf[FT_SHADE_PARTS_MAX]);
/* shade.glsl's uniform locations of a program, and their values for a
 * colour state (palette ramp, sun, light; bands and aircraft altitude in the
 * relative variant). The program must be current for the values. */
void ft_program_shade_locate(const ft_gl *gl, GLuint prog, ft_shade_locs *u);
void ft_program_shade_uniforms(const ft_gl *gl, const ft_shade_locs *u, const ft_shade_state *st);

#endif
