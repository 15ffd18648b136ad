// Whether a group of the draw order needs the test by place (GpuCulling): cull_groups.comp asks it of
// every group, cull.comp of its own group where it tests every group (u_every). A group whose decals,
// all drawable by the projector, lie on at most kGroupBoxes objects needs none when each of its boxes
// (GroupBounds) lies outside one of the view's side planes, with margins for rounding, or its object
// collapsed. Needs projector.glsl and cull_group_bounds.glsl.

// Whether box `g`, in its object's space, lies wholly outside one of the view's four side
// planes: its centre relative to the eye and the half extents of a box around its image there.
bool boxOutside(GroupBox g, ProjectorObject o) {
    vec4 c = vec4((o.model * vec4(g.center, 1.0)).xyz, 1.0);
    mat3 m = mat3(o.model);
    vec3 extent = mat3(abs(m[0]), abs(m[1]), abs(m[2])) * g.extent;
    vec4 w = vec4(u_viewProj[0][3], u_viewProj[1][3], u_viewProj[2][3], u_viewProj[3][3]);
    for (int k = 0; k < 4; ++k) {
        int row = k / 2;
        vec4 axis = vec4(u_viewProj[0][row], u_viewProj[1][row], u_viewProj[2][row], u_viewProj[3][row]);
        vec4 plane = (k & 1) == 0 ? w + axis : w - axis; // inside: dot(plane, c) >= 0
        float reach = dot(abs(plane.xyz), extent);
        float slack = reach * 1e-3 + 1e-5 * (dot(abs(plane), abs(c)) + reach);
        if (dot(plane, c) + reach < -slack) return true;
    }
    return false;
}

// Whether the group's places need the test by place.
bool byPlace(uint group) {
    for (uint k = 0u; k < kGroupBoxes; ++k) {
        GroupBox g = groupBoxes[group * kGroupBoxes + k];
        if (g.state == kBoxByPlace) return true;
        if (g.state != kBoxUsed) continue;
        if (!(float(g.object) < u_params.y)) return true;
        ProjectorObject o = objects[g.object];
        if (o.info.w != 0u) return true; // the host draws its decals: counted by place
        if (o.info.z == 0u && !boxOutside(g, o)) return true;
    }
    return false;
}
