#pragma once
// Encoders of animation frames (internal to the drawing module): frames arrive as Cairo RGB24
// images (32 bits a pixel, B G R x in memory) and go to a temporary file renamed on finish().

#include <memory>
#include <string>

namespace softdrop::detail {

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// One frame of the size given at creation; `stride` bytes between rows.
  virtual void add(const unsigned char* data, int stride) = 0;
  /// Completes the file and renames it to its path; throws std::runtime_error naming it.
  virtual void finish() = 0;
};

/// Animated GIF with giflib: a fixed palette (6 x 6 x 6 cube and 40 greys), looping.
std::unique_ptr<FrameSink> gif_sink(const std::string& path, int width, int height, double fps);
/// MP4 (H.264, yuv420p) through the ffmpeg program; throws naming the file if ffmpeg is missing.
std::unique_ptr<FrameSink> video_sink(const std::string& path, int width, int height, double fps);

}  // namespace softdrop::detail
