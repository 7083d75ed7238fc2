#include "capture.hpp"

#include <GL/glew.h>
#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstring>

#include "anyphys/error.hpp"

namespace anyphys::testbed {
namespace {

// The path in single quotes for /bin/sh, quotes inside escaped.
std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

Image readFramebuffer(int width, int height) {
    Image image;
    image.width = width;
    image.height = height;
    std::vector<unsigned char> bottomUp(static_cast<std::size_t>(width) * height * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
    image.rgb.resize(bottomUp.size());
    const std::size_t row = static_cast<std::size_t>(width) * 3;
    for (int y = 0; y < height; ++y)
        std::memcpy(&image.rgb[static_cast<std::size_t>(y) * row], &bottomUp[static_cast<std::size_t>(height - 1 - y) * row], row);
    return image;
}

void writePng(const Image& image, const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) throw Error("cannot write " + path + ": " + std::strerror(errno));
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        std::fclose(file);
        throw Error("cannot write " + path + ": libpng failed");
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    const std::size_t row = static_cast<std::size_t>(image.width) * 3;
    for (int y = 0; y < image.height; ++y)
        png_write_row(png, const_cast<png_bytep>(&image.rgb[static_cast<std::size_t>(y) * row]));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fclose(file) != 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, int framesPerSecond)
    : path_(path), width_(width), height_(height) {
    const std::string filters = endsWith(path, ".gif")
                                    ? "-vf 'split[a][b];[a]palettegen[p];[b][p]paletteuse' "
                                    : "-c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' ";
    const std::string command = "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgb24 -s " + std::to_string(width) + "x" +
                                std::to_string(height) + " -r " + std::to_string(framesPerSecond) + " -i - " + filters +
                                shellQuote(path);
    pipe_ = popen(command.c_str(), "w");
    if (!pipe_) throw Error("--video: cannot start ffmpeg (is Debian's ffmpeg package installed?)");
}

VideoWriter::~VideoWriter() {
    if (pipe_) pclose(pipe_);
}

void VideoWriter::add(const Image& frame) {
    if (!pipe_ || frame.width != width_ || frame.height != height_) return;
    std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_);
}

void VideoWriter::finish() {
    if (!pipe_) return;
    const int status = pclose(pipe_);
    pipe_ = nullptr;
    if (status != 0) throw Error("--video: ffmpeg failed writing " + path_ + " (exit status " + std::to_string(status) + ")");
}

}  // namespace anyphys::testbed
