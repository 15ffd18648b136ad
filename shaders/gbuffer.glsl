// Texture units of the G-buffer as the lighting and view passes read it.
layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_albedo;
layout(binding = 2) uniform sampler2D s_normal;
layout(binding = 3) uniform sampler2D s_material;
layout(binding = 4) uniform usampler2D s_ids;
layout(binding = 5) uniform sampler2D s_coverage;
