#pragma once
// The checks DecalProjector makes on a HostFrame before it touches any GL state: every texture
// exists, is a 2D texture holding the viewport, and has a format its role can take; the camera can
// be inverted and its depth direction is the one the frame states. The same for the forward path's
// ForwardFrame.

#include "spatter/render/DecalProjector.hpp"

#include <epoxy/gl.h>

#include <string>

namespace spatter::render_detail {

// What a texture's internal format holds, as far as the projector cares.
struct FormatFacts {
    int channels = 0; // 0: a format the projector does not know
    bool depth = false;
    bool integer = false;  // unsigned integer
    bool isSigned = false; // snorm or float: can hold negative values
    bool renderable = false;
};

FormatFacts formatFacts(GLenum internalFormat);

// The internal format of level 0 of a texture (0 when it is not a texture).
GLenum textureFormat(GLuint texture);

// Empty when `frame` (with `options`) fits; otherwise an error naming the field.
std::string hostFrameProblem(const HostFrame& frame, const ProjectorDraw& options);

// The largest forward viewport side, pixels.
constexpr int kMaxForwardSize = 16384;

// The forward frame's viewport and camera as a HostFrame without textures (window depth).
HostFrame cameraFrame(const ForwardFrame& frame);
// The host frame's viewport and camera as a ForwardFrame (its window depth's clip range and Z order).
ForwardFrame forwardFrame(const HostFrame& frame);

// Empty when `frame` fits; otherwise an error naming the field.
std::string forwardFrameProblem(const ForwardFrame& frame);

// The current context's shader storage binding points and combined texture units, queried once (at
// DecalProjector::create) so that no later call waits on a query.
struct ContextLimits {
    GLint storageBindings = 0, textureUnits = 0;
};
ContextLimits contextLimits();

// Empty when a context of `limits` has the binding points and texture units `bindings` names, each
// once; otherwise an error naming the field.
std::string forwardBindingsProblem(const ForwardBindings& bindings, const ContextLimits& limits);

} // namespace spatter::render_detail
