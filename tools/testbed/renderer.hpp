#pragma once
// Draws batches with OpenGL 3.3 core: one streamed vertex buffer for the shaded triangles, one for
// the lines; shading is ambient plus one two-sided directional light, a scalar on the body's
// colour (so a pixel keeps its body's colour ratios: the tests rely on it).
#include <GL/glew.h>

#include "batch.hpp"
#include "camera.hpp"

namespace anyphys::testbed {

/// A rectangle of the framebuffer, pixels from its top-left corner.
struct Rect {
    int x = 0;
    int y = 0;
    int w = 1;
    int h = 1;
};

/// Shading constants: a triangle's pixel is colour * (kAmbient + kDiffuse * |n . light|).
inline constexpr float kAmbient = 0.45f;
inline constexpr float kDiffuse = 0.55f;
/// The background every view is cleared to (8-bit sRGB values).
inline constexpr unsigned char kBackground[3] = {38, 44, 56};

class Renderer {
public:
    Renderer() = default;
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Compiles the shaders and makes the buffers; needs a current GL 3.3 context. Throws
    /// anyphys::Error with the GL log if a shader fails.
    void init();
    /// Clears a framebuffer `height` pixels high within `rect` and draws `batch` seen by `camera`.
    void draw(const Batch& batch, const Camera& camera, const Rect& rect, int framebufferHeight);

private:
    GLuint triangleProgram_ = 0;
    GLuint lineProgram_ = 0;
    GLuint triangleVao_ = 0, triangleVbo_ = 0;
    GLuint lineVao_ = 0, lineVbo_ = 0;
    GLint triangleMvp_ = -1, lineMvp_ = -1;
    GLint lightDirection_ = -1;
};

/// An off-screen colour + depth target (the headless mode renders into one).
class OffscreenTarget {
public:
    OffscreenTarget(int width, int height);
    ~OffscreenTarget();
    OffscreenTarget(const OffscreenTarget&) = delete;
    OffscreenTarget& operator=(const OffscreenTarget&) = delete;
    void bind() const;

private:
    GLuint framebuffer_ = 0, color_ = 0, depth_ = 0;
};

}  // namespace anyphys::testbed
