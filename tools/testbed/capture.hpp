#pragma once
// Pictures out of the testbed: the framebuffer read back (glReadPixels), written as PNG with
// libpng, or piped as raw frames into ffmpeg for --video FILE.mp4 / .gif.
#include <cstdio>
#include <string>
#include <vector>

namespace anyphys::testbed {

/// An RGB image, rows from the top.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<unsigned char> rgb;
};

/// Reads the bound framebuffer's colour (width x height from the bottom-left) into an image.
Image readFramebuffer(int width, int height);
/// Writes `image` as an 8-bit RGB PNG; throws anyphys::Error naming the file if it cannot.
void writePng(const Image& image, const std::string& path);

/// Frames piped into ffmpeg (from Debian's ffmpeg package, found on PATH). A .gif gets a palette
/// made from the whole clip; anything else is encoded as H.264 in yuv420p (plays everywhere).
class VideoWriter {
public:
    VideoWriter(const std::string& path, int width, int height, int framesPerSecond);
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;
    void add(const Image& frame);
    /// Waits for ffmpeg; throws anyphys::Error if it failed.
    void finish();

private:
    std::string path_;
    int width_, height_;
    std::FILE* pipe_ = nullptr;
};

}  // namespace anyphys::testbed
