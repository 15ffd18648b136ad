// An include that compiles.
vec3 libColor() {
    return vec3(0.5);
}
