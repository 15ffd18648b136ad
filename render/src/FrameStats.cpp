#include "spatter/render/FrameStats.hpp"

#include <cmath>
#include <cstdio>

namespace spatter {

namespace {

std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += char(c);
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(c));
            out += buf;
        } else {
            out += char(c);
        }
    }
    return out + "\"";
}

std::string jsonNumber(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

} // namespace

std::string toJson(const FrameStats& s) {
    std::string j = "{";
    auto field = [&](const char* name, const std::string& value) {
        if (j.size() > 1) j += ",";
        j += "\"";
        j += name;
        j += "\":" + value;
    };
    field("frame", std::to_string(s.frame));
    field("width", std::to_string(s.width));
    field("height", std::to_string(s.height));
    field("view", quoted(toString(s.view)));
    field("decals", std::to_string(s.decals));
    field("decals_invalid", std::to_string(s.decalsInvalid));
    field("decals_culled", std::to_string(s.decalsCulled));
    field("decals_drawn", std::to_string(s.decalsDrawn));
    field("decals_inside", std::to_string(s.decalsInside));
    field("decal_bytes_uploaded", std::to_string(s.decalBytesUploaded));
    field("decal_pass_skipped", s.decalPassSkipped ? "true" : "false");
    field("decal_variant", quoted(s.decalVariant));
    field("decal_normal_copy", quoted(s.decalNormalCopy));
    field("overlay_lines", std::to_string(s.overlayLines));
    field("decals_texture_space", std::to_string(s.decalsTextureSpace));
    field("decals_splatted", std::to_string(s.decalsSplatted));
    field("decals_volumetric", std::to_string(s.decalsVolumetric));
    field("texture_space_objects", std::to_string(s.textureSpaceObjects));
    field("texture_space_bytes", std::to_string(s.textureSpaceBytes));
    field("draw_calls", std::to_string(s.drawCalls));
    field("triangles", std::to_string(s.triangles));
    field("cpu_ms", jsonNumber(s.cpuMs));
    field("gpu_ms",
          "{\"geometry\":" + jsonNumber(s.gpu.geometryMs) + ",\"decals\":" + jsonNumber(s.gpu.decalsMs) +
              ",\"late\":" + jsonNumber(s.gpu.lateMs) + ",\"lighting\":" + jsonNumber(s.gpu.lightingMs) +
              ",\"overlay\":" + jsonNumber(s.gpu.overlayMs) + ",\"splat\":" + jsonNumber(s.gpu.splatMs) +
              ",\"volumetric\":" + jsonNumber(s.gpu.volumetricMs) + ",\"total\":" +
              jsonNumber(s.gpu.totalMs()) + ",\"frame\":" + std::to_string(s.gpu.frame) + "}");
    const ProjectorStageTimes& st = s.decalStages;
    field("decal_stages_ms", "{\"cull\":" + jsonNumber(st.cullMs) + ",\"bin\":" + jsonNumber(st.binMs) +
                                 ",\"draw\":" + jsonNumber(st.drawMs) + ",\"read_back\":" +
                                 jsonNumber(st.readBackMs) + ",\"frame\":" + std::to_string(st.frame) + "}");
    field("gl_renderer", quoted(s.glRenderer));
    field("gl_vendor", quoted(s.glVendor));
    field("gl_version", quoted(s.glVersion));
    return j + "}";
}

} // namespace spatter
