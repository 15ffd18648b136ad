// Overlay lines: a flat colour, written as it is into the output image (sRGB-encoded RGBA8).
flat in vec3 v_color;

layout(location = 0) out vec4 o_color;

void main() {
    o_color = vec4(v_color, 1.0);
}
