/* The taps of a method's deinterleaved program (OB_DEINTERLEAVED; issue 18, Bavoil 2014): the
 * dispatch's z is the class c of the 4x4 noise tile (0..15, pixel offset (c & 3, c >> 2)), its xy
 * the class's texel t, AO pixel 4 t + offset. A far tap reads the nearest pixel of its own class
 * (deinterleave.glsl's layer c): up to 2 pixels from where the plain program reads, every one of a
 * class's far taps in one compact layer. A tap less than OB_DEINTERLEAVED_NEAR pixels from the
 * invocation's pixel on both axes reads its own pixel of the full texture, as the plain program
 * does: snapped, the taps within 2 pixels would all land on the invocation's own pixel and see no
 * occluder (the densest part of ssao's kernel, hbao's first step), and every method read lighter
 * (16 views at 320x240, before this: ssao's mean RMSE +11 %, hbao's +8 %). Near taps need no
 * deinterleaving: a group's near taps are its own neighbourhood. A warp's lanes share one rotation,
 * so they take the near or far branch together. A method reads the tap's position at the pixel it
 * read (as the plain programs do at theirs), so a plane stays a plane: the snap moves where a tap
 * samples, not what a sample means. The rotation and jitter of the 4x4 tile are a class's own
 * already (noise.glsl's pix % 4), so a deinterleaved program's noise is the plain one's.
 * Without OB_DEINTERLEAVED the functions are the plain reads, so a method writes its taps once. */
#ifndef OB_DEINTERLEAVED_TAPS_GLSL
#define OB_DEINTERLEAVED_TAPS_GLSL

#ifdef OB_DEINTERLEAVED
layout(binding = 4) uniform sampler2DArray depth_layers; /* deinterleave.glsl's, R32F */

/* This invocation's class: its pixel offset in the 4x4 tile. */
ivec2 ob_invocation_class() { return ivec2(int(gl_GlobalInvocationID.z) & 3, int(gl_GlobalInvocationID.z) >> 2); }

/* This invocation's AO pixel. */
ivec2 ob_invocation_pixel() { return 4 * ivec2(gl_GlobalInvocationID.xy) + ob_invocation_class(); }

#define OB_DEINTERLEAVED_NEAR 4 /* one class period: nearer taps read their own pixel */

/* The pixel a tap aimed at pixel q (inside the image of `size`) reads: q itself when near,
 * else the nearest pixel of this invocation's class, clamped to the class's pixels inside the
 * image. */
ivec2 ob_tap_pixel(ivec2 q, ivec2 size)
{
    ivec2 c = ob_invocation_class();
    if (all(lessThan(abs(q - ob_invocation_pixel()), ivec2(OB_DEINTERLEAVED_NEAR)))) return q;
    ivec2 t = clamp((q - c + 2) >> 2, ivec2(0), (size - 1 - c) >> 2);
    return 4 * t + c;
}

/* The linear depth at a pixel ob_tap_pixel returned: from the class's layer when it is one of the
 * class's pixels, else (a near tap) from the full texture. */
float ob_tap_depth(sampler2D depth, ivec2 q)
{
    if (all(equal(q & 3, ob_invocation_class()))) return texelFetch(depth_layers, ivec3(q >> 2, int(gl_GlobalInvocationID.z)), 0).r;
    return texelFetch(depth, q, 0).r;
}
#else
ivec2 ob_invocation_pixel() { return ivec2(gl_GlobalInvocationID.xy); }
ivec2 ob_tap_pixel(ivec2 q, ivec2 size) { return q; }
float ob_tap_depth(sampler2D depth, ivec2 q) { return texelFetch(depth, q, 0).r; }
#endif

#endif
