#version 300 es
/* GLSL ES 3.00 (GLES 3): the few spellings that differ from 1.00. */
#define FT_ES3 1
#define FT_IN_VS in
#define FT_OUT_VS out
#define FT_IN_FS in
precision highp float;
/* Samplers default to lowp in the vertex stage; Mesa then returns float
 * heights at half precision (2059 m read back as 2058 m). */
precision highp sampler2D;
