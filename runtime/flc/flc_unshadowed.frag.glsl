// FLC's own visibility term (flc.h): Laurent 2016 ignores what lies between
// a VPL and the receiver it lights (its Fig. 12, no indirect shadows).
float flc_visibility(ivec2 pixel, vec3 x, vec3 y) { return 1.0; }
