// Forward Light Cuts with implicit visibility (flc_iv.h): FLC's visibility
// term (flc.h) from the pixel's element's depth map, its bins those of
// implicit_bins.h (Dong 2007, 4.2.2): face 2 axis + (d[axis] < 0), u and v
// the next two axes over |d[axis]|.
layout(std430, binding = 11) readonly buffer Depths { uint depths[]; };  // two a word
layout(std430, binding = 12) readonly buffer Centres { vec4 element_centres[]; };
layout(binding = 12) uniform usampler2D element_ids;  // 3 elements, 2 weights
uniform int bins_n;
uniform int bin_filter;          // 0 bilinear, 1 nearest
uniform float bias_bin;          // GB_FLC_IV_BIAS_BIN / N
uniform float bias_element;      // GB_FLC_IV_BIAS_ELEMENT x element size
uniform float depth_unit;        // the scene's diagonal / GB_FLC_IV_DEPTH_FAR

// The depth of bin in element e's map, or infinity for an empty bin.
float bin_depth(uint e, uint bin) {
    uint k = e * uint(6 * bins_n * bins_n) + bin;
    uint depth = (depths[k >> 1u] >> (16u * (k & 1u))) & 0xffffu;
    return depth == 0xffffu ? 1.0 / 0.0 : float(depth) * depth_unit;
}

float seen(uint e, int face, ivec2 cell, float r) {
    cell = clamp(cell, ivec2(0), ivec2(bins_n - 1));
    uint bin = uint((face * bins_n + cell.y) * bins_n + cell.x);
    return r <= bin_depth(e, bin) * (1.0 + bias_bin) + bias_element ? 1.0 : 0.0;
}

// The VPL at y seen from element e's centre, through its bins.
float element_visibility(uint e, vec3 y) {
    vec3 d = y - element_centres[e].xyz;
    float r = length(d);
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (abs(d[a]) > abs(d[axis]))
            axis = a;
    float major = abs(d[axis]);
    if (!(major > 0.0))
        return 1.0;
    int face = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
    vec2 t = vec2(d[(axis + 1) % 3], d[(axis + 2) % 3]) / major;    // in [-1, 1]
    vec2 s = 0.5 * (t + 1.0) * float(bins_n);                       // bins along u, v
    if (bin_filter == 1)
        return seen(e, face, ivec2(floor(s)), r);
    vec2 c = s - 0.5;
    ivec2 i = ivec2(floor(c));
    vec2 f = c - vec2(i);
    return mix(mix(seen(e, face, i, r), seen(e, face, i + ivec2(1, 0), r), f.x),
               mix(seen(e, face, i + ivec2(0, 1), r), seen(e, face, i + ivec2(1, 1), r), f.x),
               f.y);
}

// The elements of the pixel's triangle weighed by its barycentric
// coordinates (flc_iv_elements), as implicit visibility interpolates its
// display: the edges of the finer triangles and of the elements do not show.
// An element shared by two corners is tested once, with both weights.
float flc_visibility(ivec2 pixel, vec3 x, vec3 y) {
    uvec4 texel = texelFetch(element_ids, pixel, 0);
    if (texel.x == 0xffffffffu)
        return 1.0;
    vec2 b = unpackUnorm2x16(texel.w);
    vec3 w = vec3(max(0.0, 1.0 - b.x - b.y), b);
    if (texel.y == texel.x) { w.x += w.y; w.y = 0.0; }
    if (texel.z == texel.x) { w.x += w.z; w.z = 0.0; }
    else if (texel.z == texel.y) { w.y += w.z; w.z = 0.0; }
    float v = w.x > 0.0 ? w.x * element_visibility(texel.x, y) : 0.0;
    if (w.y > 0.0)
        v += w.y * element_visibility(texel.y, y);
    if (w.z > 0.0)
        v += w.z * element_visibility(texel.z, y);
    return v / max(w.x + w.y + w.z, 1e-6);
}
