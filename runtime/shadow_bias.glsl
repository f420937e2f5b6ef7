// Shadow-map bias: the receiver moves along its geometric normal by
// NORMAL_OFFSET texels of the map, and the compared depth by DEPTH_BIAS.
const float NORMAL_OFFSET = 1.5;
const float DEPTH_BIAS = 2e-5;
// The direct pass's (direct_light.frag.glsl, slope_offsets): offsets in
// texels scaled by the light's incidence, so that surfaces facing the
// light move little and contact shadows stay.
const float SLOPE_NORMAL_OFFSET = 0.25;
const float SLOPE_DEPTH_BIAS = 0.5;
