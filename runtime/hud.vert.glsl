// The HUD (hud.h), vertices: stb_easy_font's quads in font pixels (y down)
// from the text's top left corner `origin`, in pixels of the framebuffer
// from its top left, times `scale`; the box's quad comes first.
#version 450 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec4 colour;
uniform vec2 origin;
uniform float scale;
uniform vec2 size;
out vec4 v_colour;
void main() {
    vec2 pixel = origin + scale * position;
    gl_Position = vec4(2.0 * pixel.x / size.x - 1.0, 1.0 - 2.0 * pixel.y / size.y, 0.0, 1.0);
    v_colour = colour;
}
