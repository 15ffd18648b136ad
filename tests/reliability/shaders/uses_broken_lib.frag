// A fragment shader that is fine itself but includes a file that does not compile (its line 3).
#include "broken_lib.glsl"

out vec4 o_color;

void main() {
    o_color = vec4(libBroken(), 1.0);
}
