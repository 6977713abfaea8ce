/* Texture and image units, named once for C (glBindTextureUnit, glBindImageTexture) and GLSL
 * (layout(binding = ...)): a pass and its shader cannot disagree on a number, and a reader can
 * tell which texture a unit holds. Included by ob_shared.h, so every *_params.h brings it.
 *
 * The numbers are per pass: each dispatch binds what its program reads, so unit 3 is the sample
 * multiplier in ssao and the depth MIP chain in gtao. Where one number means different things in
 * different passes, each meaning has its own name (with the same value), and the comment says who
 * uses it. A unit a pass does not read may hold anything; every sampler a program declares gets a
 * valid texture (a stand-in where the input is off), see the binds in src/methods/. */
#ifndef OB_UNITS_H
#define OB_UNITS_H

/* ---- texture units ------------------------------------------------------------------------- */

/* The AO grid's inputs, read by every method (ob_method_kit_use), the edge pass, the floor pass,
 * the sample pack and the depth split (deinterleave.glsl), the depth MIP pass; at full resolution
 * the same two are the G-buffer's for lighting, compose, downsample and upsample. */
#define OB_UNIT_DEPTH 0  /* R32F linear depth, 0 = no geometry */
#define OB_UNIT_NORMAL 1 /* RGBA16F view-space normal */

/* Every method: the 4x4 rotation tile (noise.glsl). */
#define OB_UNIT_NOISE 2

/* The random-kernel methods (ssao, crytek, hbao, alchemy; ob_method_kit_bind_multiplier). */
#define OB_UNIT_SAMPLE_MULTIPLIER 3 /* adaptive sampling's R32F multiplier (the noise tile when off) */
/* Their taps' far depth (taps.glsl), and ssdo's: one of the two, by program variant. */
#define OB_UNIT_DEPTH_LAYERS 4    /* OB_DEINTERLEAVED: the depth split into 16 layers (deinterleave.c) */
#define OB_UNIT_TAPS_DEPTH_MIPS 4 /* OB_TAPS_DEPTH_MIPS: the depth MIP chain (ob_taps_bind_mips) */

/* The slice methods (gtao, vbao, vbgi: slice_march.glsl, ob_slice_use). */
#define OB_UNIT_SLICE_DEPTH_MIPS 3 /* the depth MIP chain (the depth itself without one) */
#define OB_UNIT_SLICE_RADIANCE 4   /* vbgi: full-resolution direct radiance, the senders' light */
#define OB_UNIT_SLICE_MULTIPLIER 5 /* adaptive sampling's multiplier (the noise tile when off) */

/* ssdo and ssdo_merged (ssdo.glsl), and the sample pack (sample_pack.glsl) that runs before them. */
#define OB_UNIT_RADIANCE 3        /* full-resolution RGBA16F direct radiance */
#define OB_UNIT_SSDO_MULTIPLIER 5 /* adaptive sampling's multiplier (the noise tile when off) */

/* The slice methods and ssdo: the second depth layer (full resolution R32F, depth peeling; the
 * depth itself where the frame has none) and the packed samples (methods/packed.c). */
#define OB_UNIT_SECOND_DEPTH 6
#define OB_UNIT_PACKED_SAMPLES 10
/* The slice methods' `facets` (OB_MARCH_FACETS): the G-buffer's facet normals (full resolution
 * RG16F octahedral; the depth itself where the frame has none, and then no variant reads it). */
#define OB_UNIT_FACET_NORMAL 11
/* second_back.glsl: the peel pass's planes (RG16F octahedral, the second layer's own triangles),
 * beside the G-buffer's facet normals at OB_UNIT_FACET_NORMAL. */
#define OB_UNIT_SECOND_PLANE 12

/* ssdo's extra view (Belonogov 2018 §4.4): its linear depth, normal (its own view space) and direct
 * radiance; this frame's own where there is none. */
#define OB_UNIT_EXTRA_DEPTH 7
#define OB_UNIT_EXTRA_NORMAL 8
#define OB_UNIT_EXTRA_RADIANCE 9

/* The G-buffer raster (gbuffer.frag.glsl) and the depth peel (peel.frag.glsl). */
#define OB_UNIT_DIFFUSE_MAP 0 /* the material's sRGB texture */
#define OB_UNIT_FIRST_LAYER 1 /* peel: the G-buffer's linear depth, the layer to peel behind */
#define OB_UNIT_FIRST_FACING 2 /* peel: the G-buffer's normal, whose w is the first layer's part and facing */

/* Lighting (lighting.glsl) and compose (compose.glsl), beside OB_UNIT_DEPTH and OB_UNIT_NORMAL. */
#define OB_UNIT_ALBEDO 2
/* Compose's own. */
#define OB_UNIT_COMPOSE_AO 3          /* R32F visibility, or RGBA16F M (a directional method) */
#define OB_UNIT_COMPOSE_DIRECT 4      /* RGBA16F direct radiance */
#define OB_UNIT_COMPOSE_ENVIRONMENT 5 /* equirectangular radiance, for the background */
#define OB_UNIT_COMPOSE_BOUNCE 6      /* RGBA16F one-bounce indirect light */
#define OB_UNIT_COMPOSE_BENT_NORMAL 7 /* RGBA16F view-space bent normal */

/* Shadow maps (shadow.glsl, bound by passes/shadow.c for the lighting pass): 8 and up, clear of
 * every unit the lighting pass itself reads.
 * Texture arrays, so that one unit serves every map of a kind and the map is picked by a layer
 * coordinate (no dynamically-uniform sampler indexing, and VSM fits beside PCF in 3 units). */
#define OB_UNIT_SHADOW_MAPS_2D 8   /* sampler2DArrayShadow: directional + spot depth maps (hard, PCF) */
#define OB_UNIT_SHADOW_MAPS_CUBE 9 /* samplerCubeArrayShadow: point-light distance cube maps */
#define OB_UNIT_SHADOW_MOMENTS 10  /* sampler2DArray: directional + spot VSM moments (z, z^2) */

/* A pass with one input: bloom (radiance, then its own scratch), the luminance reduction, the
 * VSM blur (the depth maps, then its scratch), the host path's output pass. */
#define OB_UNIT_SOURCE 0

/* The AO filters (filters/kernel.c; copy, box4, gaussian, bilateral, bilateral_sep, geometry,
 * crease): the AO to filter, then the guides some of them read. */
#define OB_UNIT_FILTER_IN 0
#define OB_UNIT_FILTER_DEPTH 1
#define OB_UNIT_FILTER_NORMAL 2

/* The joint bilateral upsample (upsample.glsl), beside the full-resolution OB_UNIT_DEPTH and
 * OB_UNIT_NORMAL: the AO grid's guides and values. */
#define OB_UNIT_UPSAMPLE_LOW_DEPTH 2
#define OB_UNIT_UPSAMPLE_LOW_NORMAL 3
#define OB_UNIT_UPSAMPLE_LOW_AO 4
#define OB_UNIT_UPSAMPLE_LOW_SECOND 5 /* a second output (bounce), RGBA16F */

/* The tone map (tonemap.glsl). */
#define OB_UNIT_TONEMAP_RADIANCE 0
#define OB_UNIT_TONEMAP_BLOOM 1

/* Temporal accumulation (temporal.glsl, passes/temporal.c), all at the AO grid. */
#define OB_UNIT_TEMPORAL_CURRENT 0        /* this frame's value (r or rgb) */
#define OB_UNIT_TEMPORAL_HISTORY 1        /* the previous frame's accumulation */
#define OB_UNIT_TEMPORAL_DEPTH 2          /* this frame's linear depth (also the motion program's) */
#define OB_UNIT_TEMPORAL_NORMAL 3         /* this frame's view normal */
#define OB_UNIT_TEMPORAL_PREV_DEPTH 4     /* the previous frame's linear depth */
#define OB_UNIT_TEMPORAL_BOUNCE_CURRENT 5 /* OB_TEMPORAL_BOUNCE: this frame's bounce */
#define OB_UNIT_TEMPORAL_BOUNCE_HISTORY 6 /* OB_TEMPORAL_BOUNCE: the previous frame's bounce (rgb, age) */
#define OB_UNIT_TEMPORAL_HISTORY_AGE 7    /* R16F, the previous frame's (not with OB_TEMPORAL_RGB) */
#define OB_UNIT_TEMPORAL_PREV_NORMAL 8    /* R32UI packed, the previous frame's */
#define OB_UNIT_TEMPORAL_HOST_MOTION 9    /* OB_TEMPORAL_HOST_MOTION: a host's motion vectors, full resolution */

/* The debug views of ob_present (view.glsl, passes/view.c). */
#define OB_UNIT_VIEW_SOURCE 0     /* the view's texture */
#define OB_UNIT_VIEW_MULTIPLIER 1 /* the samples view under adaptive sampling */

/* The host path's input pass (host_input.glsl, passes/host.c): the engine's own textures, read
 * through a sampler object. Its output pass reads OB_UNIT_SOURCE and writes OB_IMAGE_UNIT_OUT. */
#define OB_UNIT_HOST_DEPTH 0        /* a depth buffer or linear depth */
#define OB_UNIT_HOST_NORMAL 1       /* normals (the depth where there are none) */
#define OB_UNIT_HOST_SECOND_DEPTH 2 /* a second layer's depth (the depth where there is none) */

/* One more than the highest texture unit any pass binds (10: OB_UNIT_PACKED_SAMPLES,
 * OB_UNIT_SHADOW_MOMENTS). The host path saves and restores the units it documents
 * (OB_HOST_TEXTURE_UNITS, obscura.h); src/gpu/pass.c checks that these are among them. A new
 * unit above the highest raises this. */
#define OB_TEXTURE_UNITS_USED 11

/* ---- image units -------------------------------------------------------------------------- */

/* Every compute pass's (first) output: a method's visibility, a filter's, lighting's radiance,
 * compose's HDR, the edge pass's multiplier, the depth split's layers (layered), fill's target,
 * the tone map's bytes, the VSM blur's moments, a debug view's display, the host output pass's
 * result. */
#define OB_IMAGE_UNIT_OUT 0
/* A method's second output: gtao's bent normal (OB_GTAO_BENT); vbgi's and ssdo's bounce. */
#define OB_IMAGE_UNIT_BENT_NORMAL 1
#define OB_IMAGE_UNIT_BOUNCE 1
/* The sample pack's RGBA32UI texels (sample_pack.glsl); 2 so that it stays clear of the
 * method's own outputs. */
#define OB_IMAGE_UNIT_PACKED 2
/* The depth MIP pass (depth_mips.glsl): level L of the chain is image OB_IMAGE_UNIT_DEPTH_MIPS + L,
 * OB_DEPTH_MIPS_LEVELS of them (ob_shared.h). */
#define OB_IMAGE_UNIT_DEPTH_MIPS 0
/* Downsample's second target (its first, the depth, is OB_IMAGE_UNIT_OUT), and upsample's. */
#define OB_IMAGE_UNIT_DOWNSAMPLE_NORMAL 1
#define OB_IMAGE_UNIT_UPSAMPLE_SECOND 1

/* The host path's input pass: the AO chain's inputs made from the engine's. */
#define OB_IMAGE_UNIT_HOST_DEPTH 0        /* R32F linear depth */
#define OB_IMAGE_UNIT_HOST_NORMAL 1       /* RGBA16F view normal */
#define OB_IMAGE_UNIT_HOST_SECOND_DEPTH 2 /* R32F second layer's linear depth */

/* Temporal accumulation (temporal.glsl, passes/temporal.c). */
#define OB_IMAGE_UNIT_TEMPORAL_RESULT 0              /* this frame's output (not with OB_TEMPORAL_NO_RESULT) */
#define OB_IMAGE_UNIT_TEMPORAL_NEXT_HISTORY 1        /* this frame's accumulation, the next one's history */
#define OB_IMAGE_UNIT_TEMPORAL_NEXT_AGE 2            /* R16F (not with OB_TEMPORAL_RGB) */
#define OB_IMAGE_UNIT_TEMPORAL_MOTION 2              /* the OB_TEMPORAL_MOTION program's RG16F offsets */
#define OB_IMAGE_UNIT_TEMPORAL_NEXT_DEPTH 3          /* R32F, for the next frame */
#define OB_IMAGE_UNIT_TEMPORAL_BOUNCE_RESULT 4       /* OB_TEMPORAL_BOUNCE */
#define OB_IMAGE_UNIT_TEMPORAL_BOUNCE_NEXT_HISTORY 5 /* OB_TEMPORAL_BOUNCE */
#define OB_IMAGE_UNIT_TEMPORAL_NEXT_NORMAL 6         /* R32UI packed, for the next frame */

/* One more than the highest image unit any pass binds (6: OB_IMAGE_UNIT_TEMPORAL_NEXT_NORMAL; the
 * depth MIP pass's reach 4). Checked like OB_TEXTURE_UNITS_USED, against OB_HOST_IMAGE_UNITS. */
#define OB_IMAGE_UNITS_USED 7

#endif
