// Shadow-map bias: the receiver moves along its geometric normal by
// NORMAL_OFFSET texels of the map, and the compared depth by DEPTH_BIAS.
const float NORMAL_OFFSET = 1.5;
const float DEPTH_BIAS = 2e-5;
