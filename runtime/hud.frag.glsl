// The HUD (hud.h), fragments: the text's or the box's colour, alpha blended.
#version 450 core
in vec4 v_colour;
out vec4 colour;
void main() {
    colour = v_colour;
}
