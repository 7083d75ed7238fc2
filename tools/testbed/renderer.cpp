#include "renderer.hpp"

#include <cstddef>
#include <string>

#include "anyphys/error.hpp"

namespace anyphys::testbed {
namespace {

const char* kTriangleVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
uniform mat4 mvp;
out vec3 vNormal;
out vec3 vColor;
void main() {
    vNormal = normal;
    vColor = color;
    gl_Position = mvp * vec4(position, 1.0);
})";

const char* kTriangleFragment = R"(#version 330 core
in vec3 vNormal;
in vec3 vColor;
uniform vec3 lightDirection;
uniform float ambient;
uniform float diffuse;
out vec4 fragColor;
void main() {
    float light = abs(dot(normalize(vNormal), lightDirection));
    fragColor = vec4(vColor * (ambient + diffuse * light), 1.0);
})";

const char* kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;
uniform mat4 mvp;
out vec3 vColor;
void main() {
    vColor = color;
    gl_Position = mvp * vec4(position, 1.0);
})";

const char* kLineFragment = R"(#version 330 core
in vec3 vColor;
out vec4 fragColor;
void main() { fragColor = vec4(vColor, 1.0); })";

GLuint compile(GLenum type, const char* source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        throw Error(std::string("testbed: shader does not compile: ") + log);
    }
    return shader;
}

GLuint link(const char* vertex, const char* fragment) {
    const GLuint program = glCreateProgram();
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        throw Error(std::string("testbed: shaders do not link: ") + log);
    }
    return program;
}

void attribute(GLuint index, int components, std::size_t stride, std::size_t offset) {
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, components, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                          reinterpret_cast<const void*>(offset));
}

}  // namespace

Renderer::~Renderer() {
    if (triangleProgram_) glDeleteProgram(triangleProgram_);
    if (lineProgram_) glDeleteProgram(lineProgram_);
    const GLuint buffers[2] = {triangleVbo_, lineVbo_};
    const GLuint arrays[2] = {triangleVao_, lineVao_};
    glDeleteBuffers(2, buffers);
    glDeleteVertexArrays(2, arrays);
}

void Renderer::init() {
    triangleProgram_ = link(kTriangleVertex, kTriangleFragment);
    lineProgram_ = link(kLineVertex, kLineFragment);
    triangleMvp_ = glGetUniformLocation(triangleProgram_, "mvp");
    lightDirection_ = glGetUniformLocation(triangleProgram_, "lightDirection");
    lineMvp_ = glGetUniformLocation(lineProgram_, "mvp");

    glGenVertexArrays(1, &triangleVao_);
    glGenBuffers(1, &triangleVbo_);
    glBindVertexArray(triangleVao_);
    glBindBuffer(GL_ARRAY_BUFFER, triangleVbo_);
    attribute(0, 3, sizeof(Vertex), offsetof(Vertex, position));
    attribute(1, 3, sizeof(Vertex), offsetof(Vertex, normal));
    attribute(2, 3, sizeof(Vertex), offsetof(Vertex, color));

    glGenVertexArrays(1, &lineVao_);
    glGenBuffers(1, &lineVbo_);
    glBindVertexArray(lineVao_);
    glBindBuffer(GL_ARRAY_BUFFER, lineVbo_);
    attribute(0, 3, sizeof(LineVertex), offsetof(LineVertex, position));
    attribute(1, 3, sizeof(LineVertex), offsetof(LineVertex, color));
    glBindVertexArray(0);
}

void Renderer::draw(const Batch& batch, const Camera& camera, const Rect& rect, int framebufferHeight) {
    const int glY = framebufferHeight - rect.y - rect.h;
    glViewport(rect.x, glY, rect.w, rect.h);
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect.x, glY, rect.w, rect.h);
    glClearColor(kBackground[0] / 255.0f, kBackground[1] / 255.0f, kBackground[2] / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);

    const Eigen::Matrix4f mvp = camera.projectionMatrix(double(rect.w) / rect.h) * camera.viewMatrix();
    const Vec3 light = Vec3(0.35, 0.85, 0.4).normalized();

    glUseProgram(triangleProgram_);
    glUniformMatrix4fv(triangleMvp_, 1, GL_FALSE, mvp.data());
    glUniform3f(lightDirection_, float(light.x()), float(light.y()), float(light.z()));
    glUniform1f(glGetUniformLocation(triangleProgram_, "ambient"), kAmbient);
    glUniform1f(glGetUniformLocation(triangleProgram_, "diffuse"), kDiffuse);
    glBindVertexArray(triangleVao_);
    glBindBuffer(GL_ARRAY_BUFFER, triangleVbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(batch.triangles.size() * sizeof(Vertex)),
                 batch.triangles.data(), GL_STREAM_DRAW);
    // Lines drawn on a surface (bounds touching faces) win over it.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(batch.triangles.size()));
    glDisable(GL_POLYGON_OFFSET_FILL);

    glUseProgram(lineProgram_);
    glUniformMatrix4fv(lineMvp_, 1, GL_FALSE, mvp.data());
    glBindVertexArray(lineVao_);
    glBindBuffer(GL_ARRAY_BUFFER, lineVbo_);
    const auto lines = [](const std::vector<LineVertex>& v) {
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(LineVertex)), v.data(), GL_STREAM_DRAW);
        glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(v.size()));
    };
    lines(batch.lines);
    glDisable(GL_DEPTH_TEST);
    lines(batch.overlayLines);
    glBindVertexArray(0);
    glDisable(GL_SCISSOR_TEST);
}

OffscreenTarget::OffscreenTarget(int width, int height) {
    glGenFramebuffers(1, &framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glGenRenderbuffers(1, &color_);
    glBindRenderbuffer(GL_RENDERBUFFER, color_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("testbed: the off-screen framebuffer is incomplete");
}

OffscreenTarget::~OffscreenTarget() {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteRenderbuffers(1, &color_);
    glDeleteRenderbuffers(1, &depth_);
}

void OffscreenTarget::bind() const { glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_); }

}  // namespace anyphys::testbed
