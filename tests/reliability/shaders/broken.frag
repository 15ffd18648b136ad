// A fragment shader that does not compile: line 7 assigns a vec3 to a float.
#include "valid_lib.glsl"

out vec4 o_color;

void main() {
    float wrong = vec3(1.0);
    o_color = vec4(libColor(), wrong);
}
