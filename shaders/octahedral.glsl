/* Unit vectors in two numbers: the octahedral map (Meyer et al. 2010; Cigolle
 * et al. 2014, "A Survey of Efficient Representations for Independent Unit Vectors", §3.1). The
 * G-buffer's facet normal is stored so in an RG16F target (gbuffer.frag.glsl): 4 bytes a pixel,
 * half of RGBA16F's, within about 1e-3 rad of the vector. */
#ifndef OB_OCTAHEDRAL_GLSL
#define OB_OCTAHEDRAL_GLSL

vec2 ob_oct_sign(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 ob_oct_encode(vec3 n)
{
    vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    return n.z >= 0.0 ? p : (1.0 - abs(p.yx)) * ob_oct_sign(p);
}

vec3 ob_oct_decode(vec2 e)
{
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * ob_oct_sign(n.xy);
    return normalize(n);
}

#endif
