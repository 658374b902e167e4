#version 100
/* GLSL ES 1.00 (GLES 2): the few spellings that differ from 3.00. */
#define FT_ES3 0
#define FT_IN_VS attribute
#define FT_OUT_VS varying
#define FT_IN_FS varying
precision highp float;
/* Samplers default to lowp in the vertex stage; Mesa then returns float
 * heights at half precision (2059 m read back as 2058 m). */
precision highp sampler2D;
