// An include that does not compile: line 3 calls a function that does not exist.
vec3 libBroken() {
    return noSuchFunction(1.0);
}
