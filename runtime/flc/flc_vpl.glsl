// A VPL as pass 1 writes it and pass 2 reads it (64 bytes): y_i and its
// level (-1: none), the triangle's normal and the VPL's tile, the
// radiosity of the front and of the back side.
struct Vpl { vec4 position_level; vec4 normal_tile; vec4 front; vec4 back; };
